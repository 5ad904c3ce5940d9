// Unit tests of the demo companions' models (companions.hpp): the wave buoy starts at rest at the
// static top and moves with the set amplitudes; the vessel starts in equilibrium with the static
// cable force, stays there in a calm sea, and answers a change of cable force as a spring; the
// static top they start from (the chain mooring's buoy) against the line shot by hand from the buoy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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

namespace {
// The chain mooring's static line shot from the buoy down, independently of the package: RK4 in
// arc length on dP/ds = -f (P the pull of the line below on the line above, f the wet weight and
// the drag of the uniform current on the line's normal and tangential projections, as in the
// paper's eqs. 10), dr/ds = (1 + |P| / EA) P / |P|, from the buoy's balance at draft d: P(0) =
// (-D(d), -(B(d) - m g)) with B the spherical cap's buoyancy and D the drag of the current on the
// submerged circular segment. The draft is found by bisection so that the line comes down
// horizontal (P_z = 0) exactly on the seabed (a smooth touchdown; the rest lies on the bottom).
struct ShotTop {
  double draft = 0.0;      ///< [m]
  double fx = 0.0, fz = 0.0;  ///< force of the line on the buoy [N]
  double x = 0.0;          ///< buoy x: grounded length (to the anchor at x = 0) plus the suspended span [m]
};

ShotTop shootChainMooring(const mooring_dynamics::core::Problem& p) {
  const auto& e = p.environment;
  const auto& b = p.top.buoy;
  const double rho = e.water_density, g = e.gravity, R = 0.5 * b.diameter, pi = M_PI;
  const double U = e.current.at(0).speed;  // uniform, toward +x (direction 0)
  struct Piece {
    double length, w, d, cdn, cdt, EA;
  };
  std::vector<Piece> pieces;  // from the top down
  double total = 0.0;
  for (auto it = p.segments.rbegin(); it != p.segments.rend(); ++it) {
    const auto& m = p.materials.at(it->material);
    pieces.push_back({it->length, m.wet_weight, m.diameter, m.cdn, m.cdt, m.EA});
    total += it->length;
  }
  auto cap = [&](double d) { return pi * d * d * (3.0 * R - d) / 3.0; };
  auto segment = [&](double d) { return R * R * std::acos((R - d) / R) - (R - d) * std::sqrt(2.0 * R * d - d * d); };
  // One shot at draft d: true when the line flattens (P_z = 0) above the seabed (the buoy
  // carries too little: the draft is larger); s0 and x0: arc length and x (from the buoy) there.
  auto shoot = [&](double d, double& s0, double& x0) {
    double P[4] = {-0.5 * rho * b.cd * segment(d) * U * U, -(rho * g * cap(d) - b.mass * g), 0.0, -d};  // Px Pz x z
    double s = 0.0;
    s0 = x0 = 0.0;
    if (P[1] >= 0.0) return true;  // the buoy's weight alone exceeds its buoyancy
    for (const Piece& pc : pieces) {
      auto rate = [&](const double* y, double* k) {
        const double T = std::hypot(y[0], y[1]), tx = y[0] / T, tz = y[1] / T;
        const double ut = U * tx, unx = U - ut * tx, unz = -ut * tz, un = std::hypot(unx, unz);
        const double cn = 0.5 * rho * pc.d * pc.cdn * un, ct = 0.5 * rho * pi * pc.d * pc.cdt * std::abs(ut) * ut;
        k[0] = -(cn * unx + ct * tx);
        k[1] = -(cn * unz + ct * tz - pc.w);
        k[2] = (1.0 + T / pc.EA) * tx;
        k[3] = (1.0 + T / pc.EA) * tz;
      };
      const int n = static_cast<int>(std::ceil(pc.length / 0.01));
      const double h = pc.length / n;
      for (int i = 0; i < n; ++i) {
        double k1[4], k2[4], k3[4], k4[4], y[4], prev[4];
        std::copy(P, P + 4, prev);
        rate(P, k1);
        for (int c = 0; c < 4; ++c) y[c] = P[c] + 0.5 * h * k1[c];
        rate(y, k2);
        for (int c = 0; c < 4; ++c) y[c] = P[c] + 0.5 * h * k2[c];
        rate(y, k3);
        for (int c = 0; c < 4; ++c) y[c] = P[c] + h * k3[c];
        rate(y, k4);
        for (int c = 0; c < 4; ++c) P[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
        s += h;
        if (P[1] >= 0.0) {  // flat: interpolate to P_z = 0
          const double a = -prev[1] / (P[1] - prev[1]);
          s0 = s - h + a * h;
          x0 = prev[2] + a * (P[2] - prev[2]);
          return prev[3] + a * (P[3] - prev[3]) > -e.depth;
        }
        if (P[3] <= -e.depth) {  // on the seabed while still pulling up
          const double a = (prev[3] + e.depth) / (prev[3] - P[3]);
          s0 = s - h + a * h;
          x0 = prev[2] + a * (P[2] - prev[2]);
          return false;
        }
      }
    }
    return false;
  };
  double lo = 1e-6, hi = b.diameter - 1e-6, s0 = 0.0, x0 = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, s0, x0) ? lo : hi) = mid;
  }
  ShotTop r;
  r.draft = 0.5 * (lo + hi);
  shoot(r.draft, s0, x0);
  r.fx = -0.5 * rho * b.cd * segment(r.draft) * U * U;
  r.fz = -(rho * g * cap(r.draft) - b.mass * g);
  r.x = (total - s0) - x0;  // the grounded chain runs straight from the anchor (stretch < 1 mm)
  return r;
}
}  // namespace

