// Lockstep driver: feeds timestamped top positions to a dynamic cable solver and decides what to
// do with each sample (start, advance, drop, re-initialise). No ROS calls here, so the policy is
// testable without a master; LockstepNode (lockstep_node.hpp) wires it to topics and logs.
//
// The solver sits behind LockstepSolver (below): core::DynamicSolver2D (makeSolver2D) for a
// problem with `model: 2d`, core::DynamicSolver3D (makeSolver3D) for `model: 3d`
// (makeSolverFor picks by Problem::formulation). Positions are (x, y, z) in the problem frame.
//
// Times are seconds on any fixed epoch (the node passes stamp - first stamp ever received); the
// solver's own time is t - t0, where t0 is the time of the sample that (re)started it.
//
// Policy (docs/ros_interface.md, "Dynamic mode"); distances and speeds are 3-D:
//  * model: 2d and |y| > kPlanarTolerance: dropped (the 2-D line lies in the plane y = 0; the
//    message names the value and points to model: 3d), state kept; a |y| within the tolerance
//    (rounding in a tf chain) is taken as y = 0.
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
//  * gap longer than `max_gap` since the last accepted sample: re-initialised as for a first
//    sample (the motion in between is unknown).
//  * a jump implying a top speed above `max_speed`: dropped; `jumps_to_reinit` such samples in a
//    row (the source really moved, e.g. a simulator reset): re-initialised at the new position.
//  * solver failure (a step fails even at the smallest cut): the last good state is kept (the
//    solver stays at its last converged step) and published for this sample with converged
//    false; the next sample continues from it, the top moving on from where it was at that
//    step. `failures_to_reinit` failures in a row: re-initialised from statics with the top at
//    the sample's position.
//  * reset(): re-initialised from statics at the last accepted top position (service ~reset);
//    reinitialiseAt(x, y, z): the same with the top at (x, y, z) (service ~solve_static with
//    reinitialise).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// The dynamic cable solver as the lockstep policy sees it: started from statics at construction,
/// told the top path of the next interval, advanced to a time. Positions in the problem frame [m],
/// times in solver seconds (0 = the static start).
class LockstepSolver {
 public:
  virtual ~LockstepSolver() = default;
  /// The static solution the run started from (solver time 0).
  virtual const core::StaticResult& initialStatic() const = 0;
  /// Top path of the next advance: linear from (x0, y0, z0) at t0 to (x1, y1, z1) at t1 > t0,
  /// with the velocity of that segment; held at the end points outside [t0, t1]. A 2-D solver
  /// uses x and z only (the driver never gives it y != 0).
  virtual void setTopSegment(double t0, double x0, double y0, double z0, double t1, double x1, double y1,
                             double z1) = 0;
  /// Advance to solver time t (base steps, the last one shortened to land on t).
  virtual core::StepReport advanceTo(double t) = 0;
  /// Current per-node values and end forces.
  virtual core::StaticResult snapshot() const = 0;
  virtual double time() const = 0;
  /// Let go an end now (line events, core::DynamicSolver3D::releaseEnd): empty when done, else
  /// why not (2-D: "model = 2d: line events need model: 3d").
  virtual std::string releaseEnd(core::LineEvent::End end, const std::string& cause) {
    (void)end, (void)cause;
    return "model = 2d: line events need model: 3d";
  }
  /// The line events so far (its problem's dynamics.events and releaseEnd calls).
  virtual std::vector<core::LineEventRecord> eventLog() const { return {}; }
  /// The winch at the top (core::DynamicSolver3D::commandWinch): empty when done, what it will
  /// do in `note`; else why not.
  virtual std::string commandWinch(double rate, double target, std::string& note) {
    (void)rate, (void)target, (void)note;
    return "model = 2d: the line node's winch needs model: 3d (a planar line gives the same results there)";
  }
  /// The line's unstretched length now [m] and the winch's rate [m/s].
  virtual double lineLength() const { return initialStatic().nodes.back().s; }
  virtual double winchRate() const { return 0.0; }
};

/// Builds a solver started from the statics of `problem` (its top boundary as given). Throws
/// std::invalid_argument (invalid problem) or std::runtime_error (statics do not converge).
using LockstepSolverFactory = std::function<std::unique_ptr<LockstepSolver>(const core::Problem&)>;

