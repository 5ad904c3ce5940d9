// Model: constitutive laws, seabed and current lookups, surface buoy hydrostatics. The validation
// messages of Problem and StaticOptions (model_validation.cpp): test_model_validation.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/model.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Closed-form values of O(1e4) computed with a handful of flops: relative rounding only.
constexpr double kRel = 1e-12;
// Central differences with step 1e-6 on smooth O(1) functions: truncation ~1e-12, rounding ~1e-10.
constexpr double kFdTol = 1e-7;
constexpr double kFdStep = 1e-6;

Material tableMaterial() {
  Material m;
  m.name = "rope";
  // Slopes 1e5 N on [0, 0.01] and 2e5 N on [0.01, 0.03].
  m.tension_strain = {{0.0, 0.0}, {0.01, 1000.0}, {0.03, 5000.0}};
  return m;
}

}  // namespace

// --- Material --------------------------------------------------------------------------------

TEST(Material, LinearEA) {
  Material m;
  m.EA = 2.5e6;
  m.compression = true;  // the law as given below zero strain (the default; compression: false has none: SlackRamp)
  for (double eps : {-0.01, 0.0, 0.004, 0.3}) {
    EXPECT_NEAR(m.tension(eps), 2.5e6 * eps, kRel * 2.5e6);
    EXPECT_EQ(m.tensionSlope(eps), 2.5e6);
  }
  EXPECT_NEAR(m.strainAt(5000.0), 0.002, kRel);
  EXPECT_NEAR(m.strainAt(m.tension(0.0123)), 0.0123, kRel);
}

TEST(Material, TensionStrainTableInterpolates) {
  Material m = tableMaterial();
  m.compression = true;  // the table as given (the slack ramp lifts T(0) by b / 8)
  EXPECT_NEAR(m.tension(0.0), 0.0, kRel * 5000.0);
  EXPECT_NEAR(m.tension(0.005), 500.0, kRel * 5000.0);
  EXPECT_NEAR(m.tension(0.02), 3000.0, kRel * 5000.0);   // 1000 + 0.01 * 2e5
  EXPECT_NEAR(m.tension(0.03), 5000.0, kRel * 5000.0);
  EXPECT_NEAR(m.tensionSlope(0.005), 1e5, kRel * 1e5);
  EXPECT_NEAR(m.tensionSlope(0.02), 2e5, kRel * 2e5);
  // The table is used, not EA (which is zero here).
  EXPECT_EQ(m.EA, 0.0);
}

TEST(Material, TensionStrainTableExtrapolatesWithEndSlopes) {
  Material m = tableMaterial();
  m.compression = true;
  EXPECT_NEAR(m.tension(0.04), 7000.0, kRel * 5000.0);   // 5000 + 0.01 * 2e5
  EXPECT_NEAR(m.tension(-0.01), -1000.0, kRel * 5000.0); // 0 - 0.01 * 1e5
  EXPECT_NEAR(m.tensionSlope(0.1), 2e5, kRel * 2e5);
  EXPECT_NEAR(m.tensionSlope(-0.1), 1e5, kRel * 1e5);
}

TEST(Material, StrainAtInvertsTheTable) {
  Material m = tableMaterial();
  m.compression = true;
  EXPECT_NEAR(m.strainAt(500.0), 0.005, kRel);
  EXPECT_NEAR(m.strainAt(3000.0), 0.02, kRel);
  EXPECT_NEAR(m.strainAt(7000.0), 0.04, kRel);    // extrapolated above
  EXPECT_NEAR(m.strainAt(-1000.0), -0.01, kRel);  // extrapolated below
  for (double eps = -0.02; eps <= 0.06; eps += 0.0037) {
    EXPECT_NEAR(m.strainAt(m.tension(eps)), eps, kRel) << "eps " << eps;
    // Slope consistent with the function (away from the breakpoints at 0.01 and 0.03).
    if (std::abs(eps - 0.01) > 2 * kFdStep && std::abs(eps - 0.03) > 2 * kFdStep) {
      const double fd = (m.tension(eps + kFdStep) - m.tension(eps - kFdStep)) / (2 * kFdStep);
      EXPECT_NEAR(m.tensionSlope(eps), fd, kFdTol * 2e5) << "eps " << eps;
    }
  }
}

