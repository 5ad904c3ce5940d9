// cable_sim: command-line parsing and subcommands.
//
// Layout: a table of subcommands, each with its option specs and a run function. A generic parser
// turns argv into ParsedArgs (long options with `--name VALUE` or `--name=VALUE`, short `-h`,
// positionals, `--` ends options); help text is generated from the same specs. Adding a
// subcommand means adding one entry to commands() and its run function.
//
// Files: this one holds the parser, the help text, the subcommand table and the shared helpers
// declared in cli_common.hpp; each subcommand's run function is in its own file (cmd_static.cpp,
// cmd_dynamic.cpp, cmd_plot.cpp).
#include "cli_app.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <ostream>
#include <string>
#include <vector>

#include "cli_common.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

// ---------------------------------------------------------------------------------------------
// Option values

double parsePositiveDouble(const std::string& option, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || !(v > 0.0))
    throw UsageError("option '--" + option + "' needs a finite number > 0, got '" + text + "'");
  return v;
}

std::size_t parsePositiveInt(const std::string& option, const std::string& text) {
  const std::string msg = "option '--" + option + "' needs an integer >= 1, got '" + text + "'";
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) throw UsageError(msg);
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || v < 1) throw UsageError(msg);
  return static_cast<std::size_t>(v);
}

double parseFiniteDouble(const std::string& option, const std::string& text, const std::string& what) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError("option '--" + option + "' needs " + what + ", got '" + text + "'");
  return v;
}

// ---------------------------------------------------------------------------------------------
// Number formatting

std::string fmtNum(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// CSV number: 12 significant digits (well below the solver tolerance), non-finite spelled out.
std::string csvNum(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  // std::to_chars is printf's %.12g (C locale), without printf's cost per number (a run writes
  // millions of them).
  char buf[32];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

// ---------------------------------------------------------------------------------------------
// Output files

bool makeOutputDir(const fs::path& dir, std::ostream& err) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) {
    err << kProg << ": error: cannot create output directory '" << dir.string() << "'"
        << (ec ? " (" + ec.message() + ")" : std::string(" (exists and is not a directory)")) << "\n";
    return false;
  }
  return true;
}

}  // namespace detail

using namespace detail;

namespace {

// ---------------------------------------------------------------------------------------------
// Generic option parsing

const OptionSpec* findLong(const std::vector<OptionSpec>& specs, const std::string& name) {
  for (const auto& s : specs)
    if (name == s.name) return &s;
  return nullptr;
}

const OptionSpec* findShort(const std::vector<OptionSpec>& specs, char c) {
  for (const auto& s : specs)
    if (s.short_name != 0 && s.short_name == c) return &s;
  return nullptr;
}

/// Parse argv[first, argc) against `specs`. `context` names the command in messages.
ParsedArgs parseOptions(int argc, const char* const* argv, int first, const std::vector<OptionSpec>& specs,
                        const std::string& context) {
  ParsedArgs p;
  bool options_done = false;
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    if (options_done || a.size() < 2 || a[0] != '-') {  // "-" alone is a positional (stdin-style name)
      p.positionals.push_back(a);
      continue;
    }
    if (a == "--") {
      options_done = true;
      continue;
    }
    const OptionSpec* spec = nullptr;
    std::string shown;  // how the user spelled the option
    std::string inline_value;
    bool has_inline = false;
    if (a[1] == '-') {
      std::string name = a.substr(2);
      const auto eq = name.find('=');
      if (eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        has_inline = true;
        name = name.substr(0, eq);
      }
      shown = "--" + name;
      spec = findLong(specs, name);
    } else {
      if (a.size() != 2) throw UsageError("unknown option '" + a + "' for " + context);
      shown = a;
      spec = findShort(specs, a[1]);
    }
    if (spec == nullptr) throw UsageError("unknown option '" + shown + "' for " + context);
    const std::string name = spec->name;
    if (spec->metavar == nullptr) {
      if (has_inline) throw UsageError("option '" + shown + "' takes no value");
      p.flags.insert(name);
      continue;
    }
    if (has_inline) {
      p.values[name] = inline_value;
    } else {
      if (i + 1 >= argc) throw UsageError("option '" + shown + "' needs a value " + spec->metavar);
      p.values[name] = argv[++i];
    }
    p.all_values[name].push_back(p.values[name]);
    p.flags.insert(name);
  }
  return p;
}

