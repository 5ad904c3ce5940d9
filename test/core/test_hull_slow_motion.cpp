// The slow surge, sway and yaw of a moored hull (core/model/hull_slow_motion.hpp) against closed
// forms: the damped response to a steady force, the period of an undamped spring-mass oscillator,
// the mean force given in the world frame acting on a yawed hull, and the field errors.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "mooring_dynamics/core/model/hull_slow_motion.hpp"

using namespace mooring_dynamics::core;

namespace {
constexpr double kPi = 3.14159265358979323846;

HullSlowMotionOptions hull() {
  HullSlowMotionOptions o;
  o.mass = 2.0e7;
  o.yaw_inertia = 1.5e10;
  o.added_mass = Eigen::Vector3d(1.0e6, 8.0e6, 5.0e9);
  return o;
}
}  // namespace

TEST(HullSlowMotion, SteadyForceAgainstDampingByTheClosedForm) {
  // (m + a) du/dt = F - b u: u(t) = F/b (1 - exp(-b t / (m + a))). Semi-implicit Euler with the
  // damping implicit is first order: at b dt / (m + a) = 1e-3 the relative error is ~5e-4.
  constexpr double kFirstOrderRelTol = 1e-3;
  HullSlowMotionOptions o = hull();
  o.damping = Eigen::Vector3d(2.1e6, 0.0, 0.0);
  HullSlowMotion h(o, RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, 0.0));
  const double f = 1.0e5, m = o.mass + o.added_mass.x(), b = o.damping.x(), dt = 0.01;
  for (int k = 0; k < 1000; ++k) h.step(dt, Eigen::Vector3d(f, 0.0, 0.0));  // t = 10 s = one time constant
  const double want = f / b * (1.0 - std::exp(-b * 10.0 / m));
  EXPECT_NEAR(h.velocity().x() / want, 1.0, kFirstOrderRelTol);
  EXPECT_EQ(h.velocity().y(), 0.0);
  EXPECT_EQ(h.velocity().z(), 0.0);
}

TEST(HullSlowMotion, SpringMassPeriodIsTwoPiSqrtMassOverStiffness) {
  // A linear spring in sway, -k y, applied by hand each step: T = 2 pi sqrt((m + a22) / k). The
  // symplectic step keeps the amplitude and errs in the period by ~(w dt)^2 / 24.
  constexpr double kPeriodRelTol = 1e-3;
  const HullSlowMotionOptions o = hull();
  HullSlowMotion h(o, RigidPose::fromRollPitchYaw(Eigen::Vector3d(0.0, 2.0, 0.0), 0.0, 0.0, 0.0));
  const double k = 2.0e5, dt = 0.1, want = 2.0 * kPi * std::sqrt((o.mass + o.added_mass.y()) / k);
  double t = 0.0, prev = h.position().y(), first_up = -1.0, last_up = -1.0;
  int ups = 0;
  while (t < 6.0 * want) {
    h.step(dt, Eigen::Vector3d(0.0, -k * h.position().y(), 0.0));
    t += dt;
    const double y = h.position().y();
    if (prev < 0.0 && y >= 0.0) {  // upward zero crossing, interpolated
      const double tc = t - dt * y / (y - prev);
      if (first_up < 0.0) first_up = tc;
      last_up = tc;
      ++ups;
    }
    prev = y;
  }
  ASSERT_GE(ups, 4);
  EXPECT_NEAR((last_up - first_up) / (ups - 1) / want, 1.0, kPeriodRelTol);
  EXPECT_NEAR(std::abs(h.position().x()), 0.0, 1e-9) << "no surge from a sway spring without yaw";
}

TEST(HullSlowMotion, MeanForceInTheWorldFrameMovesAYawedHull) {
  // The hull heads north (yaw 90 deg); a mean force toward +x (east) is sway to starboard in its
  // axes, and it moves east: after n semi-implicit Euler steps x = F dt^2 n (n + 1) / (2 (m + a22))
  // (velocity first, then position: the sum of k dt F / M over k = 1..n), y stays.
  constexpr double kQuadraticRelTol = 1e-12;  // rounding of 100 sums
  HullSlowMotionOptions o = hull();
  o.mean_force = Eigen::Vector3d(1.0e5, 0.0, 0.0);
  HullSlowMotion h(o, RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, kPi / 2.0));
  for (int k = 0; k < 100; ++k) h.step(0.1, Eigen::Vector3d::Zero());
  EXPECT_NEAR(h.position().x() / (1.0e5 * 0.01 * 100.0 * 101.0 / (2.0 * (o.mass + o.added_mass.y()))), 1.0, kQuadraticRelTol);
  EXPECT_NEAR(h.position().y(), 0.0, 1e-9);
  EXPECT_LT(h.velocity().y(), 0.0) << "east is the hull's starboard side (body -y)";
}

TEST(HullSlowMotion, FieldErrors) {
  HullSlowMotionOptions o = hull();
  o.mass = 0.0;
  EXPECT_NE(o.validate().find("vessel.low_frequency.mass = 0: must be finite and > 0"), std::string::npos) << o.validate();
  o = hull();
  o.damping.z() = -1.0;
  EXPECT_NE(o.validate().find("damping (yaw) = -1"), std::string::npos) << o.validate();
  EXPECT_THROW(HullSlowMotion(o, RigidPose()), std::invalid_argument);
}
