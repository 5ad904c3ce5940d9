// The pose and motion of a rigid body (a moored vessel, a buoy hull) and of the points fixed to it
// (fairleads). Frames (REP 103 / REP 105): the world frame has x east, y north, z up, z = 0 at the
// mean sea surface; the body frame has x forward, y left, z up. A pose maps body-frame points to
// the world frame: p_world = position + R(orientation) p_body.
#pragma once

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mooring_dynamics {
namespace core {

/// [-] A quaternion whose norm differs from 1 by more than this is not an orientation (a sample
/// with it is rejected, not normalized): 1e-3 admits the rounding of single-precision sources and
/// of messages printed with 4-5 digits, and refuses anything that is not meant as a rotation.
constexpr double kUnitQuaternionTolerance = 1e-3;

struct RigidPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                 ///< body origin in the world [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();    ///< body -> world rotation

  /// World position of a body-frame point [m].
  Eigen::Vector3d apply(const Eigen::Vector3d& r_body) const { return position + orientation * r_body; }
  /// A world vector seen in the body frame.
  Eigen::Vector3d toBody(const Eigen::Vector3d& v_world) const { return orientation.conjugate() * v_world; }

  /// Roll, pitch, yaw [rad] (rotations about the body's x, y, z, applied as R = Rz(yaw) Ry(pitch) Rx(roll)).
  static RigidPose fromRollPitchYaw(const Eigen::Vector3d& position, double roll, double pitch, double yaw);
  /// The yaw [rad] of that decomposition: the heading of the body x axis projected on the
  /// horizontal, counterclockwise from world +x.
  double yaw() const;

  /// Empty when usable, else a message naming `what` (e.g. "vessel.pose"), the value and the
  /// constraint: finite position, finite quaternion of unit norm within kUnitQuaternionTolerance.
  std::string validate(const std::string& what) const;
};

/// The state of motion of a rigid body at one time: pose, linear velocity of its origin and
/// angular velocity, both in the world frame.
struct RigidMotion {
  RigidPose pose;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          ///< of the body origin [m/s], world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< [rad/s], world

  /// Velocity of a body-frame point [m/s], world: v + omega x (R r).
  Eigen::Vector3d pointVelocity(const Eigen::Vector3d& r_body) const {
    return velocity + angular_velocity.cross(pose.orientation * r_body);
  }
};

/// A twist in the body frame (REP 105: nav_msgs/Odometry's twist is in its child frame, the body):
/// the origin's velocity [m/s] and the angular velocity [rad/s], both in body axes.
struct BodyTwist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  /// Empty when finite, else a message naming `what` (e.g. "twist") and the value.
  std::string validate(const std::string& what) const;
};

/// A timestamped pose, with or without its body twist: one row of a vessel motion table
/// (core/io/vessel_motion_io.hpp), one sample of a generated motion (core/model/storm_motion.hpp).
struct PoseSample {
  PoseSample() = default;
  PoseSample(double time, const RigidPose& p) : t(time), pose(p) {}  ///< a pose-only sample
  double t = 0.0;  ///< [s]
  RigidPose pose;  ///< world frame
  bool has_twist = false;
  BodyTwist twist;  ///< body frame (has_twist)
};

/// The world-frame motion of a body at `pose` with body twist `twist`: v = R v_body,
/// omega = R omega_body (R = pose.orientation, body -> world).
RigidMotion motionFromBodyTwist(const RigidPose& pose, const BodyTwist& twist);

/// The path between two samples that the lockstep drivers follow between them. Outside [t0, t1]
/// the end poses are held, at rest.
///  * From two poses (pose-only): the origin moves on the straight line at constant velocity, the
///    orientation turns about one axis at a constant rate (slerp along the shorter arc), so velocity
///    and angular velocity are the exact derivatives of the pose.
///  * From two poses with their velocities (RigidMotion, world frame; e.g. from an odometry twist):
///    the path meets both poses *and* both velocities. The origin follows the cubic Hermite curve
///    of the two positions and velocities. The orientation is R(t) = R_a Exp(phi(t)) with phi the
///    cubic Hermite curve in the rotation vector from phi(t0) = 0 to phi(t1) = Log(R_a^T R_b)
///    (shorter arc), with the end rates phi'(t0) = R_a^T omega_a and phi'(t1) = J_r(phi1)^-1 R_b^T
///    omega_b (J_r the right Jacobian of SO(3)), so that the angular velocity
///    omega(t) = R(t) J_r(phi(t)) phi'(t) is omega_a at t0 and omega_b at t1. (The constant-rate
///    rotation of the pose-only path cannot meet two given angular velocities: its rate is fixed by
///    the poses.) A constant rate with the matching twist gives the constant-rate rotation again
///    (phi linear), and a constant velocity the straight line. Velocities are the exact derivatives
///    of the path. The rotation between two samples must stay below pi (J_r^-1 is singular there):
///    at coupling rates it is a few degrees.
class RigidSegment {
 public:
  RigidSegment() = default;
  /// t1 > t0 [s].
  RigidSegment(double t0, const RigidPose& a, double t1, const RigidPose& b);
  /// The Hermite path; t1 > t0 [s]; velocities and angular velocities in the world frame.
  RigidSegment(double t0, const RigidMotion& a, double t1, const RigidMotion& b);
  /// A body at rest at `pose` for all times.
  static RigidSegment hold(const RigidPose& pose);
  RigidMotion at(double t) const;

 private:
  double t0_ = 0.0, t1_ = 0.0;
  RigidPose a_, b_;
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega_body_ = Eigen::Vector3d::Zero();   ///< rotation vector of a^-1 b per second, body frame of a
  Eigen::Vector3d omega_world_ = Eigen::Vector3d::Zero();  ///< the same in the world frame (constant along the path)
  bool moving_ = false;
  bool hermite_ = false;
  Eigen::Vector3d va_ = Eigen::Vector3d::Zero(), vb_ = Eigen::Vector3d::Zero();  ///< Hermite: end velocities, world
  Eigen::Vector3d phi1_ = Eigen::Vector3d::Zero();                             ///< Hermite: Log(R_a^T R_b)
  Eigen::Vector3d dphi0_ = Eigen::Vector3d::Zero(), dphi1_ = Eigen::Vector3d::Zero();  ///< Hermite: end rates of phi
};

/// The right Jacobian of SO(3) at the rotation vector phi, and its inverse (|phi| < pi).
Eigen::Matrix3d rightJacobianSO3(const Eigen::Vector3d& phi);
Eigen::Matrix3d rightJacobianSO3Inverse(const Eigen::Vector3d& phi);

}  // namespace core
}  // namespace mooring_dynamics
