#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "dynamics3d_impl.hpp"
#include "dynamics3d_step_system.hpp"
#include "lumped_line.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/solvers/adaptive_mesh.hpp"
#include "mooring_dynamics/core/solvers/drifting.hpp"
#include "mooring_dynamics/core/solvers/dynamic_run.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq3d;

// ------------------------------------------------------------------------------------------------

namespace {

/// A towed line starts from the steady tow at the tow point's initial velocity (section 7.1:
/// "steady tow, then the manoeuvre"): statics in the frame moving with it (start.top.tow_v),
/// then every node given that velocity V0, which is a steady state of the dynamic equations.
void steadyTowStart(const Problem& problem, Problem& start, double* V0) {
  const TopState s0 = makeTopMotion(problem.dynamics.top_motion, problem.top.x, problem.top.y, problem.top.z,
                                    nullptr)(0.0);
  constexpr double kVelocityMismatch = 1e-6;  // [m/s]
  const bool given = problem.top.tow_vx != 0.0 || problem.top.tow_vy != 0.0;
  if (given && std::hypot(problem.top.tow_vx - s0.vx, problem.top.tow_vy - s0.vy) > kVelocityMismatch)
    throw std::invalid_argument("top.tow_velocity = (" + std::to_string(problem.top.tow_vx) + ", " +
                                std::to_string(problem.top.tow_vy) + ") m/s: differs from the top motion's velocity at "
                                "t = 0, (" + std::to_string(s0.vx) + ", " + std::to_string(s0.vy) +
                                ") m/s; leave it out to start from the motion's");
  start.top.tow_vx = V0[0] = s0.vx;
  start.top.tow_vy = V0[1] = s0.vy;
}

/// The static solution the run starts from, on im.mesh (section 3: the adaptive mesh of eq. 22
/// when the options ask).
StaticState3D solveStart(DynamicSolver3D::Impl& im, const Problem& problem, const Problem& start) {
  StaticState3D st = solveStatic3DOnMesh(start, im.mesh, start.static_options);
  if (st.result.summary.converged && problem.dynamics.adaptive_mesh) {
    // Section 3: redistribute the nodes by eq. 22. The curvature fed to eq. 21 is the magnitude
    // of the bending curvature (Omega2, Omega3) with the sign of Omega3, which is the 2-D
    // Omega3 for a planar line.
    StaticResult shape = st.result;
    for (auto& ns : shape.nodes)
      ns.curvature = std::copysign(std::hypot(ns.curvature, ns.curvature_b), ns.curvature);
    im.mesh = buildAdaptiveMesh(start, im.mesh, shape, problem.dynamics.mesh_weight);
    st = solveStatic3DOnMesh(start, im.mesh, start.static_options);
  }
  if (!st.result.summary.converged)
    throw std::runtime_error("the 3-D static solution that starts the dynamic run did not converge: " +
                             st.result.summary.message);
  return st;
}

/// The top motion of the problem file, started at the static top.
void setTopMotion(DynamicSolver3D::Impl& im, const Problem& problem) {
  const NodeState& topNode = im.statics.nodes.back();
  const TopMotion& tm = problem.dynamics.top_motion;
  constexpr double kStartMismatch = 0.01;  // [m] a position table must start where statics put the top
  const std::string bad = topMotionStartError(tm, topNode.x, topNode.y, topNode.z, kStartMismatch);
  if (!bad.empty()) throw std::invalid_argument(bad);
  im.top = makeTopMotion(tm, topNode.x, topNode.y, topNode.z, &im.waves);
}

/// The start state from the statics Y: at rest, or every node moving at V0 (a tow or a drift).
void startState(DynamicSolver3D::Impl& im, const Eigen::VectorXd& Y, bool moving, bool drifter, const double* V0) {
  im.t = 0.0;
  im.Y = Y;
  if (moving) {
    for (int j = 0; j < im.nodes(); ++j) {
      double* y = im.Y.data() + N * j;
      double R[9];
      quat::matrix(y + Q0, R);
      quat::toLocal(R, V0, y + U1);
    }
  }
  im.Yd = Eigen::VectorXd::Zero(im.Y.size());
  if (drifter) {
    // The drifter's top kinematics integrate the position rate: start it at V_d (every node
    // moves so), else the first step loses (1 - gamma) dt V_d of the drift.
    for (int j = 0; j < im.nodes(); ++j)
      for (int i = 0; i < 3; ++i) im.Yd[N * j + X + i] = V0[i];
  }
}

/// Error scales chi_m of eq. 39, as in 2-D.
void setErrorScales(DynamicSolver3D::Impl& im, const Problem& problem) {
  double Tc = 1.0, stiffest = 0.0;
  for (const auto& ns : im.statics.nodes) Tc = std::max(Tc, std::abs(ns.tension));
  for (const auto& m : problem.materials) stiffest = std::max(stiffest, m.rawTensionSlope(0.0));
  im.chi[EPS] = Tc / stiffest;
  im.chi[S2] = im.chi[S3] = Tc;
  im.chi[U1] = im.chi[U2] = im.chi[U3] = 1.0;  // [m/s]
  im.chi[O1] = im.chi[O2] = im.chi[O3] = 1.0 / std::max(im.mesh.minSpacing(), 1e-3);
  im.chi[Q0] = im.chi[Q1] = im.chi[Q2] = im.chi[Q3] = 1.0;
  im.chi[X] = im.chi[eq3d::Y] = im.chi[Z] = 1.0;  // [m]
}

}  // namespace