TEST(Material, RopesAndChainsCarryNoCompression) {
  // compression: false: slackRamp of EA eps over the band b = EA kSlackStrain: exactly EA eps from
  // eps = kSlackStrain / 2 up, exactly 0 from -kSlackStrain / 2 down, never negative, value and
  // slope continuous at both joins.
  for (bool table : {false, true}) {
    Material m;
    if (table) {
      m = tableMaterial();  // slope 1e5 at zero strain
    } else {
      m.EA = 2.5e6;
    }
    EXPECT_TRUE(m.compression) << "the default: WHOI Cable's law through zero";
    m.compression = false;
    const double k0 = table ? 1e5 : 2.5e6, b = k0 * kSlackStrain;
    EXPECT_EQ(m.slackBand(), b);
    EXPECT_EQ(m.tension(0.004), m.rawTension(0.004));  // taut: the law as given, bit for bit
    EXPECT_EQ(m.tension(0.5 * kSlackStrain), m.rawTension(0.5 * kSlackStrain));
    EXPECT_EQ(m.tension(-0.01), 0.0);
    EXPECT_FALSE(std::signbit(m.tension(-0.01)));  // +0, never -0
    EXPECT_EQ(m.tensionSlope(-0.01), kSlackJacobianFraction * k0);  // the slope Newton sees
    EXPECT_NEAR(m.tension(0.0), b / 8.0, kRel * b);  // the ramp's largest lift, at zero strain
    for (double e = -kSlackStrain; e <= kSlackStrain; e += kSlackStrain / 16.0) {
      EXPECT_GE(m.tension(e), 0.0) << e;
      const double h = 1e-9;
      const double fd = (m.tension(e + h) - m.tension(e - h)) / (2.0 * h);
      EXPECT_NEAR(m.tensionSlope(e), std::max(fd, kSlackJacobianFraction * k0), 1e-3 * k0) << e;
      if (m.tension(e) > 0.0) {
        EXPECT_NEAR(m.strainAt(m.tension(e)), e, 1e-12) << e;
      }
    }
    EXPECT_NEAR(m.strainAt(0.0), -0.5 * kSlackStrain, 1e-15);  // where the law reaches zero
    m.compression = true;
    EXPECT_EQ(m.tension(-0.01), m.rawTension(-0.01));
  }
}

// --- Environment -----------------------------------------------------------------------------

TEST(Environment, FlatSeabed) {
  Environment env;
  env.depth = 123.0;
  for (double x : {-1000.0, 0.0, 55.5}) {
    EXPECT_EQ(env.seabedElevation(x), -123.0);
    EXPECT_EQ(env.seabedSlope(x), 0.0);
  }
  EXPECT_TRUE(env.flatSeabed());
}

TEST(Environment, SeabedProfile) {
  Environment env;
  env.depth = 999.0;  // ignored when a profile is given
  // Depth 100 m at x = 0 rising to 50 m at x = 100, then flat to 60 m deep at x = 200.
  env.seabed.profile = {{0.0, 100.0}, {100.0, 50.0}, {200.0, 60.0}};
  EXPECT_FALSE(env.flatSeabed());
  EXPECT_NEAR(env.seabedElevation(0.0), -100.0, kRel * 100);
  EXPECT_NEAR(env.seabedElevation(50.0), -75.0, kRel * 100);
  EXPECT_NEAR(env.seabedElevation(150.0), -55.0, kRel * 100);
  EXPECT_NEAR(env.seabedSlope(50.0), 0.5, kRel);    // z_bot rises 50 m over 100 m
  EXPECT_NEAR(env.seabedSlope(150.0), -0.1, kRel);  // z_bot falls 10 m over 100 m
  // Beyond the ends the bottom is held flat at the end depths.
  EXPECT_NEAR(env.seabedElevation(-30.0), -100.0, kRel * 100);
  EXPECT_NEAR(env.seabedElevation(500.0), -60.0, kRel * 100);
  EXPECT_EQ(env.seabedSlope(-30.0), 0.0);
  EXPECT_EQ(env.seabedSlope(500.0), 0.0);
  // The slope is the derivative of the elevation inside each piece.
  for (double x : {10.0, 42.0, 99.0, 101.0, 177.0}) {
    const double fd = (env.seabedElevation(x + kFdStep) - env.seabedElevation(x - kFdStep)) / (2 * kFdStep);
    EXPECT_NEAR(env.seabedSlope(x), fd, kFdTol) << "x " << x;
  }
}

