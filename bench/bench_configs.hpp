// Shipped problem files for the benchmarks: where the package is, and loading one into a
// benchmark (a missing or bad file skips the benchmark with the reason).
#pragma once

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include <unistd.h>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace bench {

/// The package root: $MD_ROOT, else the source folder recorded in the CMakeCache.txt three levels
/// above this executable (<build>/devel/lib/mooring_dynamics/<bench>). Empty when neither is found.
inline std::string packageRoot() {
  if (const char* env = std::getenv("MD_ROOT"); env != nullptr && *env != '\0') return env;
  char buf[4096];
  const ssize_t len = ::readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (len <= 0) return {};
  std::string exe(buf, static_cast<std::size_t>(len));
  for (int up = 0; up < 4; ++up) exe = exe.substr(0, exe.find_last_of('/'));  // strip name + 3 dirs
  std::ifstream cache(exe + "/CMakeCache.txt");
  const std::string key = "mooring_dynamics_SOURCE_DIR:STATIC=";
  for (std::string line; std::getline(cache, line);)
    if (line.rfind(key, 0) == 0) return line.substr(key.size());
  return {};
}

/// Loads config/<file> into `problem`, without whole-line snapshots (the run is timed, not the
/// copies). False, with the benchmark skipped and the reason given, when that fails.
inline bool loadShippedConfig(benchmark::State& state, const std::string& file, core::Problem& problem) {
  const std::string root = packageRoot();
  if (root.empty()) {
    state.SkipWithError(("config/" + file + " not found: set MD_ROOT (source scripts/env.sh)").c_str());
    return false;
  }
  try {
    problem = core::loadProblemFromFile(root + "/config/" + file);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
  problem.dynamics.snapshot_interval = 0.0;
  return true;
}

}  // namespace bench
}  // namespace mooring_dynamics
