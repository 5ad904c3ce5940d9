// Health of the lockstep dynamic mode, summarised for diagnostic_msgs (ROS-free: the node feeds
// it wall-clock seconds and driver results, and turns the summary into a DiagnosticStatus).
//
// One summary per diagnostics period ("window"): real-time factor, step cuts, Newton iterations,
// slack events (a published state whose min tension <= 0 after one that was not), dropped and
// re-initialised samples, the last error. Levels (docs/ros_interface.md, "Diagnostics"):
//   ERROR  the solver failed in the window (the last good state kept and published, or after
//          failures in a row re-initialised; the message names the line), or statics could not
//          be solved at a requested top (run not started / sample dropped)
//   WARN   no motion for more than `motion_timeout` (silent source, or none yet); input dropped
//          (NaN, old stamp, unknown frame, jump); re-initialised (bag loop, gap, reset); step cuts;
//          real-time factor below `min_real_time_factor`; the line is slack now; the utilization
//          (largest tension over the material's minimum breaking load, Material::mbl) of the
//          published state is above `max_utilization`
//   OK     otherwise
// The message lists the reasons of the level, most severe first.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/ros/nodes/event_tally.hpp"
#include "mooring_dynamics/ros/nodes/lockstep.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

struct MonitorOptions {
  double motion_timeout = 1.0;        ///< [s, wall] no motion for longer than this: WARN (silent source)
  double min_real_time_factor = 1.0;  ///< window real-time factor below this: WARN (cannot keep up)
  std::string line_name;              ///< the line, named in failure messages
  /// Utilization (T / MBL) of the published state above this: WARN. The default is the inverse of
  /// the intact safety factor 1.67 that mooring design codes ask of a dynamic analysis.
  double max_utilization = 0.6;
  /// Minimum breaking load of each segment's material [N] (index = NodeState::segment); 0 or a
  /// missing entry: none given, no utilization there.
  std::vector<double> segment_mbl;
};

/// Keys of the counts in the diagnostics values, each reported as "<key> (window / total)".
namespace lockstep_keys {
constexpr const char* kNonFinite = "dropped: non-finite position";
constexpr const char* kZeroStamp = "dropped: zero stamp";
constexpr const char* kUnknownFrame = "dropped: unknown frame";
constexpr const char* kOffPlane = "dropped: off the plane y = 0";
constexpr const char* kSameStamp = "dropped: same stamp";
constexpr const char* kStampBack = "dropped: stamp back";
constexpr const char* kJump = "dropped: jump";
constexpr const char* kStartFailed = "dropped: statics failed at the sample";
constexpr const char* kNoTransform = "no transform (tf source)";
constexpr const char* kGnssRejected = "dropped: GNSS input rejected";  ///< fixes and headings, by reason in the "gnss ..." values
constexpr const char* kOrientationNonFinite = "accepted: non-finite orientation (unused)";
constexpr const char* kOrientationNonUnit = "accepted: non-unit orientation (unused)";
constexpr const char* kReinitLoop = "re-initialised: bag loop";
constexpr const char* kReinitGap = "re-initialised: gap";
constexpr const char* kReinitJumps = "re-initialised: jumps";
constexpr const char* kReinitRequest = "re-initialised: reset or request";
constexpr const char* kReinitFailures = "re-initialised: solver failures";
constexpr const char* kFailedKept = "solver failed: last good state kept";
constexpr const char* kRequestRejected = "service requests rejected";
constexpr const char* kOther = "dropped: other";
}  // namespace lockstep_keys

class LockstepMonitor {
 public:
  enum Level { OK = 0, WARN = 1, ERROR = 2 };  // values of diagnostic_msgs::DiagnosticStatus levels
  struct Summary {
    Level level = OK;
    std::string message;
    std::vector<std::pair<std::string, std::string>> values;  ///< key (with unit), value
  };

  explicit LockstepMonitor(const MonitorOptions& options = MonitorOptions(), double wall_now = 0.0);

  /// A motion message arrived at wall time `wall_now` (before any check).
  void onMotionReceived(double wall_now);
  /// Input rejected before the driver (bad frame, tf lookup failed, NaN): a WARN reason, counted
  /// under `key` (lockstep_keys).
  void onInputRejected(double wall_now, const std::string& message, const std::string& key = lockstep_keys::kOther);
  /// A sample accepted although a field the node does not use is bad (the pose's orientation):
  /// counted under `key`; a WARN reason when `warn`.
  void onInputNote(double wall_now, const std::string& message, const std::string& key, bool warn);
  /// A service request refused for bad values: a WARN reason, counted.
  void onRequestRejected(double wall_now, const std::string& message);
  /// A driver result; `wall_spent` [s] the wall time of the call; `state` the published state (if
  /// any); `solver_time` [s] the solver's time after the call.
  void onResult(const LockstepDriver::Result& r, double wall_now, double wall_spent,
                const core::StaticResult* state, double solver_time);

  /// Summary of the window since the last call (and totals); starts a new window.
  Summary summarise(double wall_now);

  long slackEvents() const { return total_.slack_events + window_.slack_events; }
  const EventTally& tally() const { return tally_; }
  double secondsSinceMotion(double wall_now) const { return wall_now - last_motion_wall_; }
  bool silent(double wall_now) const { return secondsSinceMotion(wall_now) > options_.motion_timeout; }
  bool everReceived() const { return ever_received_; }

 private:
  struct Counts {
    long samples = 0, published = 0, dropped = 0, rejected = 0, reinit = 0, failures = 0, start_failures = 0;
    long steps = 0, cuts = 0, newton = 0, slack_events = 0, fallback = 0;
    double sim = 0.0, wall = 0.0;  ///< solver time advanced, wall time spent [s]
  };
  static void add(Counts& a, const Counts& b);
  void setError(double wall_now, const std::string& message);
  /// "line <name>" (or "the line" without a name).
  std::string lineName() const { return options_.line_name.empty() ? "the line" : "line " + options_.line_name; }

  MonitorOptions options_;
  Counts window_, total_;
  EventTally tally_;
  long notes_warn_ = 0, requests_rejected_ = 0;  ///< in the window
  std::string last_note_, last_request_;
  double last_motion_wall_ = 0.0;
  bool ever_received_ = false;
  std::string last_error_, last_drop_, last_reinit_, last_failure_;
  double last_error_wall_ = -1.0;
  bool slack_now_ = false;
  bool have_state_ = false;
  double min_tension_ = 0.0, top_tension_ = 0.0, solver_time_ = 0.0;
  double max_tension_ = 0.0;          ///< largest tension of the last published state [N]
  double utilization_ = -1.0;         ///< its utilization (< 0: no MBL given) [-]
  double peak_utilization_ = -1.0;    ///< largest utilization over the run [-]
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
