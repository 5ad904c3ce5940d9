// 3-D dynamic-solver cost (equations3d.hpp: N = 13 plus coordinates, generalized-alpha, Newton
// with adaptive relaxation, banded LU with kl = 25, ku = 21).
//
// BM_Dynamic3DStepCost/<nodes>/<threads>: cost of one time step against node count on the grounded chain
// of bench_static / bench_dynamic (bench_problems.hpp), model: 3d, with a uniform 0.5 m/s current
// at 45 deg to the line's plane (a non-planar line), heaved at the top, z = z0 + 1 m
// (1 - cos(2 pi t / 10 s)) from rest, lambda_inf = -0.5, dt = 0.1 s, 20 steps per benchmark
// iteration. Only advanceTo() is timed. Counters as in bench_dynamic: nodes, steps, cuts,
// newton_iters, newton_per_step, ns_per_step_node, and ns_per_iter_node (wall time per Newton
// iteration and node). <threads>: dynamics.threads (1 or 2, same results).
//
// BM_TowedArrayCase1RealTimeFactor: the paper's A.1 Case 1 (config/towed_array.yaml), 940 s.
//
// BM_ChainMooring3DRealTimeFactor: config/chain_mooring_3d.yaml (A.3 in a 60 deg cross current,
// heave 2 m and sway 1 m at 8 s, dt 0.1 s), 20 s through runDynamic3D.
//
// BM_STether3DWavesRealTimeFactor: config/s_tether.yaml in the 3-D model, first 100 s.
//
// BM_WinchLoweringRealTimeFactor: config/winch_lowering.yaml (an instrument paid out 50 -> 150 m
// and hauled in to 60 m, 240 s): the winch's nodes added and taken out, 11 to 31 nodes.
//
// The whole-run benchmarks count real_time_factor, newton_iters and jacobians per run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>

#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "bench_configs.hpp"
#include "bench_problems.hpp"

namespace md = mooring_dynamics::core;

namespace {

constexpr double kDt = 0.1;  // [s]
constexpr int kSteps = 20;
constexpr double kTwoPi = 6.283185307179586;

md::Problem heavedChain3D(int nodes) {
  md::Problem p = mooring_dynamics::bench::chainWithSeabed(nodes);
  p.name = "bench heaved chain in a cross current (3-D)";
  p.formulation = md::Formulation::ThreeD;
  p.environment.seabed.damping = 2.0e4;
  md::CurrentPoint c;
  c.speed = 0.5;
  c.direction = 0.25 * kTwoPi / 2.0;  // 45 deg
  p.environment.current = {c};
  md::DynamicOptions& d = p.dynamics;
  d.duration = kSteps * kDt;
  d.dt = kDt;
  d.scheme = md::GeneralizedAlpha::fromLambdaInf(-0.5);
  d.top_motion.type = md::TopMotion::Type::Sinusoid;
  d.top_motion.amplitude_z = 1.0;
  d.top_motion.period = 10.0;
  d.top_motion.phase = -0.25 * kTwoPi;
  return p;
}

void BM_Dynamic3DStepCost(benchmark::State& state) {
  md::Problem problem = heavedChain3D(static_cast<int>(state.range(0)));
  problem.dynamics.threads = static_cast<int>(state.range(1));
  long steps = 0, cuts = 0, newton = 0, iterations = 0;
  std::size_t node_count = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    md::DynamicSolver3D solver(problem);
    node_count = solver.nodeArclengths().size();
    const auto t0 = std::chrono::steady_clock::now();
    const md::StepReport rep = solver.advanceTo(kSteps * kDt);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(dt);
    if (!rep.ok) {
      state.SkipWithError(("dynamic run failed: " + rep.message).c_str());
      return;
    }
    seconds += dt;
    steps += rep.steps;
    cuts += rep.cuts;
    newton += rep.newton_iterations;
    ++iterations;
  }
  if (iterations == 0) return;
  const double n = static_cast<double>(iterations), nodes = static_cast<double>(node_count);
  state.counters["nodes"] = nodes;
  state.counters["steps"] = static_cast<double>(steps) / n;
  state.counters["cuts"] = static_cast<double>(cuts) / n;
  state.counters["newton_iters"] = static_cast<double>(newton) / n;
  state.counters["newton_per_step"] = static_cast<double>(newton) / static_cast<double>(steps);
  state.counters["ns_per_step_node"] = 1e9 * seconds / (static_cast<double>(steps) * nodes);
  state.counters["ns_per_iter_node"] = 1e9 * seconds / (static_cast<double>(newton) * nodes);
}

