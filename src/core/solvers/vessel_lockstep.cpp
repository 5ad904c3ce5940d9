#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {

namespace {
std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

std::string VesselLockstepOptions::validate() const {
  if (!(start_tolerance >= 0.0)) return "start_tolerance = " + num(start_tolerance) + " m: must be >= 0";
  if (!(start_angle_tolerance >= 0.0)) return "start_angle_tolerance = " + num(start_angle_tolerance) + " rad: must be >= 0";
  if (!(loop_back > 0.0)) return "loop_back = " + num(loop_back) + " s: must be > 0";
  if (jumps_to_reinit < 1) return "jumps_to_reinit = " + std::to_string(jumps_to_reinit) + ": must be >= 1";
  if (failures_to_reinit < 1) return "failures_to_reinit = " + std::to_string(failures_to_reinit) + ": must be >= 1";
  if (threads < 1) return "threads = " + std::to_string(threads) + ": must be >= 1";
  if (!(std::isfinite(solve_interval) && solve_interval >= 0.0))
    return "solve_interval = " + num(solve_interval) + " s: must be finite and >= 0";
  return {};
}

const char* toString(VesselLockstep::Outcome o) {
  switch (o) {
    case VesselLockstep::Outcome::Started: return "started";
    case VesselLockstep::Outcome::Advanced: return "advanced";
    case VesselLockstep::Outcome::LinesRestarted: return "advanced, lines restarted";
    case VesselLockstep::Outcome::Reinitialised: return "reinitialised";
    case VesselLockstep::Outcome::Failed: return "failed, last good state kept";
    case VesselLockstep::Outcome::RecoveredFailure: return "recovered from a failure";
    case VesselLockstep::Outcome::Held: return "held (answered from the last solve)";
    case VesselLockstep::Outcome::Dropped: return "dropped";
  }
  return "?";
}

VesselLockstep::VesselLockstep(const SystemProblem& system, const DynamicOptions& dynamics,
                               const VesselLockstepOptions& options)
    : system_(system), dynamics_(dynamics), options_(options) {
  const std::string e = options.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  sim_ = std::make_unique<SystemDynamics>(system_, dynamics_, options_.threads);
  sim_->setRestartFailedGroups(options_.restart_failed_lines);
  last_pose_ = system_.vessel.pose;
}

VesselLockstep::~VesselLockstep() = default;

void VesselLockstep::setFailureInjection(std::function<bool(std::size_t, double)> fail) {
  fail_hook_ = std::move(fail);
  sim_->setFailureInjection(fail_hook_);
}

double VesselLockstep::solverTime() const { return sim_->time(); }

std::vector<StaticResult> VesselLockstep::lines() const {
  std::vector<StaticResult> out;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) out.push_back(sim_->line(i));
  return out;
}