DynamicSolver3D::DynamicSolver3D(const Problem& problem) : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  const std::string err = problem.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  im.problem = problem;
  im.opt = problem.dynamics;
  im.ga = problem.dynamics.scheme;
  im.mesh = buildMesh(problem);
  if (im.opt.fallback_after_cuts == DynamicOptions::kFallbackAfterCutsAuto) {
    // (DynamicOptions::fallback_after_cuts) 1 where the line can go slack and snap.
    bool slack_law = false;
    for (int j = 0; j < im.nodes(); ++j) slack_law = slack_law || !im.mat(j).compression;
    im.opt.fallback_after_cuts = slack_law ? 1 : 4;
  }
  // A towed line starts from its steady tow, a drifter from its steady drift: the statics find
  // the drift velocity V_d, and every node moves at it.
  const bool drifter = isDrifter(problem);
  const bool towed = problem.lower_end == Problem::LowerEnd::Free && !drifter;
  Problem start = problem;
  double V0[3] = {0.0, 0.0, 0.0};
  if (towed) steadyTowStart(problem, start, V0);
  const StaticState3D st = solveStart(im, problem, start);
  im.statics = st.result;
  im.lower = makeLowerEnd3D(im.problem, im.mat(0));
  im.upper = makeUpperEnd3D(im.problem, im.mat(im.nodes() - 1));
  if (drifter) {
    V0[0] = st.result.drift_vx;
    V0[1] = st.result.drift_vy;
  }
  if (problem.environment.waves.type != WaveSpec::Type::None)
    im.waves = WaveField(problem.environment.waves, problem.environment.depth, problem.environment.gravity);
  im.wave_cache = WaveVelocityCache(&im.waves, im.mesh.nodes.size(), true);
  im.current = CurrentProfile(problem.environment.current);
  if (im.opt.threads > 1) {  // the second thread: the upper half of every iteration
    im.fork = std::make_unique<ForkJoin>();
    im.newton_matrix.setParallel(im.fork.get());
  }
  setTopMotion(im, problem);
  im.events = problem.dynamics.events;
  im.event_done.assign(im.events.size(), 0);
  startState(im, st.Y, towed || drifter, drifter, V0);
  im.waterField(im.Y, 0.0, im.water);
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, 0.0);
  setErrorScales(im, problem);
  winchSetUp(im);
}

DynamicSolver3D::~DynamicSolver3D() = default;

