// A 6-DOF rigid-body vessel for the two-way coupling example (vessel6dof_sim, vessel_6dof.launch):
// what a vessel simulator on the other side of the topics does with the moored vessel's wrench.
// Plain C++ (Eigen), no ROS, unit-tested in test/ros/unit_rigid_body_vessel.cpp.
//
// Linear seakeeping about a mean pose, full kinematics: body velocity nu = (u, v, w, p, q, r)
// in the body frame (REP 103: x forward, y left, z up), pose (position, unit quaternion) in the
// world frame (x east, y north, z up).
//   (M_rb + A) d(nu)/dt = -C_rb(nu) nu - D nu + tau_hydrostatic + tau_wave + tau_mooring - tau_0
// M_rb: mass and inertia about the body origin (the centre of gravity), A: constant added mass
// (diagonal), C_rb: rigid-body Coriolis, D: linear damping (diagonal), tau_hydrostatic: heave
// -rho g A_wp (z - z0) and the metacentric moments -rho g V GM_T phi, -rho g V GM_L theta (small
// roll and pitch), tau_wave: sinusoidal forces and moments ramped in, tau_mooring: the lines'
// wrench about the body origin in the body frame, tau_0: that wrench at the start, so the vessel
// starts in equilibrium (its ballast trimmed to the mooring's static pull). Integrated by the
// classical Runge-Kutta method with the mooring wrench held over a step (explicit coupling).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mooring_dynamics {
namespace ros_bridge {

struct RigidBodyVesselOptions {
  double mass = 5.0e6;                  ///< [kg] (a 90 m vessel of 5000 t)
  Eigen::Vector3d inertia{2.5e8, 2.5e9, 2.6e9};  ///< Ixx, Iyy, Izz about the origin [kg m^2]
  /// Added mass: surge, sway, heave [kg], roll, pitch, yaw [kg m^2].
  Eigen::Matrix<double, 6, 1> added_mass = (Eigen::Matrix<double, 6, 1>() << 2.5e5, 2.5e6, 5.0e6, 5.0e7, 2.5e9, 1.3e9).finished();
  /// Linear damping per degree of freedom [N s/m, N m s/rad].
  Eigen::Matrix<double, 6, 1> damping = (Eigen::Matrix<double, 6, 1>() << 5.0e4, 2.0e5, 2.0e6, 2.0e7, 1.0e9, 2.0e8).finished();
  double water_density = 1025.0;        ///< [kg/m^3]
  double gravity = 9.81;                ///< [m/s^2]
  double waterplane_area = 1440.0;      ///< [m^2]
  double gm_transverse = 2.0;           ///< [m]
  double gm_longitudinal = 100.0;       ///< [m]
  /// Wave force amplitudes (body frame): surge, sway, heave [N], roll, pitch, yaw [N m].
  Eigen::Matrix<double, 6, 1> wave_amplitude = (Eigen::Matrix<double, 6, 1>() << 4.0e5, 1.0e5, 4.0e6, 5.0e6, 6.0e7, 2.0e6).finished();
  double wave_period = 8.0;             ///< [s]
  double ramp = 10.0;                   ///< [s] the wave forces grow from zero over this time
  /// Empty when usable, else the field, its value and the constraint.
  std::string validate() const;
};

class RigidBodyVessel {
 public:
  /// Starts at rest at `pose` with the mooring wrench `mooring0` (body frame, about the origin:
  /// force, moment) in equilibrium.
  RigidBodyVessel(const RigidBodyVesselOptions& o, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                  const Eigen::Matrix<double, 6, 1>& mooring0);
  /// One step of dt [s] with the mooring wrench (body frame) held over it.
  void step(double dt, const Eigen::Matrix<double, 6, 1>& mooring);

  double t() const { return t_; }
  const Eigen::Vector3d& position() const { return p_; }
  const Eigen::Quaterniond& orientation() const { return q_; }
  /// Body velocity (u, v, w, p, q, r).
  const Eigen::Matrix<double, 6, 1>& velocity() const { return nu_; }
  /// Natural periods of the uncoupled heave, roll and pitch (hydrostatics and mass + added mass) [s].
  double heavePeriod() const;
  double rollPeriod() const;

 private:
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  /// d(nu)/dt at a state.
  Vec6 acceleration(double t, const Eigen::Vector3d& p, const Eigen::Quaterniond& q, const Vec6& nu, const Vec6& mooring) const;

  RigidBodyVesselOptions o_;
  Eigen::Matrix<double, 6, 6> M_;  ///< rigid-body plus added mass
  Vec6 tau0_;
  Eigen::Vector3d p0_;
  double t_ = 0.0;
  Eigen::Vector3d p_;
  Eigen::Quaterniond q_;
  Vec6 nu_ = Vec6::Zero();
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
