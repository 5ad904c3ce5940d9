// Subsurface moorings (issue 6; paper: "surface and subsurface single-point mooring problems"): a
// buoyant body at the top held only by the line (top.body, 3-D model). Checks: the vertical line
// under a submerged buoy in still water (exact), the top force against the body's buoyancy and
// drag computed by hand in a current, the heave natural frequency of a buoy on
// an elastic tether (sqrt(k / M), added mass included), and the input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Exact solutions of the box rows: Newton tolerance.
constexpr double kExactRelTol = 1e-6;
// Natural frequency from zero crossings: 80 steps per period (test_dynamics2d's bound).
constexpr double kFrequencyRelTol = 0.02;

Problem subsurface(double B) {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 200.0;
  Material m;
  m.name = "wire";
  m.EA = 1.0e7;
  m.EI = 1.0e-2;
  m.GJ = 1.0e-2;
  m.mass = 1.0;
  m.added_mass = 0.2;
  m.wet_weight = 8.0;
  m.diameter = 0.012;
  m.cdn = 1.2;
  m.cdt = 0.01;
  p.materials.push_back(m);
  Segment s;
  s.length = 100.0;
  s.spacing = 2.0;
  p.segments.push_back(s);
  Body b;
  b.name = "sphere";
  b.mass = 500.0;
  b.added_mass = 250.0;
  b.wet_weight = -B;  // buoyant
  b.diameter = 1.2;
  b.cdn = 0.5;
  b.cdt = 0.5;  // a sphere: the same drag in every direction
  p.bodies.push_back(b);
  p.anchor_z = -200.0;
  p.top.type = TopBoundary::Type::Body;
  p.top.body = 0;
  return p;
}

}  // namespace

TEST(Subsurface, VerticalLineUnderASubmergedBuoyInStillWater) {
  const double B = 5000.0, w = 8.0, L = 100.0, EA = 1.0e7;
  const Problem p = subsurface(B);
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  for (const auto& n : r.nodes) {
    EXPECT_NEAR(n.tension, B - w * (L - n.s), kExactRelTol * B);
    EXPECT_NEAR(n.z - p.anchor_z, n.s + (B - w * L) * n.s / EA + w * n.s * n.s / (2.0 * EA), 1e-6);
    EXPECT_NEAR(n.x, 0.0, 1e-9);
  }
  EXPECT_NEAR(r.top_force_z, B, kExactRelTol * B);
}

TEST(Subsurface, InCurrentTheTopForceIsTheBodysBuoyancyAndDrag) {
  // The line's pull at the top against the body's load computed here by hand from the solved
  // tangent: net buoyancy B up, drag 1/2 rho A (cdt |u_t| u_t t + cdn |u_n| u_n) on the current's
  // components along and across the tangent t (the paper's independent normal and tangential
  // loads). The buoy is knocked down and pulled downstream.
  const double B = 5000.0, U = 0.8, dir = 0.3;
  Problem p = subsurface(B);
  p.bodies[0].cdt = 0.2;
  CurrentPoint c;
  c.speed = U;
  c.direction = dir;
  p.environment.current = {c};
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const NodeState& top = r.nodes.back();
  const double t[3] = {std::sin(top.angle) * std::cos(top.azimuth), std::sin(top.angle) * std::sin(top.azimuth),
                       std::cos(top.angle)};
  const double w[3] = {U * std::cos(dir), U * std::sin(dir), 0.0};
  const double wt = w[0] * t[0] + w[1] * t[1] + w[2] * t[2];
  const double wn[3] = {w[0] - wt * t[0], w[1] - wt * t[1], w[2] - wt * t[2]};
  const double wnm = std::sqrt(wn[0] * wn[0] + wn[1] * wn[1] + wn[2] * wn[2]);
  const Body& b = p.bodies[0];
  const double q = 0.5 * p.environment.water_density * 0.25 * kPi * b.diameter * b.diameter;
  double P[3];
  for (int i = 0; i < 3; ++i) P[i] = q * (b.cdt * std::abs(wt) * wt * t[i] + b.cdn * wnm * wn[i]);
  P[2] += B;
  EXPECT_NEAR(r.top_force_x, P[0], kExactRelTol * B);
  EXPECT_NEAR(r.top_force_y, P[1], kExactRelTol * B);
  EXPECT_NEAR(r.top_force_z, P[2], kExactRelTol * B);
  EXPECT_GT(r.top_force_x * std::cos(dir) + r.top_force_y * std::sin(dir), 0.5 * q * b.cdn * U * U);
  EXPECT_LT(top.z, p.anchor_z + 100.0 - 0.01);  // knocked down
  EXPECT_NEAR(std::atan2(top.y, top.x), dir, 1e-6);  // downstream
}

