// Dynamics of a system of lines (system.hpp): free points (surface buoys, submerged bodies) at the
// ends of lines, e.g. a multi-leg buoy or a branched array's junction float.
//
// Partitioned implicit coupling: each line is advanced by its own DynamicSolver3D (the 3-D box
// scheme and generalized-alpha of dynamics3d.hpp) with its top following its upper point
// (velocity and position fed back, as a vessel's fairlead) and its anchor following its lower
// point (setLowerEndInput) when that point is free; each free point is a rigid point mass (mass and
// added mass, buoyancy from the draft for a buoy, net buoyancy for a body, quadratic drag on the
// velocity relative to the current, wind on a buoy) integrated by Newmark's trapezoidal rule
// (gamma = 1/2, beta = 1/4). Every base step solves the points' new positions by Newton
// iterations: for trial positions every line re-runs the step from the same start (save /
// restore), and the residual is each point's force balance M a = sum of the lines' pulls + its
// own load. The point Jacobian (finite differences, 3 unknowns per point) is kept across steps
// and refreshed when the iteration slows. Cost per step: the lines' steps times the iterations.
//
// A moored vessel: `vessel` points (fairleads) follow the vessel's prescribed rigid motion
// (setVesselMotion: pose, velocity and angular velocity in time); every line with an end on the
// vessel is advanced through each step with that end on its fairlead's path, p + R r and
// v + omega x (R r). Lines that touch no free point are independent within a step and run on
// the thread pool (`threads`); every result is summed in line order, so the bits do not depend
// on the thread count.
//
// Failures (issue 19: "one line that fails to converge is reported by name; the others go on"):
// the lines form independent groups, a group being the lines joined through free points (a buoy's
// legs, a branched array's lines at its junction float: they share the points' force balance, so
// they fail and restart together) or a single line touching no free point (a vessel's mooring
// leg). Every group's step is solved on its own (its own point iteration), so one group's steps do
// not depend on another's. When a group fails in a base step [t, t1] (a line's smallest step does
// not converge, or its point iteration does not), it alone restarts from statics at t1 (the
// vessel's pose at t1, its free points solved again), at rest, and the other groups go on with
// the bits they would have had anyway; lastRestarts() names the lines. Only when those statics
// fail too does advanceTo return false. With setRestartFailedGroups(false) (an offline run, which
// stops rather than go on from statics) a failed group makes advanceTo return false at once.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

namespace mooring_dynamics {
namespace core {

/// A group of lines that failed in a step of advanceTo and restarted from statics.
struct LineGroupRestart {
  double time = 0.0;               ///< [s] the end of the failed step, where the group restarted
  std::vector<std::size_t> lines;  ///< the group's lines (indices), in line order
  std::string reason;              ///< the failure, "line <name>: <solver message>"
};

class SystemDynamics {
 public:
  /// Solves the system's statics and starts every line and point from them, at rest. Throws
  /// std::invalid_argument for an invalid system or invalid options; std::runtime_error when the
  /// statics fail.
  /// `threads` >= 1: threads that advance the lines side by side (each line on one thread).
  /// The vessel (if any) starts at rest at system.vessel.pose.
  SystemDynamics(const SystemProblem& system, const DynamicOptions& options, int threads = 1);
  ~SystemDynamics();
  SystemDynamics(const SystemDynamics&) = delete;
  SystemDynamics& operator=(const SystemDynamics&) = delete;

  /// An external force [N] (problem frame) on point `point` as a function of time [s], e.g. a
  /// pull on the buoy. Only free points move; a force on a fixed point is ignored.
  void setPointForce(std::size_t point, std::function<std::array<double, 3>(double)> force);

  /// The vessel's motion as a function of time [s] (world frame), defined for every t >= time();
  /// by default it holds still at system.vessel.pose. E.g. RigidSegment::at between two samples.
  void setVesselMotion(std::function<RigidMotion(double)> motion);
  /// The vessel's pose now (system.vessel.pose before any motion).
  const RigidPose& vesselPose() const;
  /// The lines' wrench on the vessel now (about its body origin; zero without vessel points).
  VesselWrench vesselWrench() const;
  int threads() const;

  /// Advance to t_end in base steps of options.dt (the last one shortened). A group of lines that
  /// fails in a step restarts alone from statics at the end of that step (lastRestarts()); true
  /// then. False, with the reason in `message`, when such a restart's statics fail too, or at once
  /// when group restarts are off (setRestartFailedGroups); the state then stays at the last
  /// completed step (time() tells which).
  bool advanceTo(double t_end, std::string* message = nullptr);
  /// The groups that restarted during the last advanceTo (empty when none did).
  const std::vector<LineGroupRestart>& lastRestarts() const;
  /// The independent groups of lines (lines joined through free points restart together), each
  /// in line order, the groups in the order of their first line.
  const std::vector<std::vector<std::size_t>>& lineGroups() const;
  /// TEST HOOK (failure injection; tests only): `fail(line, t1)` true makes line `line`'s step
  /// ending at t1 count as not converged, as if its smallest step had failed ("failure injected
  /// (test hook)"). Empty (the default): no injection. Used by test_system_dynamics to check that
  /// the other groups continue bit for bit.
  void setFailureInjection(std::function<bool(std::size_t line, double t1)> fail);
  /// true (the default): a failed group restarts alone from statics (see advanceTo); false: the
  /// step fails and advanceTo returns false with the failed line named.
  void setRestartFailedGroups(bool restart);

  /// Line events (issue 21): `options.events` naming a line happen by themselves in advanceTo;
  /// this lets line `line`'s end go now (from the next step on it is a free end that pulls
  /// nothing). Throws std::out_of_range for a bad index, std::logic_error when the end is free
  /// already. A group with a line that was let go or parted does not restart from statics. A
  /// line let go from everything that moves (its top let go, its lower end on a fixed anchor or
  /// free) whose solver then fails (a chain collapsing onto the seabed) is retired: held at its
  /// last converged state, no longer advanced, and reported as a "retired" event.
  void releaseLineEnd(std::size_t line, LineEvent::End end, const std::string& cause);
  /// Every line's events so far, in time order (system time, line named).
  std::vector<LineEventRecord> lineEvents() const;
  /// The winch at line `line`'s top (DynamicSolver3D::commandWinch; throws its
  /// std::invalid_argument) and the line's length now [m].
  std::string commandLineWinch(std::size_t line, double rate, double target);
  double lineLength(std::size_t line) const;
  double lineWinchRate(std::size_t line) const;

  double time() const;
  const SystemStaticResult& initialStatic() const;
  /// Points now: positions [m], the lines' pulls [N] and, for free points, the velocity is in
  /// pointVelocity().
  std::vector<SystemPointResult> points() const;
  std::array<double, 3> pointVelocity(std::size_t point) const;
  /// Line i now (nodes, end forces).
  StaticResult line(std::size_t i) const;
  /// Point iterations and line steps taken so far (cost bookkeeping).
  long pointIterations() const;
  long lineSteps() const;
  /// Steps of line i taken by its solver's fallback so far (docs/method.md "Slack and snap: the
  /// fallback step"), over its restarts too.
  long lineFallbackSteps(std::size_t i) const;
  /// Cost counters of line i's solver since it last started (a restart begins them again):
  /// steps, cuts, Newton iterations, Jacobians, fallback steps and sub-steps.
  DynamicSolver3D::Totals lineTotals(std::size_t i) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace core
}  // namespace mooring_dynamics
