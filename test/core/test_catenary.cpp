// Closed-form catenary: round trip through catenaryEnd, the rigid (inextensible) textbook
// relations, the grounded line, and the elastic end position against a direct quadrature of the
// elastic-catenary ODE.
#include <gtest/gtest.h>

#include <cmath>

#include "mooring_dynamics/core/equations/catenary.hpp"

using namespace mooring_dynamics::core;

namespace {

// solveCatenary declares convergence at an end-position residual <= 1e-9 L; with O(1) condition
// numbers the forces are then good to ~1e-8 relative.
constexpr double kForceRel = 1e-7;
// End positions of a given (H, V): closed form vs Simpson quadrature with 4000 panels of a
// smooth integrand (error ~ h^4 ~ 1e-8 of a metre is far below this).
constexpr double kQuadTol = 1e-7;  // [m]
// EA large enough that the elastic terms (~ w L^2 / EA ~ 1e-9 m) vanish against kForceRel.
constexpr double kRigidEA = 1e15;

CatenaryInput input(double L, double w, double EA, double X, double Z, bool seabed) {
  CatenaryInput in;
  in.L = L;
  in.w = w;
  in.EA = EA;
  in.X = X;
  in.Z = Z;
  in.seabed = seabed;
  return in;
}

/// Integrates the elastic catenary from the anchor: H constant, V(s) = Va + w s over the
/// suspended part (s unstretched), dx/ds = (1 + T/EA) H/T, dz/ds = (1 + T/EA) V/T, T = |(H, V)|.
/// With a seabed and V < w L, the first L - V/w lie flat with tension H.
void integrateEnd(const CatenaryInput& in, double H, double V, double& X, double& Z) {
  double grounded = 0.0, Va = V - in.w * in.L;
  if (in.seabed && Va < 0.0) {
    grounded = in.L - V / in.w;
    Va = 0.0;
  }
  const double Ls = in.L - grounded;
  const int n = 4000;  // even, Simpson
  const double h = Ls / n;
  double sx = 0.0, sz = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double v = Va + in.w * (i * h);
    const double T = std::hypot(H, v);
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sx += c * (1.0 + T / in.EA) * H / T;
    sz += c * (1.0 + T / in.EA) * v / T;
  }
  X = grounded * (1.0 + H / in.EA) + sx * h / 3.0;
  Z = sz * h / 3.0;
}

}  // namespace

TEST(Catenary, EndPositionMatchesQuadratureSuspended) {
  // Soft line (strains up to ~0.15) so the elastic terms matter.
  const CatenaryInput in = input(150.0, 100.0, 1e5, 0.0, 0.0, false);
  for (const auto& [H, V] : {std::pair{5000.0, 12000.0}, std::pair{2000.0, 16000.0}, std::pair{8000.0, 7000.0}}) {
    double X, Z, Xq, Zq;
    catenaryEnd(in, H, V, X, Z);
    integrateEnd(in, H, V, Xq, Zq);
    EXPECT_NEAR(X, Xq, kQuadTol) << "H " << H << " V " << V;
    EXPECT_NEAR(Z, Zq, kQuadTol) << "H " << H << " V " << V;
  }
}

TEST(Catenary, EndPositionMatchesQuadratureGrounded) {
  const CatenaryInput in = input(200.0, 100.0, 1e5, 0.0, 0.0, true);
  for (const auto& [H, V] : {std::pair{3000.0, 8000.0}, std::pair{500.0, 15000.0}}) {
    double X, Z, Xq, Zq;
    catenaryEnd(in, H, V, X, Z);
    integrateEnd(in, H, V, Xq, Zq);
    EXPECT_NEAR(X, Xq, kQuadTol) << "H " << H << " V " << V;
    EXPECT_NEAR(Z, Zq, kQuadTol) << "H " << H << " V " << V;
  }
}

TEST(Catenary, SolveRoundTripsThroughCatenaryEnd) {
  struct Case { double L, w, EA, H, V; bool seabed; };
  for (const Case c : {Case{150.0, 100.0, 1e7, 5000.0, 12000.0, false},   // both ends pulled down
                       Case{150.0, 100.0, 1e7, 4000.0, 18000.0, false},   // anchor pulled up
                       Case{150.0, 100.0, 1e5, 6000.0, 10000.0, false},   // soft line
                       Case{200.0, 100.0, 1e7, 3000.0, 8000.0, true},     // 120 m grounded
                       Case{300.0, 50.0, 1e6, 20000.0, 9000.0, true}}) {  // taut, mostly grounded
    CatenaryInput in = input(c.L, c.w, c.EA, 0.0, 0.0, c.seabed);
    catenaryEnd(in, c.H, c.V, in.X, in.Z);
    const CatenarySolution s = solveCatenary(in);
    ASSERT_TRUE(s.converged) << "H " << c.H << " V " << c.V;
    EXPECT_NEAR(s.H, c.H, kForceRel * std::hypot(c.H, c.V)) << "H " << c.H << " V " << c.V;
    EXPECT_NEAR(s.V, c.V, kForceRel * std::hypot(c.H, c.V)) << "H " << c.H << " V " << c.V;
  }
}