TEST(Subsurface, HeaveNaturalFrequencyOfABuoyOnAnElasticTether) {
  // A weightless, dragless tether (EA / L = 1e4 N/m) under a buoy of mass + added mass 1000 kg,
  // plucked by a short upward force pulse (force_table): f = sqrt(k / M) / (2 pi), M with a
  // third of the tether's mass.
  Problem p = subsurface(3000.0);
  Material& m = p.materials[0];
  m.EA = 2.0e5;
  m.mass = 0.1;
  m.added_mass = 0.0;
  m.wet_weight = 0.0;
  m.cdn = m.cdt = 0.0;
  p.segments[0].length = 20.0;
  p.segments[0].spacing = 1.0;
  Body& b = p.bodies[0];
  b.mass = 800.0;
  b.added_mass = 200.0;
  b.cdn = b.cdt = 0.0;
  const double L = 20.0, k = m.EA / L, M = b.mass + b.added_mass + m.mass * L / 3.0;
  const double f1 = std::sqrt(k / M) / (2.0 * kPi), P = 1.0 / f1;
  p.dynamics.dt = P / 80.0;
  p.dynamics.duration = 10.0 * P;
  p.dynamics.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  p.dynamics.record_s = {L};
  p.dynamics.top_motion.type = TopMotion::Type::ForceTable;
  p.dynamics.top_motion.table = {{0.0, 0.0, 0.0, 0.0}, {0.1 * P, 0.0, 0.0, 500.0}, {0.2 * P, 0.0, 0.0, 0.0}};
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  const double z0 = r.node_z[0].front();
  std::vector<double> up;
  for (std::size_t i = 1; i < r.t.size(); ++i) {
    const double a = r.node_z[0][i - 1] - z0, c = r.node_z[0][i] - z0;
    if (r.t[i - 1] > 0.5 * P && a < 0.0 && c >= 0.0) up.push_back(r.t[i - 1] + (r.t[i] - r.t[i - 1]) * (-a) / (c - a));
  }
  ASSERT_GE(up.size(), 8u);
  const double f = (up.size() - 1) / (up.back() - up.front());
  std::printf("subsurface heave: measured %.4f Hz, sqrt(k/M)/2pi %.4f Hz\n", f, f1);
  EXPECT_NEAR(f, f1, kFrequencyRelTol * f1);
}

TEST(Subsurface, ProblemFileAndChecks) {
  const std::string text = R"(model: 3d
environment: {depth: 500, current: {speed: 0.5, direction_deg: 0}}
materials:
  wire: {EA: 1.0e7, EI: 0.01, GJ: 0.01, mass: 1.0, added_mass: 0.2, wet_weight: 8.0, diameter: 0.012, cdn: 1.2, cdt: 0.01}
bodies:
  float: {mass: 400, added_mass: 200, wet_weight: -4000, diameter: 1.0, cdn: 0.5, cdt: 0.5}
line:
  - {material: wire, length: 300, spacing: 5}
top:
  body: float
)";
  const Problem p = loadProblemFromString(text);
  EXPECT_EQ(p.top.type, TopBoundary::Type::Body);
  const StaticResult r = solveStatic3D(p);
  EXPECT_TRUE(r.summary.converged) << r.summary.message;
  EXPECT_LT(r.nodes.back().z, -200.0);  // 300 m of line from 500 m: the float stays well under
  std::string two = text;
  two.replace(0, 10, "");
  try {
    loadProblemFromString(two);
    ADD_FAILURE() << "a body top loaded with model: 2d";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("model: 3d"), std::string::npos) << e.what();
  }
  Problem q = p;
  q.dynamics.top_motion.type = TopMotion::Type::Sinusoid;
  EXPECT_NE(q.validate().find("dynamics.top_motion"), std::string::npos) << q.validate();
}

