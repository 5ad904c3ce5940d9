#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"

#include <algorithm>
#include <cstdio>

#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

std::string fmt(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

LockstepMonitor::LockstepMonitor(const MonitorOptions& options, double wall_now)
    : options_(options),
      tally_({lockstep_keys::kNonFinite, lockstep_keys::kZeroStamp, lockstep_keys::kUnknownFrame,
              lockstep_keys::kOffPlane, lockstep_keys::kSameStamp, lockstep_keys::kStampBack, lockstep_keys::kJump,
              lockstep_keys::kStartFailed, lockstep_keys::kNoTransform, lockstep_keys::kGnssRejected,
              lockstep_keys::kOrientationNonFinite,
              lockstep_keys::kOrientationNonUnit, lockstep_keys::kReinitLoop, lockstep_keys::kReinitGap,
              lockstep_keys::kReinitJumps, lockstep_keys::kReinitRequest, lockstep_keys::kReinitFailures,
              lockstep_keys::kFailedKept, lockstep_keys::kRequestRejected}),
      last_motion_wall_(wall_now) {}

void LockstepMonitor::add(Counts& a, const Counts& b) {
  a.samples += b.samples;
  a.published += b.published;
  a.dropped += b.dropped;
  a.rejected += b.rejected;
  a.reinit += b.reinit;
  a.failures += b.failures;
  a.start_failures += b.start_failures;
  a.steps += b.steps;
  a.cuts += b.cuts;
  a.fallback += b.fallback;
  a.newton += b.newton;
  a.slack_events += b.slack_events;
  a.sim += b.sim;
  a.wall += b.wall;
}

void LockstepMonitor::setError(double wall_now, const std::string& message) {
  last_error_ = message;
  last_error_wall_ = wall_now;
}

void LockstepMonitor::onMotionReceived(double wall_now) {
  last_motion_wall_ = wall_now;
  ever_received_ = true;
  ++window_.samples;
}

void LockstepMonitor::onInputRejected(double wall_now, const std::string& message, const std::string& key) {
  ++window_.rejected;
  tally_.count(key);
  last_drop_ = message;
  setError(wall_now, message);
}

void LockstepMonitor::onInputNote(double, const std::string& message, const std::string& key, bool warn) {
  tally_.count(key);
  if (warn) {
    ++notes_warn_;
    last_note_ = message;
  }
}

void LockstepMonitor::onRequestRejected(double wall_now, const std::string& message) {
  ++requests_rejected_;
  tally_.count(lockstep_keys::kRequestRejected);
  last_request_ = message;
  setError(wall_now, message);
}

void LockstepMonitor::onResult(const LockstepDriver::Result& r, double wall_now, double wall_spent,
                               const core::StaticResult* state, double solver_time) {
  using O = LockstepDriver::Outcome;
  solver_time_ = solver_time;
  window_.wall += wall_spent;
  window_.steps += r.report.steps;
  window_.cuts += r.report.cuts;
  window_.fallback += r.report.fallback_steps;
  window_.newton += r.report.newton_iterations;
  using R = LockstepDriver::Reason;
  namespace k = lockstep_keys;
  switch (r.outcome) {
    case O::Dropped:
      if (r.start_failed) {
        ++window_.start_failures;
        tally_.count(k::kStartFailed);
        setError(wall_now, r.message);
      } else {
        ++window_.dropped;
        tally_.count(r.reason == R::NonFinite   ? k::kNonFinite
                     : r.reason == R::OffPlane  ? k::kOffPlane
                     : r.reason == R::SameStamp ? k::kSameStamp
                     : r.reason == R::StampBack ? k::kStampBack
                     : r.reason == R::Jump      ? k::kJump
                                                : k::kOther);
        last_drop_ = r.message;
        setError(wall_now, r.message);
      }
      break;
    case O::Advanced: window_.sim += r.advanced; break;
    case O::Reinitialised:
      ++window_.reinit;
      tally_.count(r.reason == R::LoopBack ? k::kReinitLoop
                   : r.reason == R::Gap    ? k::kReinitGap
                   : r.reason == R::Jumps  ? k::kReinitJumps
                                           : k::kReinitRequest);
      last_reinit_ = r.message;
      break;
    case O::Failed:
      ++window_.failures;
      window_.sim += r.advanced;
      tally_.count(k::kFailedKept);
      last_failure_ = r.message;
      setError(wall_now, lineName() + ": " + r.message);
      break;
    case O::RecoveredFailure:
      ++window_.failures;
      tally_.count(k::kReinitFailures);
      last_failure_ = r.message + "; re-initialised from statics at the sample";
      setError(wall_now, lineName() + ": " + r.message);
      break;
    case O::Started: break;
  }
  if (r.publish && state && !state->nodes.empty()) {
    ++window_.published;
    double tmin = state->nodes.front().tension;
    for (const auto& n : state->nodes) tmin = std::min(tmin, n.tension);
    const bool slack = tmin <= 0.0;
    if (slack && !slack_now_) ++window_.slack_events;
    slack_now_ = slack;
    have_state_ = true;
    min_tension_ = tmin;
    top_tension_ = state->nodes.back().tension;
    max_tension_ = state->nodes.front().tension;
    utilization_ = -1.0;
    for (const auto& n : state->nodes) {
      max_tension_ = std::max(max_tension_, n.tension);
      const std::size_t seg = static_cast<std::size_t>(n.segment);
      if (seg < options_.segment_mbl.size() && options_.segment_mbl[seg] > 0.0)
        utilization_ = std::max(utilization_, n.tension / options_.segment_mbl[seg]);
    }
    peak_utilization_ = std::max(peak_utilization_, utilization_);
  }
}

LockstepMonitor::Summary LockstepMonitor::summarise(double wall_now) {
  Summary s;
  const Counts w = window_;
  add(total_, w);
  window_ = Counts();

  std::vector<std::string> errors, warnings;
  if (w.failures > 0)
    errors.push_back(std::to_string(w.failures) + " solver failure(s) on " + lineName() + ": " + last_failure_);
  if (w.start_failures > 0)
    errors.push_back("statics failed at the requested top " + std::to_string(w.start_failures) + " time(s)");
  const double quiet = wall_now - last_motion_wall_;
  if (quiet > options_.motion_timeout)
    warnings.push_back(ever_received_ ? "no motion for " + fmt(quiet, "%.1f") + " s (last good state kept)"
                                      : "waiting for motion (none received yet)");
  if (w.dropped + w.rejected > 0)
    warnings.push_back(std::to_string(w.dropped + w.rejected) + " motion sample(s) dropped: " + last_drop_);
  if (w.reinit > 0) warnings.push_back(std::to_string(w.reinit) + " re-initialisation(s): " + last_reinit_);
  if (notes_warn_ > 0)
    warnings.push_back(std::to_string(notes_warn_) + " sample(s) with a bad unused field accepted: " + last_note_);
  if (requests_rejected_ > 0)
    warnings.push_back(std::to_string(requests_rejected_) + " service request(s) rejected: " + last_request_);
  notes_warn_ = 0;
  requests_rejected_ = 0;
  if (w.cuts > 0) warnings.push_back(std::to_string(w.cuts) + " step cut(s)");
  const double rtf = w.wall > 0.0 ? w.sim / w.wall : 0.0;
  if (w.sim > 0.0 && rtf < options_.min_real_time_factor)
    warnings.push_back("real-time factor " + fmt(rtf, "%.2f") + " < " + fmt(options_.min_real_time_factor, "%g"));
  if (slack_now_) warnings.push_back("line slack (min tension " + fmt(min_tension_, "%.1f") + " N)");
  if (have_state_ && utilization_ > options_.max_utilization)
    warnings.push_back("utilization " + fmt(utilization_, "%.3f") + " > " + fmt(options_.max_utilization, "%g") +
                       " (max tension " + fmt(max_tension_, "%.1f") + " N)");

  std::string msg;
  auto join = [&msg](const std::vector<std::string>& v) {
    for (const auto& x : v) msg += (msg.empty() ? "" : "; ") + x;
  };
  join(errors);
  join(warnings);
  s.level = !errors.empty() ? ERROR : !warnings.empty() ? WARN : OK;
  if (s.level == OK)
    msg = w.sim > 0.0 ? "running, real-time factor " + fmt(rtf, "%.1f") : "running";

  s.message = msg;
  const double total_rtf = total_.wall > 0.0 ? total_.sim / total_.wall : 0.0;
  auto kv = [&s](const std::string& k, const std::string& v) { s.values.emplace_back(k, v); };
  kv("real-time factor (window)", w.sim > 0.0 ? fmt(rtf) : "-");
  kv("real-time factor (total)", total_.sim > 0.0 ? fmt(total_rtf) : "-");
  kv("solver wall time (window) [s]", fmt(w.wall));
  kv("simulated time advanced (window) [s]", fmt(w.sim));
  kv("solver time [s]", fmt(solver_time_));
  kv("motion samples (window)", std::to_string(w.samples));
  kv("states published (window)", std::to_string(w.published));
  kv("motion samples (window / total)", std::to_string(w.samples) + " / " + std::to_string(total_.samples));
  kv("states published (window / total)", std::to_string(w.published) + " / " + std::to_string(total_.published));
  kv("samples dropped (window / total)", std::to_string(w.dropped + w.rejected) + " / " +
                                             std::to_string(total_.dropped + total_.rejected));
  kv("re-initialisations (window / total)", std::to_string(w.reinit) + " / " + std::to_string(total_.reinit));
  kv("solver failures (window / total)", std::to_string(w.failures) + " / " + std::to_string(total_.failures));
  kv("steps (window / total)", std::to_string(w.steps) + " / " + std::to_string(total_.steps));
  kv("step cuts (window / total)", std::to_string(w.cuts) + " / " + std::to_string(total_.cuts));
  kv("fallback steps (window / total)", std::to_string(w.fallback) + " / " + std::to_string(total_.fallback));
  kv("Newton iterations (window / total)", std::to_string(w.newton) + " / " + std::to_string(total_.newton));
  kv("Newton iterations per step (window)", w.steps > 0 ? fmt(static_cast<double>(w.newton) / w.steps) : "-");
  tally_.closeWindow(s.values);
  kv("slack events (total)", std::to_string(total_.slack_events));
  kv("slack now", slack_now_ ? "true" : "false");
  kv("min tension [N]", have_state_ ? fmt(min_tension_, "%.6g") : "-");
  kv("top tension [N]", have_state_ ? fmt(top_tension_, "%.6g") : "-");
  kv("max tension [N]", have_state_ ? fmt(max_tension_, "%.6g") : "-");
  kv("utilization (T / MBL)", have_state_ && utilization_ >= 0.0 ? fmt(utilization_, "%.4g") : "-");
  kv("utilization (max, total)", peak_utilization_ >= 0.0 ? fmt(peak_utilization_, "%.4g") : "-");
  kv("seconds since last motion [s]", ever_received_ ? fmt(quiet, "%.3g") : "-");
  kv("last error", last_error_.empty() ? "none" : last_error_);
  kv("last error age [s]", last_error_wall_ >= 0.0 ? fmt(wall_now - last_error_wall_, "%.3g") : "-");
  return s;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
