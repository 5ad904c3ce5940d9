// libFuzzer target (issue 22): YAML text in, a validated Problem or a ProblemError out. Anything
// else (another exception, a crash, a leak, undefined behaviour, a hang) is a finding.
// Built and run by scripts/fuzz (clang++ -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"

namespace {
/// Inputs beyond this are cut: problem files are a few kB; larger inputs only slow the search.
constexpr std::size_t kMaxInputBytes = 64 * 1024;
/// Files the text names (seabed grids) resolve here: a directory that does not exist.
constexpr const char* kBaseDir = "/nonexistent/md_fuzz";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInputBytes) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mooring_dynamics::core::Problem p = mooring_dynamics::core::loadProblemFromString(text, kBaseDir);
    // A loaded problem is valid: validate() again must agree.
    if (!p.validate().empty()) __builtin_trap();
  } catch (const mooring_dynamics::core::ProblemError&) {
  }
  return 0;
}