/// A 4 x 3 grid from (-100, 50) with spacings 50 m (x) and 20 m (y), depths from `f(x, y)`.
template <class F>
SeabedGrid gridOf(F f) {
  SeabedGrid g;
  g.x0 = -100.0;
  g.y0 = 50.0;
  g.dx = 50.0;
  g.dy = 20.0;
  g.nx = 4;
  g.ny = 3;
  for (std::size_t iy = 0; iy < g.ny; ++iy)
    for (std::size_t ix = 0; ix < g.nx; ++ix) g.depths.push_back(f(g.x0 + ix * g.dx, g.y0 + iy * g.dy));
  return g;
}

TEST(Environment, SeabedGridIsExactOnAPlaneAndABilinearSurface) {
  // Bilinear interpolation reproduces a + b x + c y + d x y exactly, between and on grid points.
  auto plane = [](double x, double y) { return 80.0 + 0.1 * x - 0.25 * y; };
  auto saddle = [](double x, double y) { return 80.0 + 0.1 * x - 0.25 * y + 1e-3 * x * y; };
  constexpr double kTol = 1e-12 * 100;  // a few flops on depths of O(100) m
  for (int which = 0; which < 2; ++which) {
    Environment env;
    env.depth = 999.0;  // not used with a grid
    env.seabed.grid = which == 0 ? gridOf(plane) : gridOf(saddle);
    ASSERT_EQ(env.seabed.grid.validate(), "");
    EXPECT_FALSE(env.flatSeabed());
    for (double x : {-100.0, -77.7, -50.0, 0.0, 12.5, 49.9, 50.0})
      for (double y : {50.0, 51.0, 70.0, 83.3, 90.0}) {
        const double d = which == 0 ? plane(x, y) : saddle(x, y);
        EXPECT_NEAR(env.seabedElevation(x, y), -d, kTol) << which << " x " << x << " y " << y;
        double dzdx, dzdy;
        env.seabedGradient(x, y, dzdx, dzdy);
        // Exact derivatives of the surface, except on the edges (clamped: 0).
        const double ex = which == 0 ? 0.1 : 0.1 + 1e-3 * y, ey = which == 0 ? -0.25 : -0.25 + 1e-3 * x;
        EXPECT_NEAR(dzdx, x > -100.0 && x < 50.0 ? -ex : 0.0, 1e-12) << which << " x " << x << " y " << y;
        EXPECT_NEAR(dzdy, y > 50.0 && y < 90.0 ? -ey : 0.0, 1e-12) << which << " x " << x << " y " << y;
      }
  }
}

TEST(Environment, SeabedGridGradientMatchesFiniteDifferences) {
  // A surface that bilinear interpolation does not reproduce: the gradient is that of the
  // interpolant (piecewise bilinear), checked away from the grid lines.
  Environment env;
  env.seabed.grid = gridOf([](double x, double y) { return 60.0 + 10.0 * std::sin(0.03 * x) * std::cos(0.05 * y); });
  constexpr double kStep = 1e-4;   // [m]: O(100) m depths, rounding 1e-14 * 100 / 1e-4 ~ 1e-8
  constexpr double kTol = 1e-7;    // the interpolant is linear along each axis within a cell: no truncation
  for (double x : {-90.0, -33.0, 10.0, 77.0})
    for (double y : {55.0, 68.0, 81.0}) {
      double dzdx, dzdy;
      env.seabedGradient(x, y, dzdx, dzdy);
      const double fx = (env.seabedElevation(x + kStep, y) - env.seabedElevation(x - kStep, y)) / (2 * kStep);
      const double fy = (env.seabedElevation(x, y + kStep) - env.seabedElevation(x, y - kStep)) / (2 * kStep);
      EXPECT_NEAR(dzdx, fx, kTol) << "x " << x << " y " << y;
      EXPECT_NEAR(dzdy, fy, kTol) << "x " << x << " y " << y;
      EXPECT_GT(std::abs(dzdx) + std::abs(dzdy), 1e-3);  // a real slope, not a trivially flat test
    }
}

