// Current-profile lookups (core::CurrentProfile::at and gradientAt) against the table's size: a
// bisection, so the cost per lookup grows with log2 of the points (a linear scan would grow with
// the points: minutes for 2e5 lookups in a million-point table). Moved here from a wall-clock
// assertion in test_model (timing belongs in benchmarks).
//
// BM_CurrentProfileLookup/<points>: one lookup of the speed and of its gradient per iteration, at
// depths spread over the table. Compare the time per iteration at 1e3 and 1e6 points: a few times
// (10 against 20 comparisons, and cache misses in a 24 MB table; measured 33 and 158 ns of CPU on
// the 2-core EPYC host), not 1000 times.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "mooring_dynamics/core/model/model.hpp"

using mooring_dynamics::core::CurrentPoint;
using mooring_dynamics::core::CurrentProfile;

namespace {

void BM_CurrentProfileLookup(benchmark::State& state) {
  const std::size_t points = static_cast<std::size_t>(state.range(0));
  constexpr double kDepth = 5000.0;  // [m]
  std::vector<CurrentPoint> table(points);
  for (std::size_t i = 0; i < points; ++i) {
    table[i].depth = kDepth * static_cast<double>(i) / static_cast<double>(points - 1);
    table[i].speed = 0.2 + 1e-4 * table[i].depth;
    table[i].direction = 0.3;
  }
  const CurrentProfile prof(table);
  constexpr int kSpread = 4096;
  int k = 0;
  for (auto _ : state) {
    const double z = -(kDepth - 1.0) * (static_cast<double>(k) + 0.5) / kSpread;
    k = (k + 1) % kSpread;
    double ux, uy, gx, gy;
    prof.at(z, ux, uy);
    prof.gradientAt(z, gx, gy);
    benchmark::DoNotOptimize(ux + uy + gx + gy);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CurrentProfileLookup)->Arg(1000)->Arg(1000000)->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
