// libFuzzer target (issue 22): the system loader, YAML text in, a validated SystemProblem or a
// ProblemError out. Built and run by scripts/fuzz.
#include <cstddef>
#include <cstdint>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/system.hpp"

namespace {
constexpr std::size_t kMaxInputBytes = 64 * 1024;  ///< as fuzz_problem.cpp
constexpr const char* kBaseDir = "/nonexistent/md_fuzz";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInputBytes) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)mooring_dynamics::core::isSystemText(text);  // must not throw
  try {
    const mooring_dynamics::core::SystemProblem s = mooring_dynamics::core::loadSystemFromString(text, kBaseDir);
    if (!s.validate().empty()) __builtin_trap();
  } catch (const mooring_dynamics::core::ProblemError&) {
  }
  return 0;
}
