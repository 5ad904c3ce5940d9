// Health of the moored-vessel lockstep mode (VesselNode), summarised for diagnostic_msgs. ROS-free:
// the node feeds it wall-clock seconds and core::VesselLockstep results, and turns the summary into
// DiagnosticStatus messages (one overall, one per line).
//
// One summary per diagnostics period ("window"). Levels (docs/ros_interface.md, "Moored vessel"):
//   overall  ERROR  a line failed in the window (the line is named): it restarted alone from
//                   statics with its group while the others went on (~restart_failed_lines); or
//                   the step could not be taken and VesselLockstep kept the last good state and
//                   published it; or after failures in a row every line restarted from statics
//                   at that sample's pose
//            WARN   no motion for more than motion_timeout; samples dropped (bad pose, NaN or
//                   non-unit quaternion, stamp not increasing, jump, no transform); restarted
//                   (bag loop, gap, reset); real-time factor below min_real_time_factor; a line's
//                   utilization (largest tension over its material's minimum breaking load,
//                   Material::mbl) in the last published state above max_utilization (named)
//            OK     otherwise
//   per line ERROR  this line failed in the window (Result::failed_lines, or named in
//                   VesselLockstep's message as "line <name>:"); WARN its utilization is above
//                   max_utilization; else OK; values: top tension, max tension, utilization (now
//                   and the largest so far), converged, failures.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/model/utilization.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/nodes/event_tally.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

struct VesselMonitorOptions {
  double motion_timeout = 1.0;        ///< [s, wall] no motion for longer than this: WARN
  double min_real_time_factor = 1.0;  ///< window real-time factor below this: WARN
  /// A line's utilization (T / MBL) in the published state above this: WARN (as the line node's
  /// LockstepMonitor). The default is the inverse of the intact safety factor 1.67 that mooring
  /// design codes ask of a dynamic analysis.
  double max_utilization = 0.6;
};

/// Keys of the counts in the overall status's values, each "<key> (window / total)".
namespace vessel_keys {
constexpr const char* kNonFinitePosition = "dropped: non-finite position";
constexpr const char* kNonFiniteOrientation = "dropped: non-finite orientation";
constexpr const char* kNonUnitOrientation = "dropped: non-unit orientation";
constexpr const char* kNonFiniteTime = "dropped: non-finite time";
constexpr const char* kBadTwist = "dropped: bad twist";
constexpr const char* kZeroStamp = "dropped: zero stamp";
constexpr const char* kUnknownFrame = "dropped: unknown frame";
constexpr const char* kGnssRejected = "dropped: GNSS input rejected";  ///< fixes and headings, by reason in the "gnss ..." values
constexpr const char* kSameStamp = "dropped: same stamp";
constexpr const char* kStampBack = "dropped: stamp back";
constexpr const char* kJump = "dropped: jump";
constexpr const char* kStartFailed = "dropped: statics failed at the pose";
constexpr const char* kRestartLoop = "restarted: bag loop";
constexpr const char* kRestartGap = "restarted: gap";
constexpr const char* kRestartJumps = "restarted: jumps";
constexpr const char* kRestartReset = "restarted: reset";
constexpr const char* kRestartBehind = "restarted: solver behind";  ///< decimated mode (~max_solver_lag)
constexpr const char* kRestartFailures = "restarted: line failures";
constexpr const char* kFailedKept = "line failed: last good state kept";
constexpr const char* kLinesRestarted = "line failed: restarted alone";
constexpr const char* kRequestRejected = "service requests rejected";
constexpr const char* kOther = "dropped: other";
}  // namespace vessel_keys

class VesselMonitor {
 public:
  enum Level { OK = 0, WARN = 1, ERROR = 2 };  // values of diagnostic_msgs::DiagnosticStatus levels
  struct Status {
    Level level = OK;
    std::string line;     ///< "" for the overall status, else the line's name
    std::string message;
    std::vector<std::pair<std::string, std::string>> values;  ///< key (with unit), value
  };

  VesselMonitor(std::vector<std::string> line_names, const VesselMonitorOptions& options = {}, double wall_now = 0.0);

