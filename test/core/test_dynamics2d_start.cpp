// The start of the 2-D dynamic solver (src/core/solvers/dynamics2d_start.cpp) against
// independent answers: a held mooring in a current, suspended or grounded, is a fixed point of
// the time stepping from its statics; the top motions the 2-D solver takes (in the x-z plane, a
// ship track straight along x) and those it refuses with the field named; the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "dynamics2d_test_util.hpp"

using namespace mooring_dynamics::core;

namespace {

// Fixed point: every step starts on the static state, so the Newton update vanishes to its
// tolerance (sigma < 1e-6 on scales of T and 1 m); 1e-6 of T and 1e-5 m leave a margin of 10.
constexpr double kFixedPointTensionRelTol = 1e-6;
constexpr double kFixedPointPositionTol = 1e-5;  // [m]
// A top position prescribed by a ship track is met to the Newton tolerance (scale 1 m, 1e-6),
// as test_dynamics2d's output grid.
constexpr double kGridPositionTol = 0.05;  // [m]

Problem chainMooring(bool grounded) { return mooring_dynamics::core::testing_util::chainMooring2D(grounded); }

/// Holds the top for 100 s at dt = 0.5 s and returns the largest change of tension [N] and of
/// position [m] over all nodes against the static start.
void holdAndMeasureDrift(const Problem& problem, int expect_grounded_at_least, double& dT, double& dX, double& T) {
  Problem p = problem;
  p.dynamics.duration = 100.0;
  p.dynamics.dt = 0.5;
  p.dynamics.top_motion.type = TopMotion::Type::Hold;
  DynamicSolver2D solver(p);
  const StaticResult s0 = solver.initialStatic();
  int grounded = 0;
  for (const auto& n : s0.nodes) {
    if (n.z < p.environment.seabedElevation(n.x) + 0.01) ++grounded;
  }
  ASSERT_GE(grounded, expect_grounded_at_least);  // the premise: contact or none, as intended
  if (expect_grounded_at_least == 0) {
    ASSERT_EQ(grounded, 0);
  }
  const StepReport rep = solver.advanceTo(100.0);
  ASSERT_TRUE(rep.ok) << rep.message;
  EXPECT_EQ(rep.cuts, 0);
  const StaticResult s = solver.snapshot();
  ASSERT_EQ(s.nodes.size(), s0.nodes.size());
  T = s0.topTension();
  dT = dX = 0.0;
  for (std::size_t j = 0; j < s.nodes.size(); ++j) {
    dT = std::max(dT, std::abs(s.nodes[j].tension - s0.nodes[j].tension));
    dX = std::max({dX, std::abs(s.nodes[j].x - s0.nodes[j].x), std::abs(s.nodes[j].z - s0.nodes[j].z)});
  }
}

}  // namespace

// --- Fixed point -------------------------------------------------------------------------------

TEST(Dynamics2D, HeldSuspendedMooringInCurrentIsAFixedPoint) {
  double dT = 0.0, dX = 0.0, T = 0.0;
  holdAndMeasureDrift(chainMooring(false), 0, dT, dX, T);
  RecordProperty("worst_tension_drift_N", std::to_string(dT));
  RecordProperty("worst_position_drift_m", std::to_string(dX));
  EXPECT_LT(dT, kFixedPointTensionRelTol * T);
  EXPECT_LT(dX, kFixedPointPositionTol);
}

// With seabed contact. Guards the Newton step conditioning at the seabed: a clip that stops a
// grounded node at the rest penetration zeroes its update, sigma (eq. 39) then reports
// convergence with a residual left (seen: 96 N in a normal force balance, the held chain drifting
// 0.30 N and 0.6 mm in 100 s).
TEST(Dynamics2D, HeldGroundedMooringInCurrentIsAFixedPoint) {
  double dT = 0.0, dX = 0.0, T = 0.0;
  holdAndMeasureDrift(chainMooring(true), 5, dT, dX, T);
  RecordProperty("worst_tension_drift_N", std::to_string(dT));
  RecordProperty("worst_position_drift_m", std::to_string(dX));
  EXPECT_LT(dT, kFixedPointTensionRelTol * T);
  EXPECT_LT(dX, kFixedPointPositionTol);
}

