// 3-D dynamic solver: the equations of equations3d.hpp (N = 13 plus coordinates, Euler
// parameters) on the half-grid box scheme, generalized-alpha in time (section 4) with the mass
// matrix averaged by alpha_k as in 2-D (docs/method.md), adaptive time stepping (4.3), started from
// the 3-D static solution. Same interface as DynamicSolver2D; the top input is a TopState
// (top_motion.hpp) in the problem frame.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"

namespace mooring_dynamics {
namespace core {

class DynamicSolver3D {
 public:
  /// Builds the mesh (adaptive if the options ask), solves the 3-D statics and starts from them.
  /// Throws std::invalid_argument for an invalid problem and std::runtime_error when the static
  /// start does not converge.
  explicit DynamicSolver3D(const Problem& problem);
  ~DynamicSolver3D();
  DynamicSolver3D(const DynamicSolver3D&) = delete;
  DynamicSolver3D& operator=(const DynamicSolver3D&) = delete;

  /// Replace the top motion of the problem file (e.g. by a live source). Called with the time
  /// [s]; must be defined for every t >= time().
  void setTopInput(std::function<TopState(double)> source);
  /// Move the anchor: its position and velocity (x, y, z, vx, vy, vz of the TopState) as a
  /// function of time, for a line below a free point of a system. Starts where statics put it.
  void setLowerEndInput(std::function<TopState(double)> source);

  /// Advance to t_end >= time() in base steps, cutting a step that does not converge (4.3). On
  /// failure the state stays at the last converged time and the report says where it failed.
  StepReport advanceTo(double t_end);

  /// Line events (issue 21; docs/method.md "Line events"), besides the problem's
  /// dynamics.events which advanceTo makes happen itself. Let an end go now, between steps: from
  /// the next step on it is a free end that carries no force. `cause` goes into the log. Throws
  /// std::logic_error when that end is free already.
  void releaseEnd(LineEvent::End end, const std::string& cause);
  /// Part the line now at node `node` (in an interval beside it; at an end node, that end is let
  /// go). Throws std::logic_error when it has parted already.
  void partAt(int node, const std::string& cause);
  /// The events that happened, in order.
  const std::vector<LineEventRecord>& eventLog() const;
  /// That end was let go (by an event or releaseEnd; a break at an end node lets it go too).
  bool endReleased(LineEvent::End end) const;

  /// The winch at the top (issue 21; docs/method.md "Winch"; the file's dynamics.winch runs
  /// by itself). The line's unstretched length now, anchor (or free end) to top [m].
  double lineLength() const;
  /// The winch's rate now [m/s] (+ pays out; 0 stopped or none).
  double winchRate() const;
  /// The top takes a winch: a position top (a ship's or a tow point's) or a surface buoy over
  /// an anchor, over a segment with length to give.
  bool hasWinch() const;
  /// Command the winch from now on: to `target` [m] at speed |rate| [m/s] and stop there, or
  /// (target NaN) at `rate` until its limit, where it stops (none when paying out without a
  /// max_length). Replaces the file's program. Returns what the winch will do ("to 120 m at
  /// 0.5 m/s, there at t = 80 s"). Throws std::invalid_argument naming the field for a target
  /// outside the limits (dynamics.winch.min_length / max_length, the top segment's shortest),
  /// a rate that is not finite, a target without a speed, and on a line without a winch or
  /// whose top is let go.
  std::string commandWinch(double rate, double target);

  double time() const;
  const StaticResult& initialStatic() const;
  StaticResult snapshot() const;
  std::vector<double> nodeArclengths() const;

  /// Largest relative difference between the assembled Jacobian of a step of size dt from the
  /// current state and central finite differences (checkJacobian); 1 outside the band.
  double jacobianFiniteDifferenceError(double dt) const;

  using Totals = DynamicSolver2D::Totals;
  Totals totals() const;
  /// Threads the solver runs on (dynamics.threads: a second thread pays on a 3-D line of any
  /// length, scripts/threads_bench).
  int threads() const;

  /// The time-stepping state (time, unknowns and rates, the previous level's weighted rows), to
  /// try a step and go back: a partitioned coupling (systems of lines) re-runs the same step with
  /// other top motions. Opaque; restore() takes one saved from this solver.
  struct Saved;
  std::shared_ptr<const Saved> save() const;
  void restore(const Saved& saved);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Run problem.dynamics with the 3-D solver from its static solution (as runDynamic in 2-D).
DynamicSeries runDynamic3D(const Problem& problem, const std::function<void(double, double)>& progress = nullptr);

}  // namespace core
}  // namespace mooring_dynamics
