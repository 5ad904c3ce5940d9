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
  Eigen::MatrixXd J;  ///< kept point Jacobian (free points x free points, 3 each)
  long iterations = 0, line_steps = 0;
  std::unique_ptr<ThreadPool> pool;
  std::function<RigidMotion(double)> vessel_motion;  ///< world frame; holds at the reference pose by default
  RigidPose vessel_pose;                             ///< now
  std::vector<std::size_t> vessel_lines;             ///< lines with an end on the vessel and none on a free point

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
      const double q = 0.5 * env.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.cdn;
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
    Problem p = im.system.lineProblem(i, xyz);
    p.dynamics = options;
    p.dynamics.top_motion = TopMotion{};
    p.dynamics.top_motion.prescribe_position = true;  // the top follows its point
    if (p.dynamics.duration <= 0.0) p.dynamics.duration = options.dt;
    p.dynamics.record_s.clear();
    im.lines.push_back(std::make_unique<DynamicSolver3D>(p));
    im.lines_at[system.lines[i].to].push_back(i);
    if (system.lines[i].from != SystemLine::kFreeEnd) im.lines_at[system.lines[i].from].push_back(i);
    const SystemLine& l = system.lines[i];
    const bool at_free = system.points[l.to].free() || (l.from != SystemLine::kFreeEnd && system.points[l.from].free());
    if (!at_free && (im.isVessel(l.to) || im.isVessel(l.from))) im.vessel_lines.push_back(i);
  }
}

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
StaticResult SystemDynamics::line(std::size_t i) const { return impl_->lines.at(i)->snapshot(); }