// --- Top motions the 2-D solver cannot follow ---------------------------------------------------

/// The message of the invalid_argument the 2-D solver throws for `p` ("" if it starts).
std::string startError(const Problem& p) {
  try {
    DynamicSolver2D solver(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Dynamics2D, RejectsTopMotionOutOfTheXZPlane) {
  Problem p = chainMooring(false);
  TopMotion& tm = p.dynamics.top_motion;
  tm.type = TopMotion::Type::Sinusoid;
  tm.amplitude_z = 0.5;
  tm.period = 8.0;
  EXPECT_EQ(startError(p), "");
  tm.amplitude_y = 0.5;
  std::string e = startError(p);
  EXPECT_NE(e.find("dynamics.top_motion.amplitude_y = 0.5"), std::string::npos) << e;
  EXPECT_NE(e.find("needs the 3-D model"), std::string::npos) << e;
  // A 3-D table with y = 0 throughout is in the plane; a y component is not.
  tm = TopMotion{};
  tm.type = TopMotion::Type::VelocityTable;
  tm.table = {{0.0, 0.0, 0.0, 0.0}, {1.0, 0.1, 0.0, 0.0}};
  EXPECT_EQ(startError(p), "");
  tm.table[1].y = 0.1;
  e = startError(p);
  EXPECT_NE(e.find("dynamics.top_motion.table[1] y = 0.1"), std::string::npos) << e;
  // A position table must start at the static top.
  tm = TopMotion{};
  tm.type = TopMotion::Type::PositionTable;
  tm.table = {{0.0, 60.0, 0.0, -1.0}};
  e = startError(p);
  EXPECT_NE(e.find("dynamics.top_motion.table[0] = (60, 0, -1): must start at the static top position (60, 0, 0)"),
            std::string::npos)
      << e;
  // A ship track that turns needs the 3-D model.
  tm = TopMotion{};
  tm.type = TopMotion::Type::ShipTrack;
  tm.ship_track.speed = 0.1;
  tm.ship_track.legs = {ShipLeg::straight(1.0), ShipLeg::turn(100.0, 0.5)};
  e = startError(p);
  EXPECT_NE(e.find("dynamics.top_motion.legs[1].turn.angle_deg"), std::string::npos) << e;
  EXPECT_NE(e.find("needs the 3-D model"), std::string::npos) << e;
}

// A ship track straight along x is a planar motion: the 2-D solver tows the top with it.
TEST(Dynamics2D, StraightShipTrackAlongXTowsTheTop) {
  Problem p = chainMooring(false);
  TopMotion& tm = p.dynamics.top_motion;
  tm.type = TopMotion::Type::ShipTrack;
  tm.ship_track.speed = 0.2;                      // [m/s]
  tm.ship_track.heading = 3.14159265358979323846;  // toward -x, back over the anchor
  tm.ship_track.legs = {ShipLeg::straight(2.0)};
  tm.prescribe_position = true;
  p.dynamics.dt = 0.25;
  DynamicSolver2D solver(p);
  ASSERT_TRUE(solver.advanceTo(4.0).ok);
  const StaticResult s = solver.snapshot();
  EXPECT_NEAR(s.nodes.back().x, 60.0 - 0.2 * 4.0, kGridPositionTol);
  EXPECT_NEAR(s.nodes.back().z, 0.0, kGridPositionTol);
}

// --- Two threads ---------------------------------------------------------------------------------

TEST(Dynamics2D, ThreadsMustBeOneOrTwo) {
  Problem p = chainMooring(true);
  p.dynamics.threads = 3;
  EXPECT_NE(p.validate().find("dynamics.threads = 3: must be 1 or 2"), std::string::npos) << p.validate();
  p.dynamics.threads = 2;
  EXPECT_EQ(p.validate(), "");
}