namespace {

// A sphere on a weightless, dragless line in a uniform current: the line is straight and the top
// force is the body's net buoyancy B (up) plus its drag 1/2 rho Cd A U^2 along the current.
Problem sphereOnWeightlessLine(Formulation f, double B, double U, double dir, Body::Drag drag) {
  Problem p = subsurface(B);
  p.formulation = f;
  Material& m = p.materials[0];
  m.wet_weight = 0.0;
  m.cdn = 0.0;
  m.cdt = 0.0;
  m.EA = 1.0e10;  // inextensible to the tolerance: the closed form has no strain
  Body& b = p.bodies[0];
  b.drag = drag;
  b.cd = 0.6;
  b.cdn = 0.6;
  b.cdt = 0.6;
  p.environment.current = {{0.0, U, dir}, {200.0, U, dir}};
  return p;
}

}  // namespace

TEST(Subsurface, SphereDragFollowsTheFlowWhateverTheLineAngle) {
  // The line leans at atan(D / B) from the vertical, about 24 degrees here: a line-aligned body
  // with cdn = cdt = Cd would feel a different force (its two components are squared separately),
  // so the sphere's closed form distinguishes the two laws.
  const double B = 5000.0, U = 1.5, dir = 0.3, rho = 1025.0;
  const double D = 0.5 * rho * 0.6 * 0.25 * kPi * 1.2 * 1.2 * U * U;
  const double T = std::hypot(D, B);
  {
    const Formulation f = Formulation::ThreeD;  // (a body top is a 3-D end; 2-D: test_dynamics2d)
    const double d = dir;
    const Problem p = sphereOnWeightlessLine(f, B, U, d, Body::Drag::Sphere);
    const StaticResult r = solveStatic3D(p);
    ASSERT_TRUE(r.summary.converged) << r.summary.message;
    EXPECT_NEAR(r.top_force_x, D * std::cos(d), kExactRelTol * T);
    EXPECT_NEAR(r.top_force_y, D * std::sin(d), kExactRelTol * T);
    EXPECT_NEAR(r.top_force_z, B, kExactRelTol * T);
    EXPECT_NEAR(r.topTension(), T, kExactRelTol * T);
    // Straight line at the angle atan(D / B) from the vertical.
    const auto& top = r.nodes.back();
    EXPECT_NEAR(std::hypot(top.x, top.y) / (top.z - p.anchor_z), D / B, 1e-5);

    const Problem pa = sphereOnWeightlessLine(f, B, U, d, Body::Drag::LineAligned);
    const StaticResult ra = solveStatic3D(pa);
    ASSERT_TRUE(ra.summary.converged) << ra.summary.message;
    std::printf("sphere drag: horizontal top force %.3f N (closed form %.3f N); line-aligned body %.3f N\n",
                std::hypot(r.top_force_x, r.top_force_y), D, std::hypot(ra.top_force_x, ra.top_force_y));
    EXPECT_GT(std::abs(std::hypot(ra.top_force_x, ra.top_force_y) - D), 100.0 * kExactRelTol * T);
  }
}

TEST(Subsurface, SphereDragKeyReadsAndExcludesTheLineAlignedKeys) {
  const std::string base = "name: s\nmodel: 3d\nenvironment: {depth: 200}\n"
                           "materials: {wire: {EA: 1e7, EI: 0.01, GJ: 0.01, mass: 1, wet_weight: 8, diameter: 0.012, "
                           "cdn: 1.2, cdt: 0.01}}\n"
                           "line: [{material: wire, length: 100, spacing: 2}]\n"
                           "anchor: {x: 0, z: -200}\ntop: {body: buoy}\n";
  const Problem p = loadProblemFromString(base + "bodies: {buoy: {mass: 500, wet_weight: -5000, diameter: 1.2, cd: 0.6}}\n");
  EXPECT_EQ(p.bodies[0].drag, Body::Drag::Sphere);
  EXPECT_EQ(p.bodies[0].cd, 0.6);
  const Problem q =
      loadProblemFromString(base + "bodies: {buoy: {mass: 500, wet_weight: -5000, diameter: 1.2, cdn: 1, cdt: 0.2}}\n");
  EXPECT_EQ(q.bodies[0].drag, Body::Drag::LineAligned);
  try {
    loadProblemFromString(base + "bodies: {buoy: {mass: 500, wet_weight: -5000, diameter: 1.2, cd: 0.6, cdn: 1}}\n");
    ADD_FAILURE() << "cd with cdn accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("bodies.buoy.cdn"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what();
  }
}
