// Static solver against independent answers: Irvine's closed-form elastic catenary (with and
// without seabed contact), the measured spatial order of the box scheme, force balances at bodies
// and buoys, drag on a taut vertical line; plus robustness and error reporting.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mooring_dynamics/core/equations/catenary.hpp"
#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"

using namespace mooring_dynamics::core;

namespace {

// The acceptance bound for the fine-mesh top tension against the closed form.
constexpr double kCatenaryRelTol = 1e-3;
// The box scheme is second order (paper section 3); a measured slope within this band of 2.
constexpr double kOrderBand = 0.15;
// Boundary-condition consistency is limited only by the Newton tolerance (1e-9 scaled).
constexpr double kConsistencyTol = 1e-6;
// Global force balances hold to the O(h^2) discretization error; 1e-3 at h = 1 m.
constexpr double kDiscretizationRelTol = 1e-3;

constexpr double kW = 100.0;     // wet weight [N/m]
constexpr double kEA = 1.0e7;    // [N]

Problem catenaryProblem(double spacing, double L) {
  Problem p;
  p.environment.depth = 100.0;
  p.environment.seabed.stiffness = 1.0e7;  // stiff foundation: penetration w/k = 1e-5 m
  Material m;
  m.name = "wire";
  m.EA = kEA;
  m.EI = 1.0e-2;  // small: the closed form has none
  m.mass = 10.0;
  m.wet_weight = kW;
  m.diameter = 0.03;
  m.cdn = 1.2;
  m.cdt = 0.01;
  p.materials.push_back(m);
  Segment s;
  s.material = 0;
  s.length = L;
  s.spacing = spacing;
  p.segments.push_back(s);
  p.anchor_x = 0.0;
  p.anchor_z = -100.0;
  p.top.type = TopBoundary::Type::Position;
  return p;
}

/// Anchor raised 50 m off the bottom: the line hangs free between (0, -150) and (80, -60).
Problem suspended(double spacing) {
  Problem p = catenaryProblem(spacing, 150.0);
  p.environment.depth = 200.0;
  p.anchor_z = -150.0;
  p.top.x = 80.0;
  p.top.z = -60.0;
  return p;
}

/// Anchor on the bottom at 100 m, top at the surface 120 m away: about 90 m of line grounded.
Problem grounded(double spacing) {
  Problem p = catenaryProblem(spacing, 200.0);
  p.top.x = 120.0;
  p.top.z = 0.0;
  return p;
}

}  // namespace

TEST(Statics2D, SuspendedCatenaryMatchesIrvine) {
  const StaticResult r = solveStatic(suspended(0.25));
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const CatenarySolution c = solveCatenary({150.0, kW, kEA, 80.0, 90.0, false});
  ASSERT_TRUE(c.converged);
  EXPECT_NEAR(r.topTension(), c.topTension(), kCatenaryRelTol * c.topTension());
  EXPECT_NEAR(r.nodes.front().tension, c.anchorTension(), kCatenaryRelTol * c.topTension());
  EXPECT_NEAR(r.top_force_x, c.H, kCatenaryRelTol * c.topTension());
  EXPECT_NEAR(r.top_force_z, c.V, kCatenaryRelTol * c.topTension());
}

TEST(Statics2D, GroundedCatenaryMatchesIrvine) {
  const StaticResult r = solveStatic(grounded(0.25));
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const CatenarySolution c = solveCatenary({200.0, kW, kEA, 120.0, 100.0, true});
  ASSERT_TRUE(c.converged);
  ASSERT_GT(c.grounded, 50.0);  // the case really has line on the seabed
  EXPECT_NEAR(r.topTension(), c.topTension(), kCatenaryRelTol * c.topTension());
  EXPECT_NEAR(r.top_force_x, c.H, kCatenaryRelTol * c.topTension());
  // Frictionless seabed: the grounded stretch and the anchor carry the horizontal tension only.
  EXPECT_NEAR(r.nodes.front().tension, c.H, kCatenaryRelTol * c.topTension());
  // Touchdown: the last node resting on the bottom sits near the closed-form grounded length.
  double touchdown = 0.0;
  for (const auto& n : r.nodes)
    if (n.z < -100.0 + 1e-3) touchdown = n.s;
  EXPECT_NEAR(touchdown, c.grounded, 2.0);  // within a few nodes of 0.25 m plus the smooth lift-off
}

