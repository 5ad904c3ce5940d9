// Static-solve time against node count: one homogeneous chain from an anchor on a flat seabed to a
// fixed top position, part of it lying on the bottom (catenary with seabed contact). The problem is
// built in code; only the node spacing changes between runs, so the timings show how the solver
// (box-scheme assembly + banded LU + adaptive relaxation) scales with the mesh.
//
// Counters: nodes, newton_iters (Newton iterations of one solve), top_tension [N] and its relative
// error against the closed-form catenary (a run further than 1e-3 off is reported as an error).
// scripts/bench derives the wall time per node per Newton iteration from the JSON output.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "mooring_dynamics/core/equations/catenary.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "bench_problems.hpp"

namespace md = mooring_dynamics::core;

namespace {

using mooring_dynamics::bench::chainWithSeabed;

void BM_StaticSolve(benchmark::State& state) {
  const int nodes = static_cast<int>(state.range(0));
  const md::Problem problem = chainWithSeabed(nodes);
  md::StaticResult result;
  for (auto _ : state) {
    result = md::solveStatic(problem);
    benchmark::DoNotOptimize(result.nodes.data());
  }
  if (!result.summary.converged) {
    state.SkipWithError(("did not converge: " + result.summary.message).c_str());
    return;
  }
  state.counters["nodes"] = static_cast<double>(result.nodes.size());
  state.counters["newton_iters"] = result.summary.iterations;
  state.counters["top_tension"] = result.topTension();

  // Sanity: the top tension must match the closed-form elastic catenary with seabed contact.
  md::CatenaryInput in;
  in.L = problem.segments[0].length;
  in.w = problem.materials[0].wet_weight;
  in.EA = problem.materials[0].EA;
  in.X = problem.top.x - problem.anchor_x;
  in.Z = problem.top.z - problem.anchor_z;
  in.seabed = true;
  const md::CatenarySolution exact = md::solveCatenary(in);
  const double rel = std::abs(result.topTension() - exact.topTension()) / exact.topTension();
  state.counters["top_tension_rel_err"] = rel;
  if (!exact.converged || rel > 1.0e-3)
    state.SkipWithError(("top tension differs from the closed-form catenary by " + std::to_string(rel)).c_str());
}

}  // namespace

BENCHMARK(BM_StaticSolve)
    ->Arg(100)
    ->Arg(300)
    ->Arg(1000)
    ->Arg(3000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
