// Ship tracks: closed-form positions after 90, 360 and 375 degree turns (and to starboard), the
// paper's Case 1 / Case 2 tracks (section 7.1), continuity of the position at every leg boundary,
// speed U everywhere, velocity = time derivative of the position, the impulsive heading change,
// and the validation messages.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/ship_track.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
// Closed-form positions of O(1e3 - 1e4) m from a few trig calls: rounding ~1e-16 * 1e4.
constexpr double kPosTol = 1e-9;  // [m]
constexpr double kAngleTol = 1e-12;  // [rad]
constexpr double kSpeedTol = 1e-12;  // [m/s], U (cos, sin) rounding
// Central differences with a 1e-4 s step of positions of O(1e4) m: rounding 1e-12 / 1e-4 = 1e-8;
// truncation on an arc U^3 / R^2 h^2 / 6 ~ 1e-12.
constexpr double kFdStep = 1e-4;   // [s]
constexpr double kFdTol = 1e-6;    // [m/s]

constexpr double kU = 9.52, kR = 640.0;  // the paper's tow: 18.5 kn, 640 m turn radius
constexpr double kX0 = 10.0, kY0 = -20.0;

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

ShipTrack track(std::vector<ShipLeg> legs, double heading = 0.0) {
  ShipTrack t;
  t.speed = kU;
  t.heading = heading;
  t.legs = std::move(legs);
  return t;
}

/// The paper's Case 1 (and, with the heading change, Case 2): 200 s straight, a 375 deg turn to
/// port of radius 640 m, 300 s straight.
ShipTrack paperTrack(bool back_to_zero) {
  std::vector<ShipLeg> legs{ShipLeg::straight(200.0), ShipLeg::turn(kR, 375.0 * kDeg)};
  if (back_to_zero) legs.push_back(ShipLeg::headingChange(0.0));
  legs.push_back(ShipLeg::straight(300.0));
  return track(legs);
}

}  // namespace

TEST(ShipTrack, StraightAheadAtTheInitialHeading) {
  const ShipTrack t = track({}, 30.0 * kDeg);
  for (double s : {0.0, 1.0, 250.0}) {
    const ShipPose p = t.at(s, kX0, kY0);
    EXPECT_NEAR(p.x, kX0 + kU * s * std::cos(30.0 * kDeg), kPosTol);
    EXPECT_NEAR(p.y, kY0 + kU * s * 0.5, kPosTol);
    EXPECT_NEAR(p.vx, kU * std::cos(30.0 * kDeg), kSpeedTol);
    EXPECT_NEAR(p.vy, kU * 0.5, kSpeedTol);
    EXPECT_EQ(p.heading, 30.0 * kDeg);
  }
  // Before t = 0 the ship comes along the same line.
  EXPECT_NEAR(t.at(-2.0, kX0, kY0).y, kY0 - 2.0 * kU * 0.5, kPosTol);
}

TEST(ShipTrack, QuarterTurnsToPortAndStarboard) {
  const double T = kR * 0.5 * kPi / kU;  // time of a 90 deg turn
  const ShipTrack port = track({ShipLeg::turn(kR, 90.0 * kDeg)});
  const ShipTrack starboard = track({ShipLeg::turn(kR, -90.0 * kDeg)});
  EXPECT_NEAR(port.legsDuration(), T, 1e-12 * T);
  const ShipPose p = port.at(T, kX0, kY0), s = starboard.at(T, kX0, kY0);
  // From heading 0 a quarter circle to port ends R ahead and R to the left, heading north.
  EXPECT_NEAR(p.x, kX0 + kR, kPosTol);
  EXPECT_NEAR(p.y, kY0 + kR, kPosTol);
  EXPECT_NEAR(p.heading, 0.5 * kPi, kAngleTol);
  EXPECT_NEAR(p.vx, 0.0, kSpeedTol);
  EXPECT_NEAR(p.vy, kU, kSpeedTol);
  EXPECT_NEAR(s.x, kX0 + kR, kPosTol);
  EXPECT_NEAR(s.y, kY0 - kR, kPosTol);
  EXPECT_NEAR(s.heading, -0.5 * kPi, kAngleTol);
  EXPECT_NEAR(s.vy, -kU, kSpeedTol);
  // Halfway (45 deg) the ship is on the circle about (x0, y0 + R): R (sin 45, 1 - cos 45).
  const ShipPose h = port.at(0.5 * T, kX0, kY0);
  EXPECT_NEAR(h.x, kX0 + kR * std::sin(kPi / 4), kPosTol);
  EXPECT_NEAR(h.y, kY0 + kR * (1.0 - std::cos(kPi / 4)), kPosTol);
  // Afterwards straight on to the north.
  const ShipPose a = port.at(T + 10.0, kX0, kY0);
  EXPECT_NEAR(a.x, kX0 + kR, kPosTol);
  EXPECT_NEAR(a.y, kY0 + kR + 10.0 * kU, kPosTol);
}

