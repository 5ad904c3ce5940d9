#include "mooring_dynamics/core/model/rigid_pose.hpp"

#include <cmath>

#include <gtest/gtest.h>

using mooring_dynamics::core::BodyTwist;
using mooring_dynamics::core::kUnitQuaternionTolerance;
using mooring_dynamics::core::motionFromBodyTwist;
using mooring_dynamics::core::rightJacobianSO3;
using mooring_dynamics::core::rightJacobianSO3Inverse;
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

// --- The Hermite path (poses with their twists, e.g. nav_msgs/Odometry) -------------------------

namespace {
// [m] closed-form positions of points 50 m from the origin after a few products and one
// quaternion exponential: rounding ~1e-14 relative, far below this.
constexpr double kClosedForm = 1e-10;
// [m/s] velocities of the same size: the same rounding.
constexpr double kVelocityExact = 1e-10;
}  // namespace

TEST(RigidSegmentHermite, RightJacobianAndItsInverse) {
  // J_r J_r^-1 = I (both branches: closed form and the small-angle series), and J_r at 0 is I.
  for (const Eigen::Vector3d& phi : {Eigen::Vector3d(0.3, -1.2, 0.7), Eigen::Vector3d(2e-5, 1e-5, -3e-5),
                                     Eigen::Vector3d(0.0, 0.0, 2.5), Eigen::Vector3d(1.5e-4, 0.0, 0.0)})
    EXPECT_NEAR((rightJacobianSO3(phi) * rightJacobianSO3Inverse(phi) - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12)
        << phi.transpose();
  EXPECT_EQ((rightJacobianSO3(Eigen::Vector3d::Zero()) - Eigen::Matrix3d::Identity()).norm(), 0.0);
  // Just below the switch angle (the series branch) J_r is the closed form, evaluated here in long
  // double (1 - cos a and a - sin a keep their digits there).
  const long double a = 0.99e-4L;
  const Eigen::Vector3d below(static_cast<double>(a), 0, 0);
  const long double c1 = (1.0L - std::cos(a)) / (a * a), c2 = (a - std::sin(a)) / (a * a * a);
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  K(1, 2) = -below.x();
  K(2, 1) = below.x();
  const Eigen::Matrix3d closed =
      Eigen::Matrix3d::Identity() - static_cast<double>(c1) * K + static_cast<double>(c2) * K * K;
  EXPECT_NEAR((rightJacobianSO3(below) - closed).norm(), 0.0, 1e-15);
  // J_r by its definition: R^T dR/dt = [J_r(phi) phi']x for R = Exp(phi(t)); central differences.
  const Eigen::Vector3d phi(0.4, -0.3, 0.9), dphi(0.2, 0.5, -0.1);
  const double h = 1e-6;
  auto R = [&](double t) {
    const Eigen::Vector3d p = phi + t * dphi;
    return Eigen::Matrix3d(Eigen::AngleAxisd(p.norm(), p.normalized()));
  };
  const Eigen::Matrix3d W = R(0).transpose() * (R(h) - R(-h)) / (2 * h);
  const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
  EXPECT_NEAR((w - rightJacobianSO3(phi) * dphi).norm(), 0.0, 1e-8);
}

TEST(RigidSegmentHermite, MeetsBothPosesAndBothTwistsAtTheSamples) {
  // Two samples of a vessel with arbitrary (unrelated) twists, as an odometry source gives them.
  const RigidPose a = RigidPose::fromRollPitchYaw({1, 2, -3}, 0.1, -0.05, 0.3);
  const RigidPose b = RigidPose::fromRollPitchYaw({1.5, 1.8, -2.7}, 0.12, -0.02, 0.45);
  BodyTwist ta, tb;
  ta.linear = {1.2, -0.3, 0.1};
  ta.angular = {0.02, -0.01, 0.25};
  tb.linear = {0.8, 0.4, -0.2};
  tb.angular = {-0.03, 0.05, 0.35};
  const RigidMotion ma = motionFromBodyTwist(a, ta), mb = motionFromBodyTwist(b, tb);
  const RigidSegment seg(10.0, ma, 10.5, mb);
  const Eigen::Vector3d r(40, 10, -5);  // a fairlead, body frame [m]
  for (int end = 0; end < 2; ++end) {
    const RigidPose& p = end ? b : a;
    const BodyTwist& tw = end ? tb : ta;
    const RigidMotion m = seg.at(end ? 10.5 : 10.0);
    EXPECT_NEAR((m.pose.position - p.position).norm(), 0.0, kExact) << "end " << end;
    EXPECT_NEAR(m.pose.orientation.angularDistance(p.orientation), 0.0, 1e-12) << "end " << end;
    // The fairlead velocity recomputed here from the sample: v + omega x (R r), with the body
    // twist turned into the world by hand (R v_body, R omega_body).
    const Eigen::Matrix3d R = p.orientation.toRotationMatrix();
    const Eigen::Vector3d v = R * tw.linear, w = R * tw.angular;
    const Eigen::Vector3d expected = v + w.cross(R * r);
    EXPECT_NEAR((m.pointVelocity(r) - expected).norm(), 0.0, kVelocityExact) << "end " << end;
    EXPECT_NEAR((m.pose.apply(r) - (p.position + R * r)).norm(), 0.0, kClosedForm) << "end " << end;
  }
  // In between, the velocities are the derivatives of the path.
  const double h = 1e-5;
  for (double t : {10.05, 10.25, 10.45}) {
    const Eigen::Vector3d fd = (seg.at(t + h).pose.apply(r) - seg.at(t - h).pose.apply(r)) / (2 * h);
    EXPECT_NEAR((seg.at(t).pointVelocity(r) - fd).norm(), 0.0, kFdTol) << "t " << t;
  }
}

TEST(RigidSegmentHermite, ConstantRateRotationWithItsExactTwistIsTheClosedForm) {
  // A vessel heeled and trimmed (roll 0.1, pitch -0.05 rad) turning at a constant 0.3 rad/s about
  // the world's vertical while its origin drifts at a constant (0.4, -0.2, 0.05) m/s: R(t) =
  // Rz(w t) R0, p(t) = c + u t. Its samples every 0.5 s carry the exact body twist,
  // v_body = R^T u, omega_body = R^T (0, 0, w). Fairlead r in the world: c + u t + Rz(w t) R0 r.
  const double w = 0.3;
  const Eigen::Vector3d c(5, -3, 0.5), u(0.4, -0.2, 0.05), r(45, 15, -8);
  const Eigen::Matrix3d R0 = RigidPose::fromRollPitchYaw({0, 0, 0}, 0.1, -0.05, 0.0).orientation.toRotationMatrix();
  auto Rz = [](double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); };
  auto sample = [&](double t) {
    RigidPose p;
    p.position = c + u * t;
    p.orientation = Eigen::Quaterniond(Rz(w * t) * R0);
    BodyTwist tw;
    tw.linear = p.orientation.conjugate() * u;
    tw.angular = p.orientation.conjugate() * Eigen::Vector3d(0, 0, w);
    return motionFromBodyTwist(p, tw);
  };
  for (double t0 : {0.0, 0.5, 1.0}) {
    const RigidSegment seg(t0, sample(t0), t0 + 0.5, sample(t0 + 0.5));
    for (double f : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const double t = t0 + 0.5 * f;
      const RigidMotion m = seg.at(t);
      const Eigen::Vector3d closed = c + u * t + Rz(w * t) * R0 * r;
      const Eigen::Vector3d closed_v = u + Eigen::Vector3d(0, 0, w).cross(Rz(w * t) * R0 * r);
      EXPECT_NEAR((m.pose.apply(r) - closed).norm(), 0.0, kClosedForm) << "t " << t;
      EXPECT_NEAR((m.pointVelocity(r) - closed_v).norm(), 0.0, kVelocityExact) << "t " << t;
    }
  }
}
