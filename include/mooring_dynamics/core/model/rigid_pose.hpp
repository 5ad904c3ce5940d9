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

/// The path between two poses that the lockstep drivers follow between samples: the origin moves
/// on the straight line at constant velocity, the orientation turns about one axis at a constant
/// rate (slerp along the shorter arc), so velocity and angular velocity are the exact derivatives
/// of the pose. Outside [t0, t1] the end poses are held, at rest.
class RigidSegment {
 public:
  RigidSegment() = default;
  /// t1 > t0 [s].
  RigidSegment(double t0, const RigidPose& a, double t1, const RigidPose& b);
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
};

}  // namespace core
}  // namespace mooring_dynamics
