// YAML problem files -> core::Problem, with validation. Errors name the key, its value and the
// violated constraint. The format is documented in docs/problem_format.md.
#pragma once

#include <stdexcept>
#include <string>

#include "mooring_dynamics/core/model.hpp"

namespace mooring_dynamics {
namespace core {

/// Raised for any bad input; what() names the key path (e.g. "materials.chain.EA"), the value
/// found and the constraint it violates.
class ProblemError : public std::runtime_error {
 public:
  explicit ProblemError(const std::string& what) : std::runtime_error(what) {}
};

/// Parse a problem from YAML text. Throws ProblemError.
Problem loadProblemFromString(const std::string& yaml_text);

/// Parse a problem from a file. Throws ProblemError (also when the file cannot be read).
Problem loadProblemFromFile(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
