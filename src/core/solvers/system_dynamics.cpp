#include "mooring_dynamics/core/solvers/system_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"
#include "mooring_dynamics/core/numerics/thread_pool.hpp"

namespace mooring_dynamics {
namespace core {

namespace {
// Newmark's trapezoidal rule for the points: second order, no numerical damping (the lines'
// generalized-alpha damps their own high frequencies).
constexpr double kGamma = 0.5;
constexpr double kBeta = 0.25;
constexpr int kMaxPointIterations = 25;
// The point iteration stops on a force residual below this fraction of the largest force on a
// point (line pulls and weight): far below the lines' own Newton tolerance of 1e-6.
constexpr double kForceTolerance = 1e-7;
constexpr double kFdStep = 1e-6;  // [m] finite-difference step of a point coordinate
}  // namespace

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
      TopState s;
      s.x = x[0];
      s.y = x[1];
      s.z = x[2];
      s.vx = v[0];
      s.vy = v[1];
      s.vz = v[2];
      return s;
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
};

SystemDynamics::SystemDynamics(const SystemProblem& system, const DynamicOptions& options, int threads)
    : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  const std::string e = system.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  const std::string eo = options.validate();
  if (!eo.empty()) throw std::invalid_argument(eo);
  if (options.threads != 1)  // (a second thread per line would have them compete for the cores)
    throw std::invalid_argument("dynamics.threads = " + std::to_string(options.threads) +
                                ": the lines of a system run on one thread (must be 1)");
  if (threads < 1) throw std::invalid_argument("threads = " + std::to_string(threads) + ": must be >= 1");
  im.system = system;
  im.system.formulation = Formulation::ThreeD;  // the lines run on the 3-D solver
  im.system.placeVessel(system.vessel.pose);
  im.vessel_pose = im.system.vessel.pose;
  const RigidPose start = im.vessel_pose;
  im.vessel_motion = [start](double) { return RigidSegment::hold(start).at(0.0); };
  im.pool = std::make_unique<ThreadPool>(threads);
  im.opt = options;
  im.statics = solveSystemStatic(im.system);
  if (!im.statics.summary.converged)
    throw std::runtime_error("the system's statics that start the run did not converge: " +
                             im.statics.summary.message);
  const std::size_t np = system.points.size();
  im.X.resize(static_cast<Eigen::Index>(3 * np));
  for (std::size_t p = 0; p < np; ++p) {
    im.X[3 * p] = im.statics.points[p].x;
    im.X[3 * p + 1] = im.statics.points[p].y;
    im.X[3 * p + 2] = im.statics.points[p].z;
    if (system.points[p].free()) im.free_pts.push_back(p);
  }
  im.V = Eigen::VectorXd::Zero(im.X.size());
  im.A = Eigen::VectorXd::Zero(im.X.size());
  im.forces.resize(np);
  im.lines_at.resize(np);
  std::vector<double> xyz(im.X.data(), im.X.data() + im.X.size());
  for (std::size_t i = 0; i < system.lines.size(); ++i) {
    im.lines.push_back(std::make_unique<DynamicSolver3D>(im.lineDynamicProblem(im.system, i, xyz)));
    im.lines_at[system.lines[i].to].push_back(i);
    if (system.lines[i].from != SystemLine::kFreeEnd) im.lines_at[system.lines[i].from].push_back(i);
    const SystemLine& l = system.lines[i];
    const bool at_free = system.points[l.to].free() || (l.from != SystemLine::kFreeEnd && system.points[l.from].free());
    if (!at_free && (im.isVessel(l.to) || im.isVessel(l.from))) im.vessel_lines.push_back(i);
  }
  im.line_t0.assign(system.lines.size(), 0.0);
  im.retired.assign(system.lines.size(), 0);
  // Groups: lines joined through free points (union-find over the lines at each free point).
  std::vector<std::size_t> root(system.lines.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = i;
  auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (std::size_t p : im.free_pts)
    for (std::size_t i : im.lines_at[p]) {
      const std::size_t a = find(i), b = find(im.lines_at[p].front());
      if (a != b) root[std::max(a, b)] = std::min(a, b);
    }
  std::vector<std::size_t> group_of_root(system.lines.size(), SystemLine::kFreeEnd);
  for (std::size_t i = 0; i < system.lines.size(); ++i) {
    const std::size_t r = find(i);
    if (group_of_root[r] == SystemLine::kFreeEnd) {
      group_of_root[r] = im.groups.size();
      im.groups.emplace_back();
      im.group_pts.emplace_back();
    }
    im.groups[group_of_root[r]].push_back(i);
  }
  for (std::size_t p : im.free_pts) im.group_pts[group_of_root[find(im.lines_at[p].front())]].push_back(p);
  im.J.resize(im.groups.size());
}

const std::vector<LineGroupRestart>& SystemDynamics::lastRestarts() const { return impl_->restarts; }
const std::vector<std::vector<std::size_t>>& SystemDynamics::lineGroups() const { return impl_->groups; }
void SystemDynamics::setFailureInjection(std::function<bool(std::size_t, double)> fail) {
  impl_->fail_hook = std::move(fail);
}
void SystemDynamics::setRestartFailedGroups(bool restart) { impl_->restart_failed_groups = restart; }

void SystemDynamics::setVesselMotion(std::function<RigidMotion(double)> motion) {
  if (!motion) throw std::invalid_argument("setVesselMotion: empty motion");
  impl_->vessel_motion = std::move(motion);
}

const RigidPose& SystemDynamics::vesselPose() const { return impl_->vessel_pose; }
int SystemDynamics::threads() const { return impl_->pool->threads(); }

VesselWrench SystemDynamics::vesselWrench() const {
  std::vector<StaticResult> lines;
  for (const auto& l : impl_->lines) lines.push_back(l->snapshot());
  return core::vesselWrench(impl_->system, impl_->vessel_pose, lines);
}

SystemDynamics::~SystemDynamics() = default;

void SystemDynamics::setPointForce(std::size_t point, std::function<std::array<double, 3>(double)> force) {
  if (point >= impl_->forces.size()) throw std::out_of_range("setPointForce: no point " + std::to_string(point));
  impl_->forces[point] = std::move(force);
}

double SystemDynamics::time() const { return impl_->t; }
const SystemStaticResult& SystemDynamics::initialStatic() const { return impl_->statics; }
long SystemDynamics::pointIterations() const { return impl_->iterations; }
long SystemDynamics::lineSteps() const { return impl_->line_steps; }
long SystemDynamics::lineFallbackSteps(std::size_t i) const {
  const long before = i < impl_->fallback_before.size() ? impl_->fallback_before[i] : 0;
  return before + impl_->lines.at(i)->totals().fallback_steps;
}
DynamicSolver3D::Totals SystemDynamics::lineTotals(std::size_t i) const { return impl_->lines.at(i)->totals(); }
StaticResult SystemDynamics::line(std::size_t i) const { return impl_->lines.at(i)->snapshot(); }

std::array<double, 3> SystemDynamics::pointVelocity(std::size_t p) const {
  return {impl_->V[3 * p], impl_->V[3 * p + 1], impl_->V[3 * p + 2]};
}

void SystemDynamics::releaseLineEnd(std::size_t line, LineEvent::End end, const std::string& cause) {
  impl_->lines.at(line)->releaseEnd(end, cause);
}

std::string SystemDynamics::commandLineWinch(std::size_t line, double rate, double target) {
  return impl_->lines.at(line)->commandWinch(rate, target);
}
double SystemDynamics::lineLength(std::size_t line) const { return impl_->lines.at(line)->lineLength(); }
double SystemDynamics::lineWinchRate(std::size_t line) const { return impl_->lines.at(line)->winchRate(); }

std::vector<LineEventRecord> SystemDynamics::lineEvents() const {
  const Impl& im = *impl_;
  std::vector<LineEventRecord> out;
  for (std::size_t i = 0; i < im.lines.size(); ++i)
    for (LineEventRecord r : im.lines[i]->eventLog()) {
      r.t += im.line_t0[i];
      r.line = im.system.lines[i].name;
      out.push_back(r);
    }
  out.insert(out.end(), im.retired_log.begin(), im.retired_log.end());
  std::stable_sort(out.begin(), out.end(), [](const LineEventRecord& a, const LineEventRecord& b) { return a.t < b.t; });
  return out;
}

std::vector<SystemPointResult> SystemDynamics::points() const {
  const Impl& im = *impl_;
  std::vector<SystemPointResult> out;
  for (std::size_t p = 0; p < im.system.points.size(); ++p) {
    SystemPointResult r;
    r.name = im.system.points[p].name;
    r.x = im.X[3 * p];
    r.y = im.X[3 * p + 1];
    r.z = im.X[3 * p + 2];
    for (std::size_t i = 0; i < im.system.lines.size(); ++i) {
      const SystemLine& l = im.system.lines[i];
      const bool top = l.to == p, bottom = l.from == p;
      if (!top && !bottom) continue;
      const StaticResult s = im.lines[i]->snapshot();
      r.fx += top ? -s.top_force_x : s.anchor_force_x;
      r.fy += top ? -s.top_force_y : s.anchor_force_y;
      r.fz += top ? -s.top_force_z : s.anchor_force_z;
    }
    if (im.system.points[p].type == SystemPoint::Type::Buoy) r.buoy_draft = -r.z;
    out.push_back(r);
  }
  return out;
}

bool SystemDynamics::advanceTo(double t_end, std::string* message) {
  Impl& im = *impl_;
  im.restarts.clear();
  const double eps = 1e-9 * im.opt.dt;
  while (im.t < t_end - eps) {
    const double dt = std::min(im.opt.dt, t_end - im.t), t1 = im.t + dt;
    std::vector<std::shared_ptr<const DynamicSolver3D::Saved>> saved;
    for (const auto& l : im.lines) saved.push_back(l->save());

    // Newmark: the new velocity and acceleration of every point from its new position.
    auto kinematics = [&](const Eigen::VectorXd& X1, Eigen::VectorXd& V1, Eigen::VectorXd& A1) {
      A1 = (X1 - im.X - dt * im.V - dt * dt * (0.5 - kBeta) * im.A) / (kBeta * dt * dt);
      V1 = im.V + dt * ((1.0 - kGamma) * im.A + kGamma * A1);
    };
    // The motion of point p over the step: position and velocity linear in time from (X, V) at
    // t to (X1, V1) at t1 (a fixed point stays where it is).
    auto pointMotion = [&](std::size_t p, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) {
      const double t0 = im.t;
      const Eigen::Vector3d x0 = im.X.segment<3>(static_cast<Eigen::Index>(3 * p)),
                            v0 = im.V.segment<3>(static_cast<Eigen::Index>(3 * p)),
                            x1 = X1.segment<3>(static_cast<Eigen::Index>(3 * p)),
                            v1 = V1.segment<3>(static_cast<Eigen::Index>(3 * p));
      return [=](double tau) {
        const double w = dt > 0.0 ? std::clamp((tau - t0) / dt, 0.0, 1.0) : 1.0;
        const Eigen::Vector3d x = x0 + w * (x1 - x0), v = v0 + w * (v1 - v0);
        TopState s;
        s.x = x[0];
        s.y = x[1];
        s.z = x[2];
        s.vx = v[0];
        s.vy = v[1];
        s.vz = v[2];
        return s;
      };
    };
    // The path of line i's end at point p over the step (the vessel's fairlead path, or the
    // point's own motion), in the line solver's time: a line restarted at t_r counts from there.
    auto endMotion = [&](std::size_t i, std::size_t p, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) {
      std::function<TopState(double)> f =
          im.isVessel(p) ? im.fairleadMotion(p) : std::function<TopState(double)>(pointMotion(p, X1, V1));
      const double off = im.line_t0[i];
      if (off == 0.0) return f;
      return std::function<TopState(double)>([f, off](double tau) { return f(tau + off); });
    };
    // Run the given lines through the step, side by side on the pool (each writes only its own
    // solver and report). Returns the failed ones, in line order: (line, "line <name>: why").
    auto runSet = [&](const std::vector<std::size_t>& all, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) {
      std::vector<std::size_t> set;
      for (std::size_t i : all)
        if (!im.retired[i]) set.push_back(i);
      std::vector<StepReport> reports(set.size());
      im.pool->parallelFor(set.size(), [&](std::size_t k) {
        const std::size_t i = set[k];
        DynamicSolver3D& line = *im.lines[i];
        const SystemLine& sl = im.system.lines[i];
        line.restore(*saved[i]);
        line.setTopInput(endMotion(i, sl.to, X1, V1));
        if (sl.from != SystemLine::kFreeEnd && (im.system.points[sl.from].free() || im.isVessel(sl.from)))
          line.setLowerEndInput(endMotion(i, sl.from, X1, V1));
        reports[k] = line.advanceTo(t1 - im.line_t0[i]);
      });
      im.line_steps += static_cast<long>(set.size());
      std::vector<std::pair<std::size_t, std::string>> failed;
      for (std::size_t k = 0; k < set.size(); ++k) {
        if (reports[k].ok && im.fail_hook && im.fail_hook(set[k], t1)) {
          reports[k].ok = false;
          reports[k].message = "failure injected (test hook)";
        }
        if (!reports[k].ok && im.loose(set[k])) {
          // Let go from everything that moves: held where it was, reported, and the step goes on.
          im.lines[set[k]]->restore(*saved[set[k]]);
          im.retired[set[k]] = 1;
          LineEventRecord r;
          r.t = im.t;
          r.what = "retired";
          r.line = im.system.lines[set[k]].name;
          r.cause = "the loose line stopped converging (" + reports[k].message +
                    "); it pulls on nothing that moves and is held where it was from here on";
          im.retired_log.push_back(r);
          continue;
        }
        if (!reports[k].ok) failed.emplace_back(set[k], "line " + im.system.lines[set[k]].name + ": " + reports[k].message);
      }
      return failed;
    };

    // Predictor: constant acceleration.
    Eigen::VectorXd X1 = im.X + dt * im.V + 0.5 * dt * dt * im.A, V1, A1;
    kinematics(X1, V1, A1);
    std::vector<Impl::Restart> restarts;
    std::string abort_why;
    const RigidMotion vm = im.vessel_motion(t1);
    auto restart = [&](std::size_t g, const std::string& reason) {
      if (!im.restart_failed_groups) {
        abort_why = reason;
        return false;
      }
      Impl::Restart r;
      std::string why;
      if (!im.restartGroup(g, t1, vm.pose, r, why)) {
        abort_why = reason + "; restarting its group from statics failed too: " + why;
        return false;
      }
      r.report.reason = reason;
      restarts.push_back(std::move(r));
      return true;
    };
    std::vector<std::size_t> group_of(im.lines.size());
    for (std::size_t g = 0; g < im.groups.size(); ++g)
      for (std::size_t i : im.groups[g]) group_of[i] = g;

    // The lines on the vessel that touch no free point (each a group of its own): once per step,
    // side by side; a failed one restarts alone.
    bool ok = true;
    for (const auto& f : runSet(im.vessel_lines, X1, V1)) ok = ok && restart(group_of[f.first], f.second);

    // Each group with free points: its own point iteration (so that its bits do not depend on
    // the other groups), its lines side by side.
    for (std::size_t g = 0; g < im.groups.size() && ok; ++g) {
      const std::vector<std::size_t>& pts = im.group_pts[g];
      if (pts.empty()) continue;
      const int m = static_cast<int>(3 * pts.size());
      std::string why;
      // Run every line with an end at one of `ps` through the step with the points at X1.
      auto runLines = [&](const std::vector<std::size_t>& ps, const Eigen::VectorXd& Xa, const Eigen::VectorXd& Va) {
        std::vector<char> done(im.lines.size(), 0);
        std::vector<std::size_t> set;
        for (std::size_t p : ps)
          for (std::size_t i : im.lines_at[p])
            if (!done[i]) {
              done[i] = 1;
              set.push_back(i);
            }
        const auto failed = runSet(set, Xa, Va);
        if (!failed.empty()) why = failed.front().second;
        return failed.empty();
      };
      // Force balance of the group's free points: M a - (pulls + own load).
      double scale = 1.0;
      auto residual = [&](const Eigen::VectorXd& Xa, const Eigen::VectorXd& Va, const Eigen::VectorXd& Aa,
                          Eigen::VectorXd& G) {
        G.resize(m);
        for (std::size_t k = 0; k < pts.size(); ++k) {
          const std::size_t p = pts[k];
          double F[3];
          im.load(p, Xa.data() + 3 * p, Va.data() + 3 * p, t1, F);
          scale = std::max({scale, std::abs(F[2])});
          for (std::size_t i : im.lines_at[p]) {
            // A line pulls its upper point with -top_force and its lower point with anchor_force.
            const StaticResult s = im.lines[i]->snapshot();
            const bool top = im.system.lines[i].to == p;
            const double f[3] = {top ? -s.top_force_x : s.anchor_force_x, top ? -s.top_force_y : s.anchor_force_y,
                                 top ? -s.top_force_z : s.anchor_force_z};
            for (int c = 0; c < 3; ++c) {
              F[c] += f[c];
              scale = std::max(scale, std::abs(f[c]));
            }
          }
          for (int c = 0; c < 3; ++c)
            G[static_cast<Eigen::Index>(3 * k + c)] = im.mass(p) * Aa[static_cast<Eigen::Index>(3 * p + c)] - F[c];
        }
      };
      // The group's step; false (why set) when a line's step fails or the iteration does not converge.
      auto stepGroup = [&]() {
        Eigen::VectorXd G;
        if (!runLines(pts, X1, V1)) return false;
        residual(X1, V1, A1, G);
        bool converged = false;
        double g_prev = 0.0;
        Eigen::MatrixXd& J = im.J[g];
        for (int it = 0; it < kMaxPointIterations && !converged; ++it) {
          const double gm = G.cwiseAbs().maxCoeff();
          if (gm < kForceTolerance * scale) {
            converged = true;
            break;
          }
          // Point Jacobian by finite differences, kept across steps while the iteration contracts.
          if (J.rows() != m || (it > 0 && gm > 0.25 * g_prev)) {
            J.resize(m, m);
            for (std::size_t k = 0; k < pts.size(); ++k) {
              const std::size_t p = pts[k];
              for (int c = 0; c < 3; ++c) {
                Eigen::VectorXd Xp = X1, Vp, Ap, Gp;
                Xp[static_cast<Eigen::Index>(3 * p + c)] += kFdStep;
                kinematics(Xp, Vp, Ap);
                if (!runLines({p}, Xp, Vp)) return false;
                residual(Xp, Vp, Ap, Gp);
                // Only the lines at p changed: the other points' rows are unchanged but for M a.
                J.col(static_cast<Eigen::Index>(3 * k + c)) = (Gp - G) / kFdStep;
              }
              if (!runLines({p}, X1, V1)) return false;  // back to the current iterate
            }
          }
          g_prev = gm;
          const Eigen::VectorXd dX = J.fullPivLu().solve(-G);
          for (std::size_t k = 0; k < pts.size(); ++k)
            X1.segment<3>(static_cast<Eigen::Index>(3 * pts[k])) += dX.segment<3>(static_cast<Eigen::Index>(3 * k));
          kinematics(X1, V1, A1);
          if (!runLines(pts, X1, V1)) return false;
          residual(X1, V1, A1, G);
          ++im.iterations;
        }
        if (!converged && G.cwiseAbs().maxCoeff() >= kForceTolerance * scale) {
          why = "the point iteration did not converge: force residual " + std::to_string(G.cwiseAbs().maxCoeff()) + " N";
          return false;
        }
        return true;
      };
      if (!stepGroup()) ok = restart(g, why);
    }
    if (!ok) {
      // A failed group not restarted, or its statics failed too: the whole step is undone (the replacements are dropped).
      for (std::size_t i = 0; i < im.lines.size(); ++i) im.lines[i]->restore(*saved[i]);
      if (message) *message = "t = " + std::to_string(t1) + " s: " + abort_why;
      return false;
    }
    // The restarted groups: their new solvers (time 0 = t1) and free points at rest.
    for (Impl::Restart& r : restarts) {
      const std::vector<std::size_t>& gl = im.groups[r.group];
      for (std::size_t k = 0; k < gl.size(); ++k) {
        if (im.fallback_before.size() < im.lines.size()) im.fallback_before.resize(im.lines.size(), 0);
        im.fallback_before[gl[k]] += im.lines[gl[k]]->totals().fallback_steps;
        im.lines[gl[k]] = std::move(r.lines[k]);
        im.line_t0[gl[k]] = t1;
      }
      const std::vector<std::size_t>& gp = im.group_pts[r.group];
      for (std::size_t k = 0; k < gp.size(); ++k) {
        X1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])) = r.points[k];
        V1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])).setZero();
        A1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])).setZero();
      }
      im.J[r.group].resize(0, 0);
      im.restarts.push_back(r.report);
    }
    // The vessel's points are where its motion puts them (the Newmark values above are only
    // meaningful for the free points).
    for (std::size_t p = 0; p < im.system.points.size(); ++p) {
      if (!im.isVessel(p)) continue;
      const Eigen::Vector3d r = im.system.points[p].body_offset;
      X1.segment<3>(static_cast<Eigen::Index>(3 * p)) = vm.pose.apply(r);
      V1.segment<3>(static_cast<Eigen::Index>(3 * p)) = vm.pointVelocity(r);
      A1.segment<3>(static_cast<Eigen::Index>(3 * p)).setZero();
    }
    im.vessel_pose = vm.pose;
    im.X = X1;
    im.V = V1;
    im.A = A1;
    im.t = t1;
  }
  im.t = std::max(im.t, t_end);
  return true;
}

}  // namespace core
}  // namespace mooring_dynamics