  /// A pose message arrived at wall time `wall_now` (before any check).
  void onMotionReceived(double wall_now);
  /// A sample rejected by the node before VesselLockstep (zero stamp, no transform to ~frame_id),
  /// counted under `key` (vessel_keys).
  void onInputRejected(double wall_now, const std::string& message, const std::string& key = vessel_keys::kOther);
  /// A service request refused for bad values (or failing): a WARN reason, counted.
  void onRequestRejected(double wall_now, const std::string& message);
  const EventTally& tally() const { return tally_; }
  /// A VesselLockstep result. `wall_spent` [s] the wall time of the call, `advanced` [s] the solver
  /// time it covered (Advanced), `top_tension` the lines' top tensions [N] when r.publish, and
  /// `solver_time` [s] the solver's time after the call. `peaks`, when given with r.publish, holds
  /// each line's largest tension and utilization in the published state (core::tensionPeak).
  void onResult(const core::VesselLockstep::Result& r, double wall_now, double wall_spent, double advanced,
                const std::vector<double>* top_tension, double solver_time,
                const std::vector<core::TensionPeak>* peaks = nullptr);

  /// Each line's fallback steps so far (SystemDynamics::lineFallbackSteps, line order): reported
  /// per line and, over all lines, as "fallback steps: 3 on bow_port_2" (a value, not a warning:
  /// a storm's slack-and-snap steps are expected; docs/method.md "Slack and snap").
  void onFallbackSteps(const std::vector<long>& per_line_total);
  /// ~solve_interval > 0 (decimated mode, docs/ros_interface.md): a pose answered at once from
  /// the last solve; `thinned` poses skipped when the solver fell too far behind (and restarted
  /// from statics at the newest); the solver's lag (newest answered stamp less the last one the
  /// solver took) [s].
  void onAnswered() { ++window_.answered; }
  void onThinned(long thinned) { window_.thinned += thinned; }
  void onSolverLag(double lag) { solver_lag_ = lag; }

  /// Overall status then one per line, for the window since the last call; starts a new window.
  std::vector<Status> summarise(double wall_now);

  /// Samples dropped or rejected so far (VesselLockstep's and the node's), failures so far.
  long droppedTotal() const { return total_.dropped + window_.dropped; }
  long failuresTotal() const { return total_.failures + window_.failures; }
  /// Index of the line a failure message names ("line <name>:"), or -1.
  int failedLine(const std::string& message) const;
  const std::string& lastEvent() const { return last_event_; }
  double secondsSinceMotion(double wall_now) const { return wall_now - last_motion_wall_; }
  bool silent(double wall_now) const { return secondsSinceMotion(wall_now) > options_.motion_timeout; }
  bool everReceived() const { return ever_received_; }

 private:
  struct Counts {
    long samples = 0, published = 0, dropped = 0, restarts = 0, failures = 0;
    long held = 0, answered = 0, thinned = 0;  ///< decimated mode (onAnswered, onThinned)
    double sim = 0.0, wall = 0.0;  ///< solver time advanced, wall time spent [s]
  };
  static void add(Counts& a, const Counts& b);
  /// Line i's utilization in the last published state is above options_.max_utilization.
  bool overUtilized(std::size_t i) const;
  /// "utilization 0.700 > 0.6 (max tension 900.0 N)" for line i.
  std::string utilizationText(std::size_t i) const;

  std::vector<std::string> names_;
  VesselMonitorOptions options_;
  Counts window_, total_;
  EventTally tally_;
  long requests_rejected_ = 0;  ///< in the window
  std::string last_request_;
  bool last_failure_kept_ = true;  ///< the last failure kept the last good state (else: restarted)
  std::vector<long> line_failures_window_, line_failures_total_;
  std::vector<long> line_fallback_total_;
  std::vector<std::string> line_last_failure_;
  std::vector<double> top_tension_, max_top_tension_;
  bool have_state_ = false;
  double solver_lag_ = -1.0;  ///< [s], < 0: not in decimated mode
  bool have_peaks_ = false;           ///< max_tension_ and utilization_ hold a published state
  std::vector<double> max_tension_;   ///< largest tension along each line in that state [N]
  std::vector<double> utilization_;   ///< its utilization (< 0: no MBL given) [-]
  std::vector<double> peak_utilization_;  ///< largest utilization so far (< 0: none) [-]
  double last_motion_wall_ = 0.0;
  bool ever_received_ = false;
  std::string last_event_, last_drop_, last_restart_, last_failure_;
  double solver_time_ = 0.0;
};

/// True when `status_name` is the run status (not a per-line one) of the node `node` (resolved name,
/// e.g. "/mooring_dynamics_node"): "mooring_dynamics: <node> lockstep" (single line),
/// "mooring_dynamics: <node> vessel lockstep" (moored vessel) or "mooring_dynamics: <node> system
/// lockstep" (system of lines). demo_monitor reads the real-time factor from it.
bool isRunStatusName(const std::string& status_name, const std::string& node);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