TEST(Environment, SeabedGridIsClampedToItsEdges) {
  Environment env;
  env.seabed.grid = gridOf([](double x, double y) { return 80.0 + 0.1 * x - 0.25 * y; });
  const SeabedGrid& g = env.seabed.grid;
  // Corners: the corner depth however far out; edges: the edge's interpolated depth.
  EXPECT_EQ(env.seabedElevation(-1e4, -1e4), -g.at(0, 0));
  EXPECT_EQ(env.seabedElevation(1e4, -1e4), -g.at(3, 0));
  EXPECT_EQ(env.seabedElevation(-1e4, 1e4), -g.at(0, 2));
  EXPECT_EQ(env.seabedElevation(1e4, 1e4), -g.at(3, 2));
  EXPECT_EQ(env.seabedElevation(-500.0, 63.0), env.seabedElevation(-100.0, 63.0));  // west
  EXPECT_EQ(env.seabedElevation(12.0, 1000.0), env.seabedElevation(12.0, 90.0));    // north
  double dzdx, dzdy;
  env.seabedGradient(-500.0, 63.0, dzdx, dzdy);  // west of the grid: flat in x, sloped in y
  EXPECT_EQ(dzdx, 0.0);
  EXPECT_NEAR(dzdy, 0.25, 1e-12);
  env.seabedGradient(1e4, 1e4, dzdx, dzdy);  // beyond a corner: flat
  EXPECT_EQ(dzdx, 0.0);
  EXPECT_EQ(dzdy, 0.0);
}

TEST(Environment, WithoutAGridTheXProfileAndFlatDepthAreUsed) {
  Environment env;
  env.depth = 77.0;
  double dzdx, dzdy;
  for (double y : {0.0, -300.0, 1e5}) {
    EXPECT_EQ(env.seabedElevation(12.0, y), -77.0);
    env.seabedGradient(12.0, y, dzdx, dzdy);
    EXPECT_EQ(dzdx, 0.0);
    EXPECT_EQ(dzdy, 0.0);
  }
  env.seabed.profile = {{0.0, 100.0}, {100.0, 50.0}, {200.0, 60.0}};
  for (double x : {-30.0, 0.0, 50.0, 100.0, 150.0, 500.0}) {
    EXPECT_EQ(env.seabedElevation(x, 0.0), env.seabedElevation(x)) << x;
    EXPECT_EQ(env.seabedElevation(x, 250.0), env.seabedElevation(x)) << x;  // no y dependence
    env.seabedGradient(x, 250.0, dzdx, dzdy);
    EXPECT_EQ(dzdx, env.seabedSlope(x)) << x;
    EXPECT_EQ(dzdy, 0.0) << x;
  }
  // With a grid, the 2-D functions are its section y = 0.
  env.seabed.profile.clear();
  env.seabed.grid = gridOf([](double x, double y) { return 80.0 + 0.1 * x - 0.25 * y + 1e-3 * x * y; });
  env.seabed.grid.y0 = -20.0;  // so that y = 0 lies inside the grid
  for (double x : {-30.0, 0.0, 75.0}) {
    EXPECT_EQ(env.seabedElevation(x), env.seabedElevation(x, 0.0)) << x;
    env.seabedGradient(x, 0.0, dzdx, dzdy);
    EXPECT_EQ(env.seabedSlope(x), dzdx) << x;
  }
}

TEST(Environment, NoCurrent) {
  Environment env;
  double ux = 1.0, uy = 1.0;
  env.currentAt(-10.0, ux, uy);
  EXPECT_EQ(ux, 0.0);
  EXPECT_EQ(uy, 0.0);
}

TEST(Environment, CurrentProfileInterpolatesVelocityComponents) {
  Environment env;
  // 1 m/s east at 10 m, 0.5 m/s north at 50 m, 0.2 m/s west at 100 m.
  env.current = {{10.0, 1.0, 0.0}, {50.0, 0.5, 0.5 * kPi}, {100.0, 0.2, kPi}};
  constexpr double kTol = 1e-12;  // a few flops on O(1) values
  double ux, uy;
  // Halfway between 10 and 50 m: the mean of (1, 0) and (0, 0.5). Interpolating speed and
  // direction instead would give 0.75 m/s toward 45 deg = (0.53, 0.53).
  env.currentAt(-30.0, ux, uy);
  EXPECT_NEAR(ux, 0.5, kTol);
  EXPECT_NEAR(uy, 0.25, kTol);
  // A quarter of the way from 50 to 100 m: (0, 0.5) + 0.25 * ((-0.2, 0) - (0, 0.5)).
  env.currentAt(-62.5, ux, uy);
  EXPECT_NEAR(ux, -0.05, kTol);
  EXPECT_NEAR(uy, 0.375, kTol);
  // At a table depth exactly.
  env.currentAt(-50.0, ux, uy);
  EXPECT_NEAR(ux, 0.0, kTol);
  EXPECT_NEAR(uy, 0.5, kTol);
  // Above the first point (and above the surface): the first point's velocity.
  for (double z : {-5.0, 0.0, 3.0}) {
    env.currentAt(z, ux, uy);
    EXPECT_NEAR(ux, 1.0, kTol) << "z " << z;
    EXPECT_NEAR(uy, 0.0, kTol) << "z " << z;
  }
  // Below the last point: the last point's velocity.
  env.currentAt(-400.0, ux, uy);
  EXPECT_NEAR(ux, -0.2, kTol);
  EXPECT_NEAR(uy, 0.0, kTol);
}