TEST(ShipTrack, FullCircleReturnsToItsStart) {
  const ShipTrack t = track({ShipLeg::turn(kR, 360.0 * kDeg)}, 0.7);
  const double T = t.legsDuration();
  EXPECT_NEAR(T, 2.0 * kPi * kR / kU, 1e-12 * T);
  const ShipPose p = t.at(T, kX0, kY0);
  EXPECT_NEAR(p.x, kX0, kPosTol);
  EXPECT_NEAR(p.y, kY0, kPosTol);
  EXPECT_NEAR(p.heading, 0.7 + 2.0 * kPi, kAngleTol);  // not wrapped
  // Halfway round the ship is 2R across, opposite its start, heading reversed.
  const ShipPose h = t.at(0.5 * T, kX0, kY0);
  EXPECT_NEAR(h.x, kX0 - 2.0 * kR * std::sin(0.7), kPosTol);
  EXPECT_NEAR(h.y, kY0 + 2.0 * kR * std::cos(0.7), kPosTol);
  EXPECT_NEAR(h.vx, -kU * std::cos(0.7), kSpeedTol);
}

TEST(ShipTrack, PaperCase1And2Tracks) {
  const double turn = kR * 375.0 * kDeg / kU;  // the paper's "circular motion lasted for 440 s"
  EXPECT_NEAR(turn, 440.0, 0.1);
  const ShipTrack c1 = paperTrack(false), c2 = paperTrack(true);
  EXPECT_NEAR(c1.legsDuration(), 200.0 + turn + 300.0, 1e-9);
  EXPECT_NEAR(c2.legsDuration(), c1.legsDuration(), 1e-9);
  // End of the turn: 200 s * U ahead, then R (sin 375, 1 - cos 375) = R (sin 15, 1 - cos 15).
  const double xe = kX0 + 200.0 * kU + kR * std::sin(15.0 * kDeg);
  const double ye = kY0 + kR * (1.0 - std::cos(15.0 * kDeg));
  const double te = 200.0 + turn;
  for (const ShipTrack* t : {&c1, &c2}) {
    const ShipPose e = t->at(te, kX0, kY0);
    EXPECT_NEAR(e.x, xe, kPosTol);
    EXPECT_NEAR(e.y, ye, kPosTol);
  }
  // Case 1 leaves on a course of 15 deg; Case 2 returns impulsively to 0 deg.
  const ShipPose a1 = c1.at(te + 100.0, kX0, kY0), a2 = c2.at(te + 100.0, kX0, kY0);
  EXPECT_NEAR(a1.heading, 375.0 * kDeg, kAngleTol);
  EXPECT_NEAR(a1.x, xe + 100.0 * kU * std::cos(15.0 * kDeg), kPosTol);
  EXPECT_NEAR(a1.y, ye + 100.0 * kU * std::sin(15.0 * kDeg), kPosTol);
  EXPECT_EQ(a2.heading, 0.0);
  EXPECT_NEAR(a2.x, xe + 100.0 * kU, kPosTol);
  EXPECT_NEAR(a2.y, ye, kPosTol);
  // The heading change: just before it the ship turns (heading 375 deg), at it and after it the
  // new heading applies; the velocity jumps, the position does not.
  constexpr double kJust = 1e-6;  // [s]
  const ShipPose before = c2.at(te - kJust, kX0, kY0), at = c2.at(te, kX0, kY0);
  EXPECT_NEAR(before.heading, 375.0 * kDeg, 1e-6);
  EXPECT_EQ(at.heading, 0.0);
  EXPECT_NEAR(at.vx, kU, kSpeedTol);
  EXPECT_NEAR(at.vy, 0.0, kSpeedTol);
  EXPECT_NEAR(before.vy, kU * std::sin(15.0 * kDeg), 1e-5);
  EXPECT_NEAR(std::hypot(at.x - before.x, at.y - before.y), kU * kJust, 1e-8);
}

