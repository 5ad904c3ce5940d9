// Shared by the YAML problem loader's tests (test_problem_io.cpp, test_problem_io_files.cpp): a
// complete good problem and a minimal one as text, the ProblemError message of a text, and
// EXPECT_ERROR_HAS (a text's error names every given part).
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace core {
namespace testing_util {

// A complete, valid problem exercising every section.
inline const char* const kGood = R"(
name: test mooring
environment:
  water_density: 1025
  air_density: 1.2
  gravity: 9.8
  depth: 100
  seabed: {stiffness: 2.0e5, damping: 10, profile: [[-100, 100], [0, 100], [200, 80]]}
  current:
    - {depth: 0, speed: 0.5, direction_deg: 90}
    - {depth: 100, speed: 0.1}
  wind: {speed: 20, direction_deg: 180}
materials:
  chain: {EA: 6.44e7, EI: 10, GJ: 0.1, mass: 3.73, added_mass: 0.48, wet_weight: 31.85,
          diameter: 0.0495, cdn: 0.5, cdt: 0.05, max_strain: 0.1}
  rope: {tension_strain: [[0, 0], [0.01, 2.0e4], [0.05, 2.0e5]], EI: 1, mass: 1, wet_weight: 2,
         diameter: 0.02, cdn: 1.5, cdt: 0.01}
bodies:
  float: {mass: 37.9, added_mass: 31.8, wet_weight: -214.8, diameter: 0.58, cdn: 1.0, cdt: 0.2}
  clump: {mass: 100, wet_weight: 800, diameter: 0.3, cdn: 1.0, cdt: 1.0}
line:
  - {body: clump}
  - {material: chain, length: 45.0, spacing: 0.5, bodies: [{body: float, at: 5.0}]}
  - {body: float}
  - {material: rope, length: 80, bodies: [{body: float, at: 10, every: 20, count: 4}]}
anchor: {x: -1.5}
top:
  position: {x: 80, z: -2}
solver:
  static: {tolerance: 1e-8, max_iterations: 200, relaxation: 0.5, adaptive_relaxation: false, R1: 1.2, R2: 1.05}
dynamics: {duration: 30, dt: 0.1, lambda_inf: -0.5}
)";

/// Load `text` and return the ProblemError message ("" if it loaded).
inline std::string errorOf(const std::string& text) {
  try {
    loadProblemFromString(text);
  } catch (const ProblemError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("WRONG EXCEPTION TYPE: ") + e.what();
  }
  return "";
}

/// The good file with the first occurrence of `from` replaced by `to`.
inline std::string mutate(const std::string& from, const std::string& to) {
  std::string s = kGood;
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << "test bug: '" << from << "' not in the good file";
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

// A minimal valid problem, for errors easier to write from scratch.
inline const char* const kMinimal = R"(
materials:
  chain: {EA: 6.44e7, EI: 10, mass: 3.73, wet_weight: 31.85, diameter: 0.0495, cdn: 0.5, cdt: 0.05}
line:
  - {material: chain, length: 150}
top:
  position: {x: 100, z: 0}
)";

inline std::string minimalWith(const std::string& extra) { return std::string(kMinimal) + extra; }

/// The first ```yaml block after `heading` in docs/problem_format.md (the test fails and "" is
/// returned when the file, the heading or the block is missing).
inline std::string documentedYaml(const std::string& heading) {
  std::ifstream f(std::string(MD_SOURCE_DIR) + "/docs/problem_format.md");
  if (!f.good()) {
    ADD_FAILURE() << "docs/problem_format.md not readable";
    return "";
  }
  const std::string doc((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto sec = doc.find(heading);
  const auto b = sec == std::string::npos ? sec : doc.find("```yaml\n", sec);
  const auto e = b == std::string::npos ? b : doc.find("```", b + 8);
  if (e == std::string::npos) {
    ADD_FAILURE() << "no yaml block after \"" << heading << "\" in docs/problem_format.md";
    return "";
  }
  return doc.substr(b + 8, e - b - 8);
}

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics

#define EXPECT_ERROR_HAS(text, ...)                                                 \
  do {                                                                              \
    const std::string msg_ = ::mooring_dynamics::core::testing_util::errorOf(text); \
    ASSERT_FALSE(msg_.empty()) << "loaded without error";                           \
    for (const std::string& part_ : std::vector<std::string>{__VA_ARGS__})          \
      EXPECT_NE(msg_.find(part_), std::string::npos)                                \
          << "message \"" << msg_ << "\" lacks \"" << part_ << "\"";                \
  } while (0)
