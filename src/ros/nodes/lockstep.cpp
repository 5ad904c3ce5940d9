#include "mooring_dynamics/ros/nodes/lockstep.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "mooring_dynamics/core/solvers/dynamic_run.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

const char* toString(LockstepDriver::Outcome o) {
  switch (o) {
    case LockstepDriver::Outcome::Started: return "started";
    case LockstepDriver::Outcome::Advanced: return "advanced";
    case LockstepDriver::Outcome::Reinitialised: return "re-initialised";
    case LockstepDriver::Outcome::Failed: return "solver failed, last good state kept";
    case LockstepDriver::Outcome::RecoveredFailure: return "recovered from a solver failure";
    case LockstepDriver::Outcome::Dropped: return "dropped";
  }
  return "?";
}

const char* toString(LockstepDriver::Reason r) {
  switch (r) {
    case LockstepDriver::Reason::None: return "none";
    case LockstepDriver::Reason::NonFinite: return "non-finite";
    case LockstepDriver::Reason::OffPlane: return "off the plane y = 0";
    case LockstepDriver::Reason::SameStamp: return "same stamp";
    case LockstepDriver::Reason::StampBack: return "stamp back";
    case LockstepDriver::Reason::Jump: return "jump";
    case LockstepDriver::Reason::StartFailed: return "statics failed";
    case LockstepDriver::Reason::LoopBack: return "bag loop";
    case LockstepDriver::Reason::Gap: return "gap";
    case LockstepDriver::Reason::Jumps: return "jumps";
    case LockstepDriver::Reason::Request: return "request";
    case LockstepDriver::Reason::SolverFailed: return "solver failed";
  }
  return "?";
}

// ------------------------------------------------------------------------------------------------
// The adapters.

core::TopInput linearTopInput(double tau, double t0, double x0, double z0, double t1, double x1, double z1) {
  return core::segmentTopInput(tau, t0, x0, z0, t1, x1, z1);
}

core::TopState linearTopState(double tau, double t0, double x0, double y0, double z0, double t1, double x1,
                              double y1, double z1) {
  return core::segmentTopState(tau, t0, x0, y0, z0, t1, x1, y1, z1);
}

namespace {

class Solver2D final : public LockstepSolver {
 public:
  explicit Solver2D(const core::Problem& p) : s_(p) {}
  const core::StaticResult& initialStatic() const override { return s_.initialStatic(); }
  void setTopSegment(double t0, double x0, double, double z0, double t1, double x1, double, double z1) override {
    s_.setTopInput([=](double tau) { return linearTopInput(tau, t0, x0, z0, t1, x1, z1); });
  }
  core::StepReport advanceTo(double t) override { return s_.advanceTo(t); }
  core::StaticResult snapshot() const override { return s_.snapshot(); }
  double time() const override { return s_.time(); }