/// core::DynamicSolver2D behind LockstepSolver (problem.formulation must be TwoD).
LockstepSolverFactory makeSolver2D();
/// core::DynamicSolver3D behind LockstepSolver (problem.formulation must be ThreeD).
LockstepSolverFactory makeSolver3D();
/// makeSolver2D or makeSolver3D, as `formulation` says.
LockstepSolverFactory makeSolverFor(core::Formulation formulation);

/// [m] model: 2d: a sample with |y| above this is dropped; within it y is taken as 0 (rounding in
/// a tf chain or a frame conversion, far below any motion the line responds to).
constexpr double kPlanarTolerance = 1e-3;

/// The exact top input the 2-D adapter gives the core for setTopSegment (shared with tests that
/// run the core offline on the same track).
core::TopInput linearTopInput(double tau, double t0, double x0, double z0, double t1, double x1, double z1);
/// The same for the 3-D adapter.
core::TopState linearTopState(double tau, double t0, double x0, double y0, double z0, double t1, double x1,
                              double y1, double z1);

struct LockstepOptions {
  double start_tolerance = 0.01;  ///< [m] first sample farther than this from the static top: re-solve statics there
  double loop_back = 1.0;         ///< [s] time going back by more than this re-initialises (bag loop)
  double max_gap = 5.0;           ///< [s] a sample later than this after the last accepted one re-initialises; <= 0: never
  double max_speed = 50.0;        ///< [m/s] a jump implying a faster top is dropped; <= 0: no check
  int jumps_to_reinit = 3;        ///< this many jumps in a row re-initialise at the new position
  int failures_to_reinit = 3;     ///< this many solver failures in a row re-initialise from statics at the sample
};

class LockstepDriver {
 public:
  enum class Outcome {
    Started,          ///< first sample: solver (re)built, state = static start; publish
    Advanced,         ///< solver advanced to the sample's time; publish
    Reinitialised,    ///< time jumped back (bag loop), a long gap, repeated jumps, reset: rebuilt from statics; publish
    Failed,           ///< solver failed at the smallest cut; the last good state kept and published (converged false)
    RecoveredFailure, ///< failures_to_reinit failures in a row: rebuilt from statics at this sample; publish
    Dropped,          ///< sample ignored (non-finite, time not increasing, jump, cannot start); state kept
  };
  /// Why a sample was dropped or the run re-initialised (counted separately in /diagnostics).
  enum class Reason {
    None,
    NonFinite,    ///< Dropped: a non-finite time or coordinate
    OffPlane,     ///< Dropped: model: 2d and |y| > kPlanarTolerance
    SameStamp,    ///< Dropped: the stamp of the last accepted sample again
    StampBack,    ///< Dropped: a stamp back by at most loop_back
    Jump,         ///< Dropped: faster than max_speed
    StartFailed,  ///< Dropped: statics could not be solved at the sample's top
    LoopBack,     ///< Reinitialised: back by more than loop_back (bag loop)
    Gap,          ///< Reinitialised: a gap over max_gap
    Jumps,        ///< Reinitialised: jumps_to_reinit jumps in a row
    Request,      ///< Reinitialised: reset() / reinitialiseAt()
    SolverFailed, ///< Failed / RecoveredFailure
  };
  struct Result {
    Outcome outcome = Outcome::Dropped;
    Reason reason = Reason::None;
    bool publish = false;           ///< a new state is available (state())
    bool start_failed = false;      ///< statics could not be solved at the requested top (Dropped)
    std::string message;            ///< what happened (for logs), empty for a plain Advanced
    core::StepReport report;        ///< of advanceTo (Advanced / RecoveredFailure)
    double advanced = 0.0;          ///< [s] solver time covered by this sample (Advanced)
  };

  /// `problem` is the loaded problem; `dt` the base time step to use (overrides problem.dynamics.dt).
  /// The top motion of the problem file is replaced by the samples (followed by position, with
  /// velocity and position feedback). Builds the first solver (static start) at once: throws
  /// std::invalid_argument / std::runtime_error like the factory when the problem's statics fail.
  /// An empty `factory` means makeSolverFor(problem.formulation).
  LockstepDriver(const core::Problem& problem, double dt, const LockstepOptions& options = LockstepOptions(),
                 LockstepSolverFactory factory = nullptr);
  ~LockstepDriver();

