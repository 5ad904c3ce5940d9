#include "mooring_dynamics/ros/lockstep.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "mooring_dynamics/ros/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

const char* toString(LockstepDriver::Outcome o) {
  switch (o) {
    case LockstepDriver::Outcome::Started: return "started";
    case LockstepDriver::Outcome::Advanced: return "advanced";
    case LockstepDriver::Outcome::Reinitialised: return "re-initialised";
    case LockstepDriver::Outcome::RecoveredFailure: return "recovered from a solver failure";
    case LockstepDriver::Outcome::Dropped: return "dropped";
  }
  return "?";
}

LockstepDriver::LockstepDriver(const core::Problem& problem, double dt, const LockstepOptions& options)
    : problem_(problem), options_(options) {
  if (!(std::isfinite(dt) && dt > 0.0)) throw std::invalid_argument("dt = " + formatNumber(dt) + ": must be > 0");
  problem_.dynamics.dt = dt;
  problem_.dynamics.output_interval = 0.0;
  // The samples drive the top: the file's top motion is not used (a position table would also
  // have to start at every re-initialisation's top).
  core::TopMotion hold;
  hold.prescribe_position = true;  // follow the vessel track: velocity with position feedback (no drift)
  problem_.dynamics.top_motion = hold;
  if (problem_.dynamics.duration <= 0.0) problem_.dynamics.duration = dt;  // unused in lockstep

  solver_ = std::make_unique<core::DynamicSolver2D>(problem_);  // throws when the statics fail
  solver_is_pristine_ = true;
  const core::NodeState& top = solver_->initialStatic().nodes.back();
  static_top_x_ = top.x;
  static_top_z_ = top.z;
}

LockstepDriver::~LockstepDriver() = default;

double LockstepDriver::solverTime() const { return solver_ ? solver_->time() : 0.0; }

std::unique_ptr<core::DynamicSolver2D> LockstepDriver::build(double x, double z, bool at_problem_top,
                                                             std::string& error) const {
  core::Problem p = problem_;
  if (!at_problem_top) {
    p.top.type = core::TopBoundary::Type::Position;
    p.top.x = x;
    p.top.z = z;
  }
  try {
    return std::make_unique<core::DynamicSolver2D>(p);
  } catch (const std::exception& e) {
    error = e.what();
  }
  return nullptr;
}

LockstepDriver::Result LockstepDriver::start(double t, double x, double z, Outcome outcome, const std::string& why) {
  Result r;
  r.outcome = outcome;
  const double dist = std::hypot(x - static_top_x_, z - static_top_z_);
  const bool near = dist <= options_.start_tolerance;
  std::string error;
  std::unique_ptr<core::DynamicSolver2D> fresh;
  if (near && solver_is_pristine_) {
    // Keep the solver built from the problem's statics.
  } else {
    fresh = build(x, z, near, error);
    if (!fresh) {
      started_ = false;
      r.outcome = Outcome::Dropped;
      r.message = (why.empty() ? std::string() : why + "; ") + "cannot start from statics with the top at (x, z) = (" +
                  formatNumber(x) + ", " + formatNumber(z) + ") m: " + error + "; waiting for the next sample";
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
  prev_z_ = top.z;
  state_ = solver_->snapshot();
  r.publish = true;
  r.message = (why.empty() ? std::string() : why + "; ") +
              (near ? "started from the problem's statics (top at (" + formatNumber(top.x) + ", " +
                          formatNumber(top.z) + ") m, sample " + formatNumber(dist) + " m away)"
                    : "sample " + formatNumber(dist) + " m from the problem's static top (" +
                          formatNumber(static_top_x_) + ", " + formatNumber(static_top_z_) +
                          ") m: started from statics re-solved with the top at (" + formatNumber(x) + ", " +
                          formatNumber(z) + ") m");
  return r;
}

LockstepDriver::Result LockstepDriver::onSample(double t, double x, double z) {
  Result r;
  if (!(std::isfinite(t) && std::isfinite(x) && std::isfinite(z))) {
    r.message = "non-finite sample (t, x, z) = (" + formatNumber(t) + ", " + formatNumber(x) + ", " +
                formatNumber(z) + ")";
    return r;
  }
  if (!started_) return start(t, x, z, Outcome::Started, "");

  const double gap = t - last_time_;
  if (gap <= 0.0) {
    if (-gap > options_.loop_back)
      return start(t, x, z, Outcome::Reinitialised,
                   "time went back by " + formatNumber(-gap) + " s (more than " + formatNumber(options_.loop_back) +
                       " s: bag loop?)");
    r.message = "time not increasing: " + formatNumber(t) + " s after " + formatNumber(last_time_) + " s (" +
                (gap == 0.0 ? std::string("same stamp") : "back by " + formatNumber(-gap) + " s") + ")";
    return r;
  }

  const double tp = prev_t_, xp = prev_x_, zp = prev_z_;
  const double tn = t - t0_;
  const double span = tn - tp;
  const double vx = (x - xp) / span, vz = (z - zp) / span;
  solver_->setTopInput([=](double tau) {
    core::TopInput in;
    const double w = std::clamp((tau - tp) / span, 0.0, 1.0);
    in.x = xp + w * (x - xp);
    in.z = zp + w * (z - zp);
    in.vx = vx;
    in.vz = vz;
    return in;
  });
  solver_is_pristine_ = false;
  r.report = solver_->advanceTo(tn);
  if (!r.report.ok) {
    const core::StepReport rep = r.report;
    r = start(t, x, z, Outcome::RecoveredFailure, "dynamic solver failed: " + rep.message);
    r.report = rep;
    return r;
  }
  prev_t_ = tn;
  prev_x_ = x;
  prev_z_ = z;
  last_time_ = t;
  state_ = solver_->snapshot();
  r.outcome = Outcome::Advanced;
  r.publish = true;
  return r;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
