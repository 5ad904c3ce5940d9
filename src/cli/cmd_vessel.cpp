// cable_sim stiffness / offset: the moored vessel's engineering curves from its static wrench
// (solvers/vessel_statics): the 6 x 6 mooring stiffness at the file's pose, and the offset curve
// (wrench and most loaded line against an offset along or about one body axis).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "gnss_input.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/vessel_motion_io.hpp"
#include "mooring_dynamics/core/model/sea_state_motion.hpp"
#include "mooring_dynamics/core/solvers/vessel_motion_source.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
const char* const kDofNames[6] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};
const char* const kWrenchUnits[6] = {"N", "N", "N", "N m", "N m", "N m"};

/// Loads a file that must have a vessel with lines on it; false (message on err) otherwise.
bool loadVesselFile(const ParsedArgs& args, core::SystemProblem& s, std::ostream& err) {
  if (args.positionals.size() != 1) throw UsageError("needs one problem file with a `vessel:` section");
  const std::string& path = args.positionals[0];
  try {
    if (!core::isSystemFile(path)) {
      err << kProg << ": error: " << path << ": no `vessel:` section (and no points and lines); see "
          << "docs/problem_format.md, \"Moored vessel\"\n";
      return false;
    }
    s = core::loadSystemFromFile(path);
  } catch (const std::exception& e) {
    err << kProg << ": error: " << e.what() << "\n";
    return false;
  }
  if (!s.vessel.present || !s.hasVesselPoints()) {
    err << kProg << ": error: " << path << ": no line ends on the vessel (give `vessel.lines`, or points of type vessel)\n";
    return false;
  }
  return true;
}

}  // namespace