TEST(Statics2D, SpatialConvergenceOrderIsTwo) {
  const CatenarySolution c = solveCatenary({150.0, kW, kEA, 80.0, 90.0, false});
  std::vector<double> logh, logerr;
  for (double h : {5.0, 2.5, 1.25, 0.625, 0.3125}) {
    const StaticResult r = solveStatic(suspended(h));
    ASSERT_TRUE(r.summary.converged) << r.summary.message;
    logh.push_back(std::log(h));
    logerr.push_back(std::log(std::abs(r.topTension() - c.topTension())));
  }
  // Least-squares slope of log(error) against log(h).
  const double n = static_cast<double>(logh.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < logh.size(); ++i) {
    sx += logh[i];
    sy += logerr[i];
    sxx += logh[i] * logh[i];
    sxy += logh[i] * logerr[i];
  }
  const double order = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  RecordProperty("measured_order", std::to_string(order));
  EXPECT_NEAR(order, 2.0, kOrderBand);
}

TEST(Statics2D, ForceBoundaryReproducesPositionSolution) {
  const StaticResult byPosition = solveStatic(grounded(1.0));
  ASSERT_TRUE(byPosition.summary.converged);
  Problem p = grounded(1.0);
  p.top.type = TopBoundary::Type::Force;
  p.top.fx = byPosition.top_force_x;
  p.top.fz = byPosition.top_force_z;
  const StaticResult byForce = solveStatic(p);
  ASSERT_TRUE(byForce.summary.converged) << byForce.summary.message;
  EXPECT_NEAR(byForce.nodes.back().x, 120.0, kConsistencyTol * 200.0);
  EXPECT_NEAR(byForce.nodes.back().z, 0.0, kConsistencyTol * 200.0);
}

TEST(Statics2D, InlineFloatCarriesItsBuoyancy) {
  Problem p = suspended(1.0);
  Body f;
  f.name = "float";
  f.wet_weight = -2000.0;  // buoyant
  f.diameter = 0.6;
  p.bodies.push_back(f);
  p.segments[0].bodies.push_back({0, 60.0});
  const StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  // Global balance (no current): top Fz - anchor Fz = line weight + body wet weight, and equal
  // horizontal forces. The box rows balance forces in the local frame at the half-grid point,
  // so the global balance holds to the scheme's O(h^2) error (about 1e-4 here at h = 1 m).
  EXPECT_NEAR(r.top_force_z - r.anchor_force_z, kW * 150.0 - 2000.0, kDiscretizationRelTol * kW * 150.0);
  EXPECT_NEAR(r.top_force_x, r.anchor_force_x, kDiscretizationRelTol * kW * 150.0);
  // Across the float (two nodes at s = 60 m) the internal force jumps by the body's wet weight.
  for (std::size_t j = 0; j + 1 < r.nodes.size(); ++j) {
    if (r.nodes[j].s == 60.0 && r.nodes[j + 1].s == 60.0) {
      auto Fz = [](const NodeState& n) { return n.tension * std::cos(n.angle) - n.shear * std::sin(n.angle); };
      EXPECT_NEAR(Fz(r.nodes[j + 1]) - Fz(r.nodes[j]), -2000.0, 1e-6 * 2000.0);
    }
  }
}

TEST(Statics2D, TautVerticalLineInUniformCurrentCarriesNormalDrag) {
  // A short, heavily pretensioned vertical line: it stays nearly straight, so the horizontal
  // load is the normal drag 1/2 rho d Cdn U^2 per unit length (eq. 2) times the length.
  Problem p = catenaryProblem(1.0, 49.9);
  p.environment.current = {{0.0, 1.0, 0.0}, {100.0, 1.0, 0.0}};
  p.top.x = 0.0;
  p.top.z = -50.0;  // 50 m above the anchor, line 49.9 m: strain ~0.2%, tension ~2e4 N
  const StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const Material& m = p.materials[0];
  const double drag = 0.5 * p.environment.water_density * m.diameter * m.cdn * 1.0 * 49.9;
  const double tilt = std::abs(r.nodes[r.nodes.size() / 2].angle);
  ASSERT_LT(tilt, 0.05);  // the premise: nearly vertical
  // The anchor and the top hold the line against the current, so the line pulls the anchor
  // downstream by more than the platform does. 1%: the small tilt (cos^2) and sqrt(1 + eps).
  EXPECT_NEAR(r.anchor_force_x - r.top_force_x, drag, 0.01 * drag);
}

