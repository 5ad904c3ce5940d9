// Lockstep driver of a moored vessel (DESIGN.md section 6): timestamped poses of the vessel in,
// the system of lines advanced to each stamp, the wrench out. ROS-free, so that the node (live or
// replaying a bag) and `cable_sim dynamic` on a motion table feed the same samples through the
// same code and get the same bits.
//
// Between two accepted samples the vessel follows RigidSegment: from poses alone the origin on the
// straight line and the orientation turning about one axis at a constant rate; when both samples
// carry a body twist (an odometry source, or a motion table with velocity columns) the Hermite
// path that meets both poses and both velocities (rigid_pose.hpp). Velocities are the exact
// derivatives of the path either way.
// Policy, per sample at time t [s] (any fixed epoch) and pose (world frame):
//  * a non-finite position or quaternion, or a quaternion whose norm is off 1 by more than
//    kUnitQuaternionTolerance: dropped (counted), state kept; an accepted quaternion is normalized;
//  * first sample: the run starts from the statics at the file's pose if the sample is within
//    start_tolerance (and start_angle_tolerance) of it, else from the statics re-solved at the
//    sample's pose; solver time 0 = this sample;
//  * time not increasing: dropped; going back by more than loop_back (a bag loop): restarted;
//  * a gap over max_gap since the last accepted sample: restarted at the sample (motion unknown);
//  * a jump implying a speed over max_speed: dropped; jumps_to_reinit in a row: restarted there;
//  * a line that fails (smallest step cut, or its group's point iteration), with
//    restart_failed_lines (the default): that line alone (with the lines sharing a free point
//    with it: its group, SystemDynamics) restarts from statics at the pose at the end of the
//    failed step, the others go on (Outcome::LinesRestarted, the lines named in failed_lines and
//    the message);
//  * a step that cannot be taken (a failed line without restart_failed_lines, or its group's
//    statics failing too): the last good state is kept (every line stays at the last converged
//    step) and published for this sample (Failed, the failed line named in the message); the
//    next sample continues from it, the vessel moving on from where it was at that step.
//    failures_to_reinit failures in a row: every line restarted from statics at the sample's
//    pose (RecoveredFailure);
//  * with solve_interval > 0, an accepted sample less than solve_interval after the last solved
//    one is held (Outcome::Held, counted): not a solver step, answered with the last solve's
//    state (the wrench of solver time lastSolvedTime() <= t); the next sample at least
//    solve_interval after the last solved one is solved, the vessel moving on RigidSegment from
//    the last solved sample to it (the held poses between are not on the path). For sources
//    faster than the solver can follow (a 1 kHz simulator: docs/ros_interface.md).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

namespace mooring_dynamics {
namespace core {

struct VesselLockstepOptions {
  double start_tolerance = 0.01;         ///< [m] first sample this close to the file's pose: its statics are the start
  double start_angle_tolerance = 1e-3;   ///< [rad] the same for the orientation
  double loop_back = 1.0;                ///< [s] time going back by more than this restarts (bag loop)
  double max_gap = 5.0;                  ///< [s] a longer gap restarts; <= 0: never
  double max_speed = 50.0;               ///< [m/s] a faster jump of the origin is dropped; <= 0: no check
  int jumps_to_reinit = 3;               ///< this many jumps in a row restart at the new pose
  int failures_to_reinit = 3;            ///< this many failed samples in a row restart from statics
  bool restart_failed_lines = true;      ///< a failed line's group restarts alone (else the step fails)
  int threads = 1;                       ///< threads that advance the lines (>= 1; same bits for any)
  /// [s] >= 0: samples closer than this to the last solved one (less kIntervalTolerance) are
  /// held, not solved (0: every accepted sample is solved). The problem's dt is the natural
  /// choice for a fast source.
  double solve_interval = 0.0;
  /// [s] stamps rounded to the nanosecond and differenced in double land a hair short of the
  /// interval (0.0999999999 s for 0.1 s): within this they count as a whole interval, so that a
  /// 1 kHz source is solved every 100 ms and not every 101 (one step of dt and one of 1 ms).
  static constexpr double kIntervalTolerance = 1e-6;
  /// Empty when valid, else the field, value and constraint.
  std::string validate() const;
};

class VesselLockstep {
 public:
  enum class Outcome { Started, Advanced, LinesRestarted, Reinitialised, Failed, RecoveredFailure, Held, Dropped };
  /// Why a sample was dropped, the run restarted or failed (counted apart in the node's diagnostics).
  enum class Reason {
    None, NonFinitePosition, NonFiniteOrientation, NonUnitOrientation, BadTwist, NonFiniteTime, SameStamp, StampBack, Jump,
    StartFailed, LoopBack, Gap, Jumps, Reset, SolverFailed, Behind
  };
  struct Result {
    Outcome outcome = Outcome::Dropped;
    Reason reason = Reason::None;
    /// a new state (wrench, lines) is available; false for Held (the last solve's state answers)
    bool publish = false;
    std::string message;      ///< what happened; empty for a plain Advanced
    /// LinesRestarted: the lines (indices, line order) that failed and restarted from statics,
    /// with the other lines of their groups.
    std::vector<std::size_t> failed_lines;
  };