TEST(Environment, CurrentGradientMatchesFiniteDifferences) {
  Environment env;
  // Same profile as above: the velocity components change with depth in both x and y.
  env.current = {{10.0, 1.0, 0.0}, {50.0, 0.5, 0.5 * kPi}, {100.0, 0.2, kPi}};
  // Interval slopes of (ux, uy) in depth: (-1/40, 0.5/40) and (-0.2/50, -0.5/50); dz = -dd.
  constexpr double kTol = 1e-12;  // a few flops on O(1) values
  double gx, gy;
  env.currentGradientAt(-30.0, gx, gy);
  EXPECT_NEAR(gx, 1.0 / 40.0, kTol);
  EXPECT_NEAR(gy, -0.5 / 40.0, kTol);
  env.currentGradientAt(-75.0, gx, gy);
  EXPECT_NEAR(gx, 0.2 / 50.0, kTol);
  EXPECT_NEAR(gy, 0.5 / 50.0, kTol);
  // Away from the table points the gradient is the derivative of currentAt.
  for (double z : {-12.0, -31.7, -49.0, -51.0, -88.8, -99.0}) {
    double uxp, uyp, uxm, uym;
    env.currentAt(z + kFdStep, uxp, uyp);
    env.currentAt(z - kFdStep, uxm, uym);
    env.currentGradientAt(z, gx, gy);
    EXPECT_NEAR(gx, (uxp - uxm) / (2 * kFdStep), kFdTol) << "z " << z;
    EXPECT_NEAR(gy, (uyp - uym) / (2 * kFdStep), kFdTol) << "z " << z;
  }
  // Held end values above the first point, above the surface and below the last point: no slope.
  for (double z : {-5.0, -10.0, 0.0, 3.0, -100.5, -400.0}) {
    env.currentGradientAt(z, gx, gy);
    EXPECT_EQ(gx, 0.0) << "z " << z;
    EXPECT_EQ(gy, 0.0) << "z " << z;
  }
  // On an inner table point: the slope of the interval above it (where currentAt interpolates).
  env.currentGradientAt(-50.0, gx, gy);
  EXPECT_NEAR(gx, 1.0 / 40.0, kTol);
  EXPECT_NEAR(gy, -0.5 / 40.0, kTol);
}

// The precomputed table of the dynamic solvers is Environment's interpolation bit for bit:
// values and gradients on a sweep through every table point, the held ends and above the
// surface, for an absent, a one-point and a three-point current.
TEST(Environment, CurrentProfileEqualsEnvironmentBitForBit) {
  const std::vector<std::vector<CurrentPoint>> tables = {
      {}, {{0.0, 0.5, 0.3}}, {{10.0, 1.0, 0.0}, {50.0, 0.5, 0.5 * kPi}, {100.0, 0.2, kPi}}};
  for (const auto& table : tables) {
    Environment env;
    env.current = table;
    const CurrentProfile profile(table);
    int compared = 0;
    for (double z = 5.0; z >= -120.0; z -= 2.5) {  // steps of 2.5 m: hits 10, 50 and 100 m exactly
      double ex, ey, px, py, gx, gy, qx, qy;
      env.currentAt(z, ex, ey);
      profile.at(z, px, py);
      env.currentGradientAt(z, gx, gy);
      profile.gradientAt(z, qx, qy);
      EXPECT_EQ(px, ex) << "z " << z << ", " << table.size() << " points";
      EXPECT_EQ(py, ey) << "z " << z << ", " << table.size() << " points";
      EXPECT_EQ(qx, gx) << "z " << z << ", " << table.size() << " points";
      EXPECT_EQ(qy, gy) << "z " << z << ", " << table.size() << " points";
      ++compared;
    }
    EXPECT_EQ(compared, 51);
  }
}

