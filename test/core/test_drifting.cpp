// Drifting systems (issue 6), statics: a surface buoy on a line with a free lower end (a drifter
// with a hanging line and drogue), 3-D model. Checks against independent answers: in a uniform
// current without wind the drifter drifts with the water and the line hangs straight down carrying
// the wet weight below each node (exact); with wind on a weightless, dragless tether the drift
// velocity has a closed form from the balance of the buoy's wind drag against the water drag of
// buoy and drogue, and the tether's angle follows from the drogue's drag and weight; in a sheared
// current the drift, draft and tether against a force balance shot by hand; input checks.
// Dynamics: test_drifting_dynamics.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "mooring_dynamics/core/solvers/drifting.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/result_io.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"
#include "drifting_test_util.hpp"

using namespace mooring_dynamics::core;
using namespace mooring_dynamics::core::testing_util;

namespace {

// The exact solutions of the box rows (a vertical or straight line), to the static Newton
// tolerance (1e-9 on the scaled update) and the drift iteration's: 1e-6 of the force scale.
constexpr double kExactRelTol = 1e-6;

/// Draft of the cylinder buoy carrying `pull` [N] below it (still water, by hand).
double cylinderDraft(const Problem& p, double pull) {
  const SurfaceBuoy& b = p.top.buoy;
  const Environment& e = p.environment;
  return (b.mass * e.gravity + pull) / (e.water_density * e.gravity * 0.25 * kPi * b.diameter * b.diameter);
}

}  // namespace

TEST(Drifting, UniformCurrentWithoutWindDriftsWithTheWaterAndHangsVertically) {
  const double U = 0.4, dir = 0.5;
  Problem p = drifter();
  p.top.buoy.wind_area = 0.0;  // no windage: still air would hold the buoy back
  uniformCurrent(p, U, dir);
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  EXPECT_TRUE(r.drifting);
  EXPECT_NEAR(r.drift_vx, U * std::cos(dir), kDriftTol);
  EXPECT_NEAR(r.drift_vy, U * std::sin(dir), kDriftTol);
  const double w = p.materials[0].wet_weight, Wd = p.bodies[0].wet_weight, L = p.segments[0].length;
  const NodeState& top = r.nodes.back();
  for (const auto& n : r.nodes) {
    // Tension = wet weight below the node plus the drogue's (s from the free end), > 0: slack-free.
    EXPECT_NEAR(n.tension, Wd + w * n.s, kExactRelTol * (Wd + w * L)) << "s = " << n.s;
    EXPECT_GT(n.tension, 0.0);
    EXPECT_NEAR(n.x, top.x, 1e-6) << "s = " << n.s;
    EXPECT_NEAR(n.y, top.y, 1e-6) << "s = " << n.s;
    EXPECT_NEAR(n.angle, 0.0, 1e-6) << "s = " << n.s;
  }
  EXPECT_NEAR(top.x, 0.0, 1e-12);
  EXPECT_NEAR(top.y, 0.0, 1e-12);
  EXPECT_NEAR(r.buoy_draft, cylinderDraft(p, Wd + w * L), kExactRelTol);
  // The drogue hangs the stretched length below the keel.
  const double EA = p.materials[0].EA;
  EXPECT_NEAR(top.z - r.nodes.front().z, L + (Wd * L + 0.5 * w * L * L) / EA, 1e-6);
}

