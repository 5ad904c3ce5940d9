// cable_sim storm-motion: a vessel motion table of a moored vessel in an irregular sea
// (core/model/storm_motion: the ASSUMED simple response model), written as the 14-column
// vessel.motion_table (poses and body twists), with a summary of the motion.
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "mooring_dynamics/core/model/storm_motion.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Each field of StormMotionOptions with the option that sets it (validate()'s messages name the
/// field; the command's name the option too).
const std::vector<std::pair<std::string, std::string>>& fieldOptions() {
  static const std::vector<std::pair<std::string, std::string>> map = {
      {"hs", "hs"},
      {"tp", "tp"},
      {"gamma", "gamma"},
      {"heading_deg", "heading"},
      {"duration", "duration"},
      {"dt", "dt"},
      {"components", "components"},
      {"f_min_factor", "f-min"},
      {"f_max_factor", "f-max"},
      {"heave_gain", "heave-gain"},
      {"pitch_gain", "pitch-gain"},
      {"roll_gain", "roll-gain"},
      {"yaw_deg", "yaw"},
      {"mean_offset", "offset"},
      {"mean_offset_heading_deg", "offset-heading"},
      {"drift_amplitude", "drift"},
      {"drift_period", "drift-period"},
      {"ramp", "ramp"},
  };
  return map;
}

std::uint32_t parseSeed(const std::string& text) {
  const std::string msg = "option '--seed' needs an integer in [0, 4294967295], got '" + text + "'";
  if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos)
    throw UsageError(msg);
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (v > 4294967295ULL) throw UsageError(msg);
  return static_cast<std::uint32_t>(v);
}

/// "X,Y,Z": three finite numbers [m].
Eigen::Vector3d parsePoint(const std::string& text) {
  const std::string msg = "option '--point' needs X,Y,Z (three finite numbers, body frame, m), got '" + text + "'";
  Eigen::Vector3d p;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos)) throw UsageError(msg);
    const std::string part = text.substr(start, i < 2 ? comma - start : std::string::npos);
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end == part.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw UsageError(msg);
    p[i] = v;
    start = comma + 1;
  }
  return p;
}

std::string deg(double rad) { return fmtNum("%.2f", rad / kDeg); }

}  // namespace

