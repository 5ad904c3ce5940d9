// Static solver against the closed-form elastic catenary, convergence order in ds, and
// robustness cases.
#include <gtest/gtest.h>

#include <cmath>

#include "mooring_dynamics/core/catenary.hpp"
#include "mooring_dynamics/core/statics2d.hpp"

using namespace mooring_dynamics::core;

namespace {

Problem catenaryProblem(double spacing, double X, double Z, double L, double depth) {
  Problem p;
  p.environment.depth = depth;
  p.environment.seabed.stiffness = 1.0e7;
  Material m;
  m.name = "wire";
  m.EA = 1.0e7;
  m.EI = 1.0e-2;
  m.mass = 10.0;
  m.wet_weight = 100.0;
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
  p.anchor_z = -depth;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = X;
  p.top.z = Z - depth;
  return p;
}

}  // namespace

TEST(Statics2D, SuspendedCatenary) {
  Problem p = catenaryProblem(1.0, 80.0, 90.0, 150.0, 200.0);
  p.anchor_z = -150.0;  // anchor raised above the bottom: no contact
  p.top.z = -60.0;
  StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  CatenaryInput in{150.0, 100.0, 1.0e7, 80.0, 90.0, false};
  CatenarySolution c = solveCatenary(in);
  ASSERT_TRUE(c.converged);
  std::printf("iters %d top T %.6f exact %.6f anchor %.6f exact %.6f\n", r.summary.iterations, r.topTension(),
              c.topTension(), r.nodes.front().tension, c.anchorTension());
  EXPECT_NEAR(r.topTension(), c.topTension(), 1e-3 * c.topTension());
}

TEST(Statics2D, GroundedCatenary) {
  Problem p = catenaryProblem(1.0, 120.0, 100.0, 200.0, 100.0);
  StaticResult r = solveStatic(p);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  CatenaryInput in{200.0, 100.0, 1.0e7, 120.0, 100.0, true};
  CatenarySolution c = solveCatenary(in);
  ASSERT_TRUE(c.converged);
  std::printf("iters %d top T %.6f exact %.6f H %.3f grounded %.3f\n", r.summary.iterations, r.topTension(),
              c.topTension(), c.H, c.grounded);
  EXPECT_NEAR(r.topTension(), c.topTension(), 1e-3 * c.topTension());
}

TEST(Statics2D, RefinementStudy) {
  CatenaryInput in{150.0, 100.0, 1.0e7, 80.0, 90.0, false};
  CatenarySolution c = solveCatenary(in);
  for (double h : {10.0, 5.0, 2.5, 1.25, 0.625, 0.3125}) {
    Problem p = catenaryProblem(h, 80.0, 90.0, 150.0, 200.0);
    p.anchor_z = -150.0;
    p.top.z = -60.0;
    StaticResult r = solveStatic(p);
    std::printf("h %.4f iters %d err top %.6e anchor %.6e\n", h, r.summary.iterations,
                r.topTension() - c.topTension(), r.nodes.front().tension - c.anchorTension());
  }
}
