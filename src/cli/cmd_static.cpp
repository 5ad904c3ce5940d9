// cable_sim static: static equilibrium of a problem file.
#include <cmath>
#include <exception>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "cli_common.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/io/result_io.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {
int runStatic(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (args.positionals.size() != 1)
    throw UsageError(args.positionals.empty() ? "missing PROBLEM.yaml"
                                              : "expected one problem file, got " +
                                                    std::to_string(args.positionals.size()) + " arguments");
  const std::string problem_path = args.positionals.front();
  const bool want_table = args.has("table") || args.has("table-stride");
  const std::size_t stride =
      args.has("table-stride") ? parsePositiveInt("table-stride", args.values.at("table-stride")) : 1;
  const double spacing_scale =
      args.has("spacing-scale") ? parsePositiveDouble("spacing-scale", args.values.at("spacing-scale")) : 1.0;
  const std::string out_dir = args.has("out") ? args.values.at("out") : std::string();
  if (args.has("out") && out_dir.empty()) throw UsageError("option '--out' needs a directory, got ''");
  if (core::isSystemFile(problem_path))  // several lines joined at points
    return runSystemStatic(problem_path, want_table, stride, spacing_scale, out_dir, out, err);

  // Load.
  core::Problem problem;
  try {
    problem = core::loadProblemFromFile(problem_path);
  } catch (const core::ProblemError& e) {
    err << kProg << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {  // anything the loader did not wrap is still a bad file
    err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
    return kExitBadInput;
  }

  // Refinement studies: scale every segment's node spacing, then check the scaled problem again
  // (spacing within each segment, node count and memory within problem.limits) before anything
  // is allocated. A failure is the option's: a usage error naming the segment's key.
  if (spacing_scale != 1.0) {
    for (auto& seg : problem.segments) seg.spacing *= spacing_scale;
    const std::string invalid = problem.validate();
    if (!invalid.empty())
      throw UsageError("--spacing-scale " + args.values.at("spacing-scale") + ": " + invalid);
  }

  // Solve.
  core::StaticResult result;
  try {
    result = core::solveStaticModel(problem);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
    return kExitBadInput;
  }

  out << core::staticSummaryText(problem, result);
  if (want_table) out << "\n" << core::staticTableText(result, stride, problem.formulation);

  // Outputs (written also when the solver did not converge: the JSON says so).
  if (!out_dir.empty()) {
    const fs::path dir(out_dir);
    if (!makeOutputDir(dir, err)) return kExitIo;
    const fs::path json = dir / "static.json";
    const fs::path csv = dir / "static_nodes.csv";
    if (!writeFile(json, [&](std::ostream& f) { core::writeStaticJson(f, problem, result); }, err)) return kExitIo;
    if (!writeFile(csv, [&](std::ostream& f) { core::writeStaticCsv(f, result, problem.formulation); }, err)) return kExitIo;
    out << "wrote " << json.string() << " and " << csv.string() << "\n";
  }

  if (!result.summary.converged) {
    err << kProg << ": error: solver did not converge after " << result.summary.iterations << " iterations";
    if (!result.summary.message.empty()) err << " (" << result.summary.message << ")";
    err << (out_dir.empty() ? "" : "; results written and marked \"converged\": false") << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