// ---------------------------------------------------------------------------------------------
// Help text

void printOptions(std::ostream& o, const std::vector<OptionSpec>& specs) {
  o << "Options:\n";
  for (const auto& s : specs) {
    std::string left = "  ";
    if (s.short_name != 0) left += std::string("-") + s.short_name + ", ";
    left += std::string("--") + s.name;
    if (s.metavar != nullptr) left += std::string(" ") + s.metavar;
    if (left.size() < 24) left.resize(24, ' ');
    else left += "\n" + std::string(24, ' ');
    o << left << s.help << "\n";
  }
}

void printExitCodes(std::ostream& o) {
  o << "Exit codes:\n"
       "  0  success\n"
       "  1  internal error (a bug; please report it)\n"
       "  2  usage error: unknown command or option, missing or malformed argument\n"
       "  3  bad input: problem file unreadable or invalid (the message names the key)\n"
       "  4  solver did not converge, or the dynamic run stopped early (results so far are still\n"
       "     written, marked \"converged\": false / \"completed\": false); sweep: a case failed or\n"
       "     was not run (DIR/status.csv)\n"
       "  5  I/O error writing the output files (plot: also gnuplot missing or failing)\n";
}

// ---------------------------------------------------------------------------------------------
// Subcommands

using RunFn = int (*)(const ParsedArgs&, std::ostream&, std::ostream&);

struct Command {
  const char* name;
  const char* synopsis;     ///< arguments after the command name
  const char* summary;      ///< one line for the command list
  const char* description;  ///< paragraph for the command's help
  std::vector<OptionSpec> options;
  RunFn run;                ///< nullptr: not implemented yet
};

const std::vector<Command>& commands();

void printCommandHelp(std::ostream& o, const Command& c) {
  o << "Usage: " << kProg << " " << c.name << " " << c.synopsis << "\n\n" << c.description << "\n\n";
  printOptions(o, c.options);
  o << "\n";
  printExitCodes(o);
}

