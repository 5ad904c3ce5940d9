// Dynamic-solver cost (paper sections 4 and 6: generalized-alpha step, Newton with adaptive
// relaxation, node-by-node block LU of the half-grid box scheme).
//
// BM_DynamicStepCost/<nodes>/<threads>: cost of one time step against node count. A grounded chain (the
// line of bench_static: 250 m of 76 mm chain in 100 m of water, top held at (200, 0), about 100 m
// on the bottom) is heaved at the top, z = z0 + 1 m (1 - cos(2 pi t / 10 s)), which starts from
// rest so no start-up transient forces step cuts; lambda_inf = -0.5, dt = 0.1 s, 50 steps (5 s)
// per iteration. Only advanceTo() is timed (manual time); building the mesh and the static start
// is not. Counters: nodes, steps, cuts, newton_iters (per iteration of the benchmark, i.e. per
// 50 steps; scripts/bench divides the wall time by nodes * newton_iters), newton_per_step,
// ns_per_step_node (wall time / (steps * nodes)). <threads>: dynamics.threads (1 or 2; the
// second thread takes the upper half of every Newton iteration, same results).
//
// BM_ChainMooringRealTimeFactor: the paper's A.3 all-chain mooring (config/chain_mooring.yaml,
// 2 m / 8 s heave, lambda_inf = -0.5 as shipped), 300 s at a 0.1 s base step, and
// BM_STetherRealTimeFactor: the A.2 deepwater S-tether (config/s_tether.yaml, Hs 9.8 m random
// sea, wave-following buoy), 600 s at 0.1 s: the speed cases, with 1 and 2 threads
// (argument). Each runs runDynamic
// (static start, time stepping and recording, as `cable_sim dynamic`, without snapshots); the
// time is the wall time of the whole run. Counter real_time_factor = simulated / wall time. The
// files are found through the environment variable MD_ROOT (exported by scripts/env.sh);
// without it, through the CMakeCache.txt of the build folder the executable sits in
// (<build>/devel/lib/mooring_dynamics/bench_dynamic).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "bench_configs.hpp"
#include "bench_problems.hpp"

namespace md = mooring_dynamics::core;

namespace {

constexpr double kDt = 0.1;        // [s] base step
constexpr int kSteps = 50;         // base steps per benchmark iteration
constexpr double kTwoPi = 6.283185307179586;

md::Problem heavedChain(int nodes) {
  md::Problem p = mooring_dynamics::bench::chainWithSeabed(nodes);
  p.name = "bench heaved chain with seabed contact";
  p.environment.seabed.damping = 2.0e4;  // ~ a quarter of critical 2 sqrt(k (m + ma))

  md::DynamicOptions& d = p.dynamics;
  d.duration = kSteps * kDt;
  d.dt = kDt;
  d.scheme = md::GeneralizedAlpha::fromLambdaInf(-0.5);
  d.scheme_name = "lambda_inf=-0.5";
  d.top_motion.type = md::TopMotion::Type::Sinusoid;
  d.top_motion.amplitude_z = 1.0;
  d.top_motion.period = 10.0;
  d.top_motion.phase = -0.25 * kTwoPi;  // z0 + a (1 - cos(2 pi t / T)): starts at rest
  return p;
}

void BM_DynamicStepCost(benchmark::State& state) {
  const int nodes = static_cast<int>(state.range(0));
  md::Problem problem = heavedChain(nodes);
  problem.dynamics.threads = static_cast<int>(state.range(1));
  long steps = 0, cuts = 0, newton = 0, iterations = 0;
  std::size_t node_count = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    md::DynamicSolver2D solver(problem);  // mesh + static start: not timed (manual time below)
    node_count = solver.nodeArclengths().size();
    const auto t0 = std::chrono::steady_clock::now();
    const md::StepReport rep = solver.advanceTo(kSteps * kDt);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(dt);
    if (!rep.ok) {
      state.SkipWithError(("dynamic run failed: " + rep.message).c_str());
      return;
    }
    benchmark::DoNotOptimize(solver.time());
    seconds += dt;
    steps += rep.steps;
    cuts += rep.cuts;
    newton += rep.newton_iterations;
    ++iterations;
  }
  if (iterations == 0) return;
  const double n = static_cast<double>(iterations);
  state.counters["nodes"] = static_cast<double>(node_count);
  state.counters["steps"] = static_cast<double>(steps) / n;
  state.counters["cuts"] = static_cast<double>(cuts) / n;
  state.counters["newton_iters"] = static_cast<double>(newton) / n;
  state.counters["newton_per_step"] = static_cast<double>(newton) / static_cast<double>(steps);
  state.counters["ns_per_step_node"] = 1e9 * seconds / (static_cast<double>(steps) * static_cast<double>(node_count));
}

/// Runs config/<file> through runDynamic (as `cable_sim dynamic`) for `duration` seconds at base
/// step `dt`, and reports the real-time factor and the solver's counts.
void runShippedCase(benchmark::State& state, const std::string& file, double duration, double dt) {
  md::Problem problem;
  if (!mooring_dynamics::bench::loadShippedConfig(state, file, problem)) return;
  problem.dynamics.duration = duration;
  problem.dynamics.dt = dt;
  problem.dynamics.output_interval = 0.0;
  problem.dynamics.threads = static_cast<int>(state.range(0));
  md::DynamicSeries r;
  double seconds = 0.0;
  long iterations = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    r = md::runDynamic(problem);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    seconds += wall;
    state.SetIterationTime(wall);
    benchmark::DoNotOptimize(r.top_tension.data());
    ++iterations;
    if (!r.completed) {
      state.SkipWithError(("run stopped early: " + r.message).c_str());
      return;
    }
  }
  if (iterations == 0) return;
  state.counters["nodes"] = static_cast<double>(r.initial_static.nodes.size());
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["cuts"] = static_cast<double>(r.cuts);
  state.counters["newton_iters"] = static_cast<double>(r.newton_iterations);
  state.counters["newton_per_step"] = static_cast<double>(r.newton_iterations) / static_cast<double>(r.steps);
  state.counters["real_time_factor"] = duration * static_cast<double>(iterations) / seconds;
}

// The speed targets: A.3 300 s at 0.1 s under 0.5 s, A.2 600 s at 0.1 s under 1 s.
void BM_ChainMooringRealTimeFactor(benchmark::State& state) { runShippedCase(state, "chain_mooring.yaml", 300.0, 0.1); }
void BM_STetherRealTimeFactor(benchmark::State& state) { runShippedCase(state, "s_tether.yaml", 600.0, 0.1); }

}  // namespace

BENCHMARK(BM_DynamicStepCost)
    ->ArgsProduct({{50, 100, 200, 500, 1000, 2000}, {1, 2}})
    ->ArgNames({"nodes", "threads"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_ChainMooringRealTimeFactor)->ArgName("threads")->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_STetherRealTimeFactor)->ArgName("threads")->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