TEST(Statics2D, SurfaceBuoyFloatsAtItsEquilibriumDraft) {
  Problem p = grounded(1.0);
  p.top.type = TopBoundary::Type::Buoy;
  p.top.buoy.shape = SurfaceBuoy::Shape::Cylinder;
  p.top.buoy.diameter = 2.5;
  p.top.buoy.height = 1.5;
  p.top.buoy.mass = 800.0;
  p.top.buoy.cd = 1.0;
  p.top.buoy.wind_area = 2.0;
  p.environment.current = {{0.0, 0.5, 0.0}, {100.0, 0.2, 0.0}};
  p.environment.wind_speed = 15.0;
  const StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const Environment& e = p.environment;
  const double d = r.buoy_draft;
  ASSERT_GT(d, 0.0);
  ASSERT_LT(d, 1.5);
  // Archimedes for a vertical cylinder: rho g pi R^2 d - m g = vertical pull of the line.
  const double lift = e.water_density * e.gravity * M_PI * 1.25 * 1.25 * d - 800.0 * e.gravity;
  EXPECT_NEAR(r.top_force_z, lift, 1e-6 * lift);
  // Horizontal: current drag on the submerged side (D d) plus wind on the given area.
  const double fx = 0.5 * e.water_density * 1.0 * 2.5 * d * 0.25 + 0.5 * e.air_density * 1.0 * 2.0 * 225.0;
  EXPECT_NEAR(r.top_force_x, fx, 1e-6 * fx);
}