void VesselLockstep::remember(double t, const RigidPose& pose, const BodyTwist* twist) {
  last_t_ = t;
  accepted_t_ = t;
  last_pose_ = pose;
  last_has_twist_ = twist != nullptr;
  last_motion_ = twist ? motionFromBodyTwist(pose, *twist) : RigidMotion{pose, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
}

VesselLockstep::Result VesselLockstep::start(double t, const RigidPose& pose, const BodyTwist* twist, Outcome outcome, const std::string& why) {
  Result r;
  const RigidPose& ref = system_.vessel.pose;
  const bool at_file_pose = (pose.position - ref.position).norm() <= options_.start_tolerance &&
                            pose.orientation.angularDistance(ref.orientation) <= options_.start_angle_tolerance;
  if (!(at_file_pose && pristine_)) {
    SystemProblem s = system_;
    s.placeVessel(at_file_pose ? ref : pose);
    try {
      sim_ = std::make_unique<SystemDynamics>(s, dynamics_, options_.threads);
      sim_->setRestartFailedGroups(options_.restart_failed_lines);
      if (fail_hook_) sim_->setFailureInjection(fail_hook_);
    } catch (const std::exception& e) {
      ++dropped_;
      r.reason = Reason::StartFailed;
      r.message = "cannot start at this pose: " + std::string(e.what());
      return r;
    }
  }
  pristine_ = false;
  started_ = true;
  t0_ = t;
  remember(t, pose, twist);
  jumps_ = 0;
  failures_ = 0;
  r.outcome = outcome;
  r.publish = true;
  r.message = why;
  return r;
}

VesselLockstep::Result VesselLockstep::onSample(double t, const RigidPose& pose_in, const BodyTwist* twist) {
  Result r;
  std::string bad = pose_in.validate("pose");
  r.reason = !pose_in.position.allFinite()                 ? Reason::NonFinitePosition
             : !pose_in.orientation.coeffs().allFinite() ? Reason::NonFiniteOrientation
                                                         : Reason::NonUnitOrientation;
  if (bad.empty() && twist) {
    bad = twist->validate("twist");
    r.reason = Reason::BadTwist;
  }
  if (bad.empty() && !std::isfinite(t)) {
    bad = "time = " + num(t) + ": must be finite";
    r.reason = Reason::NonFiniteTime;
  }
  if (!bad.empty()) {
    ++dropped_;
    r.message = bad;
    return r;
  }
  r.reason = Reason::None;
  RigidPose pose = pose_in;
  pose.orientation.normalize();
  if (!started_) return start(t, pose, twist, Outcome::Started, "");
  if (t <= accepted_t_) {
    if (accepted_t_ - t > options_.loop_back)
      return withReason(start(t, pose, twist, Outcome::Reinitialised, "time went back by " + num(accepted_t_ - t) + " s (bag loop)"),
                        Reason::LoopBack);
    ++dropped_;
    r.message = "time " + num(t) + " s not after the last sample's " + num(accepted_t_) + " s";
    r.reason = t == accepted_t_ ? Reason::SameStamp : Reason::StampBack;
    return r;
  }
  const double gap = t - accepted_t_;
  if (options_.max_gap > 0.0 && gap > options_.max_gap)
    return withReason(start(t, pose, twist, Outcome::Reinitialised, "gap of " + num(gap) + " s since the last sample"),
                      Reason::Gap);
  const double speed = (pose.position - last_pose_.position).norm() / (t - last_t_);
  if (options_.max_speed > 0.0 && speed > options_.max_speed) {
    if (++jumps_ >= options_.jumps_to_reinit)
      return withReason(start(t, pose, twist, Outcome::Reinitialised, "the vessel jumped"), Reason::Jumps);
    ++dropped_;
    r.message = "jump implying " + num(speed) + " m/s (max_speed " + num(options_.max_speed) + ")";
    r.reason = Reason::Jump;
    return r;
  }
  jumps_ = 0;
  if (t - last_t_ < options_.solve_interval - VesselLockstepOptions::kIntervalTolerance) {
    accepted_t_ = t;
    ++held_;
    r.outcome = Outcome::Held;
    return r;
  }
  // Both ends with a twist: the Hermite path through both poses and velocities; else pose-only.
  const RigidSegment seg = (last_has_twist_ && twist)
                               ? RigidSegment(last_t_ - t0_, last_motion_, t - t0_, motionFromBodyTwist(pose, *twist))
                               : RigidSegment(last_t_ - t0_, last_pose_, t - t0_, pose);
  sim_->setVesselMotion([seg](double tau) { return seg.at(tau); });
  std::string why;
  if (!sim_->advanceTo(t - t0_, &why)) {
    if (++failures_ >= options_.failures_to_reinit)
      return withReason(start(t, pose, twist, Outcome::RecoveredFailure,
                              "restarted from statics after " + std::to_string(failures_) + " failures in a row: " + why),
                        Reason::SolverFailed);
    // Keep the last good state: every line stays at the last converged step ts, where the vessel
    // was on this sample's path; the next sample moves it on from there.
    const double ts = sim_->time();
    last_motion_ = seg.at(ts);
    last_pose_ = last_motion_.pose;
    last_has_twist_ = last_has_twist_ && twist != nullptr;
    last_t_ = t0_ + ts;
    accepted_t_ = last_t_;
    r.outcome = Outcome::Failed;
    r.reason = Reason::SolverFailed;
    r.publish = true;
    r.message = why + "; the last good state (t = " + num(ts) + " s) is kept; failure " + std::to_string(failures_) +
                " of " + std::to_string(options_.failures_to_reinit) + " in a row before a restart from statics";
    return r;
  }
  failures_ = 0;
  remember(t, pose, twist);
  r.outcome = Outcome::Advanced;
  r.publish = true;
  for (const LineGroupRestart& g : sim_->lastRestarts()) {
    std::string names;
    for (std::size_t i : g.lines) {
      names += (names.empty() ? "" : ", ") + system_.lines[i].name;
      r.failed_lines.push_back(i);
    }
    r.outcome = Outcome::LinesRestarted;
    r.message += (r.message.empty() ? "" : "; ") + g.reason + " (t = " + num(g.time) + " s); restarted from statics at " +
                 "the vessel's pose there: " + names + "; the other lines go on";
  }
  return r;
}

std::string VesselLockstep::releaseLine(const std::string& line, LineEvent::End end, const std::string& cause) {
  std::string names;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    names += (i ? ", " : "") + system_.lines[i].name;
    if (system_.lines[i].name != line) continue;
    try {
      sim_->releaseLineEnd(i, end, cause);
    } catch (const std::logic_error& e) {
      return "line = " + line + ": " + e.what();
    }
    return {};
  }
  return "line = " + line + ": no line of that name (lines: " + names + ")";
}