void DynamicSolver3D::setTopInput(std::function<TopState(double)> source) { impl_->top = std::move(source); }
void DynamicSolver3D::setLowerEndInput(std::function<TopState(double)> source) {
  Impl& im = *impl_;
  if (im.problem.lower_end == Problem::LowerEnd::Free)
    throw std::invalid_argument("setLowerEndInput: the line's lower end is free; it has no anchor to move");
  std::unique_ptr<EndCondition3D>& held = im.lower_kept ? im.lower_kept : im.lower;  // a released anchor stays so
  im.lower_path = source;
  held = source ? makeMovingAnchor3D(im.problem, std::move(source)) : makeLowerEnd3D(im.problem, im.mat(0));
}
double DynamicSolver3D::time() const { return impl_->t; }
double DynamicSolver3D::lineLength() const { return impl_->mesh.nodes.back().s; }
bool DynamicSolver3D::hasWinch() const { return impl_->winch.able; }
double DynamicSolver3D::winchRate() const {
  const WinchState& w = impl_->winch;
  constexpr double kAfter = 1e-9;  // [s] the rate of the piece that starts now
  return w.active() ? w.program.rateAt(impl_->t + kAfter) : 0.0;
}
const StaticResult& DynamicSolver3D::initialStatic() const { return impl_->statics; }
DynamicSolver3D::Totals DynamicSolver3D::totals() const { return impl_->totals; }
int DynamicSolver3D::threads() const { return impl_->fork ? 2 : 1; }

std::vector<double> DynamicSolver3D::nodeArclengths() const {
  std::vector<double> s;
  for (const auto& n : impl_->mesh.nodes) s.push_back(n.s);
  return s;
}

StaticResult DynamicSolver3D::snapshot() const {
  StaticResult r = staticResult3DFromState(impl_->problem, impl_->mesh, impl_->Y);
  r.summary.converged = true;
  return r;
}

void rowsChanged(DynamicSolver3D::Impl& im) {
  im.newton_matrix.setZero();
  im.factored_dt = 0.0;
}

namespace {

void addReport(StepReport& total, const StepReport& rep) {
  total.ok = rep.ok;
  total.steps += rep.steps;
  total.cuts += rep.cuts;
  total.newton_iterations += rep.newton_iterations;
  total.fallback_steps += rep.fallback_steps;
  if (rep.smallest_dt > 0.0)
    total.smallest_dt = total.smallest_dt > 0.0 ? std::min(total.smallest_dt, rep.smallest_dt) : rep.smallest_dt;
  total.message = rep.message;
}


/// One attempted step of size dt from the accepted state; on success the state advances.
bool tryStep(DynamicSolver3D::Impl& im, double dt, StepReport& rep) {
  const double t_new = im.t + dt;
  if (!winchBeginStep(im, t_new, rep.message)) return false;
  DynamicStepSystem3D sys(im, t_new, dt, im.top(t_new));
  // Predictor: constant rate; with modified Newton (smooth problems) the rate's change over the
  // last step of the same size is extrapolated too, which starts the iteration closer.
  Eigen::VectorXd Yv = im.Y + dt * im.Yd;
  if (im.opt.jacobian_reuse && sameStepSize(im.last_dt, dt) && im.Yd_prev.size() == im.Yd.size())
    Yv += 0.5 * dt * (im.Yd - im.Yd_prev);
  // A predicted stretch 1 + eps below kStretchFloor of the last one (a slack stretch whose strain
  // rate carries no restoring force) starts from the last strain instead.
  for (int i = 0; i + N <= static_cast<int>(Yv.size()); i += N)
    if (1.0 + Yv[i + EPS] < DynamicStepSystem3D::kStretchFloor * (1.0 + im.Y[i + EPS])) Yv[i + EPS] = im.Y[i + EPS];
  // A kept factorization belongs to one step size (the matrix holds 1 / (gamma dt)).
  if (!sameStepSize(dt, im.factored_dt)) im.newton_matrix.setZero();
  // Back from a fallback step: a few iterations say whether the implicit step holds again.
  const NewtonOptions no =
      im.in_fallback ? lumped::retryNewtonOptions(stepNewtonOptions(im.opt)) : stepNewtonOptions(im.opt);
  NewtonWork work;
  const SolverSummary s = solveNewton(sys, Yv, no, &im.newton_matrix, &work);
  im.factored_dt = dt;
  rep.newton_iterations += s.iterations;
  im.totals.newton_iterations += s.iterations;
  im.totals.jacobians += work.assemblies;
  if (!s.converged) {
    lumped::countFailedTry(im, work.assemblies);
    winchUndoStep(im);
    im.newton_matrix.setZero();  // factored at an iterate that did not converge
    std::ostringstream os;
    os << "t = " << t_new << " s (dt = " << dt << " s): " << s.message;
    rep.message = os.str();
    return false;
  }
  if (const std::string off = topOffItsPath(im, Yv, t_new); !off.empty()) {
    ++im.totals.top_off_path;
    im.newton_matrix.setZero();
    rep.message = "t = " + fmtNum(t_new) + " s (dt = " + fmtNum(dt) + " s): " + off;
    return false;
  }
  const double g = im.ga.gamma;
  im.Yd_prev = im.Yd;
  im.last_dt = dt;
  im.Yd = (Yv - im.Y) / (g * dt) - ((1.0 - g) / g) * im.Yd;  // eq. 26
  im.Y = Yv;
  im.t = t_new;
  im.water = sys.water();
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, im.t);
  winchRemesh(im);
  breakOnTension(im);
  im.in_fallback = false;
  im.skipped_cap = lumped::kMaxSkippedTime;
  ++rep.steps;
  ++im.totals.steps;
  rep.smallest_dt = rep.smallest_dt > 0.0 ? std::min(rep.smallest_dt, dt) : dt;
  return true;
}

}  // namespace

