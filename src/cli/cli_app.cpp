// cable_sim: command-line parsing and subcommands.
//
// Layout: a table of subcommands, each with its option specs and a run function. A generic parser
// turns argv into ParsedArgs (long options with `--name VALUE` or `--name=VALUE`, short `-h`,
// positionals, `--` ends options); help text is generated from the same specs. Adding a
// subcommand (e.g. `dynamic`) means adding one entry to commands() and its run function.
#include "cli_app.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/dynamics2d.hpp"
#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/core/problem_io.hpp"
#include "mooring_dynamics/core/result.hpp"
#include "mooring_dynamics/core/result_io.hpp"
#include "mooring_dynamics/core/statics2d.hpp"
#include "mooring_dynamics/core/time_integration.hpp"

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
       "  4  solver did not converge, or the dynamic run stopped early (results so far are still\n"
       "     written, marked \"converged\": false / \"completed\": false)\n"
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

// ---------------------------------------------------------------------------------------------
// dynamic

double parseFiniteDouble(const std::string& option, const std::string& text, const std::string& what) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError("option '--" + option + "' needs " + what + ", got '" + text + "'");
  return v;
}

std::string fmtNum(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// CSV number: 12 significant digits (well below the solver tolerance), non-finite spelled out.
std::string csvNum(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmtNum("%.12g", v);
}

/// JSON number: the shortest form that reads back exactly; JSON has no NaN/Inf, so those become null.
std::string jsonNum(double v) {
  if (!std::isfinite(v)) return "null";
  for (const char* f : {"%.15g", "%.16g"}) {
    const std::string s = fmtNum(f, v);
    if (std::strtod(s.c_str(), nullptr) == v) return s;
  }
  return fmtNum("%.17g", v);
}

std::string jsonStr(const std::string& s) {
  std::string o = "\"";
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"') o += "\\\"";
    else if (c == '\\') o += "\\\\";
    else if (c == '\n') o += "\\n";
    else if (c == '\t') o += "\\t";
    else if (c < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      o += b;
    } else {
      o += ch;
    }
  }
  return o + "\"";
}

struct Stats {
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;
};

Stats statsOf(const std::vector<double>& v) {
  Stats s;
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(v.size()));  // population standard deviation
  return s;
}

/// One-line progress bar redrawn in place on a terminal (at most ~10 times a second).
class ProgressBar {
 public:
  explicit ProgressBar(std::ostream& err) : err_(err), start_(std::chrono::steady_clock::now()) {}
  void update(double t, double duration) {
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && t < duration && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    const double frac = duration > 0.0 ? std::clamp(t / duration, 0.0, 1.0) : 1.0;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(std::lround(frac * kWidth));
    const double wall = std::chrono::duration<double>(now - start_).count();
    std::string line = "\r[" + std::string(filled, '#') + std::string(kWidth - filled, ' ') + "] " +
                       fmtNum("%3.0f", 100.0 * frac) + "%  t = " + fmtNum("%.1f", t) + " / " +
                       fmtNum("%.1f", duration) + " s";
    if (frac > 0.0 && frac < 1.0) line += "  ETA " + fmtNum("%.0f", wall * (1.0 - frac) / frac) + " s";
    line += "    ";
    err_ << line << std::flush;
  }
  void finish() {
    if (drawn_) err_ << "\n" << std::flush;
  }

 private:
  std::ostream& err_;
  std::chrono::steady_clock::time_point start_, last_;
  bool drawn_ = false;
};

std::string recordLabel(double s) { return fmtNum("%.6g", s); }

