#include "mooring_dynamics/core/model/rigid_pose.hpp"

#include <cmath>
#include <sstream>

namespace mooring_dynamics {
namespace core {

RigidPose RigidPose::fromRollPitchYaw(const Eigen::Vector3d& position, double roll, double pitch, double yaw) {
  RigidPose p;
  p.position = position;
  p.orientation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return p;
}

std::string RigidPose::validate(const std::string& what) const {
  std::ostringstream os;
  if (!position.allFinite()) {
    os << what << ".position = (" << position.x() << ", " << position.y() << ", " << position.z()
       << "): must be finite";
    return os.str();
  }
  const Eigen::Vector4d q = orientation.coeffs();
  if (!q.allFinite()) {
    os << what << ".orientation = (x " << q[0] << ", y " << q[1] << ", z " << q[2] << ", w " << q[3]
       << "): must be finite";
    return os.str();
  }
  if (std::abs(q.norm() - 1.0) > kUnitQuaternionTolerance) {
    os << what << ".orientation = (x " << q[0] << ", y " << q[1] << ", z " << q[2] << ", w " << q[3] << "): norm "
       << q.norm() << ", must be 1 within " << kUnitQuaternionTolerance;
    return os.str();
  }
  return {};
}

RigidSegment::RigidSegment(double t0, const RigidPose& a, double t1, const RigidPose& b)
    : t0_(t0), t1_(t1), a_(a), b_(b), moving_(t1 > t0) {
  if (!moving_) return;
  const double dt = t1 - t0;
  velocity_ = (b.position - a.position) / dt;
  Eigen::Quaterniond rel = a.orientation.conjugate() * b.orientation;  // b = a rel, in a's body frame
  if (rel.w() < 0.0) rel.coeffs() = -rel.coeffs();                      // the shorter arc
  const Eigen::AngleAxisd aa(rel);
  omega_body_ = aa.axis() * (aa.angle() / dt);
  omega_world_ = a.orientation * omega_body_;
}

RigidSegment RigidSegment::hold(const RigidPose& pose) {
  RigidSegment s;
  s.a_ = s.b_ = pose;
  return s;
}

RigidMotion RigidSegment::at(double t) const {
  RigidMotion m;
  if (!moving_ || t < t0_) {
    m.pose = a_;
    return m;
  }
  if (t > t1_) {
    m.pose = b_;
    return m;
  }
  const double s = t - t0_;
  m.pose.position = a_.position + velocity_ * s;
  const double rate = omega_body_.norm();
  m.pose.orientation = rate > 0.0 ? a_.orientation * Eigen::Quaterniond(Eigen::AngleAxisd(rate * s, omega_body_ / rate))
                                  : a_.orientation;
  m.velocity = velocity_;
  m.angular_velocity = omega_world_;
  return m;
}

}  // namespace core
}  // namespace mooring_dynamics
