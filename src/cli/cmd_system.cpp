// cable_sim static on a system file (points and lines: multi-leg and branched moorings).
#include <chrono>
#include <cmath>
#include <memory>
#include <exception>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli_common.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/result_io.hpp"
#include "mooring_dynamics/core/model/utilization.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {

const char* pointType(core::SystemPoint::Type t) {
  switch (t) {
    case core::SystemPoint::Type::Anchor: return "anchor";
    case core::SystemPoint::Type::Fixed: return "fixed";
    case core::SystemPoint::Type::Buoy: return "buoy";
    case core::SystemPoint::Type::Body: return "body";
    case core::SystemPoint::Type::Vessel: return "vessel";
  }
  return "?";
}

std::string jsonText(const std::string& s) {
  std::string o = "\"";
  for (char c : s) o += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return o + "\"";
}

void writeSystemJson(std::ostream& f, const core::SystemProblem& s, const core::SystemStaticResult& r) {
  f << "{\n  \"name\": " << jsonText(s.name) << ",\n  \"model\": \""
    << (s.formulation == core::Formulation::ThreeD ? "3d" : "2d") << "\",\n";
  f << "  \"summary\": {\"converged\": " << (r.summary.converged ? "true" : "false")
    << ", \"iterations\": " << r.summary.iterations << ", \"force_residual\": " << csvNum(r.summary.error)
    << ", \"message\": " << jsonText(r.summary.message) << "},\n";
  f << "  \"points\": [\n";
  for (std::size_t p = 0; p < r.points.size(); ++p) {
    const auto& pt = r.points[p];
    f << "    {\"name\": " << jsonText(pt.name) << ", \"type\": \"" << pointType(s.points[p].type)
      << "\", \"position\": [" << csvNum(pt.x) << ", " << csvNum(pt.y) << ", " << csvNum(pt.z)
      << "], \"line_force\": [" << csvNum(pt.fx) << ", " << csvNum(pt.fy) << ", " << csvNum(pt.fz)
      << "], \"residual\": " << csvNum(pt.residual) << ", \"buoy_draft\": " << csvNum(pt.buoy_draft) << "}"
      << (p + 1 < r.points.size() ? "," : "") << "\n";
  }
  f << "  ],\n  \"lines\": [\n";
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    const auto& l = r.lines[i];
    double tmin = 0.0;
    for (std::size_t j = 0; j < l.nodes.size(); ++j) tmin = j ? std::min(tmin, l.nodes[j].tension) : l.nodes[j].tension;
    const core::TensionPeak pk = core::tensionPeak(s.materials, s.lines[i].segments, l.nodes);
    f << "    {\"name\": " << jsonText(s.lines[i].name) << ", \"nodes\": " << l.nodes.size()
      << ", \"max_tension\": " << csvNum(pk.max_tension) << ", \"utilization\": "
      << (pk.has_mbl ? csvNum(pk.utilization) : std::string("null"))
      << ", \"top_tension\": " << csvNum(l.topTension()) << ", \"min_tension\": " << csvNum(tmin)
      << ", \"top_force\": [" << csvNum(l.top_force_x) << ", " << csvNum(l.top_force_y) << ", "
      << csvNum(l.top_force_z) << "], \"lower_end_force\": [" << csvNum(l.anchor_force_x) << ", "
      << csvNum(l.anchor_force_y) << ", " << csvNum(l.anchor_force_z) << "], \"csv\": \"static_nodes_"
      << s.lines[i].name << ".csv\"}" << (i + 1 < r.lines.size() ? "," : "") << "\n";
  }
  f << "  ],\n  \"units\": {\"position\": \"m\", \"force\": \"N\", \"tension\": \"N\"}\n}\n";
}

/// Load a system file; false (and the message on err) when it is bad.
bool loadSystem(const std::string& path, core::SystemProblem& s, std::ostream& err) {
  try {
    s = core::loadSystemFromFile(path);
    return true;
  } catch (const std::exception& e) {
    err << kProg << ": error: " << e.what() << "\n";
    return false;
  }
}

}  // namespace