TEST(ShipTrack, PositionIsContinuousAndSpeedIsUEverywhere) {
  const ShipTrack t = track({ShipLeg::straight(50.0), ShipLeg::turn(300.0, -120.0 * kDeg), ShipLeg::headingChange(2.0),
                             ShipLeg::straight(0.0), ShipLeg::turn(150.0, 400.0 * kDeg), ShipLeg::straight(20.0),
                             ShipLeg::headingChange(-1.0)},
                            0.3);
  // Leg boundaries.
  std::vector<double> bounds;
  double s = 0.0;
  for (const ShipLeg& l : t.legs) bounds.push_back(s += t.legDuration(l));
  constexpr double kJust = 1e-7;  // [s]
  for (double b : bounds) {
    const ShipPose a = t.at(b - kJust, kX0, kY0), c = t.at(b, kX0, kY0);
    // The ship moves U * kJust in between, never more (no jump of the position).
    EXPECT_LE(std::hypot(c.x - a.x, c.y - a.y), kU * kJust + 1e-9) << "boundary t = " << b;
  }
  // Speed U everywhere and velocity = time derivative of the position inside the legs.
  for (double time = 1.0; time < bounds.back() + 30.0; time += 7.3) {
    const ShipPose p = t.at(time, kX0, kY0);
    EXPECT_NEAR(std::hypot(p.vx, p.vy), kU, kSpeedTol) << time;
    EXPECT_NEAR(p.vx, kU * std::cos(p.heading), kSpeedTol) << time;
    bool near_bound = false;
    for (double b : bounds) near_bound = near_bound || std::abs(time - b) < 2 * kFdStep;
    if (near_bound) continue;
    const ShipPose f = t.at(time + kFdStep, kX0, kY0), g = t.at(time - kFdStep, kX0, kY0);
    EXPECT_NEAR(p.vx, (f.x - g.x) / (2 * kFdStep), kFdTol) << time;
    EXPECT_NEAR(p.vy, (f.y - g.y) / (2 * kFdStep), kFdTol) << time;
  }
}

TEST(ShipTrack, ValidationNamesKeyValueAndConstraint) {
  ShipTrack t = paperTrack(true);
  EXPECT_EQ(t.validate(), "");
  t.speed = 0.0;
  EXPECT_TRUE(contains(t.validate(), "dynamics.top_motion.speed = 0: must be > 0"));
  t = paperTrack(true);
  t.legs[1].radius = -5.0;
  EXPECT_TRUE(contains(t.validate(), "dynamics.top_motion.legs[1].turn.radius = -5: must be > 0"));
  t = paperTrack(true);
  t.legs[0].duration = -1.0;
  EXPECT_TRUE(contains(t.validate("top"), "top.legs[0].straight = -1: must be >= 0"));
  t = paperTrack(true);
  t.legs[2].heading = std::nan("");
  EXPECT_TRUE(contains(t.validate(), "dynamics.top_motion.legs[2].heading_deg = nan: must be finite"));
  t = paperTrack(true);
  t.legs[1].angle = INFINITY;
  EXPECT_TRUE(contains(t.validate(), "dynamics.top_motion.legs[1].turn.angle_deg = inf: must be finite"));
}

TEST(ShipTrack, WhichTracksStayOnTheXAxis) {
  EXPECT_EQ(track({}).leavesXAxis(), "");
  EXPECT_EQ(track({ShipLeg::straight(10.0)}, kPi).leavesXAxis(), "");
  EXPECT_EQ(track({ShipLeg::straight(10.0), ShipLeg::headingChange(kPi), ShipLeg::turn(50.0, 0.0)}).leavesXAxis(), "");
  std::string e = track({}, 30.0 * kDeg).leavesXAxis();
  EXPECT_TRUE(contains(e, "dynamics.top_motion.heading_deg = 30"));
  EXPECT_TRUE(contains(e, "needs the 3-D model"));
  e = paperTrack(false).leavesXAxis();
  EXPECT_TRUE(contains(e, "dynamics.top_motion.legs[1].turn.angle_deg = 375"));
  EXPECT_TRUE(contains(e, "needs the 3-D model"));
  e = track({ShipLeg::headingChange(-45.0 * kDeg)}).leavesXAxis();
  EXPECT_TRUE(contains(e, "dynamics.top_motion.legs[0].heading_deg = -45"));
}