TEST(Environment, UniformOrAbsentCurrentHasNoGradient) {
  Environment env;
  double gx = 1.0, gy = 1.0;
  env.currentGradientAt(-20.0, gx, gy);  // no current
  EXPECT_EQ(gx, 0.0);
  EXPECT_EQ(gy, 0.0);
  env.current = {{0.0, 0.5, 0.3}};  // one point
  gx = gy = 1.0;
  env.currentGradientAt(-20.0, gx, gy);
  EXPECT_EQ(gx, 0.0);
  EXPECT_EQ(gy, 0.0);
  env.current = {{0.0, 0.5, 0.3}, {200.0, 0.5, 0.3}};  // the uniform shorthand's two points
  env.currentGradientAt(-20.0, gx, gy);
  EXPECT_EQ(gx, 0.0);
  EXPECT_EQ(gy, 0.0);
}

TEST(Environment, CurrentDirectionIsCounterclockwiseFromEast) {
  Environment env;
  env.current = {{0.0, 2.0, kPi / 6.0}};
  constexpr double kTol = 1e-12;
  double ux, uy;
  env.currentAt(-20.0, ux, uy);
  EXPECT_NEAR(ux, 2.0 * std::sqrt(3.0) / 2.0, kTol);
  EXPECT_NEAR(uy, 1.0, kTol);
}

// --- Surface buoy ----------------------------------------------------------------------------

TEST(SurfaceBuoy, SphereVolumeAndArea) {
  SurfaceBuoy b;
  b.shape = SurfaceBuoy::Shape::Sphere;
  b.diameter = 2.0;
  const double R = 1.0;
  const double full = 4.0 / 3.0 * kPi * R * R * R;
  EXPECT_NEAR(b.totalHeight(), 2.0, kRel);
  EXPECT_NEAR(b.submergedVolume(0.0), 0.0, kRel);
  EXPECT_NEAR(b.submergedVolume(1.0), 0.5 * full, kRel * full);
  EXPECT_NEAR(b.submergedVolume(2.0), full, kRel * full);
  EXPECT_NEAR(b.submergedVolume(5.0), full, kRel * full);  // clamped: fully submerged
  EXPECT_NEAR(b.submergedVolume(-1.0), 0.0, kRel);         // clamped: out of the water
  // Cap of height R/2: pi h^2 (3R - h) / 3 = pi * 0.25 * 2.5 / 3.
  EXPECT_NEAR(b.submergedVolume(0.5), kPi * 0.25 * 2.5 / 3.0, kRel);
  // Waterplane at the equator is the great circle.
  EXPECT_NEAR(b.submergedVolumeSlope(1.0), kPi * R * R, kRel);
  // Projected area: half and full disc.
  EXPECT_NEAR(b.submergedArea(1.0), 0.5 * kPi * R * R, kRel);
  EXPECT_NEAR(b.submergedArea(2.0), kPi * R * R, kRel);
  EXPECT_NEAR(b.submergedArea(0.0), 0.0, kRel);
  EXPECT_NEAR(b.submergedAreaSlope(1.0), 2.0 * R, kRel);  // chord at the equator = diameter
  for (double d : {0.1, 0.5, 0.9, 1.3, 1.9}) {
    const double fv = (b.submergedVolume(d + kFdStep) - b.submergedVolume(d - kFdStep)) / (2 * kFdStep);
    const double fa = (b.submergedArea(d + kFdStep) - b.submergedArea(d - kFdStep)) / (2 * kFdStep);
    EXPECT_NEAR(b.submergedVolumeSlope(d), fv, kFdTol) << "d " << d;
    EXPECT_NEAR(b.submergedAreaSlope(d), fa, kFdTol) << "d " << d;
  }
  // No change outside [0, height].
  EXPECT_EQ(b.submergedVolumeSlope(-0.5), 0.0);
  EXPECT_EQ(b.submergedVolumeSlope(2.5), 0.0);
  EXPECT_EQ(b.submergedAreaSlope(2.5), 0.0);
}

