// 3-D top motion (makeTopMotion): every type against its closed form, velocities against finite
// differences of the positions, 3-column (x-z plane) and 4-column tables, the wave follower at
// (x0, y0), and the checks the 2-D solver relies on (planar motion, position table start).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/top_motion.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Closed forms evaluated with a handful of flops on positions of O(100) m: rounding only.
constexpr double kExact = 1e-12 * 100;
// Central differences of O(100) m positions with step 1e-5 s: rounding 1e-14 * 100 / 1e-5 = 1e-7
// dominates the truncation (~ a w^3 h^2 / 6 < 1e-10 for the motions below).
constexpr double kFdStep = 1e-5;
constexpr double kFdTol = 1e-6;

constexpr double kX0 = 100.0, kY0 = -40.0, kZ0 = -3.0;  // static top [m]

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

/// The velocity of a kinematic source equals the time derivative of its position at `times`
/// (away from table kinks).
void expectVelocityIsDerivative(const std::function<TopState(double)>& f, const std::vector<double>& times) {
  for (double t : times) {
    const TopState s = f(t), p = f(t + kFdStep), m = f(t - kFdStep);
    EXPECT_NEAR(s.vx, (p.x - m.x) / (2 * kFdStep), kFdTol) << "t " << t;
    EXPECT_NEAR(s.vy, (p.y - m.y) / (2 * kFdStep), kFdTol) << "t " << t;
    EXPECT_NEAR(s.vz, (p.z - m.z) / (2 * kFdStep), kFdTol) << "t " << t;
  }
}

}  // namespace

TEST(TopMotion, HoldStaysAtTheStaticTop) {
  const auto f = makeTopMotion(TopMotion{}, kX0, kY0, kZ0, nullptr);
  for (double t : {0.0, 1.0, 1e4}) {
    const TopState s = f(t);
    EXPECT_FALSE(s.force);
    EXPECT_EQ(s.x, kX0);
    EXPECT_EQ(s.y, kY0);
    EXPECT_EQ(s.z, kZ0);
    EXPECT_EQ(s.vx, 0.0);
    EXPECT_EQ(s.vy, 0.0);
    EXPECT_EQ(s.vz, 0.0);
    EXPECT_EQ(s.heading, 0.0);
  }
}

TEST(TopMotion, SinusoidIn3D) {
  TopMotion m;
  m.type = TopMotion::Type::Sinusoid;
  m.amplitude_x = 0.5;
  m.amplitude_y = -1.5;
  m.amplitude_z = 2.0;
  m.period = 8.0;
  m.phase = kPi / 6;
  const auto f = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  // Starts at the static top, whatever the phase.
  const TopState s0 = f(0.0);
  EXPECT_NEAR(s0.x, kX0, kExact);
  EXPECT_NEAR(s0.y, kY0, kExact);
  EXPECT_NEAR(s0.z, kZ0, kExact);
  // A quarter period later the argument is pi/2 + pi/6: sin = cos(pi/6) = sqrt(3)/2.
  const double s = std::sqrt(3.0) / 2 - 0.5;
  const TopState q = f(2.0);
  EXPECT_NEAR(q.x, kX0 + 0.5 * s, kExact);
  EXPECT_NEAR(q.y, kY0 - 1.5 * s, kExact);
  EXPECT_NEAR(q.z, kZ0 + 2.0 * s, kExact);
  const double w = 2 * kPi / 8.0, c = -0.5;  // cos(pi/2 + pi/6) = -sin(pi/6)
  EXPECT_NEAR(q.vy, -1.5 * w * c, kExact);
  expectVelocityIsDerivative(f, {0.0, 0.7, 2.0, 5.3, 13.0});
}