  /// One sample: top at (x, y, z) [m] at time t [s].
  Result onSample(double t, double x, double y, double z);

  /// Re-initialise from statics at the last accepted top position, keeping the time of the last
  /// sample (the next sample advances from there). Dropped (nothing to do) before the first sample.
  Result reset();
  /// Re-initialise from statics with the top held at (x, y, z), at the time of the last sample.
  /// Before the first sample: Dropped (the run starts at the first sample anyway).
  Result reinitialiseAt(double x, double y, double z, const std::string& why);

  bool started() const { return started_; }
  /// Static top position of the problem (where the first sample should be) [m].
  double staticTopX() const { return static_top_x_; }
  double staticTopY() const { return static_top_y_; }
  double staticTopZ() const { return static_top_z_; }
  bool threeD() const { return problem_.formulation == core::Formulation::ThreeD; }
  /// Empty when a top at this y can be followed (3-D: any y; 2-D: |y| <= kPlanarTolerance), else
  /// "y = 0.5 m: the problem is model: 2d ..." (the node prefixes the message field).
  std::string planarError(double y) const;
  /// Solver time of the current state [s] (t - t0).
  double solverTime() const;
  /// Time of the last accepted sample [s] (valid once started).
  double lastTime() const { return last_time_; }
  /// Current state (valid once a sample was published; after a Failed sample the last good state,
  /// summary.converged false).
  const core::StaticResult& state() const { return state_; }
  /// The problem the solver runs (the file's, with the samples as top motion and dt applied).
  const core::Problem& problem() const { return problem_; }
  /// Let go an end of the line now (issue 21): from the next sample's step on it is a free end
  /// that carries no force. Empty when done, else why not (no solver yet, 2-D, let go already).
  /// After a line event a failing solver is not rebuilt from statics (statics would heal the
  /// line): its samples stay Failed with the last good state; reset() starts it intact.
  std::string release(core::LineEvent::End end, const std::string& cause);
  /// The line events of the current solver (empty after a re-initialisation).
  std::vector<core::LineEventRecord> events() const;
  /// Command the winch at the top (LockstepSolver::commandWinch): empty when done, else why not.
  std::string winch(double rate, double target, std::string& note);
  /// The line's length [m] and the winch's rate [m/s] now (the file's length before the start).
  double lineLength() const;
  double winchRate() const;

 private:
  Result start(double t, double x, double y, double z, Outcome outcome, const std::string& why);
  /// `r` with `reason` unless its start failed (then it keeps StartFailed).
  static Result withReason(Result r, Reason reason);
  std::unique_ptr<LockstepSolver> build(double x, double y, double z, bool at_problem_top, std::string& error) const;
  /// The top motion the solver starts from: held, or for a tow (free_end, top.tow_velocity) the
  /// steady tow at that velocity through the top.
  static void setStartMotion(core::Problem& p);
  /// Empty when (x, y, z) is a usable top position for the model, else why not.
  std::string positionError(double x, double y, double z) const;
  /// "(x, z)" in 2-D, "(x, y, z)" in 3-D, for messages.
  std::string point(double x, double y, double z) const;

  core::Problem problem_;
  LockstepOptions options_;
  LockstepSolverFactory factory_;
  std::unique_ptr<LockstepSolver> solver_;
  bool solver_is_pristine_ = false;  ///< solver_ is the problem's static start, not yet advanced
  double static_top_x_ = 0.0, static_top_y_ = 0.0, static_top_z_ = 0.0;
  bool started_ = false;
  double t0_ = 0.0;                  ///< sample time of solver time 0
  double prev_t_ = 0.0, prev_x_ = 0.0, prev_y_ = 0.0, prev_z_ = 0.0;  ///< last accepted sample (solver time, position)
  double last_time_ = 0.0;           ///< time of the last accepted sample (epoch time)
  int jumps_ = 0;                    ///< consecutive samples dropped as jumps
  int failures_ = 0;                 ///< consecutive samples on which the solver failed
  core::StaticResult state_;
};

const char* toString(LockstepDriver::Outcome o);
const char* toString(LockstepDriver::Reason r);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