StepReport DynamicSolver3D::advanceTo(double t_end) {
  Impl& im = *impl_;
  // The fallback (dynamics3d_fallback.cpp) takes what is left of a base step that fails at
  // dynamics.fallback_after_cuts cuts; right after a fallback step a failed base step goes to it
  // at once, and while the line is still slack (stayInFallback) the base step goes to it
  // without an implicit try.
  struct Fallback {
    Impl* im;
    int levels(int max_levels) const {
      // A line the fallback cannot take (a buoy, body or force top; the winch running) keeps every
      // cut level, as without the fallback.
      if (!im->opt.fallback || !fallbackUnavailable(*im, im->t + im->opt.dt).empty()) return max_levels;
      if (lumped::waitAfterFailedRetry(*im) || stayInFallback(*im)) return -1;
      return im->in_fallback ? 0 : std::min(max_levels, im->opt.fallback_after_cuts);
    }
    bool operator()(double dt, StepReport& rep) const {
      if (!im->opt.fallback) return false;
      const bool skipped = stayInFallback(*im);
      if (!fallbackStep(*im, dt, rep)) return false;
      im->fallback_skipped_time = skipped ? im->fallback_skipped_time + dt : 0.0;
      breakOnTension(*im);
      return true;
    }
  };
  auto run = [&im](double t1) {
    return advanceWithCuts(
        im.t, im.opt.dt, im.opt.max_cut_levels, t1, [&im](double dt, StepReport& rep) { return tryStep(im, dt, rep); },
        [&im]() { ++im.totals.cuts; }, Fallback{&im});
  };
  // Timed events up to t_end: advance to each, then let it happen (a break on tension happens
  // inside tryStep, after the step in which its limit is first exceeded).
  const double eps = 1e-9 * im.opt.dt;
  StepReport total;
  for (int i = nextTimedEvent(im); i >= 0 && im.events[static_cast<std::size_t>(i)].t <= t_end + eps;
       i = nextTimedEvent(im)) {
    const double te = im.events[static_cast<std::size_t>(i)].t;
    if (te > im.t + eps) {
      addReport(total, run(te));
      if (!total.ok) return total;
    }
    applyEvent(im, static_cast<std::size_t>(i), "at t = " + fmtNum(te) + " s");
  }
  addReport(total, run(t_end));
  return total;
}

