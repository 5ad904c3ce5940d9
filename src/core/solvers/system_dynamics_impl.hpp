// SystemDynamics' state (the private Impl of system_dynamics.hpp), shared by
// system_dynamics.cpp (construction, restarts, queries) and system_dynamics_step.cpp (the step:
// the lines through it, the free points' Newmark iteration, restarts of failed groups).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"
#include "mooring_dynamics/core/numerics/thread_pool.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"

namespace mooring_dynamics {
namespace core {

namespace system_dynamics_detail {
// Newmark's trapezoidal rule for the points: second order, no numerical damping (the lines'
// generalized-alpha damps their own high frequencies).
constexpr double kGamma = 0.5;
constexpr double kBeta = 0.25;
constexpr int kMaxPointIterations = 25;
// The point iteration stops on a force residual below this fraction of the largest force on a
// point (line pulls and weight): far below the lines' own Newton tolerance of 1e-6.
constexpr double kForceTolerance = 1e-7;
constexpr double kFdStep = 1e-6;  // [m] finite-difference step of a point coordinate
}  // namespace system_dynamics_detail

using namespace system_dynamics_detail;

struct SystemDynamics::Impl {
  SystemProblem system;
  DynamicOptions opt;
  SystemStaticResult statics;
  std::vector<std::unique_ptr<DynamicSolver3D>> lines;
  std::vector<std::size_t> free_pts;                 ///< point indices of the free points
  std::vector<std::vector<std::size_t>> lines_at;    ///< lines with an end at each point
  std::vector<std::function<std::array<double, 3>(double)>> forces;
  // Point state at time t: position, velocity, acceleration (3 per point, all points).
  double t = 0.0;
  Eigen::VectorXd X, V, A;
  std::vector<std::vector<std::size_t>> groups;     ///< lines of each independent group, in line order
  std::vector<std::vector<std::size_t>> group_pts;  ///< free points of each group, in point order
  std::vector<Eigen::MatrixXd> J;                   ///< per group: kept point Jacobian (its free points, 3 each)
  std::vector<double> line_t0;                      ///< system time at which each line's solver started (0, or its restart)
  std::function<bool(std::size_t, double)> fail_hook;  ///< test hook: failure injection
  bool restart_failed_groups = true;                  ///< a failed group restarts from statics (else the step fails)
  std::vector<LineGroupRestart> restarts;           ///< of the last advanceTo
  long iterations = 0, line_steps = 0;
  std::unique_ptr<ThreadPool> pool;
  std::function<RigidMotion(double)> vessel_motion;  ///< world frame; holds at the reference pose by default
  RigidPose vessel_pose;                             ///< now
  std::vector<std::size_t> vessel_lines;             ///< lines with an end on the vessel and none on a free point
  /// Lines let go from everything that moves whose solver then failed (a released chain
  /// collapsing on the seabed): no longer advanced, held at their last converged state.
  std::vector<char> retired;
  std::vector<LineEventRecord> retired_log;
  /// Fallback steps of each line's solvers before its last restart (a restart makes a new solver).
  std::vector<long> fallback_before;

  /// Line i pulls on nothing that moves: its top is let go, and its lower end is on a fixed
  /// anchor, let go, or free (what happens to it no longer changes the system).
  bool loose(std::size_t i) const {
    const SystemLine& l = system.lines[i];
    if (!lines[i]->endReleased(LineEvent::End::Top)) return false;
    if (l.from == SystemLine::kFreeEnd || lines[i]->endReleased(LineEvent::End::Anchor)) return true;
    return !system.points[l.from].free() && !isVessel(l.from);
  }

  bool isVessel(std::size_t p) const { return p != SystemLine::kFreeEnd && system.points[p].type == SystemPoint::Type::Vessel; }

  /// A fairlead's path: p + R r and v + omega x (R r) of the vessel's motion.
  std::function<TopState(double)> fairleadMotion(std::size_t p) const {
    const Eigen::Vector3d r = system.points[p].body_offset;
    const std::function<RigidMotion(double)> motion = vessel_motion;
    return [motion, r](double tau) {
      const RigidMotion m = motion(tau);
      const Eigen::Vector3d x = m.pose.apply(r), v = m.pointVelocity(r);
      return TopState::prescribed(x.data(), v.data());
    };
  }

