#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

#include <algorithm>
#include <cstdio>

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

std::string fmt(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

VesselMonitor::VesselMonitor(std::vector<std::string> line_names, const VesselMonitorOptions& options, double wall_now)
    : names_(std::move(line_names)),
      options_(options),
      line_failures_window_(names_.size(), 0),
      line_failures_total_(names_.size(), 0),
      line_fallback_total_(names_.size(), 0),
      line_last_failure_(names_.size()),
      top_tension_(names_.size(), 0.0),
      max_top_tension_(names_.size(), 0.0),
      max_tension_(names_.size(), 0.0),
      utilization_(names_.size(), -1.0),
      peak_utilization_(names_.size(), -1.0),
      last_motion_wall_(wall_now) {
  namespace k = vessel_keys;
  tally_ = EventTally({k::kNonFinitePosition, k::kNonFiniteOrientation, k::kNonUnitOrientation, k::kBadTwist,
                       k::kNonFiniteTime, k::kZeroStamp, k::kUnknownFrame, k::kGnssRejected, k::kSameStamp,
                       k::kStampBack, k::kJump, k::kStartFailed,
                       k::kRestartLoop, k::kRestartGap, k::kRestartJumps, k::kRestartReset, k::kRestartBehind, k::kRestartFailures,
                       k::kFailedKept, k::kLinesRestarted, k::kRequestRejected});
}

void VesselMonitor::add(Counts& a, const Counts& b) {
  a.samples += b.samples;
  a.published += b.published;
  a.dropped += b.dropped;
  a.restarts += b.restarts;
  a.failures += b.failures;
  a.held += b.held;
  a.answered += b.answered;
  a.thinned += b.thinned;
  a.sim += b.sim;
  a.wall += b.wall;
}

int VesselMonitor::failedLine(const std::string& message) const {
  // SystemDynamics names the first failed line (in line order) as "line <name>: ...". The longest
  // matching name wins, so that "a" does not match a message about "a_2".
  int best = -1;
  std::size_t best_len = 0;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const std::string key = "line " + names_[i] + ":";
    if (message.find(key) != std::string::npos && key.size() > best_len) {
      best = static_cast<int>(i);
      best_len = key.size();
    }
  }
  return best;
}

void VesselMonitor::onMotionReceived(double wall_now) {
  last_motion_wall_ = wall_now;
  ever_received_ = true;
  ++window_.samples;
}

void VesselMonitor::onInputRejected(double, const std::string& message, const std::string& key) {
  ++window_.dropped;
  tally_.count(key);
  last_drop_ = message;
  last_event_ = "dropped: " + message;
}

void VesselMonitor::onRequestRejected(double, const std::string& message) {
  ++requests_rejected_;
  tally_.count(vessel_keys::kRequestRejected);
  last_request_ = message;
  last_event_ = "request rejected: " + message;
}

