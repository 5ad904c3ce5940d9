// Internal to cable_sim (not installed): what the parser in cli_app.cpp and the subcommands in
// cmd_static.cpp, cmd_dynamic.cpp and cmd_plot.cpp share. Exit codes are in cli_app.hpp.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/system.hpp"

#include "cli_app.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace fs = std::filesystem;

inline constexpr const char* kProg = "cable_sim";

/// A command-line mistake: reported with a hint to --help, exit code 2.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& what) : std::runtime_error(what) {}
};

// ---------------------------------------------------------------------------------------------
// Parsed command line (filled by the parser in cli_app.cpp)

struct OptionSpec {
  const char* name;     ///< long name without the leading "--"
  char short_name;      ///< single-letter alias, 0 if none
  const char* metavar;  ///< placeholder of the value; nullptr for a flag without value
  const char* help;
};

struct ParsedArgs {
  std::map<std::string, std::string> values;  ///< options with a value (the last one given wins)
  std::map<std::string, std::vector<std::string>> all_values;  ///< every value of each option, in order (repeatable options)
  std::set<std::string> flags;                ///< flags and options that were given
  std::vector<std::string> positionals;

  bool has(const std::string& name) const { return flags.count(name) != 0; }
};

// ---------------------------------------------------------------------------------------------
// Option values (cli_app.cpp); each throws UsageError naming the option on a malformed value

double parsePositiveDouble(const std::string& option, const std::string& text);
std::size_t parsePositiveInt(const std::string& option, const std::string& text);
double parseFiniteDouble(const std::string& option, const std::string& text, const std::string& what);

// ---------------------------------------------------------------------------------------------
// Number formatting (cli_app.cpp)

/// printf-style formatting of one number.
std::string fmtNum(const char* f, double v);
/// CSV number: 12 significant digits (well below the solver tolerance), non-finite spelled out.
std::string csvNum(double v);

// ---------------------------------------------------------------------------------------------
// gnuplot (gnuplot.cpp)

/// A single-quoted shell word.
std::string shellQuote(const std::string& s);
/// A double-quoted gnuplot string (backslash escapes are processed in double quotes).
std::string gpString(const std::string& s);
/// gnuplot is on PATH.
bool gnuplotAvailable();
/// Write `script` to dir/name.gp and run gnuplot on it; false with gnuplot's log on err (also
/// when gnuplot is not installed).
bool runGnuplot(const fs::path& dir, const std::string& name, const std::string& script, std::ostream& err);

// ---------------------------------------------------------------------------------------------
// Output files

/// Create the output directory `dir` (and its parents); false, with the message on err, when that fails.
bool makeOutputDir(const fs::path& dir, std::ostream& err);

/// Write `what` to `path` with `writer`; false (and a message on err) on any I/O failure.
template <class Writer>
bool writeFile(const fs::path& path, Writer writer, std::ostream& err) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) {
    err << kProg << ": error: cannot open '" << path.string() << "' for writing\n";
    return false;
  }
  writer(f);
  f.flush();
  f.close();
  if (f.fail()) {
    err << kProg << ": error: failed writing '" << path.string() << "'\n";
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Subcommands: run functions of the table in cli_app.cpp. UsageError for command-line mistakes,
// otherwise one of ExitCode.

int runStatic(const ParsedArgs& args, std::ostream& out, std::ostream& err);      // cmd_static.cpp
int runDynamicCmd(const ParsedArgs& args, std::ostream& out, std::ostream& err);  // cmd_dynamic.cpp
int runPlot(const ParsedArgs& args, std::ostream& out, std::ostream& err);        // cmd_plot.cpp
int runStiffness(const ParsedArgs& args, std::ostream& out, std::ostream& err);   // cmd_vessel.cpp
int runOffset(const ParsedArgs& args, std::ostream& out, std::ostream& err);      // cmd_vessel.cpp
int runSweep(const ParsedArgs& args, std::ostream& out, std::ostream& err);       // cmd_sweep.cpp
int runStormMotion(const ParsedArgs& args, std::ostream& out, std::ostream& err);  // cmd_storm_motion.cpp
/// `static` on a system file (points and lines), cmd_system.cpp.
int runSystemStatic(const std::string& path, bool want_table, std::size_t stride, double spacing_scale,
                    const std::string& out_dir, std::ostream& out, std::ostream& err);
/// `dynamic` on a file with a vessel (cmd_vessel.cpp): the vessel follows vessel.motion_table
/// (or holds still) through core::VesselLockstep, the lines on `threads` threads.
/// dynamic_summary.json of a system or vessel run: the keys of a single line's summary that apply.
struct RunSummary {
  std::string problem, kind;  ///< kind: "system" or "vessel"
  bool completed = false;
  std::string message;        ///< why the run stopped ("" when completed)
  double simulated_time = 0.0, duration = 0.0, wall_seconds = 0.0;
  std::size_t samples = 0;
  std::string timeseries;     ///< the CSV file written
  std::vector<core::LineEventRecord> events;  ///< line events that happened (releases, breaks)
  /// Fallback steps of each line (docs/method.md "Slack and snap"), by line name, in line order.
  std::vector<std::pair<std::string, long>> fallback_steps;
};
/// "fallback steps: 3 on bow_port_2, 1 on stern_stbd_1" (lines with none left out), or "" when
/// no line fell back.
std::string fallbackStepsText(const std::vector<std::pair<std::string, long>>& per_line);
void writeRunSummaryJson(std::ostream& f, const RunSummary& s);  // cmd_system.cpp

/// The "events" array of a dynamic_summary.json, without the key (cmd_dynamic.cpp).
std::string lineEventsJson(const std::vector<core::LineEventRecord>& events);

int runVesselDynamic(const core::SystemProblem& s, int threads, const std::string& out_dir, std::ostream& out,
                     std::ostream& err);
/// `dynamic` on a system file, cmd_system.cpp: `overrides` applies the command-line options.
int runSystemDynamic(const std::string& path, const std::function<void(core::DynamicOptions&)>& overrides,
                     const std::string& out_dir, std::ostream& out, std::ostream& err);

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
