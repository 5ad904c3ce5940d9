#include "mooring_dynamics/core/model/rigid_pose.hpp"

#include <cmath>

#include <gtest/gtest.h>

using mooring_dynamics::core::kUnitQuaternionTolerance;
using mooring_dynamics::core::RigidMotion;
using mooring_dynamics::core::RigidPose;
using mooring_dynamics::core::RigidSegment;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kExact = 1e-12;  // [m], [-]: rounding of a few products
// Central differences with h = 1e-5 s on motions of O(1) m/s: truncation ~h^2, rounding ~1e-16/h.
constexpr double kFdTol = 1e-8;
}  // namespace

TEST(RigidPose, RollPitchYawTurnsPointsAsTheRotationMatricesSay) {
  // Yaw 90 deg: body x (forward) points north (world y), body y (left) points west.
  const RigidPose yaw = RigidPose::fromRollPitchYaw({1, 2, 3}, 0.0, 0.0, kPi / 2);
  EXPECT_NEAR((yaw.apply({10, 0, 0}) - Eigen::Vector3d(1, 12, 3)).norm(), 0.0, kExact);
  EXPECT_NEAR((yaw.apply({0, 10, 0}) - Eigen::Vector3d(-9, 2, 3)).norm(), 0.0, kExact);
  // Roll 90 deg (starboard down, REP 103: positive roll about x turns y toward z): body y -> world z.
  const RigidPose roll = RigidPose::fromRollPitchYaw({0, 0, 0}, kPi / 2, 0.0, 0.0);
  EXPECT_NEAR((roll.apply({0, 5, 0}) - Eigen::Vector3d(0, 0, 5)).norm(), 0.0, kExact);
  // Roll 30 deg by hand: R_x = [[1,0,0],[0,c,-s],[0,s,c]].
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  const RigidPose r30 = RigidPose::fromRollPitchYaw({0, 0, 0}, kPi / 6, 0.0, 0.0);
  EXPECT_NEAR((r30.apply({1, 2, 3}) - Eigen::Vector3d(1, 2 * c - 3 * s, 2 * s + 3 * c)).norm(), 0.0, kExact);
  EXPECT_NEAR((yaw.toBody(yaw.orientation * Eigen::Vector3d(1, 2, 3)) - Eigen::Vector3d(1, 2, 3)).norm(), 0.0, kExact);
}

TEST(RigidPose, ValidateNamesNonFiniteAndNonUnitQuaternions) {
  RigidPose p;
  EXPECT_EQ(p.validate("vessel.pose"), "");
  p.orientation = Eigen::Quaterniond(1.0, 0.0, 0.0, std::nan(""));
  EXPECT_NE(p.validate("vessel.pose").find("vessel.pose.orientation"), std::string::npos);
  EXPECT_NE(p.validate("vessel.pose").find("finite"), std::string::npos);
  p.orientation = Eigen::Quaterniond(1.0, 0.1, 0.0, 0.0);  // norm 1.005
  EXPECT_NE(p.validate("x").find("norm"), std::string::npos);
  p.orientation = Eigen::Quaterniond(1.0 + 0.5 * kUnitQuaternionTolerance, 0.0, 0.0, 0.0);
  EXPECT_EQ(p.validate("x"), "");
  p = RigidPose();
  p.position.x() = INFINITY;
  EXPECT_NE(p.validate("pose").find("pose.position"), std::string::npos);
}

TEST(RigidSegment, EndsAtItsPosesAndItsVelocitiesAreTheDerivatives) {
  const RigidPose a = RigidPose::fromRollPitchYaw({1, 2, -3}, 0.1, -0.05, 0.3);
  const RigidPose b = RigidPose::fromRollPitchYaw({1.5, 1.8, -2.7}, 0.12, -0.02, 0.45);
  const RigidSegment seg(10.0, a, 10.5, b);
  const RigidMotion m0 = seg.at(10.0), m1 = seg.at(10.5);
  EXPECT_NEAR((m0.pose.position - a.position).norm(), 0.0, kExact);
  EXPECT_NEAR(m0.pose.orientation.angularDistance(a.orientation), 0.0, kExact);
  EXPECT_NEAR((m1.pose.position - b.position).norm(), 0.0, kExact);
  EXPECT_NEAR(m1.pose.orientation.angularDistance(b.orientation), 0.0, 1e-9);
  // A fairlead 40 m forward, 10 m to port, 5 m down: its velocity is the derivative of its path.
  const Eigen::Vector3d r(40, 10, -5);
  const double h = 1e-5;
  for (double t : {10.1, 10.25, 10.4}) {
    const Eigen::Vector3d fd = (seg.at(t + h).pose.apply(r) - seg.at(t - h).pose.apply(r)) / (2 * h);
    EXPECT_NEAR((seg.at(t).pointVelocity(r) - fd).norm(), 0.0, kFdTol) << "t " << t;
  }
  // Held (at rest) outside the segment.
  EXPECT_EQ(seg.at(9.0).velocity.norm(), 0.0);
  EXPECT_EQ(seg.at(11.0).angular_velocity.norm(), 0.0);
  EXPECT_NEAR((seg.at(11.0).pose.position - b.position).norm(), 0.0, kExact);
}

TEST(RigidSegment, TakesTheShorterArc) {
  // q and -q are the same rotation: a segment between them does not turn.
  const RigidPose a = RigidPose::fromRollPitchYaw({0, 0, 0}, 0.0, 0.0, 0.2);
  RigidPose b = a;
  b.orientation.coeffs() = -b.orientation.coeffs();
  const RigidSegment seg(0.0, a, 1.0, b);
  EXPECT_NEAR(seg.at(0.5).angular_velocity.norm(), 0.0, kExact);
}
