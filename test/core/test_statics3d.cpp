// 3-D static solver against independent answers: the 2-D solver on planar problems (the 3-D rows
// reduce to the 2-D rows, DESIGN.md section 3), invariance of a catenary under a rotation about
// the vertical, Irvine's closed-form catenary, the exact vertical hanging line (a singular
// orientation for angle-based frames), and the assembled Jacobian against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mooring_dynamics/core/equations/catenary.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/quaternion.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"

using namespace mooring_dynamics::core;

namespace {

// Planar 3-D and 2-D solve the same discrete equations (up to the drag-speed floor, < 1e-10 N
// here): they agree to the Newton tolerance, a few 1e-9 relative on tensions.
constexpr double kPlanarRelTol = 1e-7;
constexpr double kPlanarPosTol = 1e-6;  // [m]
// Rotating the whole problem about z changes only round-off and Newton's path.
constexpr double kRotationRelTol = 1e-7;
constexpr double kRotationPosTol = 1e-6;  // [m]
// Irvine's catenary at 0.25 m spacing: the O(h^2) box-scheme error is below 1e-4 relative.
constexpr double kCatenaryRelTol = 1e-3;
// Exact Jacobian (AutoDiff) against central differences of relative step 1e-6.
constexpr double kJacobianTol = 1e-5;
constexpr double kPi = 3.14159265358979323846;

Material wire() {
  Material m;
  m.name = "wire";
  m.EA = 1.0e7;
  m.EI = 1.0e-2;
  m.GJ = 1.0e-2;
  m.mass = 10.0;
  m.added_mass = 2.0;
  m.wet_weight = 100.0;
  m.diameter = 0.03;
  m.cdn = 1.2;
  m.cdt = 0.01;
  return m;
}

/// 150 m of wire from (0, 0, -150) to (80, 0, -60) in 200 m of water: hangs free.
Problem suspended(double spacing) {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 200.0;
  p.environment.seabed.stiffness = 1.0e7;
  p.materials.push_back(wire());
  Segment s;
  s.length = 150.0;
  s.spacing = spacing;
  p.segments.push_back(s);
  p.anchor_z = -150.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = 80.0;
  p.top.z = -60.0;
  return p;
}

/// 200 m of wire on the bottom at 100 m, top at the surface 120 m away, current 0.4 m/s: grounded.
Problem grounded() {
  Problem p = suspended(1.0);
  p.environment.depth = 100.0;
  p.environment.seabed.stiffness = 1.0e5;
  p.segments[0].length = 200.0;
  p.anchor_z = -100.0;
  p.top.x = 120.0;
  p.top.z = 0.0;
  CurrentPoint c0, c1;
  c0.depth = 0.0;
  c0.speed = 0.4;
  c1.depth = 100.0;
  c1.speed = 0.1;
  p.environment.current = {c0, c1};
  return p;
}

Problem load(const std::string& file) {
  Problem p = loadProblemFromFile(file);
  p.formulation = Formulation::ThreeD;
  return p;
}

void expectPlanarAgreement(const Problem& p3) {
  Problem p2 = p3;
  p2.formulation = Formulation::TwoD;
  const StaticResult r2 = solveStatic(p2);
  const StaticResult r3 = solveStatic3D(p3);
  ASSERT_TRUE(r2.summary.converged) << r2.summary.message;
  ASSERT_TRUE(r3.summary.converged) << r3.summary.message;
  ASSERT_EQ(r2.nodes.size(), r3.nodes.size());
  double Tmax = 0.0;
  for (const auto& n : r2.nodes) Tmax = std::max(Tmax, std::abs(n.tension));
  for (std::size_t j = 0; j < r2.nodes.size(); ++j) {
    const NodeState &a = r2.nodes[j], &b = r3.nodes[j];
    EXPECT_NEAR(a.tension, b.tension, kPlanarRelTol * Tmax) << "node " << j;
    EXPECT_NEAR(a.shear, b.shear, kPlanarRelTol * Tmax) << "node " << j;
    EXPECT_NEAR(a.x, b.x, kPlanarPosTol) << "node " << j;
    EXPECT_NEAR(a.z, b.z, kPlanarPosTol) << "node " << j;
    EXPECT_NEAR(b.y, 0.0, kPlanarPosTol) << "node " << j;
    EXPECT_NEAR(b.shear_b, 0.0, kPlanarRelTol * Tmax) << "node " << j;
  }
  EXPECT_NEAR(r2.top_force_x, r3.top_force_x, kPlanarRelTol * Tmax);
  EXPECT_NEAR(r2.top_force_z, r3.top_force_z, kPlanarRelTol * Tmax);
  EXPECT_NEAR(r2.buoy_draft, r3.buoy_draft, kPlanarPosTol);
}

}  // namespace

