// The vessel node's diagnostics: the snapshot of line events, lengths and winch rates taken after
// each solve (and service), and the /diagnostics timer that reports it with the monitor's
// statuses without waiting for a solve in progress. The node itself: vessel_node.cpp.
#include <diagnostic_msgs/DiagnosticArray.h>

#include "mooring_dynamics/ros/nodes/vessel_node.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {
constexpr double kWarnPeriod = 5.0;  // [s] throttle of repeated warnings (as vessel_node.cpp)
}  // namespace

void VesselNode::snapshotForDiagnostics() {
  // Copied here, swapped in under the monitor's lock (held briefly: the receiving thread takes it).
  std::vector<core::LineEventRecord> events = lockstep_->dynamics().lineEvents();
  std::vector<double> lengths = lockstep_->lineLengths(), rates(system_.lines.size(), 0.0);
  for (std::size_t i = 0; i < system_.lines.size(); ++i) rates[i] = lockstep_->dynamics().lineWinchRate(i);
  std::lock_guard<std::mutex> l(monitor_mutex_);
  diag_events_.swap(events);
  diag_lengths_.swap(lengths);
  diag_rates_.swap(rates);
}

namespace {
/// A system line's unstretched length in the file [m].
double fileLength(const core::SystemLine& l) {
  double L = 0.0;
  for (const core::Segment& g : l.segments) L += g.length;
  return L;
}
}  // namespace

void VesselNode::onDiagnosticsTimer(const ros::WallTimerEvent&) {
  // Not on solver_mutex_: the line events and lengths come from the last solve's snapshot, so
  // that the timer never waits for a solve in progress (decimated mode answers poses meanwhile).
  bool answered = false;
  ros::Time newest;
  if (decimated_) {
    std::lock_guard<std::mutex> a(answer_mutex_);
    answered = answered_any_;
    newest = last_answered_;
  }
  std::unique_lock<std::mutex> monitor(monitor_mutex_);
  // The solver's lag: the newest answered pose's stamp less the last one the solver took.
  if (decimated_ && answered && have_processed_) monitor_->onSolverLag(std::max(0.0, (newest - last_processed_).toSec()));
  const double now = wallNow();
  if (monitor_->silent(now) && monitor_->everReceived())
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: no vessel pose for %.1f s; last good state kept (latched)",
                      monitor_->secondsSinceMotion(now));
  std::vector<VesselMonitor::Status> statuses = monitor_->summarise(now);
  if (gnss_ && !statuses.empty())
    for (const auto& kv : gnss_->values()) statuses.front().values.push_back(kv);
  // Line events (a line let go or parted): counted, the last one shown, and a warning.
  const std::vector<core::LineEventRecord>& events = diag_events_;
  if (!statuses.empty()) {
    VesselMonitor::Status& o = statuses.front();
    o.values.emplace_back("line events", std::to_string(events.size()));
    // Lines a winch paid out or hauls in: their length and rate.
    for (std::size_t i = 0; i < diag_lengths_.size() && i < diag_rates_.size(); ++i)
      if (diag_lengths_[i] != fileLength(system_.lines[i]) || diag_rates_[i] != 0.0)
        o.values.emplace_back("line length " + system_.lines[i].name,
                              formatNumber(diag_lengths_[i]) + " m, winch " + formatNumber(diag_rates_[i]) + " m/s");
    if (!events.empty()) {
      o.values.emplace_back("last line event", core::lineEventText(events.back()));
      if (o.level < VesselMonitor::WARN) {
        o.level = VesselMonitor::WARN;
        o.message = "line event: " + core::lineEventText(events.back());
      }
    }
  }
  monitor.unlock();
  diag_pub_.publish(toDiagnostics(statuses, ros::this_node::getName(), "vessel lockstep", system_.name, ros::Time::now()));
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
