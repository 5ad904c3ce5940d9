// Unit tests of the demo companions' models (companions.hpp): the wave buoy starts at rest at the
// static top and moves with the set amplitudes; the vessel starts in equilibrium with the static
// cable force, stays there in a calm sea, and answers a change of cable force as a spring.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

using namespace mooring_dynamics::ros_bridge;

namespace {
// Rounding of a few hundred explicit steps of O(1) numbers.
constexpr double kRounding = 1e-9;
}  // namespace

TEST(WaveBuoy, StartsAtRestAndMoves) {
  WaveBuoyOptions o;  // heave 1 m, surge 0.5 m, 8 s, ramp 10 s
  double x = 0, z = 0, x1 = 0, z1 = 0;
  waveBuoyPosition(o, 32.6, -0.48, 0.0, x, z);
  EXPECT_DOUBLE_EQ(x, 32.6);
  EXPECT_DOUBLE_EQ(z, -0.48);
  waveBuoyPosition(o, 32.6, -0.48, 1e-3, x1, z1);  // velocity ~ 0 at the start (ramp slope 0)
  EXPECT_LT(std::hypot(x1 - x, z1 - z) / 1e-3, 1e-3);
  double zmax = -1e9, zmin = 1e9;
  for (double t = 10.0; t < 60.0; t += 0.05) {
    waveBuoyPosition(o, 0.0, 0.0, t, x, z);
    zmax = std::max(zmax, z);
    zmin = std::min(zmin, z);
  }
  // Two components: 1 m and 0.35 m; the crest lies between the larger alone and their sum.
  EXPECT_GT(zmax, 1.0);
  EXPECT_LT(zmax, 1.35 + kRounding);
  EXPECT_LT(zmin, -1.0);
}

TEST(Vessel, EquilibriumAndSpring) {
  VesselOptions o;
  o.wave_heave_force = 0.0;
  o.wave_surge_force = 0.0;
  const double fx0 = -60.0, fz0 = -2200.0;  // the chain mooring's pull on its buoy [N]
  VesselModel calm(o, 32.6, -0.48, fx0, fz0);
  for (int k = 0; k < 300; ++k) calm.step(0.1, fx0, fz0);
  EXPECT_NEAR(calm.x(), 32.6, kRounding);
  EXPECT_NEAR(calm.z(), -0.48, kRounding);
  // 1 kN more downward pull: settles 1000 / k_heave lower.
  VesselModel pulled(o, 32.6, -0.48, fx0, fz0);
  for (int k = 0; k < 3000; ++k) pulled.step(0.01, fx0, fz0 - 1000.0);
  EXPECT_NEAR(pulled.z(), -0.48 - 1000.0 / o.heave_stiffness, 1e-6);
  // Invalid options name the field.
  o.mass = -1.0;
  EXPECT_EQ(o.validate(), "mass = -1: must be > 0");
}

TEST(StaticTop, ChainMooring) {
  const auto p = mooring_dynamics::core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/chain_mooring.yaml");
  const StaticTop t = staticTop(p);
  EXPECT_NEAR(t.z, -0.48, 0.01);  // buoy draft ~0.48 m (cable_sim static)
  EXPECT_LT(t.fz, 0.0);           // the line pulls the buoy down
}