void writeRunSummaryJson(std::ostream& f, const RunSummary& s) {
  f << "{\n  \"problem\": " << jsonText(s.problem) << ",\n  \"kind\": " << jsonText(s.kind)
    << ",\n  \"completed\": " << (s.completed ? "true" : "false") << ",\n  \"message\": " << jsonText(s.message)
    << ",\n  \"simulated_time\": " << csvNum(s.simulated_time) << ",\n  \"duration\": " << csvNum(s.duration)
    << ",\n  \"samples\": " << s.samples << ",\n  \"wall_seconds\": " << csvNum(s.wall_seconds)
    << ",\n  \"real_time_factor\": " << csvNum(s.wall_seconds > 0.0 ? s.simulated_time / s.wall_seconds : 0.0)
    << ",\n  \"events\": " << lineEventsJson(s.events) << ",\n  \"fallback_steps\": {";
  for (std::size_t i = 0; i < s.fallback_steps.size(); ++i)
    f << (i ? ", " : "") << jsonText(s.fallback_steps[i].first) << ": " << s.fallback_steps[i].second;
  f << "},\n  \"timeseries\": " << jsonText(s.timeseries) << "\n}\n";
}

std::string fallbackStepsText(const std::vector<std::pair<std::string, long>>& per_line) {
  std::string text;
  for (const auto& [name, count] : per_line)
    if (count > 0) text += (text.empty() ? "fallback steps: " : ", ") + std::to_string(count) + " on " + name;
  return text;
}