TEST(TopMotion, PositionTableIn3DAndInThePlane) {
  TopMotion m;
  m.type = TopMotion::Type::PositionTable;
  m.table = {{1.0, 100.0, -40.0, -3.0}, {3.0, 104.0, -42.0, -2.0}, {4.0, 104.0, -42.0, -5.0}};
  const auto f = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  const TopState a = f(2.5);  // 3/4 of the first interval
  EXPECT_NEAR(a.x, 103.0, kExact);
  EXPECT_NEAR(a.y, -41.5, kExact);
  EXPECT_NEAR(a.z, -2.25, kExact);
  EXPECT_NEAR(a.vx, 2.0, kExact);  // slope of the interval
  EXPECT_NEAR(a.vy, -1.0, kExact);
  EXPECT_NEAR(a.vz, 0.5, kExact);
  // At a row time: the row's position and the slope of the interval that ends there (a solver
  // step landing on the row followed that interval; a zero velocity there froze a top whose
  // rows share the solver's time grid).
  const TopState at3 = f(3.0), at4 = f(4.0);
  EXPECT_EQ(at3.x, 104.0);
  EXPECT_EQ(at3.z, -2.0);
  EXPECT_NEAR(at3.vx, 2.0, kExact);
  EXPECT_NEAR(at3.vy, -1.0, kExact);
  EXPECT_NEAR(at3.vz, 0.5, kExact);
  EXPECT_EQ(at4.z, -5.0);
  EXPECT_NEAR(at4.vx, 0.0, kExact);
  EXPECT_NEAR(at4.vz, -3.0, kExact);
  // Held before the first and after the last row, at rest.
  for (double t : {0.0, 0.5, 4.000001, 100.0}) {
    const TopState s = f(t);
    const TopMotion::Row& r = t < 1.0 ? m.table.front() : m.table.back();
    EXPECT_EQ(s.x, r.x) << t;
    EXPECT_EQ(s.y, r.y) << t;
    EXPECT_EQ(s.z, r.z) << t;
    EXPECT_EQ(s.vx, 0.0) << t;
    EXPECT_EQ(s.vz, 0.0) << t;
  }
  expectVelocityIsDerivative(f, {1.5, 2.2, 3.5});
  // A 3-column row {t, x, z} is the 4-column row {t, x, 0, z}.
  TopMotion planar = m, spatial = m;
  planar.table = {{0.0, 100.0, -3.0}, {2.0, 101.0, -1.0}};
  spatial.table = {{0.0, 100.0, 0.0, -3.0}, {2.0, 101.0, 0.0, -1.0}};
  const auto fp = makeTopMotion(planar, kX0, 0.0, kZ0, nullptr);
  const auto fs = makeTopMotion(spatial, kX0, 0.0, kZ0, nullptr);
  for (double t : {0.0, 0.3, 1.9, 5.0}) {
    EXPECT_EQ(fp(t).x, fs(t).x);
    EXPECT_EQ(fp(t).y, 0.0);
    EXPECT_EQ(fp(t).z, fs(t).z);
    EXPECT_EQ(fp(t).vz, fs(t).vz);
  }
}

TEST(TopMotion, VelocityTableIsIntegratedExactly) {
  // vx ramps 0 -> 2 m/s over 4 s then holds; vy = -1 m/s throughout; vz a triangle 0 -> 1 -> 0.
  TopMotion m;
  m.type = TopMotion::Type::VelocityTable;
  m.table = {{0.0, 0.0, -1.0, 0.0}, {2.0, 1.0, -1.0, 1.0}, {4.0, 2.0, -1.0, 0.0}};
  const auto f = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  for (double t : {0.0, 1.0, 2.0, 3.0, 4.0, 7.5}) {
    const TopState s = f(t);
    // Closed forms: x = t^2 / 4 up to 4 s, then 4 + 2 (t - 4); z the triangle's area so far.
    const double x = t <= 4.0 ? t * t / 4.0 : 4.0 + 2.0 * (t - 4.0);
    const double z = t <= 2.0 ? t * t / 4.0 : t <= 4.0 ? 2.0 - (4.0 - t) * (4.0 - t) / 4.0 : 2.0;
    EXPECT_NEAR(s.x, kX0 + x, kExact) << t;
    EXPECT_NEAR(s.y, kY0 - t, kExact) << t;
    EXPECT_NEAR(s.z, kZ0 + z, kExact) << t;
  }
  expectVelocityIsDerivative(f, {0.5, 1.3, 2.9, 3.7, 6.0});
}

TEST(TopMotion, ForceTable) {
  TopMotion m;
  m.type = TopMotion::Type::ForceTable;
  m.table = {{0.0, 1000.0, 200.0, 3000.0}, {10.0, 2000.0, -200.0, 3000.0}};
  const auto f = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  const TopState s = f(2.5);
  EXPECT_TRUE(s.force);
  EXPECT_NEAR(s.fx, 1250.0, kExact * 10);
  EXPECT_NEAR(s.fy, 100.0, kExact * 10);
  EXPECT_NEAR(s.fz, 3000.0, kExact * 10);
  EXPECT_EQ(f(50.0).fx, 2000.0);  // held after the last row
}

TEST(TopMotion, WaveFollowerHeavesWithTheSurfaceAtTheTop) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Regular;
  spec.height = 2.0;
  spec.period = 7.0;
  spec.direction = kPi / 2;  // travelling north: the elevation depends on y, not on x
  const WaveField waves(spec, 100.0, 9.81);
  TopMotion m;
  m.type = TopMotion::Type::WaveFollower;
  const auto f = makeTopMotion(m, kX0, kY0, 0.0, &waves);
  for (double t : {0.0, 1.1, 3.3}) {
    const TopState s = f(t);
    EXPECT_EQ(s.x, kX0);
    EXPECT_EQ(s.y, kY0);
    EXPECT_EQ(s.z, waves.elevation(kX0, kY0, t));
    EXPECT_EQ(s.vz, waves.elevationRate(kX0, kY0, t));
    EXPECT_NE(s.z, waves.elevation(kX0, 0.0, t));  // y0 matters for waves travelling north
  }
  expectVelocityIsDerivative(f, {0.4, 2.0, 5.5});
  // Without waves the top is held.
  const auto g = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  EXPECT_EQ(g(3.0).z, kZ0);
  const WaveField none;
  EXPECT_EQ(makeTopMotion(m, kX0, kY0, kZ0, &none)(3.0).z, kZ0);
}