std::string VesselLockstep::winchLine(const std::string& line, double rate, double target, std::string& note) {
  if (!started_ || !sim_) return "no motion sample yet: the run starts at the first one; command the winch after it";
  std::string names;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    names += (i ? ", " : "") + system_.lines[i].name;
    if (system_.lines[i].name != line) continue;
    try {
      note = sim_->commandLineWinch(i, rate, target);
    } catch (const std::invalid_argument& e) {
      return "line = " + line + ": " + e.what();
    }
    return {};
  }
  return "line = " + line + ": no line of that name (lines: " + names + ")";
}

std::vector<double> VesselLockstep::lineLengths() const {
  std::vector<double> out;
  if (!sim_) return out;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) out.push_back(sim_->lineLength(i));
  return out;
}

VesselLockstep::Result VesselLockstep::reset() {
  if (!started_) return {};
  const BodyTwist tw{last_motion_.pose.toBody(last_motion_.velocity), last_motion_.pose.toBody(last_motion_.angular_velocity)};
  return withReason(start(last_t_, last_pose_, last_has_twist_ ? &tw : nullptr, Outcome::Reinitialised, "reset"),
                    Reason::Reset);
}

VesselLockstep::Result VesselLockstep::restartAt(double t, const RigidPose& pose_in, const std::string& why) {
  Result r;
  const std::string bad = pose_in.validate("pose");
  if (!bad.empty() || !std::isfinite(t)) {
    ++dropped_;
    r.reason = !bad.empty() ? Reason::NonUnitOrientation : Reason::NonFiniteTime;
    if (!pose_in.position.allFinite()) r.reason = Reason::NonFinitePosition;
    else if (!pose_in.orientation.coeffs().allFinite()) r.reason = Reason::NonFiniteOrientation;
    r.message = !bad.empty() ? bad : "time = " + num(t) + ": must be finite";
    return r;
  }
  RigidPose pose = pose_in;
  pose.orientation.normalize();
  return withReason(start(t, pose, nullptr, Outcome::Reinitialised, why), Reason::Behind);
}

VesselLockstep::Result VesselLockstep::withReason(Result r, Reason reason) {
  if (r.reason == Reason::None) r.reason = reason;
  return r;
}

}  // namespace core
}  // namespace mooring_dynamics
