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

double RigidPose::yaw() const {
  const Eigen::Matrix3d r = orientation.normalized().toRotationMatrix();
  return std::atan2(r(1, 0), r(0, 0));
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

std::string BodyTwist::validate(const std::string& what) const {
  std::ostringstream os;
  if (!linear.allFinite()) {
    os << what << ".linear = (" << linear.x() << ", " << linear.y() << ", " << linear.z() << "): must be finite";
    return os.str();
  }
  if (!angular.allFinite()) {
    os << what << ".angular = (" << angular.x() << ", " << angular.y() << ", " << angular.z() << "): must be finite";
    return os.str();
  }
  return {};
}

RigidMotion motionFromBodyTwist(const RigidPose& pose, const BodyTwist& twist) {
  RigidMotion m;
  m.pose = pose;
  m.velocity = pose.orientation * twist.linear;
  m.angular_velocity = pose.orientation * twist.angular;
  return m;
}

namespace {
Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}
// [rad] below this angle the coefficients of J_r and J_r^-1 are their Taylor series (the closed
// forms lose digits to cancellation): the series' next terms are below 1e-20 there.
constexpr double kSmallAngle = 1e-4;
Eigen::Quaterniond expSO3(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  return a > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(a, phi / a)) : Eigen::Quaterniond::Identity();
}
}  // namespace

Eigen::Matrix3d rightJacobianSO3(const Eigen::Vector3d& phi) {
  const double a = phi.norm(), a2 = a * a;
  const double c1 = a < kSmallAngle ? 0.5 - a2 / 24.0 : (1.0 - std::cos(a)) / a2;
  const double c2 = a < kSmallAngle ? 1.0 / 6.0 - a2 / 120.0 : (a - std::sin(a)) / (a2 * a);
  const Eigen::Matrix3d K = skew(phi);
  return Eigen::Matrix3d::Identity() - c1 * K + c2 * K * K;
}

Eigen::Matrix3d rightJacobianSO3Inverse(const Eigen::Vector3d& phi) {
  const double a = phi.norm(), a2 = a * a;
  const double c2 = a < kSmallAngle ? 1.0 / 12.0 + a2 / 720.0 : 1.0 / a2 - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
  const Eigen::Matrix3d K = skew(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * K + c2 * K * K;
}

RigidSegment::RigidSegment(double t0, const RigidMotion& a, double t1, const RigidMotion& b)
    : t0_(t0), t1_(t1), a_(a.pose), b_(b.pose), moving_(t1 > t0), hermite_(true), va_(a.velocity), vb_(b.velocity) {
  if (!moving_) return;
  Eigen::Quaterniond rel = a.pose.orientation.conjugate() * b.pose.orientation;  // R_a^T R_b
  if (rel.w() < 0.0) rel.coeffs() = -rel.coeffs();                                // the shorter arc
  const Eigen::AngleAxisd aa(rel);
  phi1_ = aa.axis() * aa.angle();
  dphi0_ = a.pose.orientation.conjugate() * a.angular_velocity;
  dphi1_ = rightJacobianSO3Inverse(phi1_) * (b.pose.orientation.conjugate() * b.angular_velocity);
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
  if (hermite_) {
    // Cubic Hermite basis on s in [0, 1] and its derivatives (per unit s).
    const double T = t1_ - t0_, s = (t - t0_) / T, s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
    m.pose.position = h00 * a_.position + h10 * T * va_ + h01 * b_.position + h11 * T * vb_;
    m.velocity = (d00 * a_.position + d10 * T * va_ + d01 * b_.position + d11 * T * vb_) / T;
    const Eigen::Vector3d phi = h10 * T * dphi0_ + h01 * phi1_ + h11 * T * dphi1_;
    const Eigen::Vector3d dphi = (d10 * T * dphi0_ + d01 * phi1_ + d11 * T * dphi1_) / T;
    m.pose.orientation = a_.orientation * expSO3(phi);
    m.angular_velocity = m.pose.orientation * (rightJacobianSO3(phi) * dphi);
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