TEST(Statics2D, UnreachableTopPositionIsAnError) {
  Problem p = grounded(1.0);
  p.top.x = 1000.0;
  try {
    solveStatic(p);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("top.position"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reach"), std::string::npos) << e.what();
  }
}

TEST(Statics2D, NonConvergenceIsAResultNotAnException) {
  StaticOptions o;
  o.max_iterations = 1;
  const StaticResult r = solveStatic(grounded(1.0), o);
  EXPECT_FALSE(r.summary.converged);
  EXPECT_EQ(r.summary.iterations, 1);
  EXPECT_NE(r.summary.message.find("did not converge"), std::string::npos) << r.summary.message;
  EXPECT_EQ(r.nodes.size(), 201u);  // the last iterate is still returned: 200 intervals
}

TEST(Statics2D, AdaptiveRelaxationRescuesAPoorStartWhereFixedRelaxationFails) {
  // A stiff (EI = 100 N m^2) line with 70 m on the seabed, started from a straight line between
  // anchor and top: plain Newton (mu fixed at 1) wanders and never settles; the adaptive rule of
  // eqs. 40-41 cuts mu while the update grows and converges.
  auto problem = [](bool adaptive) {
    Problem p = catenaryProblem(1.0, 200.0);
    p.materials[0].EI = 100.0;
    p.materials[0].EA = 1.0e8;
    p.materials[0].diameter = 0.05;
    p.environment.seabed.stiffness = 1.0e6;
    p.top.x = 130.0;
    p.top.z = 0.0;
    p.static_options.initial_guess = StaticOptions::InitialGuess::StraightLine;
    p.static_options.adaptive_relaxation = adaptive;
    p.static_options.max_iterations = 500;
    p.materials[0].compression = true;  // the paper's law (eq. 9): without compression plain Newton settles here
    return p;
  };
  const StaticResult fixed = solveStatic(problem(false));
  EXPECT_FALSE(fixed.summary.converged) << fixed.summary.message;
  const StaticResult adaptive = solveStatic(problem(true));
  ASSERT_TRUE(adaptive.summary.converged) << adaptive.summary.message;
  EXPECT_LT(adaptive.summary.iterations, 100);
  // And it found the same equilibrium as the default catenary start.
  Problem reference = problem(true);
  reference.static_options.initial_guess = StaticOptions::InitialGuess::Catenary;
  const StaticResult r = solveStatic(reference);
  ASSERT_TRUE(r.summary.converged);
  EXPECT_NEAR(adaptive.topTension(), r.topTension(), kConsistencyTol * r.topTension());
}

TEST(Statics2D, SeabedCapOfEquation35) {
  // Mean seabed reaction of each interval as the equations apply it (capped or not).
  auto maxMeanReaction = [&](const Problem& p, const StaticResult& r) {
    double worst = 0.0;
    for (std::size_t j = 0; j + 1 < r.nodes.size(); ++j) {
      double ya[6] = {0, 0, 0, 0, r.nodes[j].x, r.nodes[j].z};
      double yb[6] = {0, 0, 0, 0, r.nodes[j + 1].x, r.nodes[j + 1].z};
      double Fa, Fb;
      eq2d::seabedForces(p.environment, p.materials[0], ya, yb, p.environment.seabed.static_cap, Fa, Fb);
      worst = std::max(worst, 0.5 * (Fa + Fb));
    }
    return worst;
  };
  // On a flat bottom the grounded line rests at F_bot = w_o: the cap changes nothing.
  Problem flat = grounded(0.5);
  const StaticResult plain = solveStatic(flat);
  flat.environment.seabed.static_cap = true;
  const StaticResult capped = solveStatic(flat);
  ASSERT_TRUE(plain.summary.converged && capped.summary.converged) << capped.summary.message;
  EXPECT_LE(maxMeanReaction(flat, capped), kW * (1.0 + 1e-6));
  // Same catenary: the cap moves grounded nodes a fraction of a millimetre (3e-6 of the tension).
  EXPECT_NEAR(capped.topTension(), plain.topTension(), 1e-5 * plain.topTension());
  // A line drawn taut over a 3 m ridge: the crest pushes up with the weight plus tension times
  // curvature, which the uncapped (default) foundation carries.
  Problem ridge = grounded(0.5);
  ridge.environment.seabed.profile = {{0.0, 100.0}, {30.0, 100.0}, {40.0, 97.0}, {50.0, 100.0}, {300.0, 100.0}};
  ridge.environment.seabed.stiffness = 1.0e5;
  ridge.top.x = 150.0;
  const StaticResult over = solveStatic(ridge);
  ASSERT_TRUE(over.summary.converged) << over.summary.message;
  EXPECT_GT(maxMeanReaction(ridge, over), 2.0 * kW);
}

TEST(Statics2D, SeabedFrictionDropsTheTensionByMuWTimesTheGroundedLength) {
  // Static friction opposes the top's pull along the grounded stretch: the tension falls from the
  // touchdown to the anchor by mu_axial w L_g (closed form). The suspended length follows from
  // the top's vertical force, V = w L_s (no vertical load at the touchdown), the horizontal
  // tension at the touchdown is the top's horizontal force H, so T_anchor = H - mu w (L - V / w).
  // mu = 0.05: the pull reaches the anchor (a larger mu uses it up before: the next test).
  const double mu = 0.05, L = 200.0;
  Problem p = grounded(0.25);
  p.materials[0].mu_axial = mu;
  const StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const double H = r.top_force_x, V = r.top_force_z;
  const double Lg = L - V / kW;
  ASSERT_GT(Lg, 50.0);
  const double expected = H - mu * kW * Lg;
  ASSERT_GT(expected, 0.2 * H);  // the pull reaches the anchor: the closed form applies
  std::printf("friction: anchor tension %.2f N, closed form %.2f N (H %.1f N, L_g %.2f m)\n",
              r.nodes.front().tension, expected, H, Lg);
  EXPECT_NEAR(r.nodes.front().tension, expected, kCatenaryRelTol * r.topTension());
  // The frictionless line carries H to the anchor: the friction moved it by far more than the tolerance.
  const StaticResult r0 = solveStatic(grounded(0.25));
  EXPECT_GT(r0.nodes.front().tension - r.nodes.front().tension, 10.0 * kCatenaryRelTol * r.topTension());
}

TEST(Statics2D, SeabedFrictionThatUsesUpThePullLeavesTheRestOfTheLineSlack) {
  // mu = 0.3 on the same line: the pull H at the touchdown is used up H / (mu w) = 29.7 m toward
  // the anchor. Closed form: T = H - mu w d at the distance d from the touchdown for
  // d < H / (mu w); beyond, the rest of the grounded line lies slack. The friction is mobilized
  // over T_f = mu w * 1 m (equations2d.hpp, staticFriction), so there the tension stays in
  // [0, T_f) and the anchor carries almost nothing. Both laws: a line without compression is
  // solved from the solution with it (docs/method.md, "Seabed friction"); they agree to within
  // the slack ramp's lift (EA kSlackStrain / 8 = 1.25 N).
  const double mu = 0.3, L = 200.0;
  const double Tf = mu * kW * 1.0;
  for (bool compression : {true, false}) {
    Problem p = grounded(0.25);
    p.materials[0].mu_axial = mu;
    p.materials[0].compression = compression;
    const StaticResult r = solveStatic(p);
    ASSERT_TRUE(r.summary.converged) << "compression " << compression << ": " << r.summary.message;
    const double H = r.top_force_x, V = r.top_force_z;
    const double s_td = L - V / kW, d_used = H / (mu * kW);
    ASSERT_GT(s_td - d_used, 50.0);  // the slack stretch is long
    double worst = 0.0;
    for (const NodeState& n : r.nodes) {
      const double d = s_td - n.s;
      if (d > 2.0 && d < d_used - 2.0) worst = std::max(worst, std::abs(n.tension - (H - mu * kW * d)));
      if (d > d_used + 2.0) {
        EXPECT_GE(n.tension, compression ? -1e-9 * H : 0.0) << "s = " << n.s;
        EXPECT_LT(n.tension, Tf) << "s = " << n.s;
      }
    }
    std::printf("friction mu = %.1f, compression %d: linear drop off by %.2f N at most; anchor %.2f N (H %.1f N)\n", mu,
                compression, worst, r.nodes.front().tension, H);
    EXPECT_LT(worst, kCatenaryRelTol * r.topTension());
    EXPECT_LT(r.nodes.front().tension, 0.01 * H);
  }
}