void VesselMonitor::onResult(const core::VesselLockstep::Result& r, double, double wall_spent, double advanced,
                             const std::vector<double>* top_tension, double solver_time,
                             const std::vector<core::TensionPeak>* peaks) {
  using O = core::VesselLockstep::Outcome;
  using R = core::VesselLockstep::Reason;
  namespace k = vessel_keys;
  solver_time_ = solver_time;
  window_.wall += wall_spent;
  switch (r.outcome) {
    case O::Dropped:
      ++window_.dropped;
      tally_.count(r.reason == R::NonFinitePosition      ? k::kNonFinitePosition
                   : r.reason == R::NonFiniteOrientation ? k::kNonFiniteOrientation
                   : r.reason == R::NonUnitOrientation   ? k::kNonUnitOrientation
                   : r.reason == R::BadTwist             ? k::kBadTwist
                   : r.reason == R::NonFiniteTime        ? k::kNonFiniteTime
                   : r.reason == R::SameStamp            ? k::kSameStamp
                   : r.reason == R::StampBack            ? k::kStampBack
                   : r.reason == R::Jump                 ? k::kJump
                   : r.reason == R::StartFailed          ? k::kStartFailed
                                                         : k::kOther);
      last_drop_ = r.message;
      last_event_ = "dropped: " + r.message;
      break;
    case O::Advanced: window_.sim += advanced; break;
    case O::Held: ++window_.held; break;
    case O::LinesRestarted: {
      // Some lines (a group) failed and restarted alone from statics; the others went on.
      window_.sim += advanced;
      ++window_.failures;
      tally_.count(k::kLinesRestarted);
      std::string names;
      for (std::size_t i : r.failed_lines) {
        if (i >= names_.size()) continue;
        names += (names.empty() ? "" : ", ") + names_[i];
        ++line_failures_window_[i];
        ++line_failures_total_[i];
        line_last_failure_[i] = "restarted alone from statics: " + r.message;
      }
      last_failure_ = r.message;
      last_event_ = "line(s) " + names + " failed and restarted alone from statics; the others went on: " + r.message;
      break;
    }
    case O::Started: last_event_ = "started" + (r.message.empty() ? std::string() : ": " + r.message); break;
    case O::Reinitialised:
      ++window_.restarts;
      tally_.count(r.reason == R::LoopBack ? k::kRestartLoop
                   : r.reason == R::Gap    ? k::kRestartGap
                   : r.reason == R::Jumps  ? k::kRestartJumps
                   : r.reason == R::Behind ? k::kRestartBehind
                                           : k::kRestartReset);
      last_restart_ = r.message;
      last_event_ = "restarted from statics: " + r.message;
      break;
    case O::Failed:
    case O::RecoveredFailure: {
      ++window_.failures;
      window_.sim += advanced;
      last_failure_kept_ = r.outcome == O::Failed;
      tally_.count(last_failure_kept_ ? k::kFailedKept : k::kRestartFailures);
      last_failure_ = r.message;
      const int i = failedLine(r.message);
      last_event_ = (i >= 0 ? "line " + names_[static_cast<std::size_t>(i)] + " failed; " : std::string()) +
                    (last_failure_kept_ ? "the last good state is kept and published: "
                                        : "every line restarted from statics at the sample's pose: ") +
                    r.message;
      if (i >= 0) {
        ++line_failures_window_[static_cast<std::size_t>(i)];
        ++line_failures_total_[static_cast<std::size_t>(i)];
        line_last_failure_[static_cast<std::size_t>(i)] =
            (last_failure_kept_ ? "the last good state is kept and published: "
                                : "every line restarted from statics at the sample's pose: ") +
            r.message;
      }
      break;
    }
  }
  if (r.publish) {
    ++window_.published;
    if (top_tension && top_tension->size() == names_.size()) {
      top_tension_ = *top_tension;
      for (std::size_t i = 0; i < names_.size(); ++i) max_top_tension_[i] = std::max(max_top_tension_[i], top_tension_[i]);
      have_state_ = true;
    }
    if (peaks && peaks->size() == names_.size()) {
      for (std::size_t i = 0; i < names_.size(); ++i) {
        const core::TensionPeak& p = (*peaks)[i];
        max_tension_[i] = p.max_tension;
        utilization_[i] = !p.empty && p.has_mbl ? p.utilization : -1.0;
        peak_utilization_[i] = std::max(peak_utilization_[i], utilization_[i]);
      }
      have_peaks_ = true;
    }
  }
}

bool VesselMonitor::overUtilized(std::size_t i) const {
  return have_peaks_ && utilization_[i] > options_.max_utilization;
}

std::string VesselMonitor::utilizationText(std::size_t i) const {
  return "utilization " + fmt(utilization_[i], "%.3f") + " > " + fmt(options_.max_utilization, "%g") +
         " (max tension " + fmt(max_tension_[i], "%.1f") + " N)";
}

void VesselMonitor::onFallbackSteps(const std::vector<long>& per_line_total) {
  if (per_line_total.size() == line_fallback_total_.size()) line_fallback_total_ = per_line_total;
}

