// cable_sim dynamic: time-domain simulation of a problem file, its summary and result files.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli_common.hpp"
#include "gnss_input.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/io/result_io.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/core/model/time_integration.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {
namespace {

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

/// 3-D runs add the y columns (top_y, y_s<S>; y in the snapshots); a winch the line's length
/// (line_length, after top_z).
void writeTimeseriesCsv(std::ostream& f, const core::DynamicSeries& r, bool three_d) {
  const bool winch = !r.line_length.empty();
  f << (three_d ? "t,top_tension,anchor_tension,top_x,top_y,top_z" : "t,top_tension,anchor_tension,top_x,top_z");
  if (winch) f << ",line_length";
  for (double s : r.record_s) {
    const std::string l = recordLabel(s);
    f << ",tension_s" << l << ",x_s" << l << (three_d ? ",y_s" + l : std::string()) << ",z_s" << l;
  }
  f << "\n";
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    f << csvNum(r.t[k]) << "," << csvNum(r.top_tension[k]) << "," << csvNum(r.anchor_tension[k]) << ","
      << csvNum(r.top_x[k]) << "," << (three_d ? csvNum(r.top_y[k]) + "," : std::string()) << csvNum(r.top_z[k]);
    if (winch) f << "," << csvNum(r.line_length[k]);
    for (std::size_t i = 0; i < r.record_s.size(); ++i)
      f << "," << csvNum(r.node_tension[i][k]) << "," << csvNum(r.node_x[i][k]) << ","
        << (three_d ? csvNum(r.node_y[i][k]) + "," : std::string()) << csvNum(r.node_z[i][k]);
    f << "\n";
  }
}

void writeSnapshotsCsv(std::ostream& f, const core::DynamicSeries& r, bool three_d) {
  f << (three_d ? "t,node,s,x,y,z,tension\n" : "t,node,s,x,z,tension\n");
  for (std::size_t k = 0; k < r.snapshots.size(); ++k) {
    const auto& nodes = r.snapshots[k].nodes;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      f << csvNum(r.snapshot_t[k]) << "," << j << "," << csvNum(nodes[j].s) << "," << csvNum(nodes[j].x) << ","
        << (three_d ? csvNum(nodes[j].y) + "," : std::string()) << csvNum(nodes[j].z) << ","
        << csvNum(nodes[j].tension) << "\n";
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

/// The peak tension and its utilization as a JSON object (utilization null without an mbl).
std::string peakJson(const core::TensionPeak& k) {
  std::string o = "{\"value\": " + jsonNum(k.max_tension) + ", \"s\": " + jsonNum(k.s_max) +
                  ", \"t\": " + jsonNum(k.t_max) + ", \"utilization\": ";
  if (!k.has_mbl) return o + "null}";
  return o + jsonNum(k.utilization) + ", \"mbl\": " + jsonNum(k.mbl) + ", \"material\": " + jsonStr(k.material) +
         ", \"utilization_s\": " + jsonNum(k.s_util) + ", \"utilization_t\": " + jsonNum(k.t_util) + "}";
}

}  // namespace

std::string lineEventsJson(const std::vector<core::LineEventRecord>& events) {
  std::string o = "[";
  for (std::size_t i = 0; i < events.size(); ++i) {
    const core::LineEventRecord& e = events[i];
    o += (i ? ",\n    " : "\n    ") + std::string("{\"t\": ") + jsonNum(e.t) + ", \"what\": " + jsonStr(e.what) +
         (e.line.empty() ? "" : ", \"line\": " + jsonStr(e.line)) + ", \"node\": " + std::to_string(e.node) +
         ", \"s\": " + jsonNum(e.s) + ", \"tension\": " + jsonNum(e.tension) + ", \"cause\": " + jsonStr(e.cause) + "}";
  }
  return o + (events.empty() ? "]" : "\n  ]");
}

namespace {

void writeDynamicSummaryJson(std::ostream& f, const core::Problem& p, const core::DynamicSeries& r,
                             const DynamicFigures& g) {
  const core::DynamicOptions& d = p.dynamics;
  f << "{\n"
    << "  \"problem\": " << jsonStr(p.name) << ",\n"
    << "  \"model\": " << jsonStr(p.formulation == core::Formulation::ThreeD ? "3d" : "2d") << ",\n"
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
    << "  \"max_tension\": " << peakJson(r.peak) << ",\n"
    << "  \"events\": " << lineEventsJson(r.events) << ",\n";
  if (!r.line_length.empty())
    f << "  \"line_length\": {\"start\": " << jsonNum(r.line_length.front()) << ", \"end\": "
      << jsonNum(r.line_length.back()) << "},\n";
  if (r.initial_static.drifting && g.simulated > 0.0)
    f << "  \"static_drift_velocity\": {\"x\": " << jsonNum(r.initial_static.drift_vx)
      << ", \"y\": " << jsonNum(r.initial_static.drift_vy) << "},\n"
      << "  \"mean_drift_velocity\": {\"x\": " << jsonNum((r.top_x.back() - r.top_x.front()) / g.simulated)
      << ", \"y\": " << jsonNum((r.top_y.back() - r.top_y.front()) / g.simulated) << "},\n";
  f << "  \"steps\": " << r.steps << ",\n"
    << "  \"cuts\": " << r.cuts << ",\n"
    << "  \"newton_iterations\": " << r.newton_iterations << ",\n"
    << "  \"jacobians\": " << r.jacobians << ",\n"
    << "  \"fallback_steps\": " << r.fallback_steps << ",\n"
    << "  \"fallback_substeps\": " << r.fallback_substeps << ",\n"
    << "  \"top_off_path\": " << r.top_off_path << ",\n"
    << "  \"threads\": " << r.threads << ",\n"
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
  o << "  max tension    " << core::tensionPeakText(r.peak, true) << "\n";
  for (const auto& e : r.events) o << "  event          " << core::lineEventText(e) << "\n";
  if (!r.line_length.empty())
    o << "  winch          line length " << fmtNum("%.3f", r.line_length.front()) << " m -> "
      << fmtNum("%.3f", r.line_length.back()) << " m\n";
  if (r.initial_static.drifting && g.simulated > 0.0)
    o << "  drift          static x = " << fmtNum("%.4f", r.initial_static.drift_vx) << ", y = "
      << fmtNum("%.4f", r.initial_static.drift_vy) << " m/s; run mean x = "
      << fmtNum("%.4f", (r.top_x.back() - r.top_x.front()) / g.simulated) << ", y = "
      << fmtNum("%.4f", (r.top_y.back() - r.top_y.front()) / g.simulated) << " m/s\n";
  o << "  solver         " << r.steps << " steps, " << r.cuts << " cuts, " << r.newton_iterations
    << " Newton iterations";
  if (r.jacobians > 0 && r.jacobians != r.newton_iterations) o << " (" << r.jacobians << " Jacobians)";
  if (r.fallback_steps > 0)
    o << ", " << r.fallback_steps << " fallback steps (" << r.fallback_substeps << " explicit sub-steps)";
  if (r.top_off_path > 0) o << ", " << r.top_off_path << " converged steps refused with the top off its path";
  o << "\n";
  o << "  wall time      " << fmtNum("%.3g", r.wall_seconds) << " s, real-time factor "
    << (std::isfinite(g.rtf) ? fmtNum("%.3g", g.rtf) : std::string("inf"))
    << (r.threads > 1 ? ", " + std::to_string(r.threads) + " threads" : std::string())
    << (r.threads < d.threads ? ", 1 thread of the " + std::to_string(d.threads) +
                                    " asked (a 2-D line of fewer than " +
                                    std::to_string(core::DynamicSolver2D::kMinNodesForTwoThreads) + " nodes runs faster on one)"
                              : std::string())
    << "\n";
  return o.str();
}

/// Writes a single line's results to `dir` (timeseries.csv, snapshots.csv, static_nodes.csv,
/// dynamic_summary.json) and names them on `out`; false, with the error on `err`, when it cannot.
bool writeDynamicOutputs(const fs::path& dir, const core::Problem& problem, const core::DynamicSeries& series,
                         const DynamicFigures& fig, std::ostream& out, std::ostream& err) {
  if (!makeOutputDir(dir, err)) return false;
  std::vector<fs::path> written;
  const bool three_d = problem.formulation == core::Formulation::ThreeD;
  const fs::path ts = dir / "timeseries.csv";
  if (!writeFile(ts, [&](std::ostream& f) { writeTimeseriesCsv(f, series, three_d); }, err)) return false;
  written.push_back(ts);
  const fs::path snaps = dir / "snapshots.csv";
  if (!series.snapshots.empty()) {
    if (!writeFile(snaps, [&](std::ostream& f) { writeSnapshotsCsv(f, series, three_d); }, err)) return false;
    written.push_back(snaps);
  } else {
    std::error_code ec;
    fs::remove(snaps, ec);  // never leave a stale file from an earlier run next to new results
  }
  const fs::path stat = dir / "static_nodes.csv";
  if (!writeFile(stat, [&](std::ostream& f) { core::writeStaticCsv(f, series.initial_static, problem.formulation); }, err))
    return false;
  written.push_back(stat);
  const fs::path js = dir / "dynamic_summary.json";
  if (!writeFile(js, [&](std::ostream& f) { writeDynamicSummaryJson(f, problem, series, fig); }, err)) return false;
  written.push_back(js);
  out << "wrote";
  for (std::size_t i = 0; i < written.size(); ++i)
    out << (i == 0 ? " " : i + 1 == written.size() ? " and " : ", ") << written[i].string();
  out << "\n";
  return true;
}

}  // namespace

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
  int threads = 1;
  if (args.has("threads")) {
    const std::string& v = args.values.at("threads");
    if (v != "1" && v != "2") throw UsageError("option '--threads' needs 1 or 2, got '" + v + "'");
    threads = v == "2" ? 2 : 1;
  }
  if (args.has("lambda-inf")) {
    lambda_inf = parseFiniteDouble("lambda-inf", args.values.at("lambda-inf"), "a number in [-1, 1)");
    if (!(lambda_inf >= -1.0 && lambda_inf < 1.0))
      throw UsageError("option '--lambda-inf' needs a number in [-1, 1), got '" + args.values.at("lambda-inf") + "'");
  }

  // Command-line overrides of the file's dynamics section (problem or system).
  const auto overrides = [&](core::DynamicOptions& dyn) {
    if (args.has("duration")) dyn.duration = duration;
    if (args.has("dt")) dyn.dt = dt;
    if (args.has("threads")) dyn.threads = threads;
    if (args.has("scheme")) {
      dyn.scheme = scheme;
      dyn.scheme_name = args.values.at("scheme");
    }
    if (args.has("lambda-inf")) {
      dyn.scheme = core::GeneralizedAlpha::fromLambdaInf(lambda_inf);
      dyn.scheme_name = "lambda_inf=" + fmtNum("%.10g", lambda_inf);
    }
  };
  // The output folder before the run: hours of a run are not lost to a folder that cannot be made.
  if (!out_dir.empty() && !makeOutputDir(out_dir, err)) return kExitIo;
  if (core::isSystemFile(problem_path))  // several lines joined at points
    return runSystemDynamic(problem_path, overrides, out_dir, out, err);

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

  core::DynamicOptions& dyn = problem.dynamics;
  overrides(dyn);
  if (dyn.gnss.enabled) {  // a real ship track: its fixes become the top's position table
    try {
      gnssTopTable(problem, out);
    } catch (const std::exception& e) {
      err << kProg << ": error: " << problem_path << ": " << e.what() << "\n";
      return kExitBadInput;
    }
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
    series = core::runDynamicModel(problem, progress);
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
  if (!out_dir.empty() && !writeDynamicOutputs(fs::path(out_dir), problem, series, fig, out, err)) return kExitIo;

  if (!series.completed) {
    err << kProg << ": error: the dynamic run stopped at t = " << fmtNum("%g", fig.simulated) << " s of "
        << fmtNum("%g", problem.dynamics.duration) << " s";
    if (!series.message.empty()) err << " (" << series.message << ")";
    err << (out_dir.empty() ? "" : "; results up to that time written, marked \"completed\": false") << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