 private:
  core::DynamicSolver2D s_;
};

class Solver3D final : public LockstepSolver {
 public:
  explicit Solver3D(const core::Problem& p) : s_(p) {}
  const core::StaticResult& initialStatic() const override { return s_.initialStatic(); }
  void setTopSegment(double t0, double x0, double y0, double z0, double t1, double x1, double y1,
                     double z1) override {
    s_.setTopInput([=](double tau) { return linearTopState(tau, t0, x0, y0, z0, t1, x1, y1, z1); });
  }
  core::StepReport advanceTo(double t) override { return s_.advanceTo(t); }
  core::StaticResult snapshot() const override { return s_.snapshot(); }
  double time() const override { return s_.time(); }
  std::string releaseEnd(core::LineEvent::End end, const std::string& cause) override {
    try {
      s_.releaseEnd(end, cause);
    } catch (const std::logic_error& e) {
      return std::string("end = ") + (end == core::LineEvent::End::Top ? "top" : "anchor") + ": " + e.what();
    }
    return {};
  }
  std::vector<core::LineEventRecord> eventLog() const override { return s_.eventLog(); }
  std::string commandWinch(double rate, double target, std::string& note) override {
    try {
      note = s_.commandWinch(rate, target);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return {};
  }
  double lineLength() const override { return s_.lineLength(); }
  double winchRate() const override { return s_.winchRate(); }

 private:
  core::DynamicSolver3D s_;
};

}  // namespace

LockstepSolverFactory makeSolver2D() {
  return [](const core::Problem& p) -> std::unique_ptr<LockstepSolver> {
    if (p.formulation != core::Formulation::TwoD)
      throw std::invalid_argument("model = 3d: the 2-D lockstep solver (makeSolver2D) needs model: 2d");
    return std::make_unique<Solver2D>(p);
  };
}

LockstepSolverFactory makeSolver3D() {
  return [](const core::Problem& p) -> std::unique_ptr<LockstepSolver> {
    if (p.formulation != core::Formulation::ThreeD)
      throw std::invalid_argument("model = 2d: the 3-D lockstep solver (makeSolver3D) needs model: 3d");
    return std::make_unique<Solver3D>(p);
  };
}

LockstepSolverFactory makeSolverFor(core::Formulation formulation) {
  return formulation == core::Formulation::ThreeD ? makeSolver3D() : makeSolver2D();
}

// ------------------------------------------------------------------------------------------------

LockstepDriver::LockstepDriver(const core::Problem& problem, double dt, const LockstepOptions& options,
                               LockstepSolverFactory factory)
    : problem_(problem), options_(options), factory_(std::move(factory)) {
  if (!(std::isfinite(dt) && dt > 0.0)) throw std::invalid_argument("dt = " + formatNumber(dt) + ": must be > 0");
  // The samples drive the line's top: a line whose top floats free (a subsurface buoy) or whose
  // lower end is free (a tow; the steady start needs the ship's velocity) is not run in lockstep.
  if (problem.top.type == core::TopBoundary::Type::Body)
    throw std::invalid_argument("top.body: the top of this line floats free (a subsurface buoy), so no motion "
                                "source can drive it; use ~mode static or cable_sim dynamic");
  if (problem.lower_end == core::Problem::LowerEnd::Free && problem.top.type != core::TopBoundary::Type::Position)
    throw std::invalid_argument("free_end with a floating top (a drifter): the samples cannot drive it; use "
                                "cable_sim dynamic");
  if (!factory_) factory_ = makeSolverFor(problem.formulation);
  problem_.dynamics.dt = dt;
  problem_.dynamics.output_interval = 0.0;
  // The samples drive the top: the file's top motion is not used (a position table would also
  // have to start at every re-initialisation's top).
  setStartMotion(problem_);
  if (problem_.dynamics.duration <= 0.0) problem_.dynamics.duration = dt;  // unused in lockstep

  solver_ = factory_(problem_);  // throws when the statics fail
  solver_is_pristine_ = true;
  const core::NodeState& top = solver_->initialStatic().nodes.back();
  static_top_x_ = top.x;
  static_top_y_ = top.y;
  static_top_z_ = top.z;
}

LockstepDriver::~LockstepDriver() = default;

LockstepDriver::Result LockstepDriver::withReason(Result r, Reason reason) {
  if (!r.start_failed) r.reason = reason;
  return r;
}

double LockstepDriver::solverTime() const { return solver_ ? solver_->time() : 0.0; }

std::string LockstepDriver::release(core::LineEvent::End end, const std::string& cause) {
  if (!threeD()) return "model = 2d: line events need model: 3d";
  if (!started_ || !solver_) return "no motion sample yet: the run starts at the first one; let go after it";
  return solver_->releaseEnd(end, cause);
}

std::string LockstepDriver::winch(double rate, double target, std::string& note) {
  if (!threeD()) return "model = 2d: the line node's winch needs model: 3d (a planar line gives the same results there)";
  if (!started_ || !solver_) return "no motion sample yet: the run starts at the first one; command the winch after it";
  return solver_->commandWinch(rate, target, note);
}
double LockstepDriver::lineLength() const { return solver_ ? solver_->lineLength() : problem_.totalLength(); }
double LockstepDriver::winchRate() const { return solver_ ? solver_->winchRate() : 0.0; }

std::vector<core::LineEventRecord> LockstepDriver::events() const {
  return solver_ ? solver_->eventLog() : std::vector<core::LineEventRecord>{};
}

std::string LockstepDriver::point(double x, double y, double z) const {
  return threeD() ? "(" + formatNumber(x) + ", " + formatNumber(y) + ", " + formatNumber(z) + ")"
                  : "(" + formatNumber(x) + ", " + formatNumber(z) + ")";
}

std::string LockstepDriver::positionError(double x, double y, double z) const {
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)))
    return "non-finite top position (x, y, z) = (" + formatNumber(x) + ", " + formatNumber(y) + ", " +
           formatNumber(z) + ")";
  return planarError(y);
}

std::string LockstepDriver::planarError(double y) const {
  if (threeD() || std::abs(y) <= kPlanarTolerance) return "";
  return "y = " + formatNumber(y) + " m: the problem is model: 2d, its line lies in the vertical x-z plane y = 0 "
         "of the frame (|y| <= " + formatNumber(kPlanarTolerance) + " m is taken as 0); set model: 3d in the "
         "problem to follow motion out of that plane";
}