std::vector<VesselMonitor::Status> VesselMonitor::summarise(double wall_now) {
  const Counts w = window_;
  add(total_, w);
  window_ = Counts();
  std::vector<Status> out;

  Status s;
  std::vector<std::string> errors, warnings;
  if (w.failures > 0) errors.push_back(std::to_string(w.failures) + " line failure(s): " + last_event_);
  const double quiet = wall_now - last_motion_wall_;
  if (quiet > options_.motion_timeout)
    warnings.push_back(ever_received_ ? "no motion for " + fmt(quiet, "%.1f") + " s (last good state kept)"
                                      : "waiting for motion (none received yet)");
  if (w.dropped > 0) warnings.push_back(std::to_string(w.dropped) + " sample(s) dropped: " + last_drop_);
  if (w.restarts > 0) warnings.push_back(std::to_string(w.restarts) + " restart(s): " + last_restart_);
  if (w.thinned > 0)
    warnings.push_back(std::to_string(w.thinned) + " pose(s) skipped: the solver fell behind and restarted from statics");
  if (requests_rejected_ > 0)
    warnings.push_back(std::to_string(requests_rejected_) + " service request(s) rejected: " + last_request_);
  requests_rejected_ = 0;
  const double rtf = w.wall > 0.0 ? w.sim / w.wall : 0.0;
  if (w.sim > 0.0 && rtf < options_.min_real_time_factor)
    warnings.push_back("real-time factor " + fmt(rtf, "%.2f") + " < " + fmt(options_.min_real_time_factor, "%g"));
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (overUtilized(i)) warnings.push_back("line " + names_[i] + " " + utilizationText(i));
  std::string msg;
  for (const auto* v : {&errors, &warnings})
    for (const auto& x : *v) msg += (msg.empty() ? "" : "; ") + x;
  s.level = !errors.empty() ? ERROR : !warnings.empty() ? WARN : OK;
  if (s.level == OK) msg = w.sim > 0.0 ? "running, real-time factor " + fmt(rtf, "%.1f") : "running";
  s.message = msg;
  const double total_rtf = total_.wall > 0.0 ? total_.sim / total_.wall : 0.0;
  auto kv = [](Status& st, const std::string& k, const std::string& v) { st.values.emplace_back(k, v); };
  kv(s, "real-time factor (window)", w.sim > 0.0 ? fmt(rtf) : "-");
  kv(s, "real-time factor (total)", total_.sim > 0.0 ? fmt(total_rtf) : "-");
  kv(s, "solver wall time (window) [s]", fmt(w.wall));
  kv(s, "simulated time advanced (window) [s]", fmt(w.sim));
  kv(s, "solver time [s]", fmt(solver_time_));
  kv(s, "motion samples (window / total)", std::to_string(w.samples) + " / " + std::to_string(total_.samples));
  kv(s, "states published (window / total)", std::to_string(w.published) + " / " + std::to_string(total_.published));
  kv(s, "samples dropped (window / total)", std::to_string(w.dropped) + " / " + std::to_string(total_.dropped));
  kv(s, "samples dropped", std::to_string(total_.dropped));
  if (solver_lag_ >= 0.0) {
    kv(s, "poses answered (window / total)", std::to_string(w.answered) + " / " + std::to_string(total_.answered));
    kv(s, "poses held, not solved (window / total)", std::to_string(w.held) + " / " + std::to_string(total_.held));
    kv(s, "poses skipped, solver behind (window / total)",
       std::to_string(w.thinned) + " / " + std::to_string(total_.thinned));
    kv(s, "solver lag [s]", fmt(solver_lag_, "%.3g"));
  }
  kv(s, "restarts (window / total)", std::to_string(w.restarts) + " / " + std::to_string(total_.restarts));
  kv(s, "line failures (window / total)", std::to_string(w.failures) + " / " + std::to_string(total_.failures));
  tally_.closeWindow(s.values);
  {
    std::string text;
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (line_fallback_total_[i] > 0)
        text += (text.empty() ? "fallback steps: " : ", ") + std::to_string(line_fallback_total_[i]) + " on " + names_[i];
    kv(s, "fallback steps (total)", text.empty() ? "none" : text);
  }
  kv(s, "seconds since last motion [s]", ever_received_ ? fmt(quiet, "%.3g") : "-");
  kv(s, "last event", last_event_.empty() ? "none" : last_event_);
  out.push_back(s);

  for (std::size_t i = 0; i < names_.size(); ++i) {
    Status l;
    l.line = names_[i];
    const bool failed = line_failures_window_[i] > 0;
    const bool over = overUtilized(i);
    l.level = failed ? ERROR : over ? WARN : OK;
    l.message = failed ? "failed: " + line_last_failure_[i]
                       : have_state_ ? "top tension " + fmt(top_tension_[i], "%.1f") + " N" : "waiting for motion";
    if (!failed && over) l.message += "; " + utilizationText(i);
    kv(l, "top tension [N]", have_state_ ? fmt(top_tension_[i], "%.6g") : "-");
    kv(l, "max top tension [N]", have_state_ ? fmt(max_top_tension_[i], "%.6g") : "-");
    kv(l, "max tension [N]", have_peaks_ ? fmt(max_tension_[i], "%.6g") : "-");
    kv(l, "utilization (T / MBL)", have_peaks_ && utilization_[i] >= 0.0 ? fmt(utilization_[i], "%.4g") : "-");
    kv(l, "utilization (max, total)", peak_utilization_[i] >= 0.0 ? fmt(peak_utilization_[i], "%.4g") : "-");
    kv(l, "converged", failed ? "false" : "true");
    kv(l, "fallback steps (total)", std::to_string(line_fallback_total_[i]));
    kv(l, "failures (window / total)",
       std::to_string(line_failures_window_[i]) + " / " + std::to_string(line_failures_total_[i]));
    kv(l, "last failure", line_last_failure_[i].empty() ? "none" : line_last_failure_[i]);
    line_failures_window_[i] = 0;
    out.push_back(l);
  }
  return out;
}

bool isRunStatusName(const std::string& status_name, const std::string& node) {
  const std::string head = "mooring_dynamics: " + node + " ";
  if (status_name.compare(0, head.size(), head) != 0) return false;
  const std::string rest = status_name.substr(head.size());
  return rest == "lockstep" || rest == "vessel lockstep" || rest == "system lockstep";
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics

