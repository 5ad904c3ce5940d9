#include "mooring_dynamics/core/model/dynamics_options.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "mooring_dynamics/core/model/field_error.hpp"

namespace mooring_dynamics {
namespace core {

std::string TopMotion::validate() const {
  const std::string k = "dynamics.top_motion.";
  switch (type) {
    case Type::Hold:
    case Type::WaveFollower:
      return {};
    case Type::ShipTrack:
      return ship_track.validate("dynamics.top_motion");
    case Type::Sinusoid:
      if (!std::isfinite(amplitude_x)) return fieldError(k + "amplitude_x", amplitude_x, "must be finite");
      if (!std::isfinite(amplitude_y)) return fieldError(k + "amplitude_y", amplitude_y, "must be finite");
      if (!std::isfinite(amplitude_z)) return fieldError(k + "amplitude_z", amplitude_z, "must be finite");
      if (!(std::isfinite(period) && period > 0.0)) return fieldError(k + "period", period, "must be > 0");
      if (!std::isfinite(phase)) return fieldError(k + "phase_deg", phase, "must be finite");
      return {};
    case Type::PositionTable:
    case Type::VelocityTable:
    case Type::ForceTable:
      if (table.empty()) return k + "table: needs at least one row [t, x, z] or [t, x, y, z]";
      for (std::size_t i = 0; i < table.size(); ++i) {
        const Row& r = table[i];
        const std::string rk = k + "table[" + std::to_string(i) + "]";
        if (!std::isfinite(r.t) || !std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
          return rk + ": values must be finite";
        if (i > 0 && !(r.t > table[i - 1].t)) return fieldError(rk + " t", r.t, "times must increase");
      }
      return {};
  }
  return {};
}

std::string lineEventText(const LineEventRecord& e) {
  auto num = [](const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return std::string(b);
  };
  std::string what = e.what;
  if (e.what == "parted")
    what = "parted between nodes " + std::to_string(e.node) + " and " + std::to_string(e.node + 1) + " (s = " +
           num("%.2f", e.s) + " m)";
  return "t = " + num("%g", e.t) + " s: " + (e.line.empty() ? "" : e.line + " ") + what +
         (e.what == "retired" ? "" : ", largest tension " + num("%.1f", e.tension) + " N") + " (" + e.cause + ")";
}

std::string LineEvent::validate(const std::string& key) const {
  const std::string k = key + ".";
  const bool timed = t >= 0.0;
  if (!(std::isfinite(t))) return fieldError(k + "t", t, "must be a finite time >= 0 [s]");
  if (!(std::isfinite(tension) && tension >= 0.0)) return fieldError(k + "tension", tension, "must be > 0 [N] or mbl");
  if (!std::isfinite(s)) return fieldError(k + "s", s, "must be a finite arclength >= 0 [m]");
  if (type == Type::Release) {
    if (!timed) return k + "t: required for a release (the time the end is let go [s])";
    if (tension > 0.0 || at_mbl) return k + "tension: only a break has a tension; a release happens at t";
    if (s >= 0.0) return k + "s: only a break has an arclength; a release lets go an end (end: top or anchor)";
    return {};
  }
  if (timed == onTension())
    return k + "t / tension: a break needs exactly one of t (a time [s]) and tension (a force [N] or mbl)";
  if (s >= 0.0 && !timed) return k + "s: a break on tension parts at the node where the tension exceeds it; s goes with t";
  return {};
}

std::string DynamicOptions::validate() const {
  const std::string k = "dynamics.";
  if (!(std::isfinite(duration) && duration >= 0.0)) return fieldError(k + "duration", duration, "must be >= 0");
  if (!(std::isfinite(dt) && dt > 0.0)) return fieldError(k + "dt", dt, "must be > 0");
  // A step longer than the run takes no step at all (the end time lies inside the first step's
  // rounding tolerance): the run would say it completed having done nothing.
  if (duration > 0.0 && dt > duration) {
    std::ostringstream os;
    os.precision(10);
    os << "must be <= dynamics.duration = " << duration << " s";
    return fieldError(k + "dt", dt, os.str());
  }
  if (!(std::isfinite(output_interval) && output_interval >= 0.0))
    return fieldError(k + "output_interval", output_interval, "must be >= 0");
  if (output_interval > 0.0) {
    const double ratio = output_interval / dt;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio || std::round(ratio) < 1.0)
      return fieldError(k + "output_interval", output_interval, "must be a whole multiple of dt = " + std::to_string(dt));
  }
  if (!(std::isfinite(snapshot_interval) && snapshot_interval >= 0.0))
    return fieldError(k + "snapshot_interval", snapshot_interval, "must be >= 0");
  for (std::size_t i = 0; i < record_s.size(); ++i)
    if (!(std::isfinite(record_s[i]) && record_s[i] >= 0.0))
      return fieldError(k + "record_s[" + std::to_string(i) + "]", record_s[i], "must be >= 0");
  std::string e = scheme.validate();
  if (!e.empty()) return e;
  if (gnss.enabled && !(e = gnss.validate()).empty()) return e;
  if (max_cut_levels < 0 || max_cut_levels > 8)
    return k + "max_cut_levels = " + std::to_string(max_cut_levels) + ": must be in [0, 8]";
  if (fallback_after_cuts != kFallbackAfterCutsAuto && (fallback_after_cuts < 0 || fallback_after_cuts > 8))
    return k + "fallback_after_cuts = " + std::to_string(fallback_after_cuts) + ": must be in [0, 8] (or not given: automatic)";
  if (!(std::isfinite(tolerance) && tolerance > 0.0)) return fieldError(k + "tolerance", tolerance, "must be > 0");
  if (max_iterations < 1) return k + "max_iterations = " + std::to_string(max_iterations) + ": must be >= 1";
  if (!(std::isfinite(jacobian_reuse_rate) && jacobian_reuse_rate > 0.0 && jacobian_reuse_rate < 1.0))
    return fieldError(k + "jacobian_reuse_rate", jacobian_reuse_rate, "must be in (0, 1)");
  if (!(std::isfinite(relaxation) && relaxation > 0.0 && relaxation <= 1.0))
    return fieldError(k + "relaxation", relaxation, "must be in (0, 1]");
  if (threads < 1 || threads > 2) return k + "threads = " + std::to_string(threads) + ": must be 1 or 2";
  if (!(std::isfinite(mesh_weight) && mesh_weight >= 0.0)) return fieldError(k + "mesh_weight", mesh_weight, "must be >= 0");
  if (winch.given && !(e = winch.validate(k + "winch")).empty()) return e;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const std::string ek = k + "events[" + std::to_string(i) + "]";
    if (!(e = events[i].validate(ek)).empty()) return e;
    if (duration > 0.0 && events[i].t > duration)
      return fieldError(ek + ".t", events[i].t, "after dynamics.duration = " + std::to_string(duration) + " s: it would never happen");
    for (std::size_t j = 0; j < i; ++j) {
      if (events[j].line != events[i].line) continue;
      const std::string of = events[i].line.empty() ? "" : " of line " + events[i].line;
      if (events[i].type == LineEvent::Type::Break && events[j].type == LineEvent::Type::Break)
        return ek + ": a second break" + of + " (events[" + std::to_string(j) + "] is one); a line parts once";
      if (events[i].type == LineEvent::Type::Release && events[j].type == LineEvent::Type::Release &&
          events[i].end == events[j].end)
        return ek + ": the same end" + of + " is released by events[" + std::to_string(j) + "] already";
    }
  }
  return top_motion.validate();
}

}  // namespace core
}  // namespace mooring_dynamics
