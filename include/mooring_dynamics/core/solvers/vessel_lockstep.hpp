// Lockstep driver of a moored vessel (DESIGN.md section 6): timestamped poses of the vessel in,
// the system of lines advanced to each stamp, the wrench out. ROS-free, so that the node (live or
// replaying a bag) and `cable_sim dynamic` on a motion table feed the same samples through the
// same code and get the same bits.
//
// Between two accepted samples the vessel follows RigidSegment (origin on the straight line,
// orientation turning about one axis at a constant rate; velocities the exact derivatives).
// Policy, per sample at time t [s] (any fixed epoch) and pose (world frame):
//  * a non-finite position or quaternion, or a quaternion whose norm is off 1 by more than
//    kUnitQuaternionTolerance: dropped (counted), state kept; an accepted quaternion is normalized;
//  * first sample: the run starts from the statics at the file's pose if the sample is within
//    start_tolerance (and start_angle_tolerance) of it, else from the statics re-solved at the
//    sample's pose; solver time 0 = this sample;
//  * time not increasing: dropped; going back by more than loop_back (a bag loop): restarted;
//  * a gap over max_gap since the last accepted sample: restarted at the sample (motion unknown);
//  * a jump implying a speed over max_speed: dropped; jumps_to_reinit in a row: restarted there;
//  * a line that fails (smallest step cut): the last good state is kept (every line stays at
//    the last converged step) and published for this sample (Failed, the failed line named in
//    the message); the next sample continues from it, the vessel moving on from where it was at
//    that step. failures_to_reinit failures in a row: restarted from statics at the sample's pose
//    (RecoveredFailure).
#pragma once

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
  int threads = 1;                       ///< threads that advance the lines (>= 1; same bits for any)
  /// Empty when valid, else the field, value and constraint.
  std::string validate() const;
};

class VesselLockstep {
 public:
  enum class Outcome { Started, Advanced, Reinitialised, Failed, RecoveredFailure, Dropped };
  /// Why a sample was dropped, the run restarted or failed (counted apart in the node's diagnostics).
  enum class Reason {
    None, NonFinitePosition, NonFiniteOrientation, NonUnitOrientation, NonFiniteTime, SameStamp, StampBack, Jump,
    StartFailed, LoopBack, Gap, Jumps, Reset, SolverFailed
  };
  struct Result {
    Outcome outcome = Outcome::Dropped;
    Reason reason = Reason::None;
    bool publish = false;     ///< a new state (wrench, lines) is available
    std::string message;      ///< what happened; empty for a plain Advanced
  };

  /// Solves the system's statics at its file pose at once (throws std::invalid_argument for an
  /// invalid system or options, std::runtime_error when those statics fail).
  VesselLockstep(const SystemProblem& system, const DynamicOptions& dynamics, const VesselLockstepOptions& options = {});
  ~VesselLockstep();

  Result onSample(double t, const RigidPose& pose);
  /// Restart from statics at the last accepted pose (Dropped before the first sample).
  Result reset();

  bool started() const { return started_; }
  /// Time of the last accepted sample [s] and the solver's time (0 at the start) [s].
  double lastTime() const { return last_t_; }
  double solverTime() const;
  const SystemDynamics& dynamics() const { return *sim_; }
  const SystemProblem& system() const { return system_; }
  /// The wrench now (state of the last published sample), and every line now.
  VesselWrench wrench() const { return sim_->vesselWrench(); }
  std::vector<StaticResult> lines() const;
  long dropped() const { return dropped_; }

 private:
  Result start(double t, const RigidPose& pose, Outcome outcome, const std::string& why);
  /// `r` with `reason` unless it has one already (StartFailed).
  static Result withReason(Result r, Reason reason);

  SystemProblem system_;
  DynamicOptions dynamics_;
  VesselLockstepOptions options_;
  std::unique_ptr<SystemDynamics> sim_;
  bool pristine_ = true;  ///< sim_ is the file pose's static start, not advanced
  bool started_ = false;
  double t0_ = 0.0, last_t_ = 0.0;
  RigidPose last_pose_;
  int jumps_ = 0;
  int failures_ = 0;  ///< consecutive failed samples
  long dropped_ = 0;
};

const char* toString(VesselLockstep::Outcome o);

}  // namespace core
}  // namespace mooring_dynamics
