// YAML problem files -> core::Problem, with validation. Errors name the key, its value and the
// violated constraint. The format is documented in docs/problem_format.md.
#pragma once

#include <stdexcept>
#include <string>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace core {

/// Raised for any bad input; what() names the key path (e.g. "materials.chain.EA"), the value
/// found and the constraint it violates.
class ProblemError : public std::runtime_error {
 public:
  explicit ProblemError(const std::string& what) : std::runtime_error(what) {}
};

/// Parse a problem from YAML text. Throws ProblemError. Files the text names (a seabed
/// `grid_file`) are read relative to the current directory unless absolute.
Problem loadProblemFromString(const std::string& yaml_text);
/// Same, with relative file names resolved against `base_dir` ("" = the current directory).
Problem loadProblemFromString(const std::string& yaml_text, const std::string& base_dir);

/// Parse a problem from a file. Throws ProblemError (also when the file cannot be read). Files it
/// names (a seabed `grid_file`) are relative to its directory.
Problem loadProblemFromFile(const std::string& path);

/// A system file holds `points` and `lines` (several lines joined at points: multi-leg and
/// branched moorings, docs/problem_format.md "Systems") instead of `line`, `anchor` and `top`.
bool isSystemText(const std::string& yaml_text);
bool isSystemFile(const std::string& path);
/// Parse a system; throws ProblemError naming the key, value and constraint.
SystemProblem loadSystemFromString(const std::string& yaml_text, const std::string& base_dir = "");
SystemProblem loadSystemFromFile(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
