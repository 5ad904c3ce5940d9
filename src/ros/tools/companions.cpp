// src/ros/tools: simulators and drivers that are not the product: the demo's wave buoy and
// vessel simulators (wave_buoy, vessel_sim, vessel6dof_sim on rigid_body_vessel.cpp), the storm
// player (sea_state_vessel), the soak driver and the demo monitor. companions.cpp (this file)
// holds the pieces the simple companions share (a buoy's motion, a vessel's surge and heave),
// testable without a master (test/ros/unit_companions.cpp).
#include "mooring_dynamics/ros/tools/companions.hpp"

#include <cmath>
#include <stdexcept>

#include "mooring_dynamics/core/solvers/solvers.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {
constexpr double kTwoPi = 6.283185307179586;
constexpr double kSecondPeriod = 0.63;     // second component: period ratio
constexpr double kSecondAmplitude = 0.35;  // and amplitude ratio
constexpr double kSecondPhase = 1.1;       // [rad]
}  // namespace

StaticTop staticTop(const core::Problem& problem) {
  const core::StaticResult r = core::solveStaticModel(problem);
  if (!r.summary.converged || r.nodes.empty())
    throw std::runtime_error("the statics of \"" + problem.name + "\" did not converge: " + r.summary.message);
  StaticTop t;
  t.x = r.nodes.back().x;
  t.y = r.nodes.back().y;
  t.z = r.nodes.back().z;
  t.fx = -r.top_force_x;
  t.fy = -r.top_force_y;
  t.fz = -r.top_force_z;
  return t;
}

double rampFactor(double t, double ramp) {
  if (ramp <= 0.0 || t >= ramp) return 1.0;
  if (t <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(M_PI * t / ramp));
}

void waveBuoyPosition(const WaveBuoyOptions& o, double x0, double z0, double t, double& x, double& z) {
  const double r = rampFactor(t, o.ramp);
  const double w1 = kTwoPi / o.period, w2 = kTwoPi / (kSecondPeriod * o.period);
  // Surge a quarter period ahead of heave (orbital motion of a buoy in a wave). The ramp (zero
  // value and slope at t = 0) makes position and velocity start at 0.
  const double h = std::sin(w1 * t) + kSecondAmplitude * std::sin(w2 * t + kSecondPhase);
  const double s = std::cos(w1 * t) + kSecondAmplitude * std::cos(w2 * t + kSecondPhase);
  x = x0 + r * o.surge * s;
  z = z0 + r * o.heave * h;
}

std::string VesselOptions::validate() const {
  const struct {
    const char* name;
    double v;
    bool positive;
  } f[] = {{"mass", mass, true},
           {"heave_stiffness", heave_stiffness, true},
           {"surge_stiffness", surge_stiffness, false},
           {"heave_damping", heave_damping, false},
           {"surge_damping", surge_damping, false},
           {"wave_heave_force", wave_heave_force, false},
           {"wave_surge_force", wave_surge_force, false},
           {"wave_period", wave_period, true},
           {"ramp", ramp, false}};
  for (const auto& k : f) {
    if (!std::isfinite(k.v) || (k.positive ? !(k.v > 0.0) : k.v < 0.0))
      return std::string(k.name) + " = " + formatNumber(k.v) + (k.positive ? ": must be > 0" : ": must be >= 0");
  }
  return "";
}

VesselModel::VesselModel(const VesselOptions& o, double x0, double z0, double cable_fx0, double cable_fz0)
    : o_(o), x_(x0), z_(z0) {
  const std::string e = o.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  // Equilibrium at (x0, z0): k (x0 - x_rest) = F_cable  =>  x_rest = x0 - F_cable / k.
  x_rest_ = o.surge_stiffness > 0.0 ? x0 - cable_fx0 / o.surge_stiffness : x0;
  z_rest_ = z0 - cable_fz0 / o.heave_stiffness;
  // With no surge stiffness the static cable force would push the vessel away: it is cancelled
  // by a constant thrust (station keeping) instead.
  thrust_x_ = o.surge_stiffness > 0.0 ? 0.0 : -cable_fx0;
}

void VesselModel::step(double dt, double cable_fx, double cable_fz) {
  const double r = rampFactor(t_, o_.ramp);
  const double ph = kTwoPi * t_ / o_.wave_period;
  const double fwx = r * o_.wave_surge_force * std::cos(ph);
  const double fwz = r * o_.wave_heave_force * std::sin(ph);
  const double ax = (fwx + cable_fx + thrust_x_ - o_.surge_damping * vx_ - o_.surge_stiffness * (x_ - x_rest_)) / o_.mass;
  const double az = (fwz + cable_fz - o_.heave_damping * vz_ - o_.heave_stiffness * (z_ - z_rest_)) / o_.mass;
  vx_ += dt * ax;
  vz_ += dt * az;
  x_ += dt * vx_;
  z_ += dt * vz_;
  t_ += dt;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