TEST(Drifting, WindDriftOfAWeightlessTetherAgainstAHandForceBalance) {
  // Weightless, dragless tether; a drogue with normal drag only (cdt = 0): only the buoy (water
  // and wind drag) and the drogue (normal drag, weight W_d) carry loads. With r = U - V_d the
  // water relative to the drifter and a = W - V_d the relative wind, all horizontal loads lie
  // along r and a, so r = -beta (W - U) and a = (1 - beta) (W - U). The drogue balances its weight
  // with its normal drag on the straight tether at phi from the vertical (the towing critical
  // angle): c_d r^2 cos^2 phi = W_d sin phi, tension T = W_d cos phi, horizontal drag
  // c_d r^2 cos^3 phi, vertical pull on the buoy T cos phi (its draft). The buoy's balance
  //   (c_b(draft) + c_d cos^3 phi) beta^2 = c_w (1 - beta)^2
  // is solved for beta by bisection here.
  const double U = 0.2, Wspd = 12.0, wind_dir = 0.5 * kPi;  // current east, wind toward north
  Problem p = drifter();
  Material& m = p.materials[0];
  m.wet_weight = 0.0;
  m.cdn = m.cdt = 0.0;
  p.bodies[0].cdt = 0.0;
  uniformCurrent(p, U, 0.0);
  p.environment.wind_speed = Wspd;
  p.environment.wind_direction = wind_dir;
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;

  const Environment& e = p.environment;
  const SurfaceBuoy& b = p.top.buoy;
  const Body& d = p.bodies[0];
  const double Wd = d.wet_weight;
  const double cd = 0.5 * e.water_density * d.cdn * 0.25 * kPi * d.diameter * d.diameter;
  const double cw = 0.5 * e.air_density * b.wind_cd * b.wind_area;
  const double Wx = Wspd * std::cos(wind_dir), Wy = Wspd * std::sin(wind_dir);
  const double rel = std::hypot(Wx - U, Wy);  // |W - U|
  double phi = 0.0, draft = 0.0;
  auto balance = [&](double beta) {
    const double R = cd * beta * beta * rel * rel / Wd;
    phi = std::asin((-1.0 + std::sqrt(1.0 + 4.0 * R * R)) / (2.0 * R));
    draft = cylinderDraft(p, Wd * std::cos(phi) * std::cos(phi));
    const double cb = 0.5 * e.water_density * b.cd * b.diameter * draft;
    const double c3 = std::cos(phi) * std::cos(phi) * std::cos(phi);
    return (cb + cd * c3) * beta * beta - cw * (1.0 - beta) * (1.0 - beta);
  };
  double lo = 1e-9, hi = 1.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (balance(mid) < 0.0 ? lo : hi) = mid;
  }
  const double beta = 0.5 * (lo + hi);
  balance(beta);
  const double Vx = U + beta * (Wx - U), Vy = beta * Wy;
  EXPECT_NEAR(r.drift_vx, Vx, kDriftTol);
  EXPECT_NEAR(r.drift_vy, Vy, kDriftTol);
  EXPECT_NEAR(r.buoy_draft, draft, kExactRelTol);
  const double T = Wd * std::cos(phi);
  const double L = p.segments[0].length * (1.0 + T / m.EA);
  const double rx = U - Vx, ry = -Vy, rn = std::hypot(rx, ry);
  const NodeState& top = r.nodes.back();
  const NodeState& end = r.nodes.front();
  for (const auto& n : r.nodes) {
    EXPECT_NEAR(n.tension, T, kExactRelTol * Wd) << "s = " << n.s;
    EXPECT_NEAR(n.angle, phi, 1e-6) << "s = " << n.s;
  }
  // The tether leans from the drogue against the relative water r: the drogue trails along r.
  EXPECT_NEAR(end.x - top.x, L * std::sin(phi) * rx / rn, 1e-6);
  EXPECT_NEAR(end.y - top.y, L * std::sin(phi) * ry / rn, 1e-6);
  EXPECT_NEAR(top.z - end.z, L * std::cos(phi), 1e-6);
  std::printf("wind drift: V_d = (%.6f, %.6f) m/s, hand (%.6f, %.6f); tether %.4f deg from vertical, hand %.4f\n",
              r.drift_vx, r.drift_vy, Vx, Vy, r.nodes[10].angle * 180.0 / kPi, phi * 180.0 / kPi);
  RecordProperty("drift_message", r.summary.message);
}