int runStormMotion(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (!args.positionals.empty())
    throw UsageError("'storm-motion' takes no file argument, got '" + args.positionals.front() + "'");
  if (!args.has("hs")) throw UsageError("missing --hs H (significant wave height, m)");
  if (!args.has("tp")) throw UsageError("missing --tp T (peak period, s)");
  if (!args.has("out")) throw UsageError("missing --out FILE.csv (the motion table to write)");
  const std::string path = args.values.at("out");
  if (path.empty()) throw UsageError("option '--out' needs a file name, got ''");

  core::StormMotionOptions o;
  auto number = [&](const char* option, double& field) {
    if (args.has(option)) field = parseFiniteDouble(option, args.values.at(option), "a finite number");
  };
  number("hs", o.hs);
  number("tp", o.tp);
  number("gamma", o.gamma);
  number("heading", o.heading_deg);
  number("duration", o.duration);
  number("dt", o.dt);
  number("yaw", o.yaw_deg);
  number("offset", o.mean_offset);
  number("offset-heading", o.mean_offset_heading_deg);
  number("drift", o.drift_amplitude);
  number("drift-period", o.drift_period);
  number("ramp", o.ramp);
  number("f-min", o.f_min_factor);
  number("f-max", o.f_max_factor);
  number("heave-gain", o.heave_gain);
  number("pitch-gain", o.pitch_gain);
  number("roll-gain", o.roll_gain);
  if (args.has("seed")) o.seed = parseSeed(args.values.at("seed"));
  if (args.has("components")) {
    const std::size_t n = parsePositiveInt("components", args.values.at("components"));
    o.components = n > static_cast<std::size_t>(INT_MAX) ? INT_MAX : static_cast<int>(n);
  }
  std::vector<Eigen::Vector3d> points;
  if (args.all_values.count("point") != 0)
    for (const std::string& p : args.all_values.at("point")) points.push_back(parsePoint(p));

  const std::string invalid = o.validate();
  if (!invalid.empty()) {
    // "storm.<field> = ...": name the option that set the field.
    std::string option;
    for (const auto& fo : fieldOptions()) {
      const std::string prefix = "storm." + fo.first + " = ";
      if (invalid.compare(0, prefix.size(), prefix) == 0) option = fo.second;
    }
    throw UsageError(option.empty() ? invalid : "option '--" + option + "': " + invalid);
  }

  const core::StormMotion motion(o);
  const std::vector<core::PoseSample> samples = core::generateStormMotion(o);
  const core::StormMotionStats st = core::stormMotionStats(samples, o.ramp);
  const std::vector<core::StormComponent>& comps = motion.components();

  std::string sea = "JONSWAP Hs " + fmtNum("%g", o.hs) + " m, Tp " + fmtNum("%g", o.tp) + " s, gamma " +
                    fmtNum("%g", o.gamma) + ", waves toward " + fmtNum("%g", o.heading_deg) + " deg, seed " +
                    std::to_string(o.seed) + ", " + std::to_string(o.components) + " components " +
                    fmtNum("%.4g", comps.front().frequency) + " .. " + fmtNum("%.4g", comps.back().frequency) + " Hz";
  std::string hull = "hull yaw " + fmtNum("%g", o.yaw_deg) + " deg, gains heave " + fmtNum("%g", o.heave_gain) +
                     " pitch " + fmtNum("%g", o.pitch_gain) + " roll " + fmtNum("%g", o.roll_gain) + ", offset " +
                     fmtNum("%g", o.mean_offset) + " m toward " + fmtNum("%g", o.mean_offset_heading_deg) +
                     " deg, drift " + fmtNum("%g", o.drift_amplitude) + " m over " + fmtNum("%g", o.drift_period) +
                     " s, ramp " + fmtNum("%g", o.ramp) + " s";

  const fs::path file(path);
  if (file.has_parent_path() && !makeOutputDir(file.parent_path(), err)) return kExitIo;
  if (!writeFile(file,
                 [&](std::ostream& f) {
                   f << "# cable_sim storm-motion (ASSUMED simple response model, not RAOs): " << sea << "; " << hull
                     << "; world x east, y north, z up; twist in body axes\n";
                   f << "t,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz\n";
                   for (const core::PoseSample& s : samples) {
                     const Eigen::Vector3d& p = s.pose.position;
                     const Eigen::Quaterniond& q = s.pose.orientation;
                     const double row[14] = {s.t,
                                             p.x(),
                                             p.y(),
                                             p.z(),
                                             q.x(),
                                             q.y(),
                                             q.z(),
                                             q.w(),
                                             s.twist.linear.x(),
                                             s.twist.linear.y(),
                                             s.twist.linear.z(),
                                             s.twist.angular.x(),
                                             s.twist.angular.y(),
                                             s.twist.angular.z()};
                     for (int c = 0; c < 14; ++c) f << (c ? "," : "") << csvNum(row[c]);
                     f << "\n";
                   }
                 },
                 err))
    return kExitIo;

  out << "storm motion: " << sea << "\n";
  out << "  " << hull << "\n";
  out << "  record         " << fmtNum("%g", samples.back().t) << " s at dt " << fmtNum("%g", o.dt) << " s, "
      << samples.size() << " samples; statistics "
      << (samples.back().t >= o.ramp ? "over t >= " + fmtNum("%g", o.ramp) + " s (after the ramp)"
                                     : std::string("over the whole record (shorter than the ramp)"))
      << "\n";
  out << "  sea            realized 4 sqrt(m0) = " << fmtNum("%.3f", 4.0 * std::sqrt(motion.elevationVariance()))
      << " m (the components' variance)\n";
  out << "  heave          std " << fmtNum("%.3f", st.heave_std) << " m\n";
  out << "  pitch          std " << deg(st.pitch_std) << " deg, largest " << deg(st.max_abs_pitch) << " deg\n";
  out << "  roll           std " << deg(st.roll_std) << " deg, largest " << deg(st.max_abs_roll) << " deg\n";
  for (const Eigen::Vector3d& p : points) {
    double t_at = 0.0;
    const double v = core::maxPointVerticalSpeed(samples, p, &t_at);
    out << "  point (" << fmtNum("%g", p.x()) << ", " << fmtNum("%g", p.y()) << ", " << fmtNum("%g", p.z())
        << ")  largest vertical speed " << fmtNum("%.2f", v) << " m/s at t = " << fmtNum("%g", t_at) << " s\n";
  }
  out << "wrote " << file.string() << "\n";
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
