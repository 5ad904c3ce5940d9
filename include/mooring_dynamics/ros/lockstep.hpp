// Lockstep driver: feeds timestamped top positions to core::DynamicSolver2D and decides what to
// do with each sample (start, advance, drop, re-initialise). No ROS calls here, so the policy is
// testable without a master; LockstepNode (lockstep_node.hpp) wires it to topics and logs.
//
// Times are seconds on any fixed epoch (the node passes stamp - first stamp ever received); the
// solver's own time is t - t0, where t0 is the time of the sample that (re)started it.
//
// Policy (docs/ros_interface.md, "Dynamic mode"):
//  * first sample (or after a re-initialisation): if the top is within `start_tolerance` of the
//    static top of the problem, the solver starts from the problem's statics; otherwise statics
//    are re-solved with the top held at the sample's position. If that fails (e.g. out of reach)
//    the sample is rejected and the driver stays unstarted. t0 = the sample's time. The state
//    published for this sample is the static start (solver time 0).
//  * later samples: the top moves linearly from the previous sample's position to the new one
//    (velocity = difference / time difference); the solver advances to t - t0. The interval after
//    the start runs from the static top position, so a start mismatch (< start_tolerance) is
//    absorbed over the first interval.
//  * non-finite coordinates: dropped, state kept.
//  * time not increasing: dropped; time going back by more than `loop_back` (a bag loop):
//    re-initialised as for a first sample.
//  * solver failure: re-initialised from statics with the top at the sample's position.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "mooring_dynamics/core/dynamics2d.hpp"
#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/core/result.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

struct LockstepOptions {
  double start_tolerance = 0.01;  ///< [m] first sample farther than this from the static top: re-solve statics there
  double loop_back = 1.0;        ///< [s] time going back by more than this re-initialises (bag loop)
};

class LockstepDriver {
 public:
  enum class Outcome {
    Started,          ///< first sample: solver (re)built, state = static start; publish
    Advanced,         ///< solver advanced to the sample's time; publish
    Reinitialised,    ///< time jumped back (bag loop): solver rebuilt at this sample; publish
    RecoveredFailure, ///< solver failed; rebuilt from statics at this sample; publish
    Dropped,          ///< sample ignored (non-finite, time not increasing, cannot start); state kept
  };
  struct Result {
    Outcome outcome = Outcome::Dropped;
    bool publish = false;           ///< a new state is available (state())
    std::string message;            ///< what happened (for logs), empty for a plain Advanced
    core::StepReport report;        ///< of advanceTo (Advanced / RecoveredFailure)
  };

  /// `problem` is the loaded problem; `dt` the base time step to use (overrides problem.dynamics.dt).
  /// The top motion of the problem file is replaced by the samples (its `prescribe` flag is kept).
  /// Builds the first solver (static start) at once: throws std::invalid_argument /
  /// std::runtime_error like core::DynamicSolver2D when the problem's statics fail.
  LockstepDriver(const core::Problem& problem, double dt, const LockstepOptions& options = LockstepOptions());
  ~LockstepDriver();

  /// One sample: top at (x, z) [m] at time t [s].
  Result onSample(double t, double x, double z);

  bool started() const { return started_; }
  /// Static top position of the problem (where the first sample should be) [m].
  double staticTopX() const { return static_top_x_; }
  double staticTopZ() const { return static_top_z_; }
  /// Solver time of the current state [s] (t - t0).
  double solverTime() const;
  /// Current state (valid once a sample was published).
  const core::StaticResult& state() const { return state_; }

 private:
  Result start(double t, double x, double z, Outcome outcome, const std::string& why);
  std::unique_ptr<core::DynamicSolver2D> build(double x, double z, bool at_problem_top, std::string& error) const;

  core::Problem problem_;
  LockstepOptions options_;
  std::unique_ptr<core::DynamicSolver2D> solver_;
  bool solver_is_pristine_ = false;  ///< solver_ is the problem's static start, not yet advanced
  double static_top_x_ = 0.0, static_top_z_ = 0.0;
  bool started_ = false;
  double t0_ = 0.0;                  ///< sample time of solver time 0
  double prev_t_ = 0.0, prev_x_ = 0.0, prev_z_ = 0.0;  ///< last accepted sample (solver time, position)
  double last_time_ = 0.0;           ///< time of the last accepted sample (epoch time)
  core::StaticResult state_;
};

const char* toString(LockstepDriver::Outcome o);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