int runStiffness(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  core::SystemProblem s;
  if (!loadVesselFile(args, s, err)) return kExitBadInput;
  core::StiffnessOptions o;
  o.solve = core::SystemSolveOptions{};
  if (args.has("translation-step")) o.translation_step = parsePositiveDouble("--translation-step", args.values.at("translation-step"));
  if (args.has("rotation-step-deg"))
    o.rotation_step = kDeg * parsePositiveDouble("--rotation-step-deg", args.values.at("rotation-step-deg"));
  core::StiffnessResult k;
  try {
    k = core::mooringStiffness(s, s.vessel.pose, o);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << args.positionals[0] << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  const core::VesselWrench& w = k.at.wrench;
  out << s.name << ": mooring stiffness at the file's pose, body axes (" << s.vessel.frame << "), "
      << s.lines.size() << " lines\n";
  out << "  wrench at the pose (body): F = (" << fmtNum("%.1f", w.force_body.x()) << ", " << fmtNum("%.1f", w.force_body.y())
      << ", " << fmtNum("%.1f", w.force_body.z()) << ") N, M = (" << fmtNum("%.1f", w.moment_body.x()) << ", "
      << fmtNum("%.1f", w.moment_body.y()) << ", " << fmtNum("%.1f", w.moment_body.z()) << ") N m\n";
  out << "  K = -d(wrench)/d(offset), central differences (" << fmtNum("%g", o.translation_step) << " m, "
      << fmtNum("%g", o.rotation_step / kDeg) << " deg); rows: force/moment, columns: offset\n";
  out << "           ";
  for (const char* n : kDofNames) out << std::string(14 - std::string(n).size(), ' ') << n;
  out << "\n";
  for (int i = 0; i < 6; ++i) {
    std::string left = std::string("  ") + kDofNames[i];
    left.resize(11, ' ');
    out << left;
    for (int j = 0; j < 6; ++j) out << fmtNum("%14.4g", k.K(i, j));
    out << "\n";
  }
  out << "  units: N/m (force by translation), N/rad (force by rotation), N m/m, N m/rad\n";
  if (args.has("out")) {
    const std::string dir = args.values.at("out");
    if (!makeOutputDir(dir, err)) return kExitIo;
    const fs::path csv = fs::path(dir) / "stiffness.csv";
    if (!writeFile(csv,
                   [&](std::ostream& f) {
                     f << "row";
                     for (const char* n : kDofNames) f << "," << n;
                     f << "\n";
                     for (int i = 0; i < 6; ++i) {
                       f << kDofNames[i];
                       for (int j = 0; j < 6; ++j) f << "," << csvNum(k.K(i, j));
                       f << "\n";
                     }
                   },
                   err))
      return kExitIo;
    out << "wrote " << csv.string() << "\n";
  }
  if (!k.converged) {
    err << kProg << ": error: a static solve did not converge (" << k.message << "); the matrix is not valid\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

int runOffset(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  core::SystemProblem s;
  if (!loadVesselFile(args, s, err)) return kExitBadInput;
  core::VesselDof dof = core::VesselDof::Surge;
  if (args.has("dof") && !core::parseVesselDof(args.values.at("dof"), dof))
    throw UsageError("option '--dof' needs surge, sway, heave, roll, pitch or yaw, got '" + args.values.at("dof") + "'");
  const bool angular = static_cast<int>(dof) >= 3;
  const double range = args.has("range") ? parsePositiveDouble("--range", args.values.at("range")) : (angular ? 10.0 : 20.0);
  const std::size_t steps = args.has("steps") ? parsePositiveInt("--steps", args.values.at("steps")) : 11;
  if (steps < 2) throw UsageError("option '--steps' needs at least 2, got " + std::to_string(steps));
  if (angular && range >= 90.0) throw UsageError("option '--range' = " + fmtNum("%g", range) + " deg: must be < 90 for " + toString(dof));
  std::vector<double> offsets;
  for (std::size_t k = 0; k < steps; ++k) {
    const double a = -range + 2.0 * range * static_cast<double>(k) / static_cast<double>(steps - 1);
    offsets.push_back(angular ? a * kDeg : a);
  }
  const std::vector<core::OffsetPoint> curve = core::offsetCurve(s, s.vessel.pose, dof, offsets);
  const int c = static_cast<int>(dof);
  const std::string unit = angular ? "deg" : "m";
  out << s.name << ": offset curve in " << toString(dof) << " (body axes, from the file's pose), " << s.lines.size()
      << " lines\n";
  out << "  offset [" << unit << "]   " << kDofNames[c] << " restoring [" << kWrenchUnits[c]
      << "]   max tension [N]   line\n";
  bool all = true;
  for (const auto& p : curve) {
    all = all && p.converged;
    out << fmtNum("%14.3f", angular ? p.offset / kDeg : p.offset) << fmtNum("%22.1f", p.wrench[c])
        << fmtNum("%18.1f", p.max_tension) << "   " << p.max_tension_line << (p.converged ? "" : "   NOT converged")
        << "\n";
  }
  if (args.has("out")) {
    const std::string dir = args.values.at("out");
    if (!makeOutputDir(dir, err)) return kExitIo;
    const fs::path csv = fs::path(dir) / "offset.csv";
    if (!writeFile(csv,
                   [&](std::ostream& f) {
                     f << "offset_" << (angular ? "deg" : "m") << ",fx,fy,fz,mx,my,mz,max_tension,max_tension_line,converged\n";
                     for (const auto& p : curve) {
                       f << csvNum(angular ? p.offset / kDeg : p.offset);
                       for (int i = 0; i < 6; ++i) f << "," << csvNum(p.wrench[i]);
                       f << "," << csvNum(p.max_tension) << "," << p.max_tension_line << "," << (p.converged ? 1 : 0) << "\n";
                     }
                   },
                   err))
      return kExitIo;
    std::ostringstream gp;
    const fs::path png = fs::path(dir) / "offset.png";
    gp << "set terminal pngcairo noenhanced size 1000,650 font \"sans,12\"\n"
       << "set output " << gpString(png.string()) << "\n"
       << "set datafile separator \",\"\nset grid\nset key top center box\n"
       << "set title " << gpString(s.name + ": offset curve in " + toString(dof)) << "\n"
       << "set xlabel " << gpString(std::string(toString(dof)) + " offset [" + unit + "]") << "\n"
       << "set ylabel " << gpString(std::string(kDofNames[c]) + " restoring [k" + kWrenchUnits[c] + "]") << "\n"
       << "set y2label \"largest line tension [kN]\"\nset y2tics\nset ytics nomirror\n"
       << "plot " << gpString(csv.string()) << " skip 1 using 1:($" << (c + 2)
       << "/1000) with linespoints lw 2 title \"restoring\", " << gpString(csv.string())
       << " skip 1 using 1:($8/1000) axes x1y2 with linespoints lw 2 title \"largest tension\"\n";
    if (!runGnuplot(dir, "offset", gp.str(), err)) return kExitIo;
    out << "wrote " << csv.string() << " and " << png.string() << "\n";
  }
  if (!all) {
    err << kProg << ": error: a static solve did not converge (rows marked NOT converged)\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

/// Where the vessel's motion comes from, for the summary.
static std::string motionSourceText(const core::SystemProblem& s) {
  if (s.vessel.sea_state) {
    const core::WaveSpec& w = s.environment.waves;
    std::string sea = w.type == core::WaveSpec::Type::Regular
                          ? "regular wave H " + fmtNum("%g", w.height) + " m, T " + fmtNum("%g", w.period) + " s"
                          : "sea state Hs " + fmtNum("%g", w.hs) + " m, Tp " + fmtNum("%g", w.tp) + " s, seed " +
                                std::to_string(w.seed);
    return sea + ", toward " + fmtNum("%g", w.direction * 180.0 / 3.14159265358979323846) + " deg, RAOs " +
           fs::path(s.vessel.raos.file).lexically_normal().string() + (s.vessel.low_frequency ? ", slow drift" : "") +
           (s.vessel.wave_drift ? (s.vessel.drift.newman ? " with Newman's wave drift" : " with mean wave drift") : "");
  }
  if (s.vessel.low_frequency) return "slow drift in still water";
  if (!s.vessel.motion_table.empty()) return s.vessel.motion_table;
  return "held at the file's pose";
}

int runVesselDynamic(const core::SystemProblem& s, int threads, const std::string& out_dir, std::ostream& out,
                     std::ostream& err) {
  // The samples: the motion table's rows, the motion the file computes (sea state, slow drift),
  // or the file's pose held at every dt.
  std::vector<core::PoseSample> samples;
  std::unique_ptr<core::VesselMotionSource> source;
  const bool computed = s.vessel.sea_state || s.vessel.low_frequency;
  if (s.dynamics.gnss.enabled && (!s.vessel.motion_table.empty() || computed)) {
    err << kProg << ": error: dynamics.gnss and vessel." << (computed ? "sea_state/low_frequency" : "motion_table")
        << ": give one motion of the vessel\n";
    return kExitBadInput;
  }
  if (s.dynamics.gnss.enabled) {  // a real ship track: its fixes become the vessel's pose samples
    try {
      samples = gnssVesselSamples(s, out);
    } catch (const std::exception& e) {
      err << kProg << ": error: " << e.what() << "\n";
      return kExitBadInput;
    }
  } else if (computed) {  // the hull's RAOs in the sea the lines see too, and/or its slow drift
    if (!(s.dynamics.duration > 0.0)) {
      err << kProg << ": error: dynamics.duration: not given (vessel.sea_state and vessel.low_frequency need it); "
             "pass --duration S\n";
      return kExitBadInput;
    }
    try {
      source = std::make_unique<core::VesselMotionSource>(s);
    } catch (const std::invalid_argument& e) {
      err << kProg << ": error: vessel: " << e.what() << "\n";
      return kExitBadInput;
    }
    const long n = static_cast<long>(std::floor(s.dynamics.duration / s.dynamics.dt + 1e-9));
    samples.resize(static_cast<std::size_t>(n + 1));  // times only: the poses come from `source`
    for (long k = 0; k <= n; ++k) samples[static_cast<std::size_t>(k)].t = static_cast<double>(k) * s.dynamics.dt;
  } else if (!s.vessel.motion_table.empty()) {
    try {
      samples = core::loadVesselMotionTable(s.vessel.motion_table);
    } catch (const std::exception& e) {
      err << kProg << ": error: vessel.motion_table: " << e.what() << "\n";
      return kExitBadInput;
    }
  } else {
    if (!(s.dynamics.duration > 0.0)) {
      err << kProg << ": error: dynamics.duration: not given (and no vessel.motion_table); pass --duration S\n";
      return kExitBadInput;
    }
    const long n = static_cast<long>(std::floor(s.dynamics.duration / s.dynamics.dt + 1e-9));
    for (long k = 0; k <= n; ++k) {
      core::PoseSample p;
      p.t = static_cast<double>(k) * s.dynamics.dt;
      p.pose = s.vessel.pose;
      samples.push_back(p);
    }
  }
  const double t_first = samples.front().t;
  const double t_last = s.dynamics.duration > 0.0 ? t_first + s.dynamics.duration : samples.back().t;
  core::VesselLockstepOptions lo;
  lo.threads = threads;
  lo.restart_failed_lines = false;  // offline, a line that cannot go on stops the run (exit 4)
  const auto wall0 = std::chrono::steady_clock::now();
  std::unique_ptr<core::VesselLockstep> run;
  try {
    run = std::make_unique<core::VesselLockstep>(s, s.dynamics, lo);
  } catch (const std::invalid_argument& e) {
    err << kProg << ": error: " << s.name << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << kProg << ": error: " << s.name << ": " << e.what() << "\n";
    return kExitNotConverged;
  }
  std::vector<std::vector<double>> rows;
  std::vector<std::string> events;
  bool ok = true;
  std::string why;
  for (const core::PoseSample& given : samples) {
    if (given.t > t_last + 1e-9) break;
    const core::PoseSample p = source ? source->sample(given.t) : given;
    const core::VesselLockstep::Result r = run->onSample(p.t, p.pose, p.has_twist ? &p.twist : nullptr);
    if (!r.message.empty()) events.push_back("t = " + fmtNum("%g", p.t) + " s: " + toString(r.outcome) + ": " + r.message);
    if (r.outcome == core::VesselLockstep::Outcome::Failed || r.outcome == core::VesselLockstep::Outcome::RecoveredFailure) {
      // As a single line's run: the run cannot go on as given; the series ends at the last good
      // sample (VesselLockstep kept that state), written below, and the run is not complete.
      ok = false;
      why = r.message.substr(0, r.message.find("; the last good state"));  // the lockstep's note on going on
      break;
    }
    const core::VesselWrench w = run->wrench();
    if (source) source->advance(s.dynamics.dt, w);  // the lines' wrench moves the slow drift
    if (!r.publish) continue;
    std::vector<double> row{p.t};
    for (int i = 0; i < 6; ++i) row.push_back(w.body6()[i]);
    for (int i = 0; i < 3; ++i) row.push_back(w.force_world[i]);
    for (int i = 0; i < 3; ++i) row.push_back(w.moment_world[i]);
    for (std::size_t i = 0; i < s.lines.size(); ++i) row.push_back(run->dynamics().line(i).topTension());
    const Eigen::Matrix3d rot = p.pose.orientation.normalized().toRotationMatrix();  // R = Rz Ry Rx
    row.push_back(p.pose.position.x());
    row.push_back(p.pose.position.y());
    row.push_back(p.pose.position.z());
    row.push_back(std::atan2(rot(2, 1), rot(2, 2)));
    row.push_back(std::asin(std::max(-1.0, std::min(1.0, -rot(2, 0)))));
    row.push_back(std::atan2(rot(1, 0), rot(0, 0)));
    if (s.vessel.wave_drift)
      for (int i = 0; i < 3; ++i) row.push_back(source->lastDrift()[i]);
    rows.push_back(row);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double simulated = rows.empty() ? 0.0 : rows.back()[0] - rows.front()[0];
  const bool reached = !rows.empty() && rows.back()[0] >= std::min(t_last, samples.back().t) - 1e-9;
  if (ok && !reached)
    why = "reached t = " + fmtNum("%g", rows.empty() ? t_first : rows.back()[0]) + " s of " + fmtNum("%g", t_last) + " s";
  ok = ok && reached;
  const double t_good = rows.empty() ? t_first : rows.back()[0];
  out << s.name << ": vessel dynamic run " << (ok ? "completed" : "STOPPED") << " (" << s.lines.size()
      << " lines, " << run->dynamics().threads() << " thread" << (run->dynamics().threads() > 1 ? "s" : "") << ")\n";
  for (const auto& e : events) out << "  event          " << e << "\n";
  if (!ok)
    out << "  stopped        " << why << "\n"
        << "  last good      t = " << fmtNum("%g", t_good) << " s (the last sample written)\n";
  out << "  time           " << fmtNum("%g", simulated) << " s of vessel motion ("
      << motionSourceText(s) << "), dt "
      << fmtNum("%g", s.dynamics.dt) << " s, " << rows.size() << " samples\n";
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    double mx = 0.0;
    for (const auto& r : rows) mx = std::max(mx, r[13 + i]);
    out << "  " << s.lines[i].name << " top tension max " << fmtNum("%.1f", mx) << " N\n";
  }
  if (!rows.empty()) {
    double fmax = 0.0;
    for (const auto& r : rows) fmax = std::max(fmax, std::hypot(r[1], r[2]));
    out << "  wrench (body)  largest horizontal force " << fmtNum("%.1f", fmax) << " N\n";
    if (computed) {  // the offset envelope of the vessel's origin from the file's pose
      const std::size_t ix = 13 + s.lines.size();
      double omax = 0.0, omean = 0.0;
      for (const auto& r : rows) {
        const double o = std::hypot(r[ix] - s.vessel.pose.position.x(), r[ix + 1] - s.vessel.pose.position.y());
        omax = std::max(omax, o);
        omean += o / static_cast<double>(rows.size());
      }
      out << "  vessel offset  largest horizontal " << fmtNum("%.2f", omax) << " m, mean " << fmtNum("%.2f", omean)
          << " m (origin, from vessel.pose)\n";
    }
  }
  std::vector<std::pair<std::string, long>> fallback;
  for (std::size_t i = 0; i < s.lines.size(); ++i)
    fallback.emplace_back(s.lines[i].name, run->dynamics().lineFallbackSteps(i));
  out << "  solver         " << run->dynamics().lineSteps() << " line steps\n";
  const std::string fallback_text = fallbackStepsText(fallback);
  if (!fallback_text.empty()) out << "  " << fallback_text << "\n";
  out << "  wall time      " << fmtNum("%.3g", wall) << " s, real-time factor " << fmtNum("%.3g", simulated / wall) << "\n";
  if (!out_dir.empty()) {
    if (!makeOutputDir(out_dir, err)) return kExitIo;
    const fs::path ts = fs::path(out_dir) / "vessel_timeseries.csv";
    if (!writeFile(ts,
                   [&](std::ostream& f) {
                     f << "t,fx_body,fy_body,fz_body,mx_body,my_body,mz_body,fx_world,fy_world,fz_world,mx_world,my_world,"
                          "mz_world";
                     for (const auto& l : s.lines) f << "," << l.name << "_top_tension";
                     f << ",vessel_x,vessel_y,vessel_z,vessel_roll,vessel_pitch,vessel_yaw";
                     f << (s.vessel.wave_drift ? ",drift_x,drift_y,drift_n\n" : "\n");
                     for (const auto& r : rows) {
                       for (std::size_t c = 0; c < r.size(); ++c) f << (c ? "," : "") << csvNum(r[c]);
                       f << "\n";
                     }
                   },
                   err))
      return kExitIo;
    RunSummary sum;
    sum.problem = s.name;
    sum.kind = "vessel";
    sum.completed = ok;
    sum.message = ok ? "" : why;
    sum.simulated_time = simulated;
    sum.duration = t_last - t_first;
    sum.wall_seconds = wall;
    sum.samples = rows.size();
    sum.timeseries = ts.filename().string();
    sum.fallback_steps = fallback;
    const fs::path js = fs::path(out_dir) / "dynamic_summary.json";
    if (!writeFile(js, [&](std::ostream& f) { writeRunSummaryJson(f, sum); }, err)) return kExitIo;
    out << "wrote " << ts.string() << " and " << js.string() << "\n";
  }
  if (!ok) {
    err << kProg << ": error: the vessel dynamic run stopped at t = " << fmtNum("%g", t_good) << " s (" << why << ")"
        << (out_dir.empty() ? "" : "; results up to that time written, marked \"completed\": false") << "\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