TEST(Quaternion, PlanarFrameIsTheTwoDimensionalFrame) {
  for (double psi : {0.0, 0.7, -2.0}) {
    for (double phi : {0.0, 0.3, 1.5707963, 2.5}) {
      double q[4], R[9];
      quat::planarFrame(psi, phi, q);
      quat::matrix(q, R);
      // e1 = (sin phi cos psi, sin phi sin psi, cos phi), e2 the in-plane normal, e3 horizontal.
      EXPECT_NEAR(R[0], std::sin(phi) * std::cos(psi), 1e-14);
      EXPECT_NEAR(R[3], std::sin(phi) * std::sin(psi), 1e-14);
      EXPECT_NEAR(R[6], std::cos(phi), 1e-14);
      EXPECT_NEAR(R[1], std::cos(phi) * std::cos(psi), 1e-14);
      EXPECT_NEAR(R[7], -std::sin(phi), 1e-14);
      EXPECT_NEAR(R[8], 0.0, 1e-14);
      EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-14);
    }
  }
}

TEST(Quaternion, ExpHalfIsTheRotationAndSmoothAtZero) {
  // A turn about local e3 by dphi moves the planar frame from phi to phi + dphi.
  double qa[4], qb[4], e[4], qe[4];
  quat::planarFrame(0.4, 0.9, qa);
  quat::planarFrame(0.4, 0.9 + 0.05, qb);
  const double th[3] = {0.0, 0.0, 0.05};
  quat::expHalf(th, e);
  quat::multiply(qa, e, qe);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(qe[i], qb[i], 1e-15);
  // Series and closed form meet continuously at the switch, and the derivative exists at zero.
  using AD = Eigen::AutoDiffScalar<Eigen::Vector3d>;
  AD t0[3] = {AD(0.0, 3, 0), AD(0.0, 3, 1), AD(0.0, 3, 2)}, e0[4];
  quat::expHalf(t0, e0);
  EXPECT_NEAR(e0[1].derivatives()[0], 0.5, 1e-15);
  EXPECT_TRUE(std::isfinite(e0[0].derivatives()[0]));
  const double below[3] = {0.999999e-3, 0.0, 0.0}, above[3] = {1.000001e-3, 0.0, 0.0};
  double eb[4], ea[4];
  quat::expHalf(below, eb);
  quat::expHalf(above, ea);
  // Both sides of the switch (|theta|^2 = 1e-6) against the closed form.
  EXPECT_NEAR(eb[1], std::sin(0.5 * below[0]), 1e-16);
  EXPECT_NEAR(ea[1], std::sin(0.5 * above[0]), 1e-16);
  EXPECT_NEAR(eb[0], std::cos(0.5 * below[0]), 1e-16);
  EXPECT_NEAR(ea[0], std::cos(0.5 * above[0]), 1e-16);
}

TEST(Statics3D, PlanarSuspendedCatenaryMatches2D) { expectPlanarAgreement(suspended(1.0)); }

TEST(Statics3D, PlanarGroundedLineInCurrentMatches2D) { expectPlanarAgreement(grounded()); }

TEST(Statics3D, PlanarChainMooringWithBuoyMatches2D) {
  // Paper A.3: chain and AxPacks, seabed contact, uniform current, surface buoy.
  expectPlanarAgreement(load("config/chain_mooring.yaml"));
}

