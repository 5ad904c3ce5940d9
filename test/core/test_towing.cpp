// Towing (free lower end, paper sections 5.2 and 7.1) against independent answers: the critical
// angle of a long towed cable with normal drag only (a straight line, closed form), the steady tow
// of a cable with a tow body against an independent RK4 integration of the static towing
// equations, the relative environment, and the input checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Core>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"
#include "mooring_dynamics/core/solvers/towing.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Critical angle: the straight line is the exact solution of the box rows up to the strain's
// sqrt(1 + eps) in the drag (eps < 1e-6 here) and bending at the ends (EI = 1e-3): 1e-4 rad.
constexpr double kAngleTol = 1e-4;  // [rad]
// RK4 with 2000 steps against the box scheme at 1 m: both far below 1e-4 of the tension; EI and
// the box scheme's O(h^2) near the body leave about 1e-5.
constexpr double kShootRelTol = 2e-4;
constexpr double kShootPosTol = 0.05;  // [m] over 300 m of cable

Material towCable(double cdt) {
  Material m;
  m.name = "tow";
  m.EA = 1.0e10;  // nearly inextensible: the closed forms have no strain
  m.EI = 1.0e-3;
  m.GJ = 1.0e-3;
  m.mass = 2.37;
  m.added_mass = 1.33;
  m.wet_weight = 10.0;
  m.diameter = 0.041;
  m.cdn = 1.5;
  m.cdt = cdt;
  return m;
}

Problem towedLine(double U, bool body) {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 2000.0;
  p.materials.push_back(towCable(0.0));
  Segment s;
  s.length = 300.0;
  s.spacing = 1.0;
  p.segments.push_back(s);
  p.lower_end = Problem::LowerEnd::Free;
  if (body) {
    Body b;
    b.name = "towfish";
    b.mass = 500.0;
    b.added_mass = 200.0;
    b.wet_weight = 2000.0;
    b.diameter = 0.6;
    b.cdn = 1.0;
    b.cdt = 1.0;
    p.bodies.push_back(b);
    p.end_body = 0;
  }
  p.top.type = TopBoundary::Type::Position;
  p.top.x = 0.0;
  p.top.z = -1.0;
  p.top.tow_vx = U;
  return p;
}

}  // namespace

TEST(Towing, RelativeEnvironmentSubtractsTheTowVelocity) {
  Environment env;
  env.current = {{0.0, 1.0, 0.5 * kPi}, {100.0, 0.5, 0.5 * kPi}};
  const Environment rel = relativeEnvironment(env, 2.0, 0.0);
  double ux, uy;
  rel.currentAt(-50.0, ux, uy);
  EXPECT_NEAR(ux, -2.0, 1e-12);
  EXPECT_NEAR(uy, 0.75, 1e-12);
  const Environment none = relativeEnvironment(Environment{}, 3.0, -1.0);
  none.currentAt(-500.0, ux, uy);
  EXPECT_NEAR(ux, -3.0, 1e-12);
  EXPECT_NEAR(uy, 1.0, 1e-12);
}

TEST(Towing, LongCableWithNormalDragOnlyTowsAtTheCriticalAngle) {
  // Normal drag balances the normal weight along a straight line: w sin(phi) = R w cos^2(phi),
  // R = rho d Cdn U^2 / (2 w), phi from the vertical; the tension grows as w cos(phi) s from the
  // free end (no tangential drag).
  for (double U : {0.5, 1.5, 3.0}) {
    const Problem p = towedLine(U, false);
    const StaticResult r = solveStatic3D(p);
    ASSERT_TRUE(r.summary.converged) << U << ": " << r.summary.message;
    const Material& m = p.materials[0];
    const double R = 0.5 * p.environment.water_density * m.diameter * m.cdn * U * U / m.wet_weight;
    const double phi = std::asin((-1.0 + std::sqrt(1.0 + 4.0 * R * R)) / (2.0 * R));
    for (std::size_t j = 5; j + 5 < r.nodes.size(); ++j) {  // away from the moment-free ends
      EXPECT_NEAR(r.nodes[j].angle, phi, kAngleTol) << "U " << U << " node " << j;
      EXPECT_NEAR(r.nodes[j].tension, m.wet_weight * std::cos(phi) * r.nodes[j].s,
                  1e-4 * m.wet_weight * r.nodes.back().s)
          << "U " << U << " node " << j;
      EXPECT_NEAR(r.nodes[j].y, 0.0, 1e-9);
    }
    EXPECT_LT(r.nodes.front().x, r.nodes.back().x);  // the cable trails behind the ship (+x tow)
  }
}