TEST(TopMotion, ShipTrackMovesTheTopAtItsStaticElevation) {
  TopMotion m;
  m.type = TopMotion::Type::ShipTrack;
  m.ship_track.speed = 2.0;
  m.ship_track.heading = kPi / 2;
  m.ship_track.legs = {ShipLeg::straight(10.0), ShipLeg::turn(50.0, -kPi / 2)};
  const auto f = makeTopMotion(m, kX0, kY0, kZ0, nullptr);
  for (double t : {0.0, 5.0, 20.0, 100.0}) {
    const TopState s = f(t);
    const ShipPose p = m.ship_track.at(t, kX0, kY0);
    EXPECT_FALSE(s.force);
    EXPECT_EQ(s.x, p.x);
    EXPECT_EQ(s.y, p.y);
    EXPECT_EQ(s.z, kZ0);
    EXPECT_EQ(s.vx, p.vx);
    EXPECT_EQ(s.vy, p.vy);
    EXPECT_EQ(s.vz, 0.0);
    EXPECT_EQ(s.heading, p.heading);
  }
  EXPECT_NEAR(f(5.0).y, kY0 + 10.0, kExact);  // north at 2 m/s
  EXPECT_NEAR(f(100.0).heading, 0.0, 1e-15);   // after the starboard quarter turn: east
  expectVelocityIsDerivative(f, {3.0, 20.0, 60.0});
}

TEST(TopMotion, PlanarCheckNamesTheOutOfPlaneValue) {
  TopMotion m;
  EXPECT_EQ(planarTopMotionError(m), "");
  m.type = TopMotion::Type::Sinusoid;
  m.amplitude_x = 1.0;
  m.amplitude_z = 1.0;
  EXPECT_EQ(planarTopMotionError(m), "");
  m.amplitude_y = 0.25;
  EXPECT_TRUE(contains(planarTopMotionError(m), "dynamics.top_motion.amplitude_y = 0.25"));
  EXPECT_TRUE(contains(planarTopMotionError(m), "needs the 3-D model"));
  m = TopMotion{};
  m.type = TopMotion::Type::VelocityTable;
  m.table = {{0.0, 1.0, 2.0}, {1.0, 1.0, 0.0, 2.0}};
  EXPECT_EQ(planarTopMotionError(m), "");  // y = 0 in every row
  m.table.push_back({2.0, 1.0, -0.5, 2.0});
  EXPECT_TRUE(contains(planarTopMotionError(m), "dynamics.top_motion.table[2] y = -0.5"));
  EXPECT_TRUE(contains(planarTopMotionError(m), "needs the 3-D model"));
  // A ship track stays in the plane only straight along +-x.
  m = TopMotion{};
  m.type = TopMotion::Type::ShipTrack;
  m.ship_track.speed = 1.0;
  m.ship_track.heading = kPi;
  m.ship_track.legs = {ShipLeg::straight(10.0)};
  EXPECT_EQ(planarTopMotionError(m), "");
  m.ship_track.legs.push_back(ShipLeg::turn(100.0, kPi));
  EXPECT_TRUE(contains(planarTopMotionError(m), "dynamics.top_motion.legs[1].turn.angle_deg = 180"));
  EXPECT_TRUE(contains(planarTopMotionError(m), "needs the 3-D model"));
}

TEST(TopMotion, PositionTableMustStartAtTheStaticTop) {
  TopMotion m;
  m.type = TopMotion::Type::PositionTable;
  m.table = {{0.0, kX0, kY0, kZ0 + 0.005}, {1.0, kX0 + 1.0, kY0, kZ0}};
  constexpr double kTolerance = 0.01;  // [m]
  EXPECT_EQ(topMotionStartError(m, kX0, kY0, kZ0, kTolerance), "");
  m.table.front().y = kY0 + 0.5;
  const std::string e = topMotionStartError(m, kX0, kY0, kZ0, kTolerance);
  EXPECT_TRUE(contains(e, "dynamics.top_motion.table[0] = (100, -39.5, -2.995)"));
  EXPECT_TRUE(contains(e, "must start at the static top position (100, -40, -3) within 0.01 m"));
  m.type = TopMotion::Type::VelocityTable;  // only position tables give absolute positions
  EXPECT_EQ(topMotionStartError(m, kX0, kY0, kZ0, kTolerance), "");
}