void printMainHelp(std::ostream& o) {
  o << "Usage: " << kProg << " <command> [options]\n"
    << "       " << kProg << " --help | --version\n\n"
    << "Offline solver for ocean cables (moorings, tethers, towed arrays) with the method of\n"
       "Gobat & Grosenbaugh (WHOI Cable). Problem files are YAML, see docs/problem_format.md.\n\n"
       "Commands:\n";
  std::size_t width = 12;  // the summaries' column: two spaces, the longest name, two spaces
  for (const auto& c : commands()) width = std::max(width, std::string(c.name).size() + 4);
  for (const auto& c : commands()) {
    std::string left = std::string("  ") + c.name;
    left.resize(width, ' ');
    o << left << c.summary << "\n";
  }
  std::string help_left = "  help";
  help_left.resize(width, ' ');
  o << help_left << "help on a command, e.g. '" << kProg << " help static'\n\n"
    << "Run '" << kProg << " <command> --help' for the options of a command.\n\n";
  printExitCodes(o);
}

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"static", "PROBLEM.yaml [--out DIR] [--table [--table-stride N]] [--spacing-scale F]",
       "static equilibrium of a problem file",
       "Solve the static equilibrium of the line described in PROBLEM.yaml (2-D, x-z plane) and print a\n"
       "summary: convergence, top and anchor forces, minimum tension. With --out, write\n"
       "  DIR/static.json        problem name, solver summary, end forces, per-node arrays (SI units)\n"
       "  DIR/static_nodes.csv   node,s,x,z,tension,shear,angle_deg,curvature,strain,segment",
       {
           {"out", 0, "DIR", "write DIR/static.json and DIR/static_nodes.csv (DIR is created)"},
           {"table", 0, nullptr, "print the node table: node, s, x, z, tension"},
           {"table-stride", 0, "N", "print every N-th node (and the last); implies --table"},
           {"spacing-scale", 0, "F", "multiply every segment's node spacing by F > 0 (refinement studies)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runStatic},
      {"dynamic", "PROBLEM.yaml [--out DIR] [--duration S] [--dt S] [--scheme NAME | --lambda-inf X] [--threads N] [--no-progress]",
       "time-domain simulation of a problem file",
       "Run the time-domain simulation of PROBLEM.yaml (section dynamics:, see docs/problem_format.md):\n"
       "start from the static solution, move the top end as dynamics.top_motion says and integrate with\n"
       "the generalized-alpha method. Prints a summary: scheme, top tension mean/std/min/max, steps,\n"
       "cuts, Newton iterations, wall time and real-time factor. With --out, write\n"
       "  DIR/timeseries.csv        t,top_tension,anchor_tension,top_x,top_z, then tension_s<S>,x_s<S>,z_s<S>\n"
       "                            for every dynamics.record_s node (one row per output sample); with\n"
       "                            dynamics.winch, line_length after top_z\n"
       "  DIR/snapshots.csv         t,node,s,x,z,tension (whole line every dynamics.snapshot_interval)\n"
       "  DIR/static_nodes.csv      the static solution the run starts from (as 'static')\n"
       "  DIR/dynamic_summary.json  problem, scheme, dt, duration, completed, message, tension statistics,\n"
       "                            steps, cuts, Newton iterations, wall time, real-time factor\n"
       "If the run stops early (a step that does not converge at the smallest time step), the results\n"
       "up to that time are written and the exit code is 4. Plot them with 'cable_sim plot DIR'.",
       {
           {"out", 0, "DIR", "write the result files into DIR (created)"},
           {"duration", 0, "S", "simulated time [s] (overrides dynamics.duration)"},
           {"dt", 0, "S", "base time step [s] (overrides dynamics.dt)"},
           {"scheme", 0, "NAME", "box, trapezoidal, backward, lambda0, lambda-0.5 or lambda0.75 (paper Table 1)"},
           {"lambda-inf", 0, "X", "generalized-alpha with lambda_inf = X in [-1, 1) (eq. 29)"},
           {"threads", 0, "N", "threads of the solver, 1 or 2 (overrides dynamics.threads; same results)"},
           {"no-progress", 0, nullptr, "no progress bar (shown on stderr only when it is a terminal)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runDynamicCmd},
      {"plot", "DIR [--out PNG_DIR]", "plot the results of 'dynamic' with gnuplot",
       "Render the files 'cable_sim dynamic --out DIR' wrote, with gnuplot (Debian package gnuplot-nox,\n"
       "installed by scripts/setup):\n"
       "  top_tension.png   top tension against time (DIR/timeseries.csv), static value dashed\n"
       "  shapes.png        line shapes z against x at up to 8 snapshot times (DIR/snapshots.csv)\n"
       "                    and the static shape (DIR/static_nodes.csv)\n"
       "The gnuplot script is kept as plot.gp next to the images, for editing.",
       {
           {"out", 0, "PNG_DIR", "write the images into PNG_DIR (created; default DIR)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runPlot},
      {"stiffness", "VESSEL.yaml [--out DIR] [--translation-step M] [--rotation-step-deg D]",
       "6 x 6 mooring stiffness of a moored vessel",
       "Solve the statics of the vessel's lines at the file's pose (vessel.pose) and at a small offset either\n"
       "way along and about each body axis (surge, sway, heave, roll, pitch, yaw), and print the mooring\n"
       "stiffness K = -d(wrench)/d(offset) in body axes about the body origin, with the wrench at the pose.\n"
       "With --out, write DIR/stiffness.csv (rows: force/moment, columns: offset). See\n"
       "docs/problem_format.md, \"Moored vessel\".",
       {
           {"out", 0, "DIR", "write DIR/stiffness.csv (DIR is created)"},
           {"translation-step", 0, "M", "central-difference step of the translations [m] (default 0.1)"},
           {"rotation-step-deg", 0, "D", "central-difference step of the rotations [deg] (default 0.1)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runStiffness},
      {"offset", "VESSEL.yaml [--dof NAME] [--range R] [--steps N] [--out DIR]",
       "offset curve of a moored vessel: restoring force and largest tension",
       "Solve the statics of the vessel's lines with the vessel moved from the file's pose along (surge,\n"
       "sway, heave; R in m, default 20) or about (roll, pitch, yaw; R in deg, default 10) one body axis,\n"
       "at N offsets from -R to R (default 11), and print the restoring force or moment in that axis and\n"
       "the largest line tension with its line. With --out, write DIR/offset.csv (offset, the six wrench\n"
       "components in body axes, largest tension, its line) and DIR/offset.png (gnuplot).",
       {
           {"dof", 0, "NAME", "surge, sway, heave, roll, pitch or yaw (default surge)"},
           {"range", 0, "R", "largest offset either way [m or deg]"},
           {"steps", 0, "N", "number of offsets, >= 2 (default 11)"},
           {"out", 0, "DIR", "write DIR/offset.csv and DIR/offset.png (DIR is created)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runOffset},
      {"sweep", "SWEEP.yaml --out DIR [--jobs N] [--emit gnu-parallel|slurm] [--no-progress] | --collect DIR",
       "load-case sweep: many dynamic runs of variations of one problem",
       "Expand SWEEP.yaml (a base problem, system or vessel file and named variations of its keys: sea\n"
       "states, headings, seeds, a line removed; see docs/design_analysis.md) into one problem file per\n"
       "case, DIR/cases/<case>.yaml, each runnable alone with 'cable_sim dynamic'. Then run the cases on\n"
       "N local processes (default: the number of cores) and summarise them, or with --emit write the\n"
       "job list for GNU parallel (DIR/jobs.txt) or a Slurm job array (DIR/sweep.slurm) instead.\n"
       "Finished cases (DIR/results/<case>/) are skipped when the sweep is started again; a failed case\n"
       "is recorded in DIR/failed/<case>/ (run.log, error.txt) and the others go on. The summary\n"
       "('--collect DIR' after an external run):\n"
       "  DIR/summary.csv   per case and line: max, mean, std of the top tension, MBL, utilization,\n"
       "                    largest horizontal top offset\n"
       "  DIR/storms.csv    per storm (the cases that differ only in their seed) and line: the per-seed\n"
       "                    maxima and their Gumbel fit's most probable maximum\n"
       "  DIR/status.csv    done / failed (with the error) / not run, per case\n"
       "  DIR/utilization_vs_<variation>.png   one curve per line (gnuplot)\n"
       "Exit code 4 when a case failed or was not run.",
       {
           {"out", 0, "DIR", "the sweep's folder (created)"},
           {"jobs", 'j', "N", "cases run at the same time on this machine (default: number of cores)"},
           {"emit", 0, "KIND", "gnu-parallel or slurm: write the job list instead of running"},
           {"collect", 0, "DIR", "summarise the results in DIR (after an external run)"},
           {"run-case", 0, "NAME", "run one case of --out DIR (what the pool, jobs.txt and sweep.slurm call)"},
           {"no-progress", 0, nullptr, "no progress bar (shown on stderr only when it is a terminal)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runSweep},
      {"storm-motion",
       "--hs H --tp T --out FILE.csv [--gamma G] [--heading DEG] [--seed N] [--duration S] [--dt S] [--yaw DEG] "
       "[--offset M] [--offset-heading DEG] [--drift M] [--drift-period S] [--ramp S] [--f-min F] [--f-max F] [--point X,Y,Z ...]",
       "vessel motion table of a moored vessel in an irregular sea",
       "Write a vessel motion table (poses and body twists, the 14 columns of vessel.motion_table:\n"
       "t,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz) of a vessel in a long-crested JONSWAP sea, from an ASSUMED\n"
       "simple response model, not an RAO model: heave follows the surface elevation at the origin, pitch\n"
       "and roll a fraction of the wave slope along and across the hull, the heading is fixed, and the\n"
       "origin sits at a steady offset with a slow sinusoidal drift along it. All motion is ramped in\n"
       "from the still pose (origin (0, 0, 0), heading --yaw) at t = 0, with a zero twist, so that a moored\n"
       "run starts from the statics at that pose. Frames: world x east, y north, z up (REP 103);\n"
       "directions in degrees counterclockwise from +x; body x forward, y left, z up; the twist in body\n"
       "axes. Prints the heave std, the pitch and roll std and largest values (after the ramp) and the\n"
       "largest vertical speed of each --point. See docs/design_analysis.md, \"Storm motion tables\".",
       {
           {"hs", 0, "H", "significant wave height [m] (required)"},
           {"tp", 0, "T", "peak period [s] (required)"},
           {"gamma", 0, "G", "JONSWAP peak enhancement, >= 1 (default 3.3)"},
           {"heading", 0, "DEG", "direction the waves travel toward, ccw from +x east (default 0)"},
           {"seed", 0, "N", "random seed, 0 .. 4294967295 (default 1)"},
           {"duration", 0, "S", "length of the record [s] (default 600)"},
           {"dt", 0, "S", "sample interval [s] (default 0.1)"},
           {"yaw", 0, "DEG", "the hull's fixed heading, ccw from +x (default 0; the file's vessel.pose yaw_deg)"},
           {"offset", 0, "M", "steady horizontal offset of the origin [m] (default 0)"},
           {"offset-heading", 0, "DEG", "direction of the offset, ccw from +x (default 0)"},
           {"drift", 0, "M", "amplitude of the slow drift along the offset's direction [m] (default 0)"},
           {"drift-period", 0, "S", "period of the drift [s] (default 110)"},
           {"ramp", 0, "S", "cosine ramp of all motion from t = 0 [s], > 0 (default 20)"},
           {"components", 0, "N", "wave frequency components, 16 .. 10000 (default 200)"},
           {"f-min", 0, "F", "lowest component frequency as a multiple of 1/Tp, in (0, 1) (default 0.5)"},
           {"f-max", 0, "F", "highest component frequency as a multiple of 1/Tp, > 1 (default 3.5; a hull hardly heaves above 2)"},
           {"heave-gain", 0, "F", "heave per metre of surface elevation (default 1)"},
           {"pitch-gain", 0, "F", "pitch per radian of wave slope along the hull (default 0.45)"},
           {"roll-gain", 0, "F", "roll per radian of wave slope across the hull (default 0.8)"},
           {"point", 0, "X,Y,Z", "a body-frame point [m] (a fairlead) whose largest vertical speed is printed; repeatable"},
           {"out", 0, "FILE.csv", "the motion table to write (required)"},
           {"help", 'h', nullptr, "show this help"},
       },
       &runStormMotion},
  };
  return list;
}

const Command* findCommand(const std::string& name) {
  for (const auto& c : commands())
    if (name == c.name) return &c;
  return nullptr;
}

std::string commandNames() {
  std::string s;
  for (const auto& c : commands()) s += (s.empty() ? "" : ", ") + std::string(c.name);
  return s;
}

}  // namespace

int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  std::string context = kProg;
  std::string help_hint = std::string("'") + kProg + " --help'";
  try {
    if (argc < 2) throw UsageError("missing command (" + commandNames() + ")");
    const std::string first = argv[1];
    if (first == "-h" || first == "--help") {
      printMainHelp(out);
      return kExitOk;
    }
    if (first == "--version") {
      out << kProg << " " << kVersion << "\n";
      return kExitOk;
    }
    if (first == "help") {
      if (argc == 2) {
        printMainHelp(out);
        return kExitOk;
      }
      const Command* c = findCommand(argv[2]);
      if (c == nullptr || argc > 3)
        throw UsageError(std::string("'help' takes one command name (") + commandNames() + ")");
      printCommandHelp(out, *c);
      return kExitOk;
    }
    if (!first.empty() && first[0] == '-') throw UsageError("unknown option '" + first + "'");
    const Command* cmd = findCommand(first);
    if (cmd == nullptr) throw UsageError("unknown command '" + first + "' (known: " + commandNames() + ")");

    context = std::string("'") + cmd->name + "'";
    help_hint = std::string("'") + kProg + " " + cmd->name + " --help'";
    const ParsedArgs args = parseOptions(argc, argv, 2, cmd->options, context);
    if (args.has("help")) {
      printCommandHelp(out, *cmd);
      return kExitOk;
    }
    if (cmd->run == nullptr) {
      err << kProg << ": '" << cmd->name << "' is not yet implemented (see docs/status.md)\n";
      return kExitUsage;
    }
    return cmd->run(args, out, err);
  } catch (const UsageError& e) {
    err << kProg << ": " << e.what() << "\n" << "Try " << help_hint << ".\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    err << kProg << ": internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}

}  // namespace cli
}  // namespace mooring_dynamics