void writeTimeseriesCsv(std::ostream& f, const core::DynamicSeries& r) {
  f << "t,top_tension,anchor_tension,top_x,top_z";
  for (double s : r.record_s) {
    const std::string l = recordLabel(s);
    f << ",tension_s" << l << ",x_s" << l << ",z_s" << l;
  }
  f << "\n";
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    f << csvNum(r.t[k]) << "," << csvNum(r.top_tension[k]) << "," << csvNum(r.anchor_tension[k]) << ","
      << csvNum(r.top_x[k]) << "," << csvNum(r.top_z[k]);
    for (std::size_t i = 0; i < r.record_s.size(); ++i)
      f << "," << csvNum(r.node_tension[i][k]) << "," << csvNum(r.node_x[i][k]) << "," << csvNum(r.node_z[i][k]);
    f << "\n";
  }
}

void writeSnapshotsCsv(std::ostream& f, const core::DynamicSeries& r) {
  f << "t,node,s,x,z,tension\n";
  for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
    const auto& nodes = r.snapshots[k].nodes;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      f << csvNum(r.snapshot_t[k]) << "," << j << "," << csvNum(nodes[j].s) << "," << csvNum(nodes[j].x) << ","
        << csvNum(nodes[j].z) << "," << csvNum(nodes[j].tension) << "\n";
  }
}

struct DynamicFigures {
  Stats top;
  double static_top = 0.0;
  double simulated = 0.0;  ///< [s] time reached
  double rtf = 0.0;        ///< simulated time / wall time (inf when the wall time is 0)
};

DynamicFigures figuresOf(const core::DynamicSeries& r) {
  DynamicFigures f;
  f.top = statsOf(r.top_tension);
  f.static_top = r.initial_static.topTension();
  f.simulated = r.t.empty() ? 0.0 : r.t.back() - r.t.front();
  f.rtf = r.wall_seconds > 0.0 ? f.simulated / r.wall_seconds : std::numeric_limits<double>::infinity();
  return f;
}

void writeDynamicSummaryJson(std::ostream& f, const core::Problem& p, const core::DynamicSeries& r,
                             const DynamicFigures& g) {
  const core::DynamicOptions& d = p.dynamics;
  f << "{\n"
    << "  \"problem\": " << jsonStr(p.name) << ",\n"
    << "  \"scheme\": {\"name\": " << jsonStr(d.scheme_name) << ", \"alpha_m\": " << jsonNum(d.scheme.alpha_m)
    << ", \"alpha_k\": " << jsonNum(d.scheme.alpha_k) << ", \"gamma\": " << jsonNum(d.scheme.gamma) << "},\n"
    << "  \"dt\": " << jsonNum(d.dt) << ",\n"
    << "  \"duration\": " << jsonNum(d.duration) << ",\n"
    << "  \"output_interval\": " << jsonNum(d.output_interval > 0.0 ? d.output_interval : d.dt) << ",\n"
    << "  \"completed\": " << (r.completed ? "true" : "false") << ",\n"
    << "  \"message\": " << jsonStr(r.message) << ",\n"
    << "  \"simulated_time\": " << jsonNum(g.simulated) << ",\n"
    << "  \"samples\": " << r.t.size() << ",\n"
    << "  \"top_tension\": {\"mean\": " << jsonNum(g.top.mean) << ", \"std\": " << jsonNum(g.top.std)
    << ", \"min\": " << jsonNum(g.top.min) << ", \"max\": " << jsonNum(g.top.max) << "},\n"
    << "  \"static_top_tension\": " << jsonNum(g.static_top) << ",\n"
    << "  \"steps\": " << r.steps << ",\n"
    << "  \"cuts\": " << r.cuts << ",\n"
    << "  \"newton_iterations\": " << r.newton_iterations << ",\n"
    << "  \"wall_seconds\": " << jsonNum(r.wall_seconds) << ",\n"
    << "  \"real_time_factor\": " << jsonNum(g.rtf) << ",\n"
    << "  \"record_s\": [";
  for (std::size_t i = 0; i < r.record_s.size(); ++i) f << (i ? ", " : "") << jsonNum(r.record_s[i]);
  f << "],\n"
    << "  \"snapshots\": " << r.snapshots.size() << ",\n"
    << "  \"units\": {\"time\": \"s\", \"tension\": \"N\", \"length\": \"m\"}\n"
    << "}\n";
}