TEST(Statics3D, PlanarSTetherWithFloatsMatches2D) {
  // Paper A.2: current profile, inline floats (pin junctions), segment junctions, buoy, wind.
  expectPlanarAgreement(load("config/s_tether.yaml"));
}

TEST(Statics3D, SuspendedCatenaryMatchesIrvine) {
  const StaticResult r = solveStatic3D(suspended(0.25));
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const CatenarySolution c = solveCatenary({150.0, 100.0, 1.0e7, 80.0, 90.0, false});
  ASSERT_TRUE(c.converged);
  EXPECT_NEAR(r.topTension(), c.topTension(), kCatenaryRelTol * c.topTension());
  EXPECT_NEAR(r.nodes.front().tension, c.anchorTension(), kCatenaryRelTol * c.topTension());
}

TEST(Statics3D, RotatedAboutVerticalGivesSameTensionsAndRotatedShape) {
  const Problem base = grounded();
  const StaticResult r0 = solveStatic3D(base);
  ASSERT_TRUE(r0.summary.converged) << r0.summary.message;
  for (double psi : {0.6, 2.2, -1.3}) {
    Problem p = base;
    const double c = std::cos(psi), s = std::sin(psi);
    p.anchor_x = 10.0;
    p.anchor_y = -5.0;
    p.top.x = p.anchor_x + c * base.top.x;
    p.top.y = p.anchor_y + s * base.top.x;
    for (auto& cp : p.environment.current) cp.direction += psi;
    const StaticResult r = solveStatic3D(p);
    ASSERT_TRUE(r.summary.converged) << r.summary.message;
    ASSERT_EQ(r.nodes.size(), r0.nodes.size());
    const double T = r0.topTension();
    for (std::size_t j = 0; j < r.nodes.size(); ++j) {
      const NodeState &a = r0.nodes[j], &b = r.nodes[j];
      EXPECT_NEAR(b.tension, a.tension, kRotationRelTol * T) << "psi " << psi << " node " << j;
      EXPECT_NEAR(b.x, p.anchor_x + c * a.x - s * a.y, kRotationPosTol);
      EXPECT_NEAR(b.y, p.anchor_y + s * a.x + c * a.y, kRotationPosTol);
      EXPECT_NEAR(b.z, a.z, kRotationPosTol);
    }
  }
}

TEST(Statics3D, CrossCurrentPushesTheLineSideways) {
  // Current across the anchor-top plane (toward +y): the line bows toward +y, symmetric loads
  // give y = 0 only at the ends, and the top force gains a -y component (it holds the line
  // against the current).
  Problem p = suspended(1.0);
  CurrentPoint c;
  c.speed = 0.5;
  c.direction = 0.5 * kPi;
  p.environment.current = {c};
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  double ymax = 0.0;
  for (const auto& n : r.nodes) ymax = std::max(ymax, n.y);
  EXPECT_GT(ymax, 1.0);
  EXPECT_NEAR(r.nodes.front().y, 0.0, 1e-9);
  EXPECT_NEAR(r.nodes.back().y, 0.0, 1e-9);
  EXPECT_LT(r.top_force_y, 0.0);
  EXPECT_GT(r.anchor_force_y, 0.0);  // the line pulls the anchor downstream
}

