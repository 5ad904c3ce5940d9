// The 6-DOF vessel of the coupling example against closed forms: free heave and roll periods,
// the forced heave amplitude of a damped oscillator, and rest in equilibrium.
#include "mooring_dynamics/ros/tools/rigid_body_vessel.hpp"

#include <cmath>

#include <gtest/gtest.h>

using mooring_dynamics::ros_bridge::RigidBodyVessel;
using mooring_dynamics::ros_bridge::RigidBodyVesselOptions;
using Vec6 = Eigen::Matrix<double, 6, 1>;

namespace {
constexpr double kPi = 3.14159265358979323846;
// [-] RK4 at dt = T/100 keeps the period to ~1e-6; 2e-3 covers finding the crossings by
// linear interpolation between steps.
constexpr double kPeriodTol = 2e-3;

RigidBodyVesselOptions still() {
  RigidBodyVesselOptions o;
  o.wave_amplitude.setZero();
  o.damping.setZero();
  return o;
}

/// Period of the oscillation of `value` about `mean` from its upward crossings [s].
template <class Value>
double measuredPeriod(RigidBodyVessel& v, double dt, int steps, Value value, double mean) {
  std::vector<double> ups;
  double prev = value(v) - mean;
  for (int k = 0; k < steps; ++k) {
    v.step(dt, Vec6::Zero());
    const double now = value(v) - mean;
    if (prev < 0.0 && now >= 0.0) ups.push_back(v.t() - dt * now / (now - prev));
    prev = now;
  }
  return ups.size() >= 2 ? (ups.back() - ups.front()) / static_cast<double>(ups.size() - 1) : 0.0;
}
}  // namespace

TEST(RigidBodyVessel, FreeHeaveAtSqrtKOverM) {
  const RigidBodyVesselOptions o = still();
  RigidBodyVessel ref(o, {0, 0, 0}, Eigen::Quaterniond::Identity(), Vec6::Zero());
  const double T = ref.heavePeriod();
  const double expected = 2 * kPi * std::sqrt((o.mass + o.added_mass[2]) / (o.water_density * o.gravity * o.waterplane_area));
  EXPECT_NEAR(T, expected, 1e-12);
  // Set swinging by an impulse (a force held over 0.2 s) about its rest at z = 0.
  RigidBodyVessel w(o, {0, 0, 0}, Eigen::Quaterniond::Identity(), Vec6::Zero());
  Vec6 kick = Vec6::Zero();
  kick[2] = 0.5 * (o.mass + o.added_mass[2]) / 0.2;  // force over 0.2 s
  w.step(0.2, kick);
  const double measured = measuredPeriod(w, T / 100.0, 1000, [](const RigidBodyVessel& s) { return s.position().z(); }, 0.0);
  EXPECT_NEAR(measured / T, 1.0, kPeriodTol);
}

TEST(RigidBodyVessel, FreeRollAtTheMetacentricPeriod) {
  const RigidBodyVesselOptions o = still();
  RigidBodyVessel v(o, {0, 0, 0}, Eigen::Quaterniond::Identity(), Vec6::Zero());
  Vec6 kick = Vec6::Zero();
  kick[3] = 0.02 * (o.inertia[0] + o.added_mass[3]) / 0.1;
  v.step(0.1, kick);
  const double T = v.rollPeriod();
  const double expected = 2 * kPi * std::sqrt((o.inertia[0] + o.added_mass[3]) / (o.mass * o.gravity * o.gm_transverse));
  EXPECT_NEAR(T, expected, 1e-12);
  const double measured = measuredPeriod(
      v, T / 100.0, 1000,
      [](const RigidBodyVessel& s) {
        const Eigen::Matrix3d R = s.orientation().toRotationMatrix();
        return std::atan2(R(2, 1), R(2, 2));
      },
      0.0);
  EXPECT_NEAR(measured / T, 1.0, kPeriodTol);
}

TEST(RigidBodyVessel, ForcedHeaveHasTheDampedOscillatorsAmplitude) {
  RigidBodyVesselOptions o = still();
  o.damping[2] = 3.0e6;
  o.wave_amplitude[2] = 4.0e6;
  o.ramp = 0.0;
  RigidBodyVessel v(o, {0, 0, 0}, Eigen::Quaterniond::Identity(), Vec6::Zero());
  const double m = o.mass + o.added_mass[2], k = o.water_density * o.gravity * o.waterplane_area, c = o.damping[2];
  const double w = 2 * kPi / o.wave_period;
  const double expected = o.wave_amplitude[2] / std::sqrt((k - m * w * w) * (k - m * w * w) + (c * w) * (c * w));
  double peak = 0.0;
  const double dt = o.wave_period / 200.0;
  for (int i = 0; i < 200 * 30; ++i) {  // 30 periods: the transient decays (damping ratio ~0.1)
    v.step(dt, Vec6::Zero());
    if (i >= 200 * 25) peak = std::max(peak, std::abs(v.position().z()));
  }
  // [-] 1 %: the sampled peak of a sinusoid at 200 points a period is within 1.2e-4 of it, and
  // the transient is below e^{-zeta w t} ~ 1e-4 after 25 periods.
  EXPECT_NEAR(peak / expected, 1.0, 1e-2);
}

TEST(RigidBodyVessel, RestsInEquilibriumWithItsStaticMooringWrench) {
  const RigidBodyVesselOptions o = still();
  Vec6 mooring0;
  mooring0 << 1e3, -2e3, -1.4e6, 5e4, -3e4, 100.0;
  RigidBodyVessel v(o, {10, -5, 0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())), mooring0);
  for (int i = 0; i < 100; ++i) v.step(0.1, mooring0);
  EXPECT_EQ(v.velocity().norm(), 0.0);
  EXPECT_NEAR((v.position() - Eigen::Vector3d(10, -5, 0)).norm(), 0.0, 1e-12);
}

TEST(RigidBodyVessel, OptionsNameTheField) {
  RigidBodyVesselOptions o;
  o.mass = -1;
  EXPECT_NE(o.validate().find("mass"), std::string::npos);
  o = RigidBodyVesselOptions();
  o.waterplane_area = 0;
  EXPECT_NE(o.validate().find("waterplane_area"), std::string::npos);
}