namespace {
/// The static towing equations without bending, integrated by RK4 from the body up in the frame
/// of the tow point: F' = -g(F / |F|), r' = (1 + T / EA) F / |F|, F(0) = -(W + D(t)) (body).
struct Shot {
  Eigen::Vector3d top_force, end;  // F at the top, body position relative to the top
};
Shot shootTow(const Problem& p) {
  using V = Eigen::Vector3d;
  const Material& m = p.materials[0];
  const Body& b = p.bodies[0];
  const double rho = p.environment.water_density, U = p.top.tow_vx;
  const V w(-U, 0.0, 0.0);
  auto drag = [&](const V& t, double cdn, double cdt, double dn, double dt_area) {
    const double wt = w.dot(t);
    const V wn = w - wt * t;
    return V(0.5 * rho * dn * cdn * wn.norm() * wn + 0.5 * rho * dt_area * cdt * std::abs(wt) * wt * t);
  };
  auto g = [&](const V& F) {
    const V t = F.normalized();
    return V(V(0, 0, -m.wet_weight) + drag(t, m.cdn, m.cdt, m.diameter, kPi * m.diameter));
  };
  V F(0, 0, 1), t(0, 0, 1);
  const double A = 0.25 * kPi * b.diameter * b.diameter;
  for (int k = 0; k < 50; ++k) {  // body balance with its tangent along the force
    F = -(V(0, 0, -b.wet_weight) + drag(t, b.cdn, b.cdt, A, A));
    t = F.normalized();
  }
  V r(0, 0, 0);
  const int steps = 2000;
  const double h = p.segments[0].length / steps;
  for (int k = 0; k < steps; ++k) {
    auto dr = [&](const V& f) { return V((1.0 + f.norm() / m.EA) * f.normalized()); };
    const V k1 = -g(F), l1 = dr(F);
    const V k2 = -g(F + 0.5 * h * k1), l2 = dr(F + 0.5 * h * k1);
    const V k3 = -g(F + 0.5 * h * k2), l3 = dr(F + 0.5 * h * k2);
    const V k4 = -g(F + h * k3), l4 = dr(F + h * k3);
    F += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    r += h / 6.0 * (l1 + 2 * l2 + 2 * l3 + l4);
  }
  return {F, -r};
}
}  // namespace

TEST(Towing, SteadyTowWithBodyMatchesAnIndependentIntegration) {
  Problem p = towedLine(2.0, true);
  p.materials[0].cdt = 0.02;  // tangential drag too
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const Shot s = shootTow(p);
  const double T = s.top_force.norm();
  EXPECT_NEAR(r.top_force_x, s.top_force.x(), kShootRelTol * T);
  EXPECT_NEAR(r.top_force_z, s.top_force.z(), kShootRelTol * T);
  EXPECT_NEAR(r.nodes.front().x - r.nodes.back().x, s.end.x(), kShootPosTol);
  EXPECT_NEAR(r.nodes.front().z - r.nodes.back().z, s.end.z(), kShootPosTol);
  RecordProperty("body_depth_m", std::to_string(-r.nodes.front().z));
}

TEST(Towing, FreeEndNeedsTheThreeDimensionalModelAndATowPoint) {
  Problem p = towedLine(1.0, false);
  p.formulation = Formulation::TwoD;
  EXPECT_NE(p.validate().find("model: 3d"), std::string::npos) << p.validate();
  p = towedLine(1.0, false);
  p.top.type = TopBoundary::Type::Force;
  EXPECT_NE(p.validate().find("top.position"), std::string::npos) << p.validate();
  p = towedLine(1.0, false);
  p.lower_end = Problem::LowerEnd::Anchor;
  EXPECT_NE(p.validate().find("top.tow_velocity"), std::string::npos) << p.validate();
}

TEST(Towing, ProblemFileKeys) {
  const std::string text = R"(model: 3d
environment: {depth: 1000}
materials:
  tow: {EA: 1.0e8, EI: 1.0, GJ: 1.0, mass: 2.4, added_mass: 1.3, wet_weight: 2.3, diameter: 0.041, cdn: 2.0, cdt: 0.015}
bodies:
  fish: {mass: 100, wet_weight: 500, diameter: 0.5, cdn: 1.0, cdt: 1.0}
line:
  - {material: tow, length: 100, spacing: 2}
free_end: {body: fish}
top:
  position: {x: 0, y: 0, z: 0}
  tow_velocity: {x: 3.0, y: 0}
)";
  const Problem p = loadProblemFromString(text);
  EXPECT_EQ(p.lower_end, Problem::LowerEnd::Free);
  EXPECT_EQ(p.end_body, 0u);
  EXPECT_DOUBLE_EQ(p.top.tow_vx, 3.0);
  const StaticResult r = solveStatic3D(p);
  EXPECT_TRUE(r.summary.converged) << r.summary.message;
  std::string both = text;
  both.insert(both.find("free_end"), "anchor: {x: 0}\n");
  try {
    loadProblemFromString(both);
    ADD_FAILURE() << "anchor and free_end together loaded";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("free_end"), std::string::npos) << e.what();
  }
}