TEST(Statics3D, VerticalLineUnderVerticalTopForceIsExact) {
  // 100 m of wire hanging vertically under a top force F > wL: T(s) = F - w (L - s), and the
  // stretched height z(s) - z_a = s + (F - w L) s / EA + w s^2 / (2 EA) exactly (constant strain
  // gradient; the box scheme integrates a quadratic exactly). A vertical tangent is a singular
  // point of angle-based 3-D frames; the Euler parameters have none.
  Problem p = suspended(1.0);
  p.segments[0].length = 100.0;
  p.anchor_z = -150.0;
  p.top.type = TopBoundary::Type::Force;
  p.top.fx = p.top.fy = 0.0;
  const double F = 2.0e4, w = 100.0, EA = 1.0e7, L = 100.0;
  p.top.fz = F;
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  for (const auto& n : r.nodes) {
    const double s = n.s;
    EXPECT_NEAR(n.tension, F - w * (L - s), 1e-6 * F);
    EXPECT_NEAR(n.z - p.anchor_z, s + (F - w * L) * s / EA + w * s * s / (2.0 * EA), 1e-6);
    EXPECT_NEAR(n.x, 0.0, 1e-9);
    EXPECT_NEAR(n.y, 0.0, 1e-9);
    EXPECT_NEAR(n.angle, 0.0, 1e-6);
  }
}

TEST(Statics3D, JacobianMatchesFiniteDifferences) {
  // Out of plane current with a depth gradient, seabed contact, bodies and a buoy: every term.
  Problem p = load("config/s_tether.yaml");
  for (auto& c : p.environment.current) c.direction = 0.4;
  p.environment.wind_direction = -0.3;
  const Mesh mesh = buildMesh(p);
  StaticState3D s = solveStatic3DOnMesh(p, mesh, p.static_options);
  ASSERT_TRUE(s.result.summary.converged) << s.result.summary.message;
  const double qref[4] = {s.Y[eq3d::Q0], s.Y[eq3d::Q1], s.Y[eq3d::Q2], s.Y[eq3d::Q3]};
  StaticSystem3D sys(p, mesh, qref);
  // Away from the solution too (velocities, twist and shear nonzero) so no term hides at zero.
  Eigen::VectorXd Y = s.Y;
  for (Eigen::Index i = 0; i < Y.size(); ++i) Y[i] += 1e-3 * std::sin(0.37 * static_cast<double>(i));
  // Nodes near the seabed go 1 cm into it, past the smoothed onset (w/k < 0.1 mm): a finite
  // difference across the onset's kink in curvature would not measure the derivative.
  constexpr double kContactDepth = 0.01;  // [m]
  for (Eigen::Index i = 0; i < Y.size(); i += eq3d::N) {
    const double zb = p.environment.seabedElevation(Y[i + eq3d::X], Y[i + eq3d::Y]);
    if (std::abs(Y[i + eq3d::Z] - zb) < kContactDepth) Y[i + eq3d::Z] = zb - kContactDepth;
  }
  const JacobianCheck c = checkJacobian(sys, Y);
  EXPECT_FALSE(c.outside_band);
  EXPECT_LT(c.worst, kJacobianTol) << "row " << c.row << " (" << sys.describe(c.row) << ") column " << c.column
                                   << " (" << sys.describe(c.column) << "): exact " << c.exact << " fd "
                                   << c.finite_difference;
}

TEST(Statics3D, RejectsTheTwoDimensionalSeabedCap) {
  Problem p = grounded();
  p.environment.seabed.static_cap = true;
  EXPECT_THROW(solveStatic3D(p), std::invalid_argument);
}

TEST(Problem3D, TwoDimensionalModelRejectsOutOfPlaneGeometry) {
  Problem p = suspended(1.0);
  p.formulation = Formulation::TwoD;
  p.top.y = 3.0;
  const std::string e = p.validate();
  EXPECT_NE(e.find("top.position.y"), std::string::npos) << e;
  EXPECT_NE(e.find("model: 3d"), std::string::npos) << e;
  p.formulation = Formulation::ThreeD;
  EXPECT_EQ(p.validate(), "");
}