/// Times whole runs of `problem` through runDynamic3D, as `cable_sim dynamic` does: counters
/// real_time_factor (simulated / wall time), newton_iters and jacobians per run.
void timeWholeRuns(benchmark::State& state, const md::Problem& problem) {
  double wall = 0.0;
  long iterations = 0, newton = 0, jacobians = 0;
  for (auto _ : state) {
    const md::DynamicSeries r = md::runDynamic3D(problem);
    if (!r.completed) {
      state.SkipWithError(("run failed: " + r.message).c_str());
      return;
    }
    state.SetIterationTime(r.wall_seconds);
    wall += r.wall_seconds;
    newton += r.newton_iterations;
    jacobians += r.jacobians;
    ++iterations;
  }
  if (iterations == 0) return;
  state.counters["real_time_factor"] = problem.dynamics.duration * static_cast<double>(iterations) / wall;
  state.counters["newton_iters"] = static_cast<double>(newton) / static_cast<double>(iterations);
  state.counters["jacobians"] = static_cast<double>(jacobians) / static_cast<double>(iterations);
}

}  // namespace

void BM_ChainMooring3DRealTimeFactor(benchmark::State& state) {
  constexpr double kDuration = 20.0;  // [s] simulated
  md::Problem problem;
  if (!mooring_dynamics::bench::loadShippedConfig(state, "chain_mooring_3d.yaml", problem)) return;
  problem.dynamics.duration = kDuration;
  timeWholeRuns(state, problem);
}

/// The paper's towed array, Case 1 (config/towed_array.yaml: 1031 nodes, 940 s at a 1 s base step,
/// modified Newton as shipped) through runDynamic3D, as `cable_sim dynamic`. The target:
/// under 3.5 s (the paper's program: about 35 s).
void BM_TowedArrayCase1RealTimeFactor(benchmark::State& state) {
  md::Problem problem;
  if (!mooring_dynamics::bench::loadShippedConfig(state, "towed_array.yaml", problem)) return;
  timeWholeRuns(state, problem);
}

/// The deepwater S-tether (config/s_tether.yaml: 274 nodes, Pierson-Moskowitz sea of 400
/// components, base step 0.5 s) in the 3-D model, first 100 s: the cost of 3-D wave kinematics
/// (WaveVelocityCache in the horizontal plane) beside the 2-D run of bench_dynamic.
void BM_STether3DWavesRealTimeFactor(benchmark::State& state) {
  constexpr double kDuration = 100.0;  // [s] of the 600 s storm
  md::Problem problem;
  if (!mooring_dynamics::bench::loadShippedConfig(state, "s_tether.yaml", problem)) return;
  problem.formulation = md::Formulation::ThreeD;
  problem.dynamics.duration = kDuration;
  timeWholeRuns(state, problem);
}

BENCHMARK(BM_Dynamic3DStepCost)->ArgsProduct({{50, 100, 200, 400, 800}, {1, 2}})->ArgNames({"nodes", "threads"})->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ChainMooring3DRealTimeFactor)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_TowedArrayCase1RealTimeFactor)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
/// An instrument lowered and recovered by a winch (config/winch_lowering.yaml, 240 s at 0.5 s):
/// the cost of the winch's remeshing (nodes added and taken out, the wave cache and the previous
/// level's rows rebuilt each time) on a short line.
void BM_WinchLoweringRealTimeFactor(benchmark::State& state) {
  md::Problem problem;
  if (!mooring_dynamics::bench::loadShippedConfig(state, "winch_lowering.yaml", problem)) return;
  timeWholeRuns(state, problem);
}

BENCHMARK(BM_STether3DWavesRealTimeFactor)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK(BM_WinchLoweringRealTimeFactor)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(5);

BENCHMARK_MAIN();