TEST(SurfaceBuoy, CylinderIsLinearInDraft) {
  SurfaceBuoy b;
  b.shape = SurfaceBuoy::Shape::Cylinder;
  b.diameter = 2.0;
  b.height = 3.0;
  const double A = kPi;  // pi R^2 with R = 1
  EXPECT_NEAR(b.totalHeight(), 3.0, kRel);
  for (double d : {0.0, 0.7, 1.5, 3.0}) {
    EXPECT_NEAR(b.submergedVolume(d), A * d, kRel * 10);
    EXPECT_NEAR(b.submergedArea(d), 2.0 * d, kRel * 10);
  }
  EXPECT_NEAR(b.submergedVolume(4.0), 3.0 * A, kRel * 10);  // clamped to the height
  EXPECT_NEAR(b.submergedArea(4.0), 6.0, kRel * 10);
  EXPECT_NEAR(b.submergedVolume(-1.0), 0.0, kRel);
  for (double d : {0.2, 1.5, 2.9}) {
    EXPECT_NEAR(b.submergedVolumeSlope(d), A, kRel * 10);
    EXPECT_NEAR(b.submergedAreaSlope(d), 2.0, kRel * 10);
    const double fv = (b.submergedVolume(d + kFdStep) - b.submergedVolume(d - kFdStep)) / (2 * kFdStep);
    EXPECT_NEAR(b.submergedVolumeSlope(d), fv, kFdTol);
  }
  EXPECT_EQ(b.submergedVolumeSlope(3.5), 0.0);
}

TEST(Environment, CurrentProfileAtAndAroundIsThreeLookUpsBitForBit) {
  const std::vector<CurrentPoint> table = {{0.0, 0.70, 0.0}, {50.0, 0.63, 0.3}, {100.0, 0.56, 0.0},
                                           {300.0, 0.25, 1.0}, {1860.0, 0.12, 0.0}};
  const CurrentProfile profile(table);
  constexpr double kDz = 1e-6;  // [m], as the 2-D solver
  std::vector<double> zs = {2.0, 0.0, -1e-7, -1e-6, -1860.0, -1900.0};
  for (double z = 0.0; z >= -1870.0; z -= 12.5) zs.push_back(z);
  for (const CurrentPoint& p : table)
    for (double off : {-2e-6, -1e-6, -5e-7, 0.0, 5e-7, 1e-6, 2e-6}) zs.push_back(-p.depth + off);
  for (double z : zs) {
    double ux, uy, up, um, ex, ey, eu, ed, unused;
    profile.atAndAround(z, kDz, ux, uy, up, um);
    profile.at(z, ex, ey);
    profile.at(z + kDz, eu, unused);
    profile.at(z - kDz, ed, unused);
    EXPECT_EQ(ux, ex) << "z " << z;
    EXPECT_EQ(uy, ey) << "z " << z;
    EXPECT_EQ(up, eu) << "z " << z;
    EXPECT_EQ(um, ed) << "z " << z;
  }
}

// Issue 22: a current table of a million points. The values are checked against the table's own
// linear law (speed = a + b * depth, one direction: the interpolation is exact). The lookup's cost
// (a bisection, not a scan) is measured in bench/bench_current.cpp, not timed here.
TEST(CurrentProfileLarge, MillionPointTableInterpolatesExactly) {
  constexpr std::size_t kPoints = 1000000;
  constexpr double kA = 0.2, kB = 1e-4, kDir = 0.3;
  std::vector<CurrentPoint> table(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    table[i].depth = 0.005 * static_cast<double>(i);  // 0 .. 5000 m
    table[i].speed = kA + kB * table[i].depth;
    table[i].direction = kDir;
  }
  Environment env;
  env.current = table;
  const CurrentProfile prof(table);
  double sum = 0.0;
  constexpr int kLookups = 200000;
  for (int k = 0; k < kLookups; ++k) {
    const double z = -4999.0 * (static_cast<double>(k) + 0.5) / kLookups;
    double ux, uy, gx, gy;
    prof.at(z, ux, uy);
    prof.gradientAt(z, gx, gy);
    sum += ux + gx;
    if (k % 20000 == 0) {
      const double speed = kA + kB * (-z);
      EXPECT_NEAR(ux, speed * std::cos(kDir), 1e-12) << z;
      EXPECT_NEAR(uy, speed * std::sin(kDir), 1e-12) << z;
      EXPECT_NEAR(gx, -kB * std::cos(kDir), 1e-9) << z;
      double eux, euy;
      env.currentAt(z, eux, euy);  // the Environment path: the same bits
      EXPECT_EQ(eux, ux);
      EXPECT_EQ(euy, uy);
    }
  }
  EXPECT_TRUE(std::isfinite(sum));
}
