// ROS-free models behind the demo's companion nodes (no ROS calls; the nodes in
// src/ros/tools/wave_buoy_main.cpp and src/ros/tools/vessel_sim_main.cpp wire them to topics):
//  * WaveBuoyMotion: a synthetic wave-driven buoy (heave and surge), kinematic, for demo.launch;
//  * VesselModel: a vessel in surge and heave as two mass-spring-dampers driven by a wave force and
//    the cable's force (two-way coupling example, vessel.launch).
// Frame: the problem frame (x east, z up, z = 0 at the mean sea surface); SI units.
#pragma once

#include <string>

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// Fairlead position and the force of the line on the platform there in the problem's statics.
struct StaticTop {
  double x = 0.0, z = 0.0;    ///< [m]
  double fx = 0.0, fz = 0.0;  ///< force of the line on the platform [N] (= -top_force)
  double y = 0.0, fy = 0.0;   ///< y components (model: 3d; 0 for model: 2d)
};
/// Solves the problem's statics (its model, core::solveStaticModel). Throws std::runtime_error
/// (naming the problem) when they fail.
StaticTop staticTop(const core::Problem& problem);

/// Smooth start: 0 at t = 0 rising to 1 at t = ramp (half cosine); 1 when ramp <= 0.
double rampFactor(double t, double ramp);

struct WaveBuoyOptions {
  double heave = 1.0;    ///< amplitude of the main heave component [m]
  double surge = 0.5;    ///< amplitude of the main surge component [m]
  double period = 8.0;   ///< period of the main component [s]; a second one at 0.63 of it and 35 % of the amplitude
  double ramp = 10.0;    ///< [s] the motion grows from rest over this time
};

/// Buoy position about (x0, z0) at time t [s] after the start: two sinusoids per axis (a
/// regular-looking swell plus a shorter sea), ramped in, so position and velocity start at 0.
void waveBuoyPosition(const WaveBuoyOptions& o, double x0, double z0, double t, double& x, double& z);

struct VesselOptions {
  double mass = 2000.0;            ///< mass plus added mass, same in surge and heave [kg]
  double heave_stiffness = 3.16e4; ///< hydrostatic, rho g A_waterplane (2 m diameter) [N/m]
  double surge_stiffness = 2.0e3;  ///< a soft hawser / station keeping [N/m]
  double heave_damping = 3.2e3;    ///< [N s/m] (about 20 % of critical)
  double surge_damping = 2.0e3;    ///< [N s/m]
  double wave_heave_force = 2.5e4; ///< amplitude of the wave force in heave [N]
  double wave_surge_force = 1.5e3; ///< amplitude of the wave force in surge [N]
  double wave_period = 8.0;        ///< [s]
  double ramp = 10.0;              ///< [s] wave force ramped in over this time
  std::string validate() const;    ///< empty when valid, else names the field, value and constraint
};

/// Surge (x) and heave (z) of a vessel whose fairlead is at its reference point:
///   m x'' + c_x x' + k_x (x - x_rest) = F_wave,x(t) + F_cable,x
///   m z'' + c_z z' + k_z (z - z_rest) = F_wave,z(t) + F_cable,z
/// The rest positions make the start (x0, z0) an equilibrium under the static cable force, so a
/// calm sea leaves the vessel where the statics put the fairlead.
class VesselModel {
 public:
  VesselModel(const VesselOptions& o, double x0, double z0, double cable_fx0, double cable_fz0);
  /// Advance from t to t + dt with the cable force (fx, fz) [N] held over the step (explicit
  /// coupling: the force answers the previous position), semi-implicit Euler.
  void step(double dt, double cable_fx, double cable_fz);
  double t() const { return t_; }
  double x() const { return x_; }
  double z() const { return z_; }
  double vx() const { return vx_; }
  double vz() const { return vz_; }

 private:
  VesselOptions o_;
  double x_rest_, z_rest_;
  double thrust_x_ = 0.0;  ///< [N] constant surge force when surge_stiffness = 0
  double t_ = 0.0, x_, z_, vx_ = 0.0, vz_ = 0.0;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