  /// dynamics.winch for line `name` (none when it names another line) on a solver whose time 0 is
  /// system time t0, the line's length L0 there: the program from t0 on.
  Winch lineWinch(const std::string& name, double L0, double t0) const {
    if (!opt.winch.given || opt.winch.line != name) return Winch();
    Winch w = opt.winch;
    w.line.clear();
    if (t0 > 0.0 && !w.table.empty()) {
      const WinchProgram p = opt.winch.program(L0);
      w.table = {{0.0, p.lengthAt(t0)}};
      for (const auto& row : opt.winch.table)
        if (row[0] > t0) w.table.push_back({row[0] - t0, row[1]});
    }
    return w;
  }

  /// The dynamic problem of line i of `sys` with its ends at `xyz` (3 per point of `sys`), for a
  /// solver whose time 0 is system time t0: the line's own events (dynamics.events naming it),
  /// their times on its clock; those before t0 are gone.
  Problem lineDynamicProblem(const SystemProblem& sys, std::size_t i, const std::vector<double>& xyz,
                             double t0 = 0.0) const {
    Problem p = sys.lineProblem(i, xyz);
    p.dynamics = opt;
    p.dynamics.events.clear();
    for (LineEvent e : opt.events) {
      if (e.line != sys.lines[i].name || (e.t >= 0.0 && e.t < t0)) continue;
      e.line.clear();
      if (e.t >= 0.0) e.t -= t0;
      p.dynamics.events.push_back(e);
    }
    p.dynamics.winch = lineWinch(sys.lines[i].name, p.totalLength(), t0);
    p.dynamics.top_motion = TopMotion{};
    p.dynamics.top_motion.prescribe_position = true;  // the top follows its point
    if (p.dynamics.duration <= 0.0) p.dynamics.duration = opt.dt;
    p.dynamics.record_s.clear();
    return p;
  }

  /// Group g restarted from statics at time t1 with the vessel at `pose`: new solvers for its lines
  /// (their time 0 = t1) and its free points' static positions. Not yet swapped in.
  struct Restart {
    std::size_t group = 0;
    std::vector<std::unique_ptr<DynamicSolver3D>> lines;  ///< the group's lines, in its order
    std::vector<Eigen::Vector3d> points;                  ///< the group's free points, in its order
    LineGroupRestart report;
  };
  /// False, with the reason in `why`, when the group's statics fail there.
  bool restartGroup(std::size_t g, double t1, const RigidPose& pose, Restart& out, std::string& why) const {
    SystemProblem placed = system;
    placed.placeVessel(pose);
    for (std::size_t i : groups[g])
      if (!lines[i]->eventLog().empty()) {
        why = "line " + system.lines[i].name + " was " + lines[i]->eventLog().front().what +
              " (line events cannot be undone by a restart from statics)";
        return false;
      } else if (lines[i]->lineLength() != lines[i]->initialStatic().nodes.back().s) {
        why = "line " + system.lines[i].name + " was paid out or hauled in by its winch (a restart from statics "
              "would give it its file length back)";
        return false;
      }
    SystemProblem sub = placed;
    sub.points.clear();
    sub.lines.clear();
    sub.dynamics.events.clear();
    std::vector<std::size_t> map(system.points.size(), SystemLine::kFreeEnd);
    auto use = [&](std::size_t p) {
      if (p == SystemLine::kFreeEnd) return p;
      if (map[p] == SystemLine::kFreeEnd) {
        map[p] = sub.points.size();
        SystemPoint pt = placed.points[p];
        if (pt.free()) {  // the first guess: where it was
          pt.x = X[static_cast<Eigen::Index>(3 * p)];
          pt.y = X[static_cast<Eigen::Index>(3 * p + 1)];
          pt.z = X[static_cast<Eigen::Index>(3 * p + 2)];
          pt.position_given = true;
        }
        sub.points.push_back(pt);
      }
      return map[p];
    };
    for (std::size_t i : groups[g]) {
      SystemLine l = system.lines[i];
      l.from = use(l.from);
      l.to = use(l.to);
      sub.lines.push_back(l);
      for (const LineEvent& e : opt.events)
        if (e.line == l.name) sub.dynamics.events.push_back(e);
    }
    try {
      const std::string bad = sub.validate();
      if (!bad.empty()) {
        why = bad;
        return false;
      }
      const SystemStaticResult st = solveSystemStatic(sub);
      if (!st.summary.converged) {
        why = "statics did not converge: " + st.summary.message;
        return false;
      }
      std::vector<double> xyz;
      for (const auto& pt : st.points) xyz.insert(xyz.end(), {pt.x, pt.y, pt.z});
      out.group = g;
      out.lines.clear();
      for (std::size_t k = 0; k < sub.lines.size(); ++k)
        out.lines.push_back(std::make_unique<DynamicSolver3D>(lineDynamicProblem(sub, k, xyz, t1)));
      out.points.clear();
      for (std::size_t p : group_pts[g]) {
        const auto& pt = st.points[map[p]];
        out.points.emplace_back(pt.x, pt.y, pt.z);
      }
      out.report.time = t1;
      out.report.lines = groups[g];
    } catch (const std::exception& e) {
      why = e.what();
      return false;
    }
    return true;
  }