// --- Dynamics -------------------------------------------------------------------------------------

#include "mooring_dynamics/core/solvers/dynamics3d.hpp"

namespace {
// Steady tow: the start gives every node the ship's velocity, R^T V in local components, which
// the discrete compatibility rows (v_b - v_a + h Omega x v = 0) satisfy only to O(h^3 Omega^2)
// per interval; that residual starts a small transient, measured at 2.5e-4 of the tension and
// 0.5 mm. A wrong start (e.g. the line at rest) gives kilonewtons.
constexpr double kSteadyTensionRelTol = 1e-3;
constexpr double kSteadyPositionTol = 0.005;  // [m]

Problem towRun(double U) {
  Problem p = towedLine(U, true);
  p.segments[0].spacing = 2.0;
  p.materials[0].cdt = 0.02;
  p.top.tow_vx = 0.0;  // from the ship track
  p.dynamics.dt = 1.0;
  p.dynamics.duration = 30.0;
  p.dynamics.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  p.dynamics.top_motion.type = TopMotion::Type::ShipTrack;
  p.dynamics.top_motion.ship_track.speed = U;
  p.dynamics.record_s = {0.0};
  return p;
}
}  // namespace

TEST(TowingDynamics, StraightTowIsASteadyState) {
  const Problem p = towRun(2.0);
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_EQ(r.cuts, 0);
  const double T0 = r.top_tension.front();
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    EXPECT_NEAR(r.top_tension[k], T0, kSteadyTensionRelTol * T0) << "t = " << r.t[k];
    // The body keeps its place behind and below the ship, which moves at 2 m/s along x.
    EXPECT_NEAR(r.node_x[0][k] - r.top_x[k], r.node_x[0][0] - r.top_x[0], kSteadyPositionTol) << r.t[k];
    EXPECT_NEAR(r.node_z[0][k], r.node_z[0][0], kSteadyPositionTol) << r.t[k];
    EXPECT_NEAR(r.top_x[k], 2.0 * r.t[k], 1e-6) << r.t[k];
  }
}

TEST(TowingDynamics, SlowingDownSinksTheBodyAndTheTensionFollowsTheNewSteadyTow) {
  // Slowing from 2 to 1 m/s (velocity table): the body sinks and, after the transient, the
  // tension settles on the steady tow at 1 m/s solved by the statics.
  Problem p = towRun(2.0);
  p.dynamics.top_motion.type = TopMotion::Type::VelocityTable;
  p.dynamics.top_motion.table = {{0.0, 2.0, 0.0, 0.0}, {10.0, 2.0, 0.0, 0.0}, {20.0, 1.0, 0.0, 0.0}};
  p.dynamics.duration = 1500.0;
  p.dynamics.dt = 3.0;
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  Problem slow = towedLine(1.0, true);
  slow.segments[0].spacing = 2.0;
  slow.materials[0].cdt = 0.02;
  const StaticResult s1 = solveStatic3D(slow);
  ASSERT_TRUE(s1.summary.converged);
  EXPECT_LT(r.node_z[0].back(), r.node_z[0].front() - 10.0);  // sank by tens of metres
  // Settling: the slow drift of a long cable to its new steady angle (time scale L / U = 300 s);
  // 1 % after 1500 s.
  constexpr double kSettledRelTol = 0.01;
  EXPECT_NEAR(r.top_tension.back(), s1.topTension(), kSettledRelTol * s1.topTension());
  EXPECT_NEAR(r.node_z[0].back(), s1.nodes.front().z, kSettledRelTol * std::abs(s1.nodes.front().z));
}