TEST(Drifting, DriftEnvironmentSubtractsTheDriftFromCurrentAndWind) {
  Environment env;
  env.current = {{0.0, 1.0, 0.0}, {50.0, 0.5, 0.0}};
  env.wind_speed = 10.0;
  env.wind_direction = 0.5 * kPi;
  const Environment rel = driftEnvironment(env, 0.25, 0.5);
  double ux, uy;
  rel.currentAt(-25.0, ux, uy);
  EXPECT_NEAR(ux, 0.75 - 0.25, 1e-12);
  EXPECT_NEAR(uy, -0.5, 1e-12);
  EXPECT_NEAR(rel.wind_speed * std::cos(rel.wind_direction), -0.25, 1e-12);
  EXPECT_NEAR(rel.wind_speed * std::sin(rel.wind_direction), 9.5, 1e-12);
}

namespace {
/// The drifter's steady drift in a current along +x sheared with depth, in still air, shot by hand
/// (independently of the package). By symmetry the drift V is along x. For a drift V and a drogue
/// depth z_d the tether is integrated by RK4 from the drogue up: Q (the pull of the line above on
/// the line below) starts by holding the drogue's weight and drag on r = U(z_d) - V (1/2 rho A
/// (Cdt |r_t| r_t t + Cdn |r_n| r_n), split along the line's end tangent t = Q(0) / |Q(0)|), and
/// dQ/ds = -(wet weight + drag on the line's normal and
/// tangential relative water, times sqrt(1 + eps) as in the paper's eq. 10), dr/ds = (1 + T / EA)
/// Q / |Q|. At the top the buoy's draft carries its weight and Q_z (d = (m g + Q_z) / (rho g A_w),
/// a cylinder); z_d is found by bisection so that the line's top is at the keel (z = -d), then V by
/// bisection so that the buoy's water drag on U(0) - V and its wind drag on -V balance Q_x.
struct DriftShot {
  double V = 0.0, draft = 0.0;
  double drogue_x = 0.0, drogue_z = 0.0;  ///< drogue relative to the top (x), and its elevation (z) [m]
  double top_tension = 0.0;               ///< [N]
};

DriftShot shootShearedDrift(const Problem& p) {
  const Environment& e = p.environment;
  const Material& m = p.materials[0];
  const Body& dr = p.bodies[0];
  const SurfaceBuoy& b = p.top.buoy;
  const double rho = e.water_density, g = e.gravity, L = p.segments[0].length;
  auto current = [&](double z) {  // the table, linear in depth, constant beyond its ends
    const auto& c = e.current;
    const double depth = -z;
    if (depth <= c.front().depth) return c.front().speed;
    for (std::size_t i = 1; i < c.size(); ++i)
      if (depth <= c[i].depth) {
        const double f = (depth - c[i - 1].depth) / (c[i].depth - c[i - 1].depth);
        return c[i - 1].speed + f * (c[i].speed - c[i - 1].speed);
      }
    return c.back().speed;
  };
  const double qd = 0.5 * rho * 0.25 * kPi * dr.diameter * dr.diameter;
  const double Aw = 0.25 * kPi * b.diameter * b.diameter;
  // Shot from the drogue at z_d: returns the top's Q and position relative to the drogue.
  auto shoot = [&](double V, double zd, double* Q) {
    // The drogue's drag split along the line's end tangent t (cdt) and across it (cdn), the law of
    // a line-aligned body, with t along Q(0) itself: a fixed point, found by iteration.
    const double r = current(zd) - V;
    double y[4] = {0.0, dr.wet_weight, 0.0, zd};  // Qx Qz x z
    for (int k = 0; k < 50; ++k) {
      const double T = std::hypot(y[0], y[1]), tx = y[0] / T, tz = y[1] / T;
      const double rt = r * tx, nx = r - rt * tx, nz = -rt * tz, rn = std::hypot(nx, nz);
      y[0] = -qd * (dr.cdt * std::abs(rt) * rt * tx + dr.cdn * rn * nx);
      y[1] = dr.wet_weight - qd * (dr.cdt * std::abs(rt) * rt * tz + dr.cdn * rn * nz);
    }
    auto rate = [&](const double* s, double* k) {
      const double T = std::hypot(s[0], s[1]), tx = s[0] / T, tz = s[1] / T;
      const double stretch = 1.0 + T / m.EA;
      const double ux = current(s[3]) - V;  // water relative to the line (at rest in the drift)
      const double ut = ux * tx, nx = ux - ut * tx, nz = -ut * tz, un = std::hypot(nx, nz);
      const double cn = 0.5 * rho * m.diameter * m.cdn * un * std::sqrt(stretch);
      const double ct = 0.5 * rho * kPi * m.diameter * m.cdt * std::abs(ut) * ut * std::sqrt(stretch);
      k[0] = -(cn * nx + ct * tx);
      k[1] = -(cn * nz + ct * tz - m.wet_weight);
      k[2] = stretch * tx;
      k[3] = stretch * tz;
    };
    const int n = 500;  // 4 cm steps: RK4's error is far below the drift iteration's 1e-7 m/s
    const double h = L / n;
    for (int i = 0; i < n; ++i) {
      double k1[4], k2[4], k3[4], k4[4], t[4];
      rate(y, k1);
      for (int c = 0; c < 4; ++c) t[c] = y[c] + 0.5 * h * k1[c];
      rate(t, k2);
      for (int c = 0; c < 4; ++c) t[c] = y[c] + 0.5 * h * k2[c];
      rate(t, k3);
      for (int c = 0; c < 4; ++c) t[c] = y[c] + h * k3[c];
      rate(t, k4);
      for (int c = 0; c < 4; ++c) y[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
    }
    std::copy(y, y + 4, Q);
  };
  // For a drift V: the drogue depth that hangs the top at the keel; Q at the top.
  auto hang = [&](double V, double& zd, double* Q) {
    double lo = -2.0 * L, hi = -0.5 * L;
    for (int k = 0; k < 45; ++k) {
      zd = 0.5 * (lo + hi);
      shoot(V, zd, Q);
      const double draft = (b.mass * g + Q[1]) / (rho * g * Aw);
      (Q[3] + draft < 0.0 ? lo : hi) = zd;
    }
  };
  double lo = 0.0, hi = current(0.0), zd = 0.0, Q[4];
  for (int k = 0; k < 45; ++k) {
    const double V = 0.5 * (lo + hi);
    hang(V, zd, Q);
    const double draft = (b.mass * g + Q[1]) / (rho * g * Aw);
    const double r = current(0.0) - V;
    const double water = 0.5 * rho * b.cd * b.diameter * draft * std::abs(r) * r;
    const double wind = -0.5 * e.air_density * b.wind_cd * b.wind_area * V * V;
    (water + wind - Q[0] > 0.0 ? lo : hi) = V;
  }
  DriftShot s;
  s.V = 0.5 * (lo + hi);
  hang(s.V, zd, Q);
  s.draft = (b.mass * g + Q[1]) / (rho * g * Aw);
  s.drogue_x = -Q[2];
  s.drogue_z = zd;
  s.top_tension = std::hypot(Q[0], Q[1]);
  return s;
}
}  // namespace

TEST(Drifting, ShearedCurrentDriftMatchesAForceBalanceShotByHand) {
  // A drogue in slower deep water (0.6 m/s at the surface, 0.1 m/s at 25 m) holds the drifter
  // back: the drift velocity, the buoy's draft, the drogue's place and the tension against the
  // line shot by hand from the drogue up (shootShearedDrift, RK4 at 4 cm). The box scheme's
  // error is O(h^2) on the curved tether: measured on the 1 m mesh 1.5e-5 m/s of drift, 0.15 mm
  // of the drogue's trail, 6e-4 N of tension, and 4.06 times less drift error on 0.5 m (4.2 on
  // 2 -> 1 m, 4.2 on 0.5 -> 0.25 m). A shot with the drogue dragged as 1/2 rho Cd A |r| r (not
  // split along the line's end) is 5e-4 m/s off, ten times the tolerance.
  constexpr double kShotDriftTol = 5e-5;      // [m/s] of 0.33 m/s
  constexpr double kShotPositionTol = 5e-4;   // [m]
  constexpr double kShotTensionRelTol = 2e-5;
  constexpr double kSecondOrderRatio = 3.0;   // halving h divides the error by 4 (2 for first order)
  Problem p = drifter();
  p.environment.current = {{0.0, 0.6, 0.0}, {25.0, 0.1, 0.0}};
  ASSERT_EQ(p.environment.wind_speed, 0.0);  // still air: the shot's V is along the current
  ASSERT_EQ(p.segments[0].spacing, 1.0);
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  Problem fine = p;
  fine.segments[0].spacing = 0.5;
  const StaticResult rf = solveStatic3D(fine);
  ASSERT_TRUE(rf.summary.converged) << rf.summary.message;
  const DriftShot s = shootShearedDrift(p);
  const NodeState& top = r.nodes.back();
  const NodeState& end = r.nodes.front();
  std::printf("sheared drift: V_d %.9f m/s (0.5 m mesh %.9f, shot %.9f), draft %.7f m (shot %.7f), drogue %.6f m "
              "astern at %.6f m (shot %.6f at %.6f), top tension %.6f N (shot %.6f)\n",
              r.drift_vx, rf.drift_vx, s.V, r.buoy_draft, s.draft, top.x - end.x, end.z, -s.drogue_x, s.drogue_z,
              top.tension, s.top_tension);
  EXPECT_NEAR(r.drift_vx, s.V, kShotDriftTol);
  EXPECT_NEAR(r.drift_vy, 0.0, kDriftTol);
  EXPECT_GT(std::abs(r.drift_vx - s.V), kSecondOrderRatio * std::abs(rf.drift_vx - s.V));
  EXPECT_NEAR(r.buoy_draft, s.draft, kShotPositionTol);
  EXPECT_NEAR(end.x - top.x, s.drogue_x, kShotPositionTol);
  EXPECT_NEAR(end.z, s.drogue_z, kShotPositionTol);
  EXPECT_NEAR(top.tension, s.top_tension, kShotTensionRelTol * s.top_tension);
  // The deep water, slower than the drifter, drags the drogue back: it trails upstream (-x).
  EXPECT_LT(end.x, top.x);
}

// --- Input ----------------------------------------------------------------------------------------

namespace {
std::string loadError(const std::string& text) {
  try {
    loadProblemFromString(text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(DriftingInput, ProblemFileAndChecks) {
  const Problem p = loadProblemFromString(kDrifterYaml);
  EXPECT_TRUE(isDrifter(p));
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  EXPECT_GT(r.drift_vx, 0.0);
  EXPECT_GT(r.drift_vy, 0.0);
  // The summary and the JSON report the drift velocity.
  EXPECT_NE(staticSummaryText(p, r).find("drift velocity"), std::string::npos) << staticSummaryText(p, r);
  std::ostringstream js;
  writeStaticJson(js, p, r);
  EXPECT_NE(js.str().find("\"drift_velocity\""), std::string::npos);

  std::string text = kDrifterYaml;
  const std::string two = text.substr(10);  // without model: 3d
  EXPECT_NE(loadError(two).find("model: 3d"), std::string::npos) << loadError(two);
  Problem q = p;
  q.top.tow_vx = 1.0;
  EXPECT_NE(q.validate().find("top.tow_velocity"), std::string::npos) << q.validate();
  q = p;
  q.dynamics.top_motion.type = TopMotion::Type::Sinusoid;
  EXPECT_NE(q.validate().find("dynamics.top_motion"), std::string::npos) << q.validate();
  q = p;
  q.top.type = TopBoundary::Type::Force;
  EXPECT_NE(q.validate().find("top.buoy"), std::string::npos) << q.validate();
  // Anchored buoy moorings keep their statics (no drift).
  q = p;
  q.lower_end = Problem::LowerEnd::Anchor;
  q.anchor_z = -10.0;
  EXPECT_FALSE(isDrifter(q));
}