void LockstepDriver::setStartMotion(core::Problem& p) {
  core::TopMotion m;
  m.prescribe_position = true;  // follow the vessel track: velocity with position feedback (no drift)
  if (p.lower_end == core::Problem::LowerEnd::Free && (p.top.tow_vx != 0.0 || p.top.tow_vy != 0.0)) {
    // A tow starts from its steady state at top.tow_velocity (paper section 7.1), which the solver
    // takes from the top motion's velocity at t = 0: rows one second either side of the top, on
    // that velocity (as cable_sim dynamic's GNSS table starts). The samples move the top from the
    // first step on (setTopSegment), so the rows after t = 0 are never followed.
    m.type = core::TopMotion::Type::PositionTable;
    for (double t : {-1.0, 0.0, 1.0})
      m.table.emplace_back(t, p.top.x + t * p.top.tow_vx, p.top.y + t * p.top.tow_vy, p.top.z);
  }
  p.dynamics.top_motion = m;
}

std::unique_ptr<LockstepSolver> LockstepDriver::build(double x, double y, double z, bool at_problem_top,
                                                      std::string& error) const {
  core::Problem p = problem_;
  if (!at_problem_top) {
    p.top.type = core::TopBoundary::Type::Position;
    p.top.x = x;
    p.top.y = threeD() ? y : 0.0;
    p.top.z = z;
    setStartMotion(p);
  }
  try {
    return factory_(p);
  } catch (const std::exception& e) {
    error = e.what();
  }
  return nullptr;
}

LockstepDriver::Result LockstepDriver::start(double t, double x, double y, double z, Outcome outcome,
                                             const std::string& why) {
  Result r;
  r.outcome = outcome;
  const double dist = std::sqrt((x - static_top_x_) * (x - static_top_x_) + (y - static_top_y_) * (y - static_top_y_) +
                                (z - static_top_z_) * (z - static_top_z_));
  const bool near = dist <= options_.start_tolerance;
  std::string error;
  if (near && solver_is_pristine_) {
    // Keep the solver built from the problem's statics.
  } else {
    std::unique_ptr<LockstepSolver> fresh = build(x, y, z, near, error);
    if (!fresh) {
      started_ = false;
      r.outcome = Outcome::Dropped;
      r.reason = Reason::StartFailed;
      r.start_failed = true;
      r.message = (why.empty() ? std::string() : why + "; ") + "cannot start from statics with the top at " +
                  (threeD() ? "(x, y, z) = " : "(x, z) = ") + point(x, y, z) + " m: " + error +
                  "; waiting for the next sample";
      return r;
    }
    solver_ = std::move(fresh);
    solver_is_pristine_ = near;
  }
  const core::NodeState& top = solver_->initialStatic().nodes.back();
  started_ = true;
  t0_ = t;
  last_time_ = t;
  prev_t_ = 0.0;
  prev_x_ = top.x;
  prev_y_ = top.y;
  prev_z_ = top.z;
  jumps_ = 0;
  failures_ = 0;
  state_ = solver_->snapshot();
  r.publish = true;
  r.message = (why.empty() ? std::string() : why + "; ") +
              (near ? "started from the problem's statics (top at " + point(top.x, top.y, top.z) + " m, sample " +
                          formatNumber(dist) + " m away)"
                    : "top " + formatNumber(dist) + " m from the problem's static top " +
                          point(static_top_x_, static_top_y_, static_top_z_) +
                          " m: started from statics re-solved with the top at " + point(x, y, z) + " m");
  return r;
}