TEST(StaticTop, ChainMooringAgainstAnIndependentShot) {
  // The buoy's draft, its pull and its position in the package's statics against the line shot
  // from the buoy down (shootChainMooring: buoyancy of the spherical cap = the buoy's weight + the
  // line's vertical pull, the line's pull from its wet weight and drag, touchdown on the seabed).
  // Tolerances: the box scheme at 0.5 m with its spring seabed (0.3 mm penetration) against a
  // 1 cm RK4 shot with a sharp touchdown; measured 5e-6 m of draft, 0.12 N of pull, 4 mm of x.
  // The draft moves 1e-4 m per 2.3 N of vertical pull (the waterplane of a 2 m sphere at 0.48 m
  // draft), i.e. per 7 cm of chain lifted off the seabed, a seventh of the node spacing; the
  // touchdown point and with it the buoy move those 7 cm. A kilogram more buoy (0.4 mm of draft)
  // or 1 % more wet weight of line (20 N of pull) in the shot fails it.
  constexpr double kDraftTol = 1e-4;         // [m]
  constexpr double kVerticalPullTol = 2.3;   // [N] of 2.2 kN: the same 1e-4 m of draft
  constexpr double kDragRelTol = 1e-3;       // the submerged segment's area changes 0.03 % per 1e-4 m of draft
  constexpr double kBuoyXTol = 0.07;         // [m]
  const auto p = mooring_dynamics::core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/chain_mooring.yaml");
  for (const auto& c : p.environment.current) {  // the shot's premise: uniform, toward +x
    ASSERT_EQ(c.speed, p.environment.current.at(0).speed);
    ASSERT_EQ(c.direction, 0.0);
  }
  ASSERT_EQ(p.anchor_x, 0.0);
  ASSERT_EQ(p.environment.wind_speed, 0.0);
  const StaticTop t = staticTop(p);
  const ShotTop s = shootChainMooring(p);
  std::printf("chain mooring buoy: draft %.6f m (shot %.6f m), pull (%.3f, %.3f) N (shot (%.3f, %.3f) N), x %.4f m "
              "(shot %.4f m)\n",
              -t.z, s.draft, t.fx, t.fz, s.fx, s.fz, t.x, s.x);
  EXPECT_NEAR(-t.z, s.draft, kDraftTol);
  EXPECT_NEAR(t.fz, s.fz, kVerticalPullTol);
  EXPECT_NEAR(t.fx, s.fx, kDragRelTol * std::abs(s.fx));
  EXPECT_NEAR(t.x, s.x, kBuoyXTol);
  // The buoy's own balance at the package's draft, exactly: the cap's buoyancy carries its weight
  // and the line's vertical pull.
  constexpr double kBalanceRelTol = 1e-6;  // the static Newton tolerance, 1e-9 of the scaled update
  const double R = 0.5 * p.top.buoy.diameter, d = -t.z, g = p.environment.gravity;
  const double B = p.environment.water_density * g * M_PI * d * d * (3.0 * R - d) / 3.0;
  EXPECT_NEAR(B, p.top.buoy.mass * g - t.fz, kBalanceRelTol * B);
  EXPECT_LT(t.fz, 0.0);  // the line pulls the buoy down
}