std::string dynamicSummaryText(const core::Problem& p, const core::DynamicSeries& r, const DynamicFigures& g) {
  const core::DynamicOptions& d = p.dynamics;
  std::ostringstream o;
  o << (p.name.empty() ? std::string("dynamic run") : p.name) << ": dynamic run "
    << (r.completed ? "completed" : "did NOT complete") << "\n";
  o << "  scheme         " << d.scheme_name << " (alpha_m = " << fmtNum("%.4g", d.scheme.alpha_m)
    << ", alpha_k = " << fmtNum("%.4g", d.scheme.alpha_k) << ", gamma = " << fmtNum("%.4g", d.scheme.gamma) << ")\n";
  o << "  time           " << fmtNum("%g", g.simulated) << " of " << fmtNum("%g", d.duration) << " s, dt "
    << fmtNum("%g", d.dt) << " s, " << r.t.size() << (r.t.size() == 1 ? " sample\n" : " samples\n");
  if (!r.completed && !r.message.empty()) o << "  stopped        " << r.message << "\n";
  o << "  top tension    mean " << fmtNum("%.1f", g.top.mean) << " N, std " << fmtNum("%.1f", g.top.std)
    << " N, min " << fmtNum("%.1f", g.top.min) << " N, max " << fmtNum("%.1f", g.top.max) << " N\n";
  o << "  static top     " << fmtNum("%.1f", g.static_top) << " N\n";
  o << "  solver         " << r.steps << " steps, " << r.cuts << " cuts, " << r.newton_iterations
    << " Newton iterations\n";
  o << "  wall time      " << fmtNum("%.3g", r.wall_seconds) << " s, real-time factor "
    << (std::isfinite(g.rtf) ? fmtNum("%.3g", g.rtf) : std::string("inf")) << "\n";
  return o.str();
}