int runSystemStatic(const std::string& path, bool want_table, std::size_t stride, double spacing_scale,
                    const std::string& out_dir, std::ostream& out, std::ostream& err) {
  core::SystemProblem s;
  if (!loadSystem(path, s, err)) return kExitBadInput;
  for (auto& l : s.lines)
    for (auto& g : l.segments) g.spacing *= spacing_scale;
  if (spacing_scale != 1.0) {
    const std::string invalid = s.validate();
    if (!invalid.empty()) throw UsageError("--spacing-scale " + fmtNum("%g", spacing_scale) + ": " + invalid);
  }
  core::SystemStaticResult r;
  try {
    r = core::solveSystemStatic(s);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << path << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  out << s.name << ": system of " << s.lines.size() << " lines and " << s.points.size() << " points, "
      << (r.summary.converged ? "converged" : "NOT converged") << " - " << r.summary.message << "\n";
  out << "  points (position [m]; pull of the lines [N]):\n";
  for (std::size_t p = 0; p < r.points.size(); ++p) {
    const auto& pt = r.points[p];
    out << "    " << pt.name << " (" << pointType(s.points[p].type) << ")  x = " << fmtNum("%.2f", pt.x)
        << ", y = " << fmtNum("%.2f", pt.y) << ", z = " << fmtNum("%.2f", pt.z) << "   pull ("
        << fmtNum("%.1f", pt.fx) << ", " << fmtNum("%.1f", pt.fy) << ", " << fmtNum("%.1f", pt.fz) << ")";
    if (s.points[p].type == core::SystemPoint::Type::Buoy) out << "   draft " << fmtNum("%.3f", pt.buoy_draft) << " m";
    out << "\n";
  }
  if (s.vessel.present && s.hasVesselPoints()) {
    const core::VesselWrench w = core::vesselWrench(s, s.vessel.pose, r.lines);
    auto vec = [](const Eigen::Vector3d& v, const char* f) {
      return "(" + fmtNum(f, v.x()) + ", " + fmtNum(f, v.y()) + ", " + fmtNum(f, v.z()) + ")";
    };
    out << "  vessel " << s.vessel.frame << " at (" << fmtNum("%.2f", s.vessel.pose.position.x()) << ", "
        << fmtNum("%.2f", s.vessel.pose.position.y()) << ", " << fmtNum("%.2f", s.vessel.pose.position.z())
        << ") m: the lines' total wrench about its origin\n"
        << "    world frame  force " << vec(w.force_world, "%.1f") << " N, moment " << vec(w.moment_world, "%.1f") << " N m\n"
        << "    body frame   force " << vec(w.force_body, "%.1f") << " N, moment " << vec(w.moment_body, "%.1f") << " N m\n";
  }
  out << "  lines (tension [N]):\n";
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    const auto& l = r.lines[i];
    double tmin = l.nodes.empty() ? 0.0 : l.nodes.front().tension;
    for (const auto& n : l.nodes) tmin = std::min(tmin, n.tension);
    out << "    " << s.lines[i].name << ": " << l.nodes.size() << " nodes, top " << fmtNum("%.1f", l.topTension())
        << ", lower end " << fmtNum("%.1f", l.nodes.empty() ? 0.0 : l.nodes.front().tension) << ", min "
        << fmtNum("%.1f", tmin) << "\n";
    out << "      max tension " << core::tensionPeakText(core::tensionPeak(s.materials, s.lines[i].segments, l.nodes), false)
        << "\n";
    if (want_table) out << core::staticTableText(l, stride, s.formulation);
  }
  if (!out_dir.empty()) {
    const fs::path dir(out_dir);
    if (!makeOutputDir(dir, err)) return kExitIo;
    if (!writeFile(dir / "system.json", [&](std::ostream& f) { writeSystemJson(f, s, r); }, err)) return kExitIo;
    for (std::size_t i = 0; i < r.lines.size(); ++i)
      if (!writeFile(dir / ("static_nodes_" + s.lines[i].name + ".csv"),
                     [&](std::ostream& f) { core::writeStaticCsv(f, r.lines[i], s.formulation); }, err))
        return kExitIo;
    out << "wrote " << (dir / "system.json").string() << " and " << r.lines.size() << " static_nodes_<line>.csv\n";
  }
  if (!r.summary.converged) {
    err << kProg << ": error: the system did not converge: " << r.summary.message << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics

namespace mooring_dynamics {
namespace cli {
namespace detail {

int runSystemDynamic(const std::string& path, const std::function<void(core::DynamicOptions&)>& overrides,
                     const std::string& out_dir, std::ostream& out, std::ostream& err) {
  core::SystemProblem s;
  if (!loadSystem(path, s, err)) return kExitBadInput;
  overrides(s.dynamics);
  // A system's lines each run on one thread; `threads` runs that many lines side by side.
  const int threads = s.dynamics.threads;
  s.dynamics.threads = 1;
  if (s.vessel.present && s.hasVesselPoints()) return runVesselDynamic(s, threads, out_dir, out, err);
  if (!(s.dynamics.duration > 0.0)) {
    err << kProg << ": error: " << path << ": dynamics.duration: not given; add `dynamics: {duration: 60, dt: 0.5}`"
        << " to the system file or pass --duration S\n";
    return kExitBadInput;
  }
  const std::string invalid = s.validate();  // again: the overrides may have changed dt and duration
  if (!invalid.empty()) {
    err << kProg << ": error: " << path << ": " << invalid << " (after the command-line overrides)\n";
    return kExitBadInput;
  }
  const auto wall0 = std::chrono::steady_clock::now();
  std::unique_ptr<core::SystemDynamics> sim;
  try {
    sim = std::make_unique<core::SystemDynamics>(s, s.dynamics, threads);
    // Offline, a line that cannot go on stops the run (exit 4, the last good state written)
    // rather than restart from statics as the node's lines do.
    sim->setRestartFailedGroups(false);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << path << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << kProg << ": error: " << path << ": " << e.what() << "\n";
    return kExitNotConverged;
  }
  // Samples on the dt grid (output_interval when given): free points' positions, tops' tensions.
  const double dout = s.dynamics.output_interval > 0.0 ? s.dynamics.output_interval : s.dynamics.dt;
  std::vector<std::vector<double>> rows;
  std::vector<core::TensionPeak> peaks(s.lines.size());
  // The line a winch pays out (dynamics.winch; none: s.lines.size()): its length, a column.
  std::size_t winched = s.lines.size();
  for (std::size_t i = 0; i < s.lines.size(); ++i)
    if (s.dynamics.winch.given && s.lines[i].name == s.dynamics.winch.line) winched = i;
  std::vector<double> lengths;
  auto sample = [&]() {
    std::vector<double> r{sim->time()};
    if (winched < s.lines.size()) lengths.push_back(sim->lineLength(winched));
    const auto pts = sim->points();
    for (std::size_t p = 0; p < pts.size(); ++p)
      if (s.points[p].free()) r.insert(r.end(), {pts[p].x, pts[p].y, pts[p].z});
    for (std::size_t i = 0; i < s.lines.size(); ++i) {
      const core::StaticResult li = sim->line(i);
      r.push_back(li.topTension());
      peaks[i].add(s.materials, s.lines[i].segments, li.nodes, sim->time());
    }
    rows.push_back(r);
  };
  sample();
  bool ok = true;
  std::string why;
  const long samples = static_cast<long>(std::floor(s.dynamics.duration / dout + 1e-9));
  for (long k = 1; k <= samples && ok; ++k) {
    ok = sim->advanceTo(k * dout, &why);
    if (ok) sample();
  }
  // The end time when the duration is not a whole number of samples (as a single line's run).
  if (ok && s.dynamics.duration - static_cast<double>(samples) * dout > 1e-9 * dout) {
    ok = sim->advanceTo(s.dynamics.duration, &why);
    if (ok) sample();
  }
  // Never "completed" short of the end time.
  if (ok && !(sim->time() >= s.dynamics.duration * (1.0 - 1e-9))) {
    ok = false;
    why = "reached t = " + fmtNum("%g", sim->time()) + " s of dynamics.duration = " +
          fmtNum("%g", s.dynamics.duration) + " s";
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  // The last sample written is the last good state: a failed step leaves the lines at their last
  // converged step, which may lie after it, but between samples nothing is written.
  const double t_good = rows.back()[0];
  out << s.name << ": system dynamic run " << (ok ? "completed" : "STOPPED") << "\n";
  if (!ok)
    out << "  stopped        " << why << "\n"
        << "  last good      t = " << fmtNum("%g", t_good) << " s (the last sample written)\n";
  out << "  time           " << fmtNum("%g", sim->time()) << " of " << fmtNum("%g", s.dynamics.duration) << " s, dt "
      << fmtNum("%g", s.dynamics.dt) << " s, " << rows.size() << " samples\n";
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    double mn = 1e300, mx = -1e300;
    for (const auto& r : rows) {
      const double T = r[r.size() - s.lines.size() + i];
      mn = std::min(mn, T);
      mx = std::max(mx, T);
    }
    out << "  " << s.lines[i].name << " top tension  min " << fmtNum("%.1f", mn) << " N, max " << fmtNum("%.1f", mx)
        << " N\n";
    out << "  " << s.lines[i].name << " max tension  " << core::tensionPeakText(peaks[i], true) << "\n";
  }
  const std::vector<core::LineEventRecord> events = sim->lineEvents();
  for (const auto& e : events) out << "  event          " << core::lineEventText(e) << "\n";
  if (!lengths.empty())
    out << "  winch          " << s.lines[winched].name << " line length " << fmtNum("%.3f", lengths.front())
        << " m -> " << fmtNum("%.3f", lengths.back()) << " m\n";
  std::vector<std::pair<std::string, long>> fallback;
  for (std::size_t i = 0; i < s.lines.size(); ++i) fallback.emplace_back(s.lines[i].name, sim->lineFallbackSteps(i));
  out << "  solver         " << sim->pointIterations() << " point iterations, " << sim->lineSteps() << " line steps\n";
  const std::string fallback_text = fallbackStepsText(fallback);
  if (!fallback_text.empty()) out << "  " << fallback_text << "\n";
  out << "  wall time      " << fmtNum("%.3g", wall) << " s, real-time factor " << fmtNum("%.3g", sim->time() / wall)
      << "\n";
  if (!out_dir.empty()) {
    const fs::path dir(out_dir);
    if (!makeOutputDir(dir, err)) return kExitIo;
    const fs::path ts = dir / "system_timeseries.csv";
    if (!writeFile(ts,
                   [&](std::ostream& f) {
                     f << "t";
                     for (const auto& p : s.points)
                       if (p.free()) f << "," << p.name << "_x," << p.name << "_y," << p.name << "_z";
                     for (const auto& l : s.lines) f << "," << l.name << "_top_tension";
                     if (!lengths.empty()) f << "," << s.lines[winched].name << "_line_length";
                     f << "\n";
                     for (std::size_t k = 0; k < rows.size(); ++k) {
                       const auto& r = rows[k];
                       for (std::size_t c = 0; c < r.size(); ++c) f << (c ? "," : "") << csvNum(r[c]);
                       if (!lengths.empty()) f << "," << csvNum(lengths[k]);
                       f << "\n";
                     }
                   },
                   err))
      return kExitIo;
    RunSummary sum;
    sum.problem = s.name;
    sum.kind = "system";
    sum.events = events;
    sum.completed = ok;
    sum.message = ok ? "" : why;
    sum.simulated_time = t_good;
    sum.duration = s.dynamics.duration;
    sum.wall_seconds = wall;
    sum.samples = rows.size();
    sum.timeseries = ts.filename().string();
    sum.fallback_steps = fallback;
    const fs::path js = dir / "dynamic_summary.json";
    if (!writeFile(js, [&](std::ostream& f) { writeRunSummaryJson(f, sum); }, err)) return kExitIo;
    out << "wrote " << ts.string() << " and " << js.string() << "\n";
  }
  if (!ok) {
    err << kProg << ": error: the system dynamic run stopped at t = " << fmtNum("%g", t_good) << " s of "
        << fmtNum("%g", s.dynamics.duration) << " s (" << why << ")"
        << (out_dir.empty() ? "" : "; results up to that time written, marked \"completed\": false") << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