TEST(Catenary, SolvedForcesPlaceTheEndAtTheTarget) {
  // Independent of catenaryEnd: the quadrature of the solved (H, V) must land on (X, Z).
  for (const bool seabed : {false, true}) {
    const CatenaryInput in = seabed ? input(200.0, 100.0, 1e5, 120.0, 100.0, true)
                                    : input(150.0, 100.0, 1e5, 80.0, 90.0, false);
    const CatenarySolution s = solveCatenary(in);
    ASSERT_TRUE(s.converged);
    double Xq, Zq;
    integrateEnd(in, s.H, s.V, Xq, Zq);
    constexpr double kEndTol = 1e-6;  // solver residual 1e-9 L plus quadrature error [m]
    EXPECT_NEAR(Xq, in.X, kEndTol) << "seabed " << seabed;
    EXPECT_NEAR(Zq, in.Z, kEndTol) << "seabed " << seabed;
  }
}

TEST(Catenary, RigidSuspendedLineTextbookRelations) {
  const double L = 150.0, w = 100.0, X = 80.0, Z = 90.0;
  const CatenarySolution s = solveCatenary(input(L, w, kRigidEA, X, Z, false));
  ASSERT_TRUE(s.converged);
  EXPECT_EQ(s.grounded, 0.0);
  EXPECT_LT(s.Va, 0.0);  // this line hangs below the anchor: the anchor is pulled down
  // Tension rises by the weight of a column of line as tall as the height difference.
  EXPECT_NEAR(s.topTension() - s.anchorTension(), w * Z, kForceRel * s.topTension());
  // Length of a rigid catenary between points X apart and Z apart: L^2 = Z^2 + (2a sinh(X/2a))^2.
  const double a = s.H / w;
  const double chord = 2.0 * a * std::sinh(X / (2.0 * a));
  EXPECT_NEAR(L * L, Z * Z + chord * chord, kForceRel * L * L);
}

TEST(Catenary, RigidAnchorPulledUpward) {
  // Short line: the anchor end leaves upward (Va > 0) and the same relations hold.
  const double L = 100.0, w = 20.0, X = 60.0, Z = 75.0;
  const CatenarySolution s = solveCatenary(input(L, w, kRigidEA, X, Z, false));
  ASSERT_TRUE(s.converged);
  EXPECT_GT(s.Va, 0.0);
  EXPECT_NEAR(s.topTension() - s.anchorTension(), w * Z, kForceRel * s.topTension());
  const double a = s.H / w;
  const double chord = 2.0 * a * std::sinh(X / (2.0 * a));
  EXPECT_NEAR(L * L, Z * Z + chord * chord, kForceRel * L * L);
}

TEST(Catenary, RigidGroundedLine) {
  const double L = 200.0, w = 100.0, X = 120.0, Z = 100.0;
  const CatenarySolution s = solveCatenary(input(L, w, kRigidEA, X, Z, true));
  ASSERT_TRUE(s.converged);
  ASSERT_GT(s.grounded, 0.0);
  // Suspended length from touchdown (where the line is horizontal): Ls^2 = Z^2 + 2 a Z, a = H/w,
  // so the grounded length L - V/w equals L - Ls.
  const double a = s.H / w;
  const double Ls = std::sqrt(Z * Z + 2.0 * a * Z);
  EXPECT_NEAR(s.grounded, L - Ls, kForceRel * L);
  // Horizontal reach: grounded stretch plus the catenary span a asinh(Ls / a).
  EXPECT_NEAR(X, (L - Ls) + a * std::asinh(Ls / a), kForceRel * L);
  // Frictionless bottom: the anchor only sees the horizontal tension, and the top tension
  // exceeds it by w Z.
  EXPECT_EQ(s.Va, 0.0);
  EXPECT_NEAR(s.anchorTension(), s.H, kForceRel * s.H);
  EXPECT_NEAR(s.topTension(), s.H + w * Z, kForceRel * s.topTension());
}