LockstepDriver::Result LockstepDriver::onSample(double t, double x, double y, double z) {
  Result r;
  if (!(std::isfinite(t) && std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
    r.message = "non-finite sample (t, x, y, z) = (" + formatNumber(t) + ", " + formatNumber(x) + ", " +
                formatNumber(y) + ", " + formatNumber(z) + ")";
    r.reason = Reason::NonFinite;
    return r;
  }
  r.message = positionError(x, y, z);
  if (!r.message.empty()) {
    r.reason = Reason::OffPlane;
    return r;
  }
  if (!threeD()) y = 0.0;
  if (!started_) return start(t, x, y, z, Outcome::Started, "");

  const double gap = t - last_time_;
  if (gap <= 0.0) {
    if (-gap > options_.loop_back)
      return withReason(start(t, x, y, z, Outcome::Reinitialised,
                              "time went back by " + formatNumber(-gap) + " s (more than " +
                                  formatNumber(options_.loop_back) + " s: bag loop?)"),
                        Reason::LoopBack);
    r.message = "time not increasing: " + formatNumber(t) + " s after " + formatNumber(last_time_) + " s (" +
                (gap == 0.0 ? std::string("same stamp") : "back by " + formatNumber(-gap) + " s") + ")";
    r.reason = gap == 0.0 ? Reason::SameStamp : Reason::StampBack;
    return r;
  }
  if (options_.max_gap > 0.0 && gap > options_.max_gap)
    return withReason(start(t, x, y, z, Outcome::Reinitialised,
                            "gap of " + formatNumber(gap) + " s since the last sample (more than " +
                                formatNumber(options_.max_gap) + " s: the motion in between is unknown)"),
                      Reason::Gap);

  const double tp = prev_t_, xp = prev_x_, yp = prev_y_, zp = prev_z_;
  const double tn = t - t0_;
  if (options_.max_speed > 0.0) {
    const double dist = std::sqrt((x - xp) * (x - xp) + (y - yp) * (y - yp) + (z - zp) * (z - zp));
    const double speed = dist / (tn - tp);
    if (speed > options_.max_speed) {
      const std::string what = "top jumped from " + point(xp, yp, zp) + " to " + point(x, y, z) + " m in " +
                               formatNumber(tn - tp) + " s: " + formatNumber(speed) +
                               " m/s, more than max_speed = " + formatNumber(options_.max_speed) + " m/s";
      if (++jumps_ >= options_.jumps_to_reinit)
        return withReason(start(t, x, y, z, Outcome::Reinitialised,
                                what + " (" + std::to_string(jumps_) + " samples in a row: the source moved)"),
                          Reason::Jumps);
      r.message = what;
      r.reason = Reason::Jump;
      return r;
    }
  }
  jumps_ = 0;

  solver_->setTopSegment(tp, xp, yp, zp, tn, x, y, z);
  solver_is_pristine_ = false;
  r.report = solver_->advanceTo(tn);
  if (!r.report.ok) {
    const core::StepReport rep = r.report;
    // A line let go or parted is not rebuilt from statics (statics would heal it).
    // Nor one its winch paid out or hauled in (statics would give it the file's length back).
    if (++failures_ >= options_.failures_to_reinit && solver_->eventLog().empty() &&
        solver_->lineLength() == solver_->initialStatic().nodes.back().s) {
      const int n = failures_;
      r = start(t, x, y, z, Outcome::RecoveredFailure,
                "dynamic solver failed (" + std::to_string(n) + " samples in a row): " + rep.message);
      r.report = rep;
      r.reason = Reason::SolverFailed;
      return r;
    }
    // Keep the last good state: the solver stays at its last converged step ts (tp <= ts < tn),
    // where the top was on this sample's segment; the next sample moves it on from there.
    const double ts = std::min(std::max(solver_->time(), tp), tn);
    const double w = tn > tp ? (ts - tp) / (tn - tp) : 0.0;
    r.advanced = ts - tp;
    prev_t_ = ts;
    prev_x_ = xp + w * (x - xp);
    prev_y_ = yp + w * (y - yp);
    prev_z_ = zp + w * (z - zp);
    last_time_ = t0_ + ts;
    state_ = solver_->snapshot();
    state_.summary.converged = false;  // not the state at this sample's time
    r.outcome = Outcome::Failed;
    r.reason = Reason::SolverFailed;
    r.publish = true;
    r.message = "dynamic solver failed: " + rep.message + "; the last good state (solver time " + formatNumber(ts) +
                " s, top at " + point(prev_x_, prev_y_, prev_z_) + " m) is kept and published with converged = "
                "false; the next sample continues from it (" + std::to_string(failures_) + " of " +
                std::to_string(options_.failures_to_reinit) + " failures in a row before statics are re-solved)";
    return r;
  }
  failures_ = 0;
  r.advanced = tn - tp;
  prev_t_ = tn;
  prev_x_ = x;
  prev_y_ = y;
  prev_z_ = z;
  last_time_ = t;
  state_ = solver_->snapshot();
  r.outcome = Outcome::Advanced;
  r.publish = true;
  return r;
}

LockstepDriver::Result LockstepDriver::reset() {
  if (!started_) {
    Result r;
    r.message = "not started yet: nothing to reset (the run starts from statics at the first motion sample)";
    return r;
  }
  return reinitialiseAt(prev_x_, prev_y_, prev_z_, "reset requested");
}

LockstepDriver::Result LockstepDriver::reinitialiseAt(double x, double y, double z, const std::string& why) {
  if (!started_) {
    Result r;
    r.message = "not started yet: the run starts from statics at the first motion sample";
    return r;
  }
  {
    Result r;
    r.message = positionError(x, y, z);
    if (!r.message.empty()) return r;
  }
  if (!threeD()) y = 0.0;
  const double t = last_time_;
  const double keep_x = prev_x_, keep_y = prev_y_, keep_z = prev_z_, keep_t0 = t0_, keep_prev_t = prev_t_;
  Result r = start(t, x, y, z, Outcome::Reinitialised, why);
  if (!r.start_failed) r.reason = Reason::Request;
  if (r.start_failed) {
    // The old solver is still there: keep running it.
    started_ = true;
    prev_x_ = keep_x;
    prev_y_ = keep_y;
    prev_z_ = keep_z;
    t0_ = keep_t0;
    prev_t_ = keep_prev_t;
    r.message = why + ": cannot solve statics with the top at " + point(x, y, z) + " m; the run goes on unchanged";
  }
  return r;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