double DynamicSolver3D::jacobianFiniteDifferenceError(double dt) const {
  const Impl& im = *impl_;
  DynamicStepSystem3D sys(im, im.t + dt, dt, im.top(im.t + dt));
  const JacobianCheck c = checkJacobian(sys, im.Y + dt * im.Yd);
  return c.outside_band ? 1.0 : c.worst;
}

struct DynamicSolver3D::Saved {
  double t = 0.0;
  Eigen::VectorXd Y, Yd, Yd_prev, S;
  std::vector<Water> water;
  std::vector<double> lower_state, upper_state;  ///< of the ends (EndCondition3D::state)
  // Line events: which had happened (a step re-run from here undoes the later ones).
  std::vector<char> event_done;
  std::size_t log_size = 0;
  bool lower_released = false, upper_released = false;
  int parted = -1;
  double last_dt = 0.0;
  bool in_fallback = false;
  double fallback_skipped_time = 0.0;
  int retry_wait = 0;
  double skipped_cap = 0.0;
  std::vector<double> fallback_ref;
  Totals totals;
  WinchSaved winch;  ///< the mesh a winch changes, its program and length
};

std::shared_ptr<const DynamicSolver3D::Saved> DynamicSolver3D::save() const {
  const Impl& im = *impl_;
  auto s = std::make_shared<Saved>();
  s->t = im.t;
  s->Y = im.Y;
  s->Yd = im.Yd;
  s->Yd_prev = im.Yd_prev;
  s->S = im.S;
  s->water = im.water;
  s->lower_state = im.lower->state();
  s->upper_state = im.upper->state();
  s->event_done = im.event_done;
  s->log_size = im.event_log.size();
  s->lower_released = im.lower_kept != nullptr;
  s->upper_released = im.upper_kept != nullptr;
  s->parted = im.parted;
  s->last_dt = im.last_dt;
  s->in_fallback = im.in_fallback;
  s->fallback_skipped_time = im.fallback_skipped_time;
  s->retry_wait = im.retry_wait;
  s->skipped_cap = im.skipped_cap;
  s->fallback_ref = im.fallback_ref;
  s->totals = im.totals;
  s->winch = winchSave(im);
  return s;
}

void DynamicSolver3D::restore(const Saved& s) {
  Impl& im = *impl_;
  im.t = s.t;
  im.Y = s.Y;
  im.Yd = s.Yd;
  im.Yd_prev = s.Yd_prev;
  im.S = s.S;
  im.water = s.water;
  if (s.lower_released != (im.lower_kept != nullptr) || s.upper_released != (im.upper_kept != nullptr) ||
      s.parted != im.parted)
    rowsChanged(im);
  if (!s.lower_released && im.lower_kept) im.lower = std::move(im.lower_kept);
  if (!s.upper_released && im.upper_kept) im.upper = std::move(im.upper_kept);
  im.parted = s.parted;
  im.event_done = s.event_done;
  im.event_log.resize(s.log_size);
  im.lower->setState(s.lower_state);
  im.upper->setState(s.upper_state);
  im.last_dt = s.last_dt;
  im.in_fallback = s.in_fallback;
  im.fallback_skipped_time = s.fallback_skipped_time;
  im.retry_wait = s.retry_wait;
  im.skipped_cap = s.skipped_cap;
  im.fallback_ref = s.fallback_ref;
  im.totals = s.totals;
  winchRestore(im, s.winch);
  // A kept factorization (modified Newton) stays: it is still a Jacobian of this step size.
}

DynamicSeries runDynamic3D(const Problem& problem, const std::function<void(double, double)>& progress) {
  return runDynamicWith<DynamicSolver3D>(problem, progress);
}

}  // namespace core
}  // namespace mooring_dynamics
