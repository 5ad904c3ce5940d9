// cable_sim: command-line parsing and subcommands.
//
// Layout: a table of subcommands, each with its option specs and a run function. A generic parser
// turns argv into ParsedArgs (long options with `--name VALUE` or `--name=VALUE`, short `-h`,
// positionals, `--` ends options); help text is generated from the same specs. Adding a
// subcommand (e.g. `dynamic`) means adding one entry to commands() and its run function.
#include "cli_app.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/core/problem_io.hpp"
#include "mooring_dynamics/core/result.hpp"
#include "mooring_dynamics/core/result_io.hpp"
#include "mooring_dynamics/core/statics2d.hpp"

namespace mooring_dynamics {
namespace cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kProg = "cable_sim";

/// Upper bound on the node count a --spacing-scale may produce (guards against typos like 1e-9).
constexpr double kMaxScaledNodes = 1.0e7;

/// A command-line mistake: reported with a hint to --help, exit code 2.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& what) : std::runtime_error(what) {}
};

// ---------------------------------------------------------------------------------------------
// Generic option parsing

struct OptionSpec {
  const char* name;     ///< long name without the leading "--"
  char short_name;      ///< single-letter alias, 0 if none
  const char* metavar;  ///< placeholder of the value; nullptr for a flag without value
  const char* help;
};

struct ParsedArgs {
  std::map<std::string, std::string> values;  ///< options with a value (the last one given wins)
  std::set<std::string> flags;                ///< flags and options that were given
  std::vector<std::string> positionals;

  bool has(const std::string& name) const { return flags.count(name) != 0; }
};

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
    p.flags.insert(name);
  }
  return p;
}

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
       "  4  solver did not converge (results are still written, marked \"converged\": false)\n"
       "  5  I/O error writing the output files\n";
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
  for (const auto& c : commands()) {
    std::string left = std::string("  ") + c.name;
    left.resize(12, ' ');
    o << left << c.summary << "\n";
  }
  o << "  help      help on a command, e.g. '" << kProg << " help static'\n\n"
    << "Run '" << kProg << " <command> --help' for the options of a command.\n\n";
  printExitCodes(o);
}

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

  // Refinement studies: scale every segment's node spacing.
  if (spacing_scale != 1.0) {
    double nodes = 1.0;
    for (auto& seg : problem.segments) {
      seg.spacing *= spacing_scale;
      if (seg.spacing > 0.0) nodes += std::ceil(seg.length / seg.spacing);
    }
    if (nodes > kMaxScaledNodes)
      throw UsageError("--spacing-scale " + args.values.at("spacing-scale") + " gives about " +
                       std::to_string(static_cast<long long>(nodes)) + " nodes (limit " +
                       std::to_string(static_cast<long long>(kMaxScaledNodes)) + ")");
  }

  // Solve.
  core::StaticResult result;
  try {
    result = core::solveStatic(problem);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
    return kExitBadInput;
  }

  out << core::staticSummaryText(problem, result);
  if (want_table) out << "\n" << core::staticTableText(result, stride);

  // Outputs (written also when the solver did not converge: the JSON says so).
  if (!out_dir.empty()) {
    const fs::path dir(out_dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir, ec)) {
      err << kProg << ": error: cannot create output directory '" << out_dir << "'"
          << (ec ? " (" + ec.message() + ")" : std::string(" (exists and is not a directory)")) << "\n";
      return kExitIo;
    }
    const fs::path json = dir / "static.json";
    const fs::path csv = dir / "static_nodes.csv";
    if (!writeFile(json, [&](std::ostream& f) { core::writeStaticJson(f, problem, result); }, err)) return kExitIo;
    if (!writeFile(csv, [&](std::ostream& f) { core::writeStaticCsv(f, result); }, err)) return kExitIo;
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
      {"dynamic", "PROBLEM.yaml [options]", "time-domain simulation (not yet implemented)",
       "Time-domain simulation (generalized-alpha). Not yet implemented.",
       {{"help", 'h', nullptr, "show this help"}},
       nullptr},
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
      err << kProg << ": '" << cmd->name << "' is not yet implemented (see README.md, Status)\n";
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