  double mass(std::size_t p) const {
    const SystemPoint& pt = system.points[p];
    if (pt.type == SystemPoint::Type::Buoy) return pt.buoy.mass + pt.buoy.added_mass;
    const Body& b = system.bodies[pt.body];
    return b.mass + b.added_mass;
  }

  /// A free point's own load at position x, velocity v and time `time` [N].
  void load(std::size_t p, const double* x, const double* v, double time, double* F) const {
    const SystemPoint& pt = system.points[p];
    const Environment& env = system.environment;
    double ux, uy;
    if (pt.type == SystemPoint::Type::Buoy) {
      const SurfaceBuoy& b = pt.buoy;
      const double d = -x[2];
      env.currentAt(0.0, ux, uy);
      const double rx = ux - v[0], ry = uy - v[1], r = std::hypot(rx, ry);
      const double q = 0.5 * env.water_density * b.cd * b.submergedArea(d);
      const double wx = env.wind_speed * std::cos(env.wind_direction) - v[0];
      const double wy = env.wind_speed * std::sin(env.wind_direction) - v[1];
      const double w = 0.5 * env.air_density * b.wind_cd * b.wind_area * std::hypot(wx, wy);
      F[0] = q * r * rx + w * wx;
      F[1] = q * r * ry + w * wy;
      F[2] = env.water_density * env.gravity * b.submergedVolume(d) - b.mass * env.gravity;
    } else {
      const Body& b = system.bodies[pt.body];
      env.currentAt(x[2], ux, uy);
      const double r[3] = {ux - v[0], uy - v[1], -v[2]};
      const double rm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      const double q = 0.5 * env.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.isotropicCd();
      for (int i = 0; i < 3; ++i) F[i] = q * rm * r[i];
      F[2] -= b.wet_weight;
    }
    if (forces[p]) {
      const std::array<double, 3> f = forces[p](time);
      for (int i = 0; i < 3; ++i) F[i] += f[i];
    }
  }

  // The step (system_dynamics_step.cpp).
  struct Step;
  /// One step of at most opt.dt towards t_end: false (why in `message`) when it cannot be taken.
  bool step(double t_end, std::string* message);
  /// Newmark: the new velocity and acceleration of every point from its new position X1.
  void kinematics(const Step& s, const Eigen::VectorXd& X1, Eigen::VectorXd& V1, Eigen::VectorXd& A1) const;
  /// The path of line i's end at point p over the step (the vessel's fairlead path, or the
  /// point's own motion), in the line solver's time: a line restarted at t_r counts from there.
  std::function<TopState(double)> endMotion(const Step& s, std::size_t i, std::size_t p, const Eigen::VectorXd& X1,
                                            const Eigen::VectorXd& V1) const;
  /// Run the given lines through the step, side by side on the pool. Returns the failed ones,
  /// in line order: (line, "line <name>: why"); a loose line that fails is retired instead.
  std::vector<std::pair<std::size_t, std::string>> runSet(const Step& s, const std::vector<std::size_t>& all,
                                                          const Eigen::VectorXd& X1, const Eigen::VectorXd& V1);
  /// Group g failed for `reason`: its restart from statics at the step's end, queued in s; false
  /// (s.abort_why set) when restarts are off or its statics fail too.
  bool restart(Step& s, std::size_t g, const std::string& reason);
  /// Group g's free points through the step (their own point iteration, the group's lines side
  /// by side); false with `why` when a line's step fails or the iteration does not converge.
  bool stepGroup(Step& s, std::size_t g, std::string& why);
  /// The queued restarts swapped in: new solvers (time 0 = t1), free points at rest.
  void commitRestarts(Step& s);
};


}  // namespace core
}  // namespace mooring_dynamics
