// The wave velocity at the nodes of a line (WaveVelocityCache::velocity): the exact sum over a
// random sea's components once per time step and node, the largest single cost of the deep
// S-tether (config/s_tether.yaml: Pierson-Moskowitz Hs 9.8 m, Tp 16 s, 400 components, 1860 m).
//
// BM_WaveVelocityStep/<nodes>: one time step per iteration (setTime at t + 0.1 s, then every node
// once at a position moved a few centimetres, as the predictor moves the nodes of the S-tether).
// The nodes run from the seabed to the surface with the S-tether's depth profile (most of the
// line deep, where the cache sums the long waves only); counters: components summed per step
// and components summed per second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

using mooring_dynamics::core::WaveField;
using mooring_dynamics::core::WaveSpec;
using mooring_dynamics::core::WaveVelocityCache;

namespace {

constexpr double kDepth = 1860.0;  // [m]
constexpr double kDt = 0.1;        // [s]

WaveField sTetherSea() {
  WaveSpec s;
  s.type = WaveSpec::Type::PiersonMoskowitz;
  s.hs = 9.8;
  s.tp = 16.0;
  s.components = 400;
  s.seed = 1;
  return WaveField(s, kDepth, 9.81);
}

void BM_WaveVelocityStep(benchmark::State& state) {
  const WaveField field = sTetherSea();
  const int nodes = static_cast<int>(state.range(0));
  std::vector<double> x0(static_cast<std::size_t>(nodes)), z0(x0.size());
  for (int p = 0; p < nodes; ++p) {  // seabed to surface, denser near the top as the S-tether's mesh
    const double u = static_cast<double>(p) / (nodes - 1);
    z0[static_cast<std::size_t>(p)] = -kDepth * std::pow(1.0 - u, 1.6);
    x0[static_cast<std::size_t>(p)] = 1500.0 * u;
  }
  WaveVelocityCache cache(&field, x0.size());
  double t = 0.0, sink = 0.0;
  std::size_t summed = 0;
  for (int p = 0; p < nodes; ++p) summed += cache.componentsAt(z0[static_cast<std::size_t>(p)]);
  for (auto _ : state) {
    t += kDt;
    cache.setTime(t);
    for (int p = 0; p < nodes; ++p) {
      const auto i = static_cast<std::size_t>(p);
      // Orbital motion of the node: 0.2 m/s, a few centimetres per step.
      const double x = x0[i] + 2.0 * std::sin(0.1 * t + p), z = z0[i] + 1.5 * std::cos(0.1 * t + 0.5 * p);
      double vx, vz;
      cache.velocity(i, x, z, vx, vz);
      sink += vx + vz;
    }
  }
  benchmark::DoNotOptimize(sink);
  state.counters["components_per_step"] = static_cast<double>(summed);
  state.counters["components_per_s"] =
      benchmark::Counter(static_cast<double>(summed) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_WaveVelocityStep)->Arg(274)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
