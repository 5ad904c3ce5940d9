// The low-frequency motion of a moored hull (issue "Design storms"; problem file
// `vessel.low_frequency`): surge, sway and yaw of a rigid body in the horizontal plane, moved by
// the mooring's wrench, a steady mean force (wind, current, mean wave drift) and linear damping:
//
//   (m + a11) du/dt = X + (m + a22) v r - b11 u
//   (m + a22) dv/dt = Y - (m + a11) u r - b22 v          (u, v, r: surge and sway velocity and
//   (I + a66) dr/dt = N - b66 r                            yaw rate in the slow body axes)
//   dx/dt = u cos(psi) - v sin(psi),  dy/dt = u sin(psi) + v cos(psi),  dpsi/dt = r
//
// (X, Y, N) in the slow body axes: the lines' wrench about the body origin plus the mean force
// (given in the world frame and turned into the body axes). Heave, roll and pitch stay those of
// the mean pose (hydrostatics holds them; their wave-frequency motion comes from the RAOs).
// Integration: one step of the semi-implicit (symplectic) Euler method per call, velocities
// first with the damping implicit, then the positions with the new velocities: the step of a
// lockstep driver whose forces come from the lines' state at the start of the step.
#pragma once

#include <string>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace core {

struct HullSlowMotionOptions {
  double mass = 0.0;                                 ///< m [kg], > 0
  double yaw_inertia = 0.0;                          ///< I about the body z axis [kg m^2], > 0
  Eigen::Vector3d added_mass = Eigen::Vector3d::Zero();  ///< a11, a22 [kg], a66 [kg m^2], >= 0
  Eigen::Vector3d damping = Eigen::Vector3d::Zero();     ///< b11, b22 [N s/m], b66 [N m s/rad], >= 0
  Eigen::Vector3d mean_force = Eigen::Vector3d::Zero();  ///< world frame: Fx, Fy [N], Mz [N m]
  /// Empty when valid, else "vessel.low_frequency.<field> = <value>: <constraint>".
  std::string validate() const;
};

class HullSlowMotion {
 public:
  /// Starts at rest at `start` (world frame); its z, roll and pitch are kept. Throws
  /// std::invalid_argument with validate()'s message.
  HullSlowMotion(const HullSlowMotionOptions& options, const RigidPose& start);

  /// Advance by dt [s] under the lines' force and moment on the hull in the *current slow body
  /// axes* (the horizontal force and the moment about z: X, Y [N], N [N m]).
  void step(double dt, const Eigen::Vector3d& lines_xyn);

  /// The slow pose: (x, y) and yaw integrated, z, roll and pitch of the start.
  RigidPose pose() const;
  /// Slow surge and sway velocity [m/s] and yaw rate [rad/s] in the slow body axes.
  const Eigen::Vector3d& velocity() const { return vel_; }
  /// x, y [m] (world) and yaw [rad].
  const Eigen::Vector3d& position() const { return pos_; }

 private:
  HullSlowMotionOptions o_;
  Eigen::Vector3d pos_ = Eigen::Vector3d::Zero();  ///< x, y, psi
  Eigen::Vector3d vel_ = Eigen::Vector3d::Zero();  ///< u, v, r
  double z_ = 0.0, roll_ = 0.0, pitch_ = 0.0;
};

}  // namespace core
}  // namespace mooring_dynamics
