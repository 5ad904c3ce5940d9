// The cable_sim command-line tool: argument parsing and subcommands, callable as a function so
// that main() stays tiny. ROS-free; uses only the core library.
#pragma once

#include <ostream>

namespace mooring_dynamics {
namespace cli {

/// Tool version; keep in step with <version> in package.xml (test_cli checks it).
inline constexpr const char* kVersion = "0.1.0";

/// Process exit codes (documented in `cable_sim --help` and docs/cli.md).
enum ExitCode : int {
  kExitOk = 0,            ///< success
  kExitInternal = 1,      ///< unexpected internal error (a bug: please report it)
  kExitUsage = 2,         ///< bad command line (unknown option or subcommand, missing argument)
  kExitBadInput = 3,      ///< problem file unreadable or invalid; the message names the key
  kExitNotConverged = 4,  ///< solver did not converge; results are still written, marked not converged
  kExitIo = 5,            ///< could not write the output files
};

/// Run the tool on argv (argv[0] is the program name). Normal output goes to `out`, diagnostics
/// to `err`. Returns one of ExitCode.
int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace cli
}  // namespace mooring_dynamics