int runDynamicCmd(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (args.positionals.size() != 1)
    throw UsageError(args.positionals.empty() ? "missing PROBLEM.yaml"
                                              : "expected one problem file, got " +
                                                    std::to_string(args.positionals.size()) + " arguments");
  const std::string problem_path = args.positionals.front();
  const std::string out_dir = args.has("out") ? args.values.at("out") : std::string();
  if (args.has("out") && out_dir.empty()) throw UsageError("option '--out' needs a directory, got ''");
  if (args.has("scheme") && args.has("lambda-inf")) throw UsageError("give --scheme or --lambda-inf, not both");
  double duration = 0.0, dt = 0.0, lambda_inf = 0.0;
  if (args.has("duration")) duration = parsePositiveDouble("duration", args.values.at("duration"));
  if (args.has("dt")) dt = parsePositiveDouble("dt", args.values.at("dt"));
  core::GeneralizedAlpha scheme;
  if (args.has("scheme")) {
    try {
      scheme = core::GeneralizedAlpha::preset(args.values.at("scheme"));
    } catch (const std::invalid_argument&) {
      throw UsageError("option '--scheme' needs one of box, trapezoidal, backward, lambda0, lambda-0.5, lambda0.75; got '" +
                       args.values.at("scheme") + "'");
    }
  }
  if (args.has("lambda-inf")) {
    lambda_inf = parseFiniteDouble("lambda-inf", args.values.at("lambda-inf"), "a number in [-1, 1)");
    if (!(lambda_inf >= -1.0 && lambda_inf < 1.0))
      throw UsageError("option '--lambda-inf' needs a number in [-1, 1), got '" + args.values.at("lambda-inf") + "'");
  }

  core::Problem problem;
  try {
    problem = core::loadProblemFromFile(problem_path);
  } catch (const core::ProblemError& e) {
    err << kProg << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
    return kExitBadInput;
  }

  // Command-line overrides of the file's dynamics section.
  core::DynamicOptions& dyn = problem.dynamics;
  if (args.has("duration")) dyn.duration = duration;
  if (args.has("dt")) dyn.dt = dt;
  if (args.has("scheme")) {
    dyn.scheme = scheme;
    dyn.scheme_name = args.values.at("scheme");
  }
  if (args.has("lambda-inf")) {
    dyn.scheme = core::GeneralizedAlpha::fromLambdaInf(lambda_inf);
    dyn.scheme_name = "lambda_inf=" + fmtNum("%.10g", lambda_inf);
  }
  if (!(dyn.duration > 0.0)) {
    err << kProg << ": error: " << problem_path
        << ": dynamics.duration: not given; a dynamic run needs the simulated time [s]: add a section\n"
           "  dynamics: {duration: 60, dt: 0.1}\n"
           "to the problem file (see docs/problem_format.md) or pass --duration S\n";
    return kExitBadInput;
  }
  const std::string invalid = problem.validate();
  if (!invalid.empty()) {
    err << kProg << ": error: " << problem_path << ": " << invalid
        << (args.has("dt") || args.has("duration") ? " (after the command-line overrides)" : "") << "\n";
    return kExitBadInput;
  }

  // Run.
  const bool show_progress = !args.has("no-progress") && ::isatty(STDERR_FILENO) == 1;
  ProgressBar bar(err);
  std::function<void(double, double)> progress;
  if (show_progress) progress = [&bar](double t, double total) { bar.update(t, total); };
  core::DynamicSeries series;
  try {
    series = core::runDynamic(problem, progress);
  } catch (const std::invalid_argument& e) {
    bar.finish();
    err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    bar.finish();
    err << kProg << ": error: " << problem_path << ": the dynamic run could not start: " << e.what() << "\n";
    return kExitNotConverged;
  }
  bar.finish();

  const DynamicFigures fig = figuresOf(series);
  out << dynamicSummaryText(problem, series, fig);

  // Outputs (also when the run stopped early: everything up to the failure).
  if (!out_dir.empty()) {
    const fs::path dir(out_dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir, ec)) {
      err << kProg << ": error: cannot create output directory '" << out_dir << "'"
          << (ec ? " (" + ec.message() + ")" : std::string(" (exists and is not a directory)")) << "\n";
      return kExitIo;
    }
    std::vector<fs::path> written;
    const fs::path ts = dir / "timeseries.csv";
    if (!writeFile(ts, [&](std::ostream& f) { writeTimeseriesCsv(f, series); }, err)) return kExitIo;
    written.push_back(ts);
    const fs::path snaps = dir / "snapshots.csv";
    if (!series.snapshots.empty()) {
      if (!writeFile(snaps, [&](std::ostream& f) { writeSnapshotsCsv(f, series); }, err)) return kExitIo;
      written.push_back(snaps);
    } else {
      fs::remove(snaps, ec);  // never leave a stale file from an earlier run next to new results
    }
    const fs::path stat = dir / "static_nodes.csv";
    if (!writeFile(stat, [&](std::ostream& f) { core::writeStaticCsv(f, series.initial_static); }, err))
      return kExitIo;
    written.push_back(stat);
    const fs::path js = dir / "dynamic_summary.json";
    if (!writeFile(js, [&](std::ostream& f) { writeDynamicSummaryJson(f, problem, series, fig); }, err))
      return kExitIo;
    written.push_back(js);
    out << "wrote";
    for (std::size_t i = 0; i < written.size(); ++i)
      out << (i == 0 ? " " : i + 1 == written.size() ? " and " : ", ") << written[i].string();
    out << "\n";
  }

  if (!series.completed) {
    err << kProg << ": error: the dynamic run stopped at t = " << fmtNum("%g", fig.simulated) << " s of "
        << fmtNum("%g", problem.dynamics.duration) << " s";
    if (!series.message.empty()) err << " (" << series.message << ")";
    err << (out_dir.empty() ? "" : "; results up to that time written, marked \"completed\": false") << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

// ---------------------------------------------------------------------------------------------
// plot

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// A CSV file with a header: column names and rows of numbers.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;

  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

/// Read `path`; on failure returns false with `why` set. Every named column must be present.
bool readCsv(const fs::path& path, const std::vector<std::string>& required, CsvTable& t, std::string& why) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    why = "cannot read '" + path.string() + "'";
    return false;
  }
  std::string line;
  if (!std::getline(f, line)) {
    why = "'" + path.string() + "' is empty";
    return false;
  }
  t.header = splitCsv(line);
  for (const auto& c : required)
    if (t.column(c) < 0) {
      why = "'" + path.string() + "': no column '" + c + "' in the header";
      return false;
    }
  std::size_t lineno = 1;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = splitCsv(line);
    if (cells.size() != t.header.size()) {
      why = "'" + path.string() + "' line " + std::to_string(lineno) + ": " + std::to_string(cells.size()) +
            " values, the header has " + std::to_string(t.header.size());
      return false;
    }
    std::vector<double> row;
    for (const auto& c : cells) {
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      if (c.empty() || *end != '\0') {
        why = "'" + path.string() + "' line " + std::to_string(lineno) + ": '" + c + "' is not a number";
        return false;
      }
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
  }
  if (t.rows.empty()) {
    why = "'" + path.string() + "' has no data rows";
    return false;
  }
  return true;
}