std::array<double, 3> SystemDynamics::pointVelocity(std::size_t p) const {
  return {impl_->V[3 * p], impl_->V[3 * p + 1], impl_->V[3 * p + 2]};
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

namespace {

/// One step of the system from im.t: the free points' new positions by Newton on their force
/// balance (Newmark's trapezoidal rule in time), every line with an end at a point run through
/// the step for each iterate of the points. On failure the lines are back at im.t.
class PointStep {
 public:
  PointStep(SystemDynamics::Impl& im, double dt, std::string* message)
      : im_(im), dt_(dt), t1_(im.t + dt), m_(static_cast<int>(3 * im.free_pts.size())), message_(message) {
    for (const auto& l : im_.lines) saved_.push_back(l->save());
  }

  /// Predict, iterate the points to balance, accept; false (message set) on failure.
  bool run() {
    // Predictor: constant acceleration.
    Eigen::VectorXd X1 = im_.X + dt_ * im_.V + 0.5 * dt_ * dt_ * im_.A, V1, A1, G;
    kinematics(X1, V1, A1);
    // The lines on the vessel that touch no free point: once per step, side by side.
    if (!runSet(im_.vessel_lines, X1, V1)) return fail(why_);
    if (!runLines(im_.free_pts, X1, V1)) return fail(why_);
    residual(X1, V1, A1, G);
    bool converged = false;
    if (!iterate(X1, V1, A1, G, converged)) return fail(why_);
    if (!converged && G.cwiseAbs().maxCoeff() >= kForceTolerance * scale_)
      return fail("the point iteration did not converge: force residual " + std::to_string(G.cwiseAbs().maxCoeff()) +
                  " N");
    accept(X1, V1, A1);
    return true;
  }

 private:
  /// Newmark: the new velocity and acceleration of every point from its new position.
  void kinematics(const Eigen::VectorXd& X1, Eigen::VectorXd& V1, Eigen::VectorXd& A1) const {
    A1 = (X1 - im_.X - dt_ * im_.V - dt_ * dt_ * (0.5 - kBeta) * im_.A) / (kBeta * dt_ * dt_);
    V1 = im_.V + dt_ * ((1.0 - kGamma) * im_.A + kGamma * A1);
  }

  /// The motion of point p over the step: position and velocity linear in time from (X, V) at
  /// t to (X1, V1) at t1 (a fixed point stays where it is).
  std::function<TopState(double)> pointMotion(std::size_t p, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) const {
    const double t0 = im_.t, dt = dt_;
    const Eigen::Vector3d x0 = im_.X.segment<3>(static_cast<Eigen::Index>(3 * p)),
                          v0 = im_.V.segment<3>(static_cast<Eigen::Index>(3 * p)),
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
  }

  /// The path of a line end at point p over the step: the vessel's fairlead path, or the
  /// point's own motion.
  std::function<TopState(double)> endMotion(std::size_t p, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) const {
    return im_.isVessel(p) ? im_.fairleadMotion(p) : pointMotion(p, X1, V1);
  }

  /// Run the given lines through the step, side by side on the pool (each writes only its own
  /// solver and report); false, naming the first line in line order that failed.
  bool runSet(const std::vector<std::size_t>& set, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) {
    std::vector<StepReport> reports(set.size());
    im_.pool->parallelFor(set.size(), [&](std::size_t k) {
      const std::size_t i = set[k];
      DynamicSolver3D& line = *im_.lines[i];
      const SystemLine& sl = im_.system.lines[i];
      line.restore(*saved_[i]);
      line.setTopInput(endMotion(sl.to, X1, V1));
      if (sl.from != SystemLine::kFreeEnd && (im_.system.points[sl.from].free() || im_.isVessel(sl.from)))
        line.setLowerEndInput(endMotion(sl.from, X1, V1));
      reports[k] = line.advanceTo(t1_);
    });
    im_.line_steps += static_cast<long>(set.size());
    for (std::size_t k = 0; k < set.size(); ++k)
      if (!reports[k].ok) {
        why_ = "line " + im_.system.lines[set[k]].name + ": " + reports[k].message;
        return false;
      }
    return true;
  }

  /// Run every line with an end at one of `pts` through the step with the points at X1.
  bool runLines(const std::vector<std::size_t>& pts, const Eigen::VectorXd& X1, const Eigen::VectorXd& V1) {
    std::vector<char> done(im_.lines.size(), 0);
    std::vector<std::size_t> set;
    for (std::size_t p : pts)
      for (std::size_t i : im_.lines_at[p])
        if (!done[i]) {
          done[i] = 1;
          set.push_back(i);
        }
    return runSet(set, X1, V1);
  }

  /// Force balance of every free point: M a - (pulls + own load).
  void residual(const Eigen::VectorXd& X1, const Eigen::VectorXd& V1, const Eigen::VectorXd& A1, Eigen::VectorXd& G) {
    G.resize(m_);
    for (std::size_t k = 0; k < im_.free_pts.size(); ++k) {
      const std::size_t p = im_.free_pts[k];
      double F[3];
      im_.load(p, X1.data() + 3 * p, V1.data() + 3 * p, t1_, F);
      scale_ = std::max({scale_, std::abs(F[2])});
      for (std::size_t i : im_.lines_at[p]) {
        // A line pulls its upper point with -top_force and its lower point with anchor_force.
        const StaticResult s = im_.lines[i]->snapshot();
        const bool top = im_.system.lines[i].to == p;
        const double f[3] = {top ? -s.top_force_x : s.anchor_force_x, top ? -s.top_force_y : s.anchor_force_y,
                             top ? -s.top_force_z : s.anchor_force_z};
        for (int c = 0; c < 3; ++c) {
          F[c] += f[c];
          scale_ = std::max(scale_, std::abs(f[c]));
        }
      }
      for (int c = 0; c < 3; ++c)
        G[static_cast<Eigen::Index>(3 * k + c)] = im_.mass(p) * A1[static_cast<Eigen::Index>(3 * p + c)] - F[c];
    }
  }

  /// Newton on the points' force balance from the predictor; `converged` when the residual G
  /// falls below kForceTolerance of the largest force. False when a line's step fails.
  bool iterate(Eigen::VectorXd& X1, Eigen::VectorXd& V1, Eigen::VectorXd& A1, Eigen::VectorXd& G, bool& converged) {
    converged = m_ == 0;
    double g_prev = 0.0;
    for (int it = 0; it < kMaxPointIterations && !converged; ++it) {
      const double g = G.cwiseAbs().maxCoeff();
      if (g < kForceTolerance * scale_) {
        converged = true;
        break;
      }
      // Point Jacobian by finite differences, kept across steps while the iteration contracts.
      if (im_.J.rows() != m_ || (it > 0 && g > 0.25 * g_prev))
        if (!pointJacobian(X1, V1, G)) return false;
      g_prev = g;
      const Eigen::VectorXd dX = im_.J.fullPivLu().solve(-G);
      for (std::size_t k = 0; k < im_.free_pts.size(); ++k)
        X1.segment<3>(static_cast<Eigen::Index>(3 * im_.free_pts[k])) += dX.segment<3>(static_cast<Eigen::Index>(3 * k));
      kinematics(X1, V1, A1);
      if (!runLines(im_.free_pts, X1, V1)) return false;
      residual(X1, V1, A1, G);
      ++im_.iterations;
    }
    return true;
  }

  /// dG/dX1 by one-sided differences of kFdStep in every free point coordinate, into im.J.
  bool pointJacobian(const Eigen::VectorXd& X1, const Eigen::VectorXd& V1, const Eigen::VectorXd& G) {
    im_.J.resize(m_, m_);
    for (std::size_t k = 0; k < im_.free_pts.size(); ++k) {
      const std::size_t p = im_.free_pts[k];
      for (int c = 0; c < 3; ++c) {
        Eigen::VectorXd Xp = X1, Vp, Ap, Gp;
        Xp[static_cast<Eigen::Index>(3 * p + c)] += kFdStep;
        kinematics(Xp, Vp, Ap);
        if (!runLines({p}, Xp, Vp)) return false;
        residual(Xp, Vp, Ap, Gp);
        // Only the lines at p changed: the other points' rows are unchanged but for M a.
        im_.J.col(static_cast<Eigen::Index>(3 * k + c)) = (Gp - G) / kFdStep;
      }
      if (!runLines({p}, X1, V1)) return false;  // back to the current iterate
    }
    return true;
  }

  /// The new level: the vessel's points where its motion puts them (the Newmark values are only
  /// meaningful for the free points), then every point's state at t1.
  void accept(Eigen::VectorXd& X1, Eigen::VectorXd& V1, Eigen::VectorXd& A1) {
    const RigidMotion vm = im_.vessel_motion(t1_);
    for (std::size_t p = 0; p < im_.system.points.size(); ++p) {
      if (!im_.isVessel(p)) continue;
      const Eigen::Vector3d r = im_.system.points[p].body_offset;
      X1.segment<3>(static_cast<Eigen::Index>(3 * p)) = vm.pose.apply(r);
      V1.segment<3>(static_cast<Eigen::Index>(3 * p)) = vm.pointVelocity(r);
      A1.segment<3>(static_cast<Eigen::Index>(3 * p)).setZero();
    }
    im_.vessel_pose = vm.pose;
    im_.X = X1;
    im_.V = V1;
    im_.A = A1;
    im_.t = t1_;
  }

  /// Every line back at the step's start; the message names the time and what failed.
  bool fail(const std::string& what) {
    for (std::size_t i = 0; i < im_.lines.size(); ++i) im_.lines[i]->restore(*saved_[i]);
    if (message_) *message_ = "t = " + std::to_string(t1_) + " s: " + what;
    return false;
  }

  SystemDynamics::Impl& im_;
  const double dt_, t1_;
  const int m_;  ///< unknowns of the point iteration: 3 per free point
  std::string* message_;
  std::vector<std::shared_ptr<const DynamicSolver3D::Saved>> saved_;  ///< the lines at the step's start
  std::string why_;      ///< what the last failed line step said
  double scale_ = 1.0;   ///< largest force on a point seen in the step [N]
};

}  // namespace

bool SystemDynamics::advanceTo(double t_end, std::string* message) {
  Impl& im = *impl_;
  const double eps = 1e-9 * im.opt.dt;
  while (im.t < t_end - eps) {
    const double dt = std::min(im.opt.dt, t_end - im.t);
    if (!PointStep(im, dt, message).run()) return false;
  }
  im.t = std::max(im.t, t_end);
  return true;
}

}  // namespace core
}  // namespace mooring_dynamics
