// A moored vessel's computed motion: wave frequency by RAOs, slow drift by the lines' wrench
// (vessel_motion_source.hpp).
#include "mooring_dynamics/core/solvers/vessel_motion_source.hpp"

#include <cmath>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {

VesselMotionSource::VesselMotionSource(const SystemProblem& system)
    : file_pose_(system.vessel.pose), raos_(system.vessel.rao_table), drift_table_(system.vessel.drift_table) {
  const Vessel& v = system.vessel;
  if (!v.sea_state && !v.low_frequency)
    throw std::invalid_argument("vessel: neither sea_state nor low_frequency: nothing computes the motion");
  if (v.low_frequency) slow_ = std::make_unique<HullSlowMotion>(v.slow, v.pose);
  if (v.sea_state) {
    sea_ = WaveField(system.environment.waves, system.environment.depth, system.environment.gravity);
    wave_motion_ = std::make_unique<SeaStateMotion>(sea_, raos_, v.pose, v.raos.reference_point);
  }
  if (v.wave_drift) {
    if (!slow_ || !wave_motion_)
      throw std::invalid_argument("vessel.low_frequency.wave_drift: needs low_frequency and sea_state");
    drift_ = std::make_unique<WaveDrift>(sea_, drift_table_, v.drift.newman);
    drift_reference_ = v.raos.reference_point;
  }
}

RigidPose VesselMotionSource::slowPose() const { return slow_ ? slow_->pose() : file_pose_; }

PoseSample VesselMotionSource::sample(double t) {
  last_t_ = t;
  // The slow pose's velocity in the world: (u, v) turned by its yaw, the yaw rate about z.
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero(), w_world = Eigen::Vector3d::Zero();
  if (slow_) {
    const double psi = slow_->position().z(), c = std::cos(psi), s = std::sin(psi);
    const Eigen::Vector3d& u = slow_->velocity();
    v_world = Eigen::Vector3d(c * u.x() - s * u.y(), s * u.x() + c * u.y(), 0.0);
    w_world = Eigen::Vector3d(0.0, 0.0, u.z());
  }
  if (wave_motion_) {
    if (slow_) wave_motion_->rebase(slow_->pose());
    const PoseSample p = wave_motion_->at(t, v_world, w_world);
    last_origin_ = p.pose.position;
    return p;
  }
  PoseSample p;
  p.t = t;
  p.pose = slow_->pose();
  p.has_twist = true;
  const Eigen::Matrix3d r = p.pose.orientation.toRotationMatrix();
  p.twist.linear = r.transpose() * v_world;
  p.twist.angular = r.transpose() * w_world;
  last_origin_ = p.pose.position;
  return p;
}

void VesselMotionSource::advance(double dt, const VesselWrench& w) {
  if (!slow_) return;
  // The lines' horizontal force and their moment about the slow origin's vertical, in the slow
  // body axes (the wrench is about the sampled origin, which the waves move off the slow one).
  const double psi = slow_->position().z(), c = std::cos(psi), s = std::sin(psi);
  const Eigen::Vector3d arm = last_origin_ - slow_->pose().position;
  const double mz = w.moment_world.z() + arm.x() * w.force_world.y() - arm.y() * w.force_world.x();
  Eigen::Vector3d f(c * w.force_world.x() + s * w.force_world.y(), -s * w.force_world.x() + c * w.force_world.y(), mz);
  if (drift_) {
    const RigidPose slow = slow_->pose();
    last_drift_ = drift_->force(last_t_, slow, slow.apply(drift_reference_));
    f += last_drift_;
  }
  slow_->step(dt, f);
}

}  // namespace core
}  // namespace mooring_dynamics