TEST(Statics3D, ShippedCrossCurrentMooringLiesInTheCurrentsPlane) {
  // config/chain_mooring_3d.yaml: the A.3 buoy mooring in a uniform current toward 60 deg. The
  // only horizontal loads (current drag on line, bodies and buoy) point along the current, so the
  // equilibrium is the planar A.3 solution turned into the current's vertical plane.
  const Problem p = loadProblemFromFile("config/chain_mooring_3d.yaml");
  ASSERT_EQ(p.formulation, Formulation::ThreeD);
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  Problem planar = p;
  planar.formulation = Formulation::TwoD;
  for (auto& c : planar.environment.current) c.direction = 0.0;
  const StaticResult r2 = solveStatic(planar);
  ASSERT_TRUE(r2.summary.converged);
  const double a = 60.0 * kPi / 180.0;
  for (std::size_t j = 0; j < r.nodes.size(); ++j) {
    EXPECT_NEAR(r.nodes[j].x, std::cos(a) * r2.nodes[j].x, kRotationPosTol);
    EXPECT_NEAR(r.nodes[j].y, std::sin(a) * r2.nodes[j].x, kRotationPosTol);
    EXPECT_NEAR(r.nodes[j].tension, r2.nodes[j].tension, kRotationRelTol * r2.topTension());
  }
}

namespace {

/// 200 m of wire from an anchor on the bottom at 100 m to the surface 120 m away along azimuth
/// psi [rad] from +x, no current: about 90 m lie on the bottom (test_statics2d's grounded line,
/// turned out of the x-z plane so that every 3-D row takes part).
Problem groundedWire(double psi, double spacing) {
  Problem p = suspended(spacing);
  p.environment.depth = 100.0;
  p.environment.seabed.stiffness = 1.0e7;
  p.segments[0].length = 200.0;
  p.anchor_x = 5.0;
  p.anchor_y = -3.0;
  p.anchor_z = -100.0;
  p.top.x = p.anchor_x + 120.0 * std::cos(psi);
  p.top.y = p.anchor_y + 120.0 * std::sin(psi);
  p.top.z = 0.0;
  return p;
}

}  // namespace

TEST(Statics3D, SeabedFrictionDropsTheTensionByMuWTimesTheGroundedLength) {
  // As in 2-D (test_statics2d): static friction opposes the top's pull along the grounded
  // stretch, so the tension falls from the touchdown to the anchor by mu_axial w L_g. With no
  // current the top's horizontal force H is the touchdown tension and its vertical force V
  // carries the suspended length V / w: T_anchor = H - mu w (L - V / w) (closed form).
  const double mu = 0.05, L = 200.0, w = 100.0, psi = 0.7;
  Problem p = groundedWire(psi, 0.5);
  p.materials[0].mu_axial = mu;
  const StaticResult r = solveStatic3D(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const double H = std::hypot(r.top_force_x, r.top_force_y), V = r.top_force_z;
  const double Lg = L - V / w;
  ASSERT_GT(Lg, 50.0);
  const double expected = H - mu * w * Lg;
  ASSERT_GT(expected, 0.2 * H);  // the pull reaches the anchor: the closed form applies
  std::printf("3-D friction: anchor tension %.2f N, closed form %.2f N (H %.1f N, L_g %.2f m)\n",
              r.nodes.front().tension, expected, H, Lg);
  EXPECT_NEAR(r.nodes.front().tension, expected, kCatenaryRelTol * r.topTension());
  // The friction acts along the line: the anchor is pulled toward the top, in the line's plane.
  EXPECT_NEAR(std::atan2(r.anchor_force_y, r.anchor_force_x), psi, 1e-6);
  // Frictionless, the anchor carries H: the friction moved it by far more than the tolerance.
  const StaticResult r0 = solveStatic3D(groundedWire(psi, 0.5));
  ASSERT_TRUE(r0.summary.converged) << r0.summary.message;
  EXPECT_GT(r0.nodes.front().tension - r.nodes.front().tension, 10.0 * kCatenaryRelTol * r.topTension());
}

TEST(Statics3D, PlanarGroundedLineWithFrictionMatches2D) {
  // The 3-D static friction is the 2-D law on the same rows: in the x-z plane the two solvers
  // agree to the Newton tolerance, node by node.
  Problem p = groundedWire(0.0, 1.0);
  p.anchor_x = p.anchor_y = 0.0;
  p.top.x = 120.0;
  p.top.y = 0.0;
  p.materials[0].mu_axial = 0.05;
  expectPlanarAgreement(p);
}