TEST(TowingDynamics, AfterATurnAndAnImpulsiveHeadingChangeTheTowSettlesBackOnTheStaticTow) {
  // A circular turn (200 m radius, 90 deg to the left, 105 s) then an impulsive return to the
  // original heading (the paper's Case 2 on a short cable). Against independent answers: the top
  // stays on the ship's track (the circle, then the straight line y = 200 m east at 3 m/s); before
  // the turn and again after the transient, the tow is the steady tow at 3 m/s solved by the 3-D
  // statics (tension, body depth, body straight astern at its static trailing distance).
  // The tension's dip at the heading change is not asserted: an impulsive change of the top's
  // velocity along a nearly inextensible cable (EA = 1e10 N, elastic wave 65 km/s) has no finite
  // answer, and the discrete one is the time step's (measured: 1.0 kN at dt = 1 s, 0.07 kN at
  // 0.5 s, spikes from -0.9 to +49 kN at 0.25 s); before it the turn's tensions agree to 0.01 N at
  // the three steps.
  constexpr double kTrackTol = 1e-6;          // [m] the top is prescribed: the track to rounding
  // At 3 m/s the start's O(h^3 Omega^2) residual (StraightTowIsASteadyState) moves the body more
  // than at 2 m/s: the dynamic rows' own steady tow lies 8 mm deeper than the statics' (measured
  // after the transients, 600 s), reached to 5 mm in the first 20 s.
  constexpr double kStartPositionTol = 0.02;  // [m]
  // Settling 475 s (4.7 L / U) after the heading change, which threw the body 20 m off the new
  // track: the lateral offset decays by e about every 55 s (measured: 0.05 m left at 600 s, the
  // tension within 0.9 N, the depth 8 mm, the trailing distance 5 mm).
  constexpr double kSettledTensionRelTol = 1e-3;
  constexpr double kSettledDepthTol = 0.05;   // [m] of 67 m
  constexpr double kSettledLateralTol = 0.25; // [m]
  constexpr double kSettledTrailTol = 0.05;   // [m] of 291 m
  const double U = 3.0, R = 200.0, t_turn = 20.0, t_change = t_turn + R * (kPi / 2) / U;
  Problem p = towRun(U);
  p.dynamics.duration = 600.0;
  auto& legs = p.dynamics.top_motion.ship_track.legs;
  legs = {ShipLeg::straight(t_turn), ShipLeg::turn(R, kPi / 2), ShipLeg::headingChange(0.0)};
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  Problem steady = towedLine(U, true);  // the same cable and body, straight tow at 3 m/s
  steady.segments[0].spacing = 2.0;
  steady.materials[0].cdt = 0.02;
  const StaticResult s = solveStatic3D(steady);
  ASSERT_TRUE(s.summary.converged) << s.summary.message;
  const double Ts = s.topTension(), trail = s.nodes.back().x - s.nodes.front().x, zs = s.nodes.front().z;
  const double ship_z = r.top_z.front();
  ASSERT_GT(trail, 250.0);  // the premise: the body trails far astern, farther than the turn's radius
  double Tmin_turn = Ts, off_at_change = 0.0;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k];
    // The ship's track: straight along x, the circle about (U t_turn, R), then east along y = R.
    double x, y;
    if (t <= t_turn) {
      x = U * t;
      y = 0.0;
    } else if (t <= t_change) {
      const double a = U * (t - t_turn) / R;
      x = U * t_turn + R * std::sin(a);
      y = R * (1.0 - std::cos(a));
    } else {
      x = U * t_turn + R + U * (t - t_change);
      y = R;
    }
    EXPECT_NEAR(r.top_x[k], x, kTrackTol) << "t = " << t;
    EXPECT_NEAR(r.top_y[k], y, kTrackTol) << "t = " << t;
    if (t <= t_turn) {  // the steady tow before the turn
      EXPECT_NEAR(r.top_tension[k], Ts, kSteadyTensionRelTol * Ts) << "t = " << t;
      EXPECT_NEAR(r.top_x[k] - r.node_x[0][k], trail, kStartPositionTol) << "t = " << t;
      EXPECT_NEAR(r.node_y[0][k], 0.0, kStartPositionTol) << "t = " << t;
      EXPECT_NEAR(r.node_z[0][k] - r.top_z[k], zs - ship_z, kStartPositionTol) << "t = " << t;
    } else if (t < t_change) {
      Tmin_turn = std::min(Tmin_turn, r.top_tension[k]);
      off_at_change = R - r.node_y[0][k];
    }
  }
  const std::size_t e = r.t.size() - 1;
  std::printf("after the turn and the heading change: tension %.2f N (static tow %.2f N), body %.3f m deep "
              "(static %.3f m), %.3f m astern (static %.3f m), %.3f m off the track; lowest tension in the turn "
              "%.1f N\n",
              r.top_tension[e], Ts, -r.node_z[0][e], -zs, r.top_x[e] - r.node_x[0][e], trail, r.node_y[0][e] - R,
              Tmin_turn);
  // The premise of settling back: the body, 291 m astern, cut the 200 m turn's corner and was far
  // off the new track when the heading changed.
  EXPECT_GT(off_at_change, 0.5 * R);
  EXPECT_NEAR(r.top_tension[e], Ts, kSettledTensionRelTol * Ts);
  EXPECT_NEAR(r.node_z[0][e] - r.top_z[e], zs - ship_z, kSettledDepthTol);
  EXPECT_NEAR(r.top_x[e] - r.node_x[0][e], trail, kSettledTrailTol);
  EXPECT_NEAR(r.node_y[0][e], R, kSettledLateralTol);
  for (double T : r.top_tension) EXPECT_TRUE(std::isfinite(T));
}