  /// Solves the system's statics at its file pose at once (throws std::invalid_argument for an
  /// invalid system or options, std::runtime_error when those statics fail).
  VesselLockstep(const SystemProblem& system, const DynamicOptions& dynamics, const VesselLockstepOptions& options = {});
  ~VesselLockstep();

  /// One sample: time t [s], pose (world frame) and, optionally, the body twist at t (body frame,
  /// REP 105: as nav_msgs/Odometry's twist; converted with the sample's normalized orientation).
  /// A non-finite twist drops the sample like a non-finite pose.
  Result onSample(double t, const RigidPose& pose, const BodyTwist* twist = nullptr);
  /// Restart from statics at the last accepted pose (Dropped before the first sample).
  Result reset();
  /// Restart from statics at this sample (time t [s], pose in the world frame), for a caller
  /// whose solver has fallen too far behind its source to follow it (Reinitialised, Reason::Behind,
  /// `why` as the message). A bad pose or time is dropped as by onSample.
  Result restartAt(double t, const RigidPose& pose, const std::string& why);

  bool started() const { return started_; }
  /// Time of the last accepted sample (solved or held) [s], of the last solved one [s], and the
  /// solver's time (0 at the start) [s].
  double lastTime() const { return accepted_t_; }
  double lastSolvedTime() const { return last_t_; }
  double solverTime() const;
  const SystemDynamics& dynamics() const { return *sim_; }
  const SystemProblem& system() const { return system_; }
  /// Let go the end of the line named `line` now (issue 21): from the next sample's step on it is
  /// a free end that pulls nothing (SystemDynamics::releaseLineEnd). Empty when done, else why
  /// not ("line = x: no line of that name (lines: a, b)", "... let go already"). A
  /// re-initialisation (reset, a loop in the stream, repeated failures) starts every line
  /// intact from statics again.
  std::string releaseLine(const std::string& line, LineEvent::End end, const std::string& cause);
  /// Command the winch at a line's fairlead (DynamicSolver3D::commandWinch: to `target` [m] at
  /// |rate| [m/s], or at `rate` until its limit with target NaN). Empty when done (what the
  /// winch will do in `note`), else why not.
  std::string winchLine(const std::string& line, double rate, double target, std::string& note);
  /// The unstretched length of each line now, in the problem's order [m] (empty before the start).
  std::vector<double> lineLengths() const;
  /// The wrench now (state of the last published sample), and every line now.
  VesselWrench wrench() const { return sim_->vesselWrench(); }
  std::vector<StaticResult> lines() const;
  long dropped() const { return dropped_; }
  /// Samples held (solve_interval) since construction.
  long held() const { return held_; }
  /// TEST HOOK (failure injection; tests only): SystemDynamics::setFailureInjection on the run,
  /// kept across restarts; `t1` is solver time (0 at the run's start).
  void setFailureInjection(std::function<bool(std::size_t line, double t1)> fail);

 private:
  Result start(double t, const RigidPose& pose, const BodyTwist* twist, Outcome outcome, const std::string& why);
  /// Keeps the last accepted sample (pose, and its world-frame velocities when it had a twist).
  void remember(double t, const RigidPose& pose, const BodyTwist* twist);
  /// `r` with `reason` unless it has one already (StartFailed).
  static Result withReason(Result r, Reason reason);

  SystemProblem system_;
  DynamicOptions dynamics_;
  VesselLockstepOptions options_;
  std::unique_ptr<SystemDynamics> sim_;
  std::function<bool(std::size_t, double)> fail_hook_;
  bool pristine_ = true;  ///< sim_ is the file pose's static start, not advanced
  bool started_ = false;
  double t0_ = 0.0, last_t_ = 0.0;  ///< first sample of the run, last solved sample [s]
  double accepted_t_ = 0.0;         ///< last accepted sample, solved or held [s]
  RigidPose last_pose_;
  bool last_has_twist_ = false;
  RigidMotion last_motion_;  ///< the last sample's pose and world velocities (when it had a twist)
  int jumps_ = 0;
  int failures_ = 0;  ///< consecutive failed samples
  long dropped_ = 0;
  long held_ = 0;
};

const char* toString(VesselLockstep::Outcome o);

}  // namespace core
}  // namespace mooring_dynamics
