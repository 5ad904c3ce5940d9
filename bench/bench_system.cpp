// Statics of a system of lines (system.hpp): config/three_leg_buoy.yaml, a surface buoy on three
// 300 m chain legs in current and wind, with the leg node spacing scaled to show how the cost of
// the partitioned point iteration grows with the node count (linear: every line is solved on its
// own banded system). Counters: nodes (all legs), point_iterations.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"

namespace md = mooring_dynamics::core;

namespace {

void BM_ThreeLegStatics(benchmark::State& state) {
  const char* root = std::getenv("MD_ROOT");
  if (root == nullptr || *root == '\0') {
    state.SkipWithError("config/three_leg_buoy.yaml not found: set MD_ROOT (source scripts/env.sh)");
    return;
  }
  md::SystemProblem s = md::loadSystemFromFile(std::string(root) + "/config/three_leg_buoy.yaml");
  const double spacing = 8.0 / static_cast<double>(state.range(0));  // 8 m / k
  long nodes = 0;
  for (auto& l : s.lines)
    for (auto& g : l.segments) {
      g.spacing = spacing;
      nodes += static_cast<long>(g.length / spacing) + 1;
    }
  int iterations = 0;
  for (auto _ : state) {
    const md::SystemStaticResult r = md::solveSystemStatic(s);
    if (!r.summary.converged) {
      state.SkipWithError(r.summary.message.c_str());
      return;
    }
    iterations = r.summary.iterations;
  }
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["point_iterations"] = iterations;
}

}  // namespace

BENCHMARK(BM_ThreeLegStatics)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