namespace {
/// rms of T[k+1] - 2 T[k] + T[k-1] for t0 <= t[k] <= t1: the odd-even (Crank-Nicolson) noise.
double oddEvenNoise(const DynamicSeries& r, double t0, double t1) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 1; k + 1 < r.t.size(); ++k)
    if (r.t[k] >= t0 && r.t[k] <= t1) {
      const double d = r.top_tension[k + 1] - 2.0 * r.top_tension[k] + r.top_tension[k - 1];
      sum += d * d;
      ++n;
    }
  return n ? std::sqrt(sum / n) : 0.0;
}
}  // namespace

TEST(TowingDynamics, ImpulsiveHeadingChangeLeavesCrankNicolsonNoiseOnlyWithTheBoxMethod) {
  // The paper's Case 2 (section 7.1, Fig. 5) on a short cable: after the ship snaps back to its
  // original heading, the box method (lambda_inf = -1, no numerical dissipation) keeps an odd-even
  // oscillation in the tension at the ship; lambda_inf = -0.5 damps it.
  // A 30 deg turn and the snap back: a velocity jump of 1.55 m/s at the ship (the paper's Case 2:
  // 15 deg at 9.52 m/s, 2.5 m/s).
  Problem p = towRun(3.0);
  p.segments[0].spacing = 3.0;  // 101 nodes: the noise is a time-integration effect
  p.dynamics.duration = 120.0;
  p.dynamics.top_motion.ship_track.legs = {ShipLeg::straight(20.0), ShipLeg::turn(200.0, kPi / 6),
                                           ShipLeg::headingChange(0.0)};
  const double t_change = 20.0 + 200.0 * kPi / 6 / 3.0;
  p.dynamics.scheme = GeneralizedAlpha::preset("box");
  const DynamicSeries box = runDynamic3D(p);
  p.dynamics.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  const DynamicSeries damped = runDynamic3D(p);
  ASSERT_TRUE(box.completed && damped.completed) << box.message << damped.message;
  const double nb = oddEvenNoise(box, t_change + 30.0, 120.0), nd = oddEvenNoise(damped, t_change + 30.0, 120.0);
  std::printf("odd-even noise of the ship tension 30 s after the heading change: box %.2f N, lambda -0.5 %.2f N\n",
              nb, nd);
  // Measured at 2 m spacing: 250 N against 0.02 N. The paper shows noise for box only; a factor
  // of 5 is a margin of three orders of magnitude that still fails if box damps like the others.
  constexpr double kNoiseRatio = 5.0;
  EXPECT_GT(nb, kNoiseRatio * nd);
}

TEST(TowingDynamics, ModifiedNewtonGivesTheSameTowWithFewerJacobians) {
  // jacobian_reuse keeps factored Jacobians across iterations and steps: the same tensions to
  // the Newton tolerance (measured 1e-7 relative on the paper's A.1), far fewer assemblies.
  Problem p = towRun(3.0);
  p.dynamics.duration = 150.0;
  p.dynamics.top_motion.ship_track.legs = {ShipLeg::straight(20.0), ShipLeg::turn(200.0, kPi / 3)};
  const DynamicSeries full = runDynamic3D(p);
  p.dynamics.jacobian_reuse = true;
  const DynamicSeries kept = runDynamic3D(p);
  ASSERT_TRUE(full.completed && kept.completed) << full.message << kept.message;
  ASSERT_EQ(full.t.size(), kept.t.size());
  constexpr double kSameRelTol = 1e-5;  // a few Newton tolerances (1e-6) of the tension
  for (std::size_t k = 0; k < full.t.size(); ++k)
    EXPECT_NEAR(kept.top_tension[k], full.top_tension[k], kSameRelTol * full.top_tension[0]) << full.t[k];
  EXPECT_EQ(full.jacobians, full.newton_iterations);
  EXPECT_LT(kept.jacobians * 5, full.jacobians);
}