/// A double-quoted gnuplot string (backslash escapes are processed in double quotes).
std::string gpString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

/// Value of `"key": ...` in our own dynamic_summary.json (flat, as written above); empty if absent.
std::string jsonField(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const auto p = json.find(k);
  if (p == std::string::npos) return "";
  std::size_t i = p + k.size();
  if (i < json.size() && json[i] == '"') {
    std::string v;
    for (++i; i < json.size() && json[i] != '"'; ++i) {
      if (json[i] == '\\' && i + 1 < json.size()) {
        ++i;
        v += json[i] == 'n' ? '\n' : json[i] == 't' ? '\t' : json[i];
      } else {
        v += json[i];
      }
    }
    return v;
  }
  const auto e = json.find_first_of(",}\n", i);
  return json.substr(i, e == std::string::npos ? std::string::npos : e - i);
}

/// Colours from dark blue through teal to yellow (viridis-like), f in [0, 1].
std::string rampColour(double f) {
  static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  f = std::clamp(f, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(f));
  const double w = f - i;
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(stops[i][0] + w * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + w * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + w * (stops[i + 1][2] - stops[i][2]))));
  return buf;
}

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

constexpr std::size_t kMaxShapes = 8;  ///< snapshot times drawn in shapes.png

int runPlot(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (args.positionals.size() != 1)
    throw UsageError(args.positionals.empty() ? "missing DIR (the --out directory of 'dynamic')"
                                              : "expected one directory, got " +
                                                    std::to_string(args.positionals.size()) + " arguments");
  const fs::path dir(args.positionals.front());
  const std::string png_arg = args.has("out") ? args.values.at("out") : std::string();
  if (args.has("out") && png_arg.empty()) throw UsageError("option '--out' needs a directory, got ''");
  const fs::path png_dir = png_arg.empty() ? dir : fs::path(png_arg);

  // Inputs.
  std::string why;
  CsvTable ts;
  if (!readCsv(dir / "timeseries.csv", {"t", "top_tension"}, ts, why)) {
    err << kProg << ": error: " << why << " (run 'cable_sim dynamic PROBLEM.yaml --out " << dir.string()
        << "' first)\n";
    return kExitBadInput;
  }
  CsvTable snaps, stat;
  const bool have_snaps = fs::exists(dir / "snapshots.csv");
  if (have_snaps && !readCsv(dir / "snapshots.csv", {"t", "x", "z"}, snaps, why)) {
    err << kProg << ": error: " << why << "\n";
    return kExitBadInput;
  }
  const bool have_static = fs::exists(dir / "static_nodes.csv");
  if (have_static && !readCsv(dir / "static_nodes.csv", {"x", "z"}, stat, why)) {
    err << kProg << ": error: " << why << "\n";
    return kExitBadInput;
  }
  std::string summary;
  {
    std::ifstream f(dir / "dynamic_summary.json", std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    summary = ss.str();
  }
  std::string name = jsonField(summary, "problem");
  if (name.empty()) name = fs::absolute(dir).lexically_normal().filename().string();
  const std::string scheme = jsonField(summary, "name");
  const std::string dt = jsonField(summary, "dt");
  const bool stopped = jsonField(summary, "completed") == "false";
  const std::string static_top = jsonField(summary, "static_top_tension");

  if (!gnuplotAvailable()) {
    err << kProg << ": error: gnuplot not found; install it with scripts/setup (Debian package gnuplot-nox)\n";
    return kExitIo;
  }
  std::error_code ec;
  fs::create_directories(png_dir, ec);
  if (ec || !fs::is_directory(png_dir, ec)) {
    err << kProg << ": error: cannot create output directory '" << png_dir.string() << "'"
        << (ec ? " (" + ec.message() + ")" : std::string(" (exists and is not a directory)")) << "\n";
    return kExitIo;
  }

  // Tension in kN when large.
  const int tcol = ts.column("t"), Tcol = ts.column("top_tension");
  double tmax = 0.0;
  for (const auto& r : ts.rows) tmax = std::max(tmax, std::fabs(r[Tcol]));
  const bool kilo = tmax >= 1.0e4;
  const double scale = kilo ? 1.0e-3 : 1.0;
  const std::string tunit = kilo ? "kN" : "N";

  // Which snapshot times to draw: up to kMaxShapes, evenly spread, first and last included.
  std::vector<double> times;
  if (have_snaps) {
    const int c = snaps.column("t");
    for (const auto& r : snaps.rows)
      if (times.empty() || r[c] != times.back()) times.push_back(r[c]);
  }
  std::vector<double> chosen;
  if (times.size() <= kMaxShapes) {
    chosen = times;
  } else {
    for (std::size_t i = 0; i < kMaxShapes; ++i)
      chosen.push_back(times[(i * (times.size() - 1) + (kMaxShapes - 1) / 2) / (kMaxShapes - 1)]);
  }
  const bool want_shapes = !chosen.empty() || have_static;

  const fs::path tension_png = png_dir / "top_tension.png";
  const fs::path shapes_png = png_dir / "shapes.png";
  const fs::path script = png_dir / "plot.gp";
  std::ostringstream gp;
  gp << "# gnuplot script written by 'cable_sim plot' (run: gnuplot plot.gp)\n"
     << "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
     << "  set terminal pngcairo noenhanced size 1100,650 font \"sans,12\"\n"
     << "} else {\n"
     << "  set terminal png noenhanced size 1100,650\n"
     << "}\n"
     << "set grid lc rgb \"#d0d0d0\"\n"
     << "set key top right box opaque\n\n";

  // Top tension.
  gp << "$tension << EOD\n";
  for (const auto& r : ts.rows) gp << csvNum(r[tcol]) << " " << csvNum(r[Tcol] * scale) << "\n";
  gp << "EOD\n";
  std::string title = name + ": top tension";
  if (!scheme.empty()) title += " (scheme " + scheme + (dt.empty() ? "" : ", dt = " + dt + " s") + ")";
  gp << "set output " << gpString(tension_png.string()) << "\n"
     << "set title " << gpString(title) << "\n"
     << "set xlabel \"time t [s]\"\n"
     << "set ylabel " << gpString("top tension [" + tunit + "]") << "\n";
  if (stopped)
    gp << "set label 1 \"run stopped early (did not complete)\" at graph 0.02, graph 0.95 tc rgb \"#c00000\"\n";
  gp << "plot $tension using 1:2 with lines lw 2 lc rgb \"#1f4e9c\" title \"top tension\"";
  char* end = nullptr;
  const double st = std::strtod(static_top.c_str(), &end);
  if (!static_top.empty() && *end == '\0' && std::isfinite(st))
    gp << ", " << csvNum(st * scale) << " with lines dt 2 lw 1.5 lc rgb \"#555555\" title \"static\"";
  gp << "\nunset label 1\n\n";

  // Line shapes.
  if (want_shapes) {
    std::vector<std::string> curves;
    if (have_static) {
      const int xc = stat.column("x"), zc = stat.column("z");
      gp << "$static << EOD\n";
      for (const auto& r : stat.rows) gp << csvNum(r[xc]) << " " << csvNum(r[zc]) << "\n";
      gp << "EOD\n";
      curves.push_back("$static using 1:2 with lines dt 2 lw 2.5 lc rgb \"#000000\" title \"static\"");
    }
    const int tc = snaps.column("t"), xc = snaps.column("x"), zc = snaps.column("z");
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      gp << "$shape" << k << " << EOD\n";
      for (const auto& r : snaps.rows)
        if (r[tc] == chosen[k]) gp << csvNum(r[xc]) << " " << csvNum(r[zc]) << "\n";
      gp << "EOD\n";
      const double f = chosen.size() > 1 ? static_cast<double>(k) / static_cast<double>(chosen.size() - 1) : 0.0;
      curves.push_back("$shape" + std::to_string(k) + " using 1:2 with lines lw 1.8 lc rgb \"" + rampColour(f) +
                       "\" title " + gpString("t = " + fmtNum("%g", chosen[k]) + " s"));
    }
    gp << "set output " << gpString(shapes_png.string()) << "\n"
       << "set title " << gpString(name + ": line shape" + (chosen.empty() ? " (static)" : " at snapshot times")) << "\n"
       << "set xlabel \"x [m]\"\n"
       << "set ylabel \"z [m]  (z = 0: mean sea surface)\"\n"
       << "set key outside right top box\n"
       << "set arrow 1 from graph 0, first 0 to graph 1, first 0 nohead lc rgb \"#4a90d9\" dt 3\n"
       << "plot ";
    for (std::size_t i = 0; i < curves.size(); ++i) gp << (i ? ", \\\n     " : "") << curves[i];
    gp << "\n";
  }

  if (!writeFile(script, [&](std::ostream& f) { f << gp.str(); }, err)) return kExitIo;
  const fs::path log = png_dir / "plot.log";
  const std::string cmd = "gnuplot " + shellQuote(script.string()) + " >" + shellQuote(log.string()) + " 2>&1";
  const int rc = std::system(cmd.c_str());
  std::string log_text;
  {
    std::ifstream f(log, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    log_text = ss.str();
  }
  if (rc != 0 || !fs::exists(tension_png) || (want_shapes && !fs::exists(shapes_png))) {
    err << kProg << ": error: gnuplot failed on " << script.string() << ":\n" << log_text;
    return kExitIo;
  }
  fs::remove(log, ec);
  out << "wrote " << tension_png.string();
  if (want_shapes) out << " and " << shapes_png.string();
  out << " (gnuplot script: " << script.string() << ")\n";
  if (!want_shapes)
    out << "no snapshots.csv or static_nodes.csv in " << dir.string()
        << ": shapes.png not drawn (set dynamics.snapshot_interval)\n";
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
      {"dynamic", "PROBLEM.yaml [--out DIR] [--duration S] [--dt S] [--scheme NAME | --lambda-inf X] [--no-progress]",
       "time-domain simulation of a problem file",
       "Run the time-domain simulation of PROBLEM.yaml (section dynamics:, see docs/problem_format.md):\n"
       "start from the static solution, move the top end as dynamics.top_motion says and integrate with\n"
       "the generalized-alpha method. Prints a summary: scheme, top tension mean/std/min/max, steps,\n"
       "cuts, Newton iterations, wall time and real-time factor. With --out, write\n"
       "  DIR/timeseries.csv        t,top_tension,anchor_tension,top_x,top_z, then tension_s<S>,x_s<S>,z_s<S>\n"
       "                            for every dynamics.record_s node (one row per output sample)\n"
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
