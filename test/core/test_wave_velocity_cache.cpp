// WaveVelocityCache: the dynamic solver's wave velocity at the nodes against the direct sum of
// WaveField::velocity (carried references, both Taylor series, the second-order expansion).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Components below the negligible velocity at a point (1e-12 m/s each) that the cache sums
/// there (those seen up to kMaxExpansionRadius higher) and WaveField::velocity leaves out: at
/// most one per component of a 400-component sea [m/s].
constexpr double kNegligibleSum = 400 * 1e-12;
constexpr double kG = 9.81;

WaveSpec regular(double height, double period) {
  WaveSpec s;
  s.type = WaveSpec::Type::Regular;
  s.height = height;
  s.period = period;
  return s;
}

/// The A.2 storm (Pierson-Moskowitz, Hs 9.8 m, Tp 16 s, 200 components) travelling toward
/// `direction` [rad], with a 20 s ramp.
WaveSpec storm(double direction) {
  WaveSpec s;
  s.type = WaveSpec::Type::PiersonMoskowitz;
  s.hs = 9.8;
  s.tp = 16.0;
  s.direction = direction;
  s.ramp = 20.0;
  return s;
}

}  // namespace

// The per-point cache of the dynamic solver against WaveField::velocity: a random sea in deep
// water (1860 m, every component in the exponential branch), one in 60 m (hyperbolic branch),
// with a ramp, at points that creep (Taylor carry) and jump (refresh) between evaluations,
// above and below the surface, over many times. Without expansions across times: the same sums
// up to rounding.
TEST(Waves, VelocityCacheMatchesDirectEvaluation) {
  constexpr double kRelTol = 1e-12;   // of the largest velocity: reordered rounding only
  for (double depth : {1860.0, 60.0}) {
    const WaveField field(storm(0.3), depth, 9.81);
    constexpr std::size_t kPoints = 4;
    WaveVelocityCache cache(&field, kPoints, false, false);  // exact at every new time
    ASSERT_FALSE(cache.empty());
    const double x0[kPoints] = {0.0, 150.0, -40.0, 900.0};
    const double z0[kPoints] = {-1.0, -15.0, 0.5, -0.5 * depth};
    int compared = 0;
    for (int step = 0; step < 60; ++step) {
      const double t = 0.37 * step;
      cache.setTime(t);
      for (std::size_t p = 0; p < kPoints; ++p) {
        // Creep by a few mm per evaluation, jump by metres every 10th step.
        const double x = x0[p] + 0.003 * step + (step % 10 == 9 ? 7.0 : 0.0);
        const double z = z0[p] + 0.2 * std::sin(0.1 * step);
        double vx, vz, ex, ey, ez;
        cache.velocity(p, x, z, vx, vz);
        field.velocity(x, 0.0, z, t, ex, ey, ez);
        const double scale = std::max({1e-3, std::abs(ex), std::abs(ez)});
        EXPECT_NEAR(vx, ex, kRelTol * scale + kNegligibleSum) << "depth " << depth << " point " << p << " t " << t;
        EXPECT_NEAR(vz, ez, kRelTol * scale + kNegligibleSum) << "depth " << depth << " point " << p << " t " << t;
        ++compared;
      }
    }
    EXPECT_EQ(compared, 240);
  }
  WaveVelocityCache none(nullptr, 3);
  EXPECT_TRUE(none.empty());
}

// Within a point's expansion radius of its last exact evaluation at the same time the cache
// returns the second-order expansion, whose error is bounded by
// WaveVelocityCache::kLinearTolerance; beyond it, or at another time (without expansions across
// times), the exact sum. Both depth branches, points below, at and above the surface,
// displacements in all directions.
TEST(Waves, VelocityCacheLinearizesWithinItsRadius) {
  constexpr double kRoundTol = 1e-12;  // of the largest velocity: reordered rounding only
  for (double depth : {1860.0, 60.0}) {
    WaveSpec spec;
    spec.type = WaveSpec::Type::PiersonMoskowitz;
    spec.hs = 9.8;
    spec.tp = 16.0;
    spec.components = 400;
    spec.direction = 0.3;
    const WaveField field(spec, depth, 9.81);
    const double z0s[] = {-0.3, -12.0, -150.0, 0.0};
    WaveVelocityCache cache(&field, 4, false, false);
    const double r_global = cache.linearRadius();
    // The radius is what makes the linearization pay: a Newton iteration moves a node by less.
    EXPECT_GT(r_global, 1e-4) << "depth " << depth;
    EXPECT_LT(r_global, 1.0) << "depth " << depth;
    int linear = 0;
    for (int trial = 0; trial < 40; ++trial) {
      const double t = 3.1 + 0.5 * trial;
      cache.setTime(t);
      for (std::size_t p = 0; p < 4; ++p) {
        const double x0 = 20.0 * p + 0.7 * trial, z0 = z0s[p];
        double vx, vz, ex, ey, ez;
        cache.velocity(p, x0, z0, vx, vz);  // exact: first evaluation at this time
        field.velocity(x0, 0.0, z0, t, ex, ey, ez);
        const double scale = std::max({1e-3, std::abs(ex), std::abs(ez)});
        EXPECT_NEAR(vx, ex, kRoundTol * scale + kNegligibleSum);
        EXPECT_NEAR(vz, ez, kRoundTol * scale + kNegligibleSum);
        // The point's own radius: none outside the water column (above the surface, below the
        // bottom); inside it at least the global bound's near the surface (within the depth
        // factors' growth), larger with depth.
        const double r = cache.expansionRadius(p);
        if (z0 >= 0.0 || z0 <= -depth) {
          EXPECT_EQ(r, 0.0);
          continue;
        }
        EXPECT_GT(r, 0.8 * r_global) << "depth " << depth << " z " << z0;
        EXPECT_LE(r, WaveVelocityCache::kMaxExpansionRadius);
        if (depth > 1000.0 && z0 < -100.0) {
          EXPECT_GT(r, 5.0 * r_global) << "z " << z0;
        }
        // A displacement of 0.9 r in direction theta: linearized, within the bound.
        const double th = 0.37 * trial + 1.3 * p, d = 0.9 * r;
        const double x1 = x0 + d * std::cos(th), z1 = z0 + d * std::sin(th);
        cache.velocity(p, x1, z1, vx, vz);
        field.velocity(x1, 0.0, z1, t, ex, ey, ez);
        EXPECT_NEAR(vx, ex, WaveVelocityCache::kLinearTolerance + kRoundTol * scale) << "depth " << depth << " p " << p;
        EXPECT_NEAR(vz, ez, WaveVelocityCache::kLinearTolerance + kRoundTol * scale) << "depth " << depth << " p " << p;
        if (std::abs(vx - ex) > kRoundTol * scale + kNegligibleSum || std::abs(vz - ez) > kRoundTol * scale + kNegligibleSum)
          ++linear;
        // Beyond the radius (from the last exact point x0, z0): exact again.
        const double x2 = x0 + 3.0 * r * std::cos(th), z2 = z0 + 3.0 * r * std::sin(th);
        cache.velocity(p, x2, z2, vx, vz);
        field.velocity(x2, 0.0, z2, t, ex, ey, ez);
        EXPECT_NEAR(vx, ex, kRoundTol * scale + kNegligibleSum);
        EXPECT_NEAR(vz, ez, kRoundTol * scale + kNegligibleSum);
      }
    }
    // The expansion was used (it differs from the exact sum by more than rounding somewhere).
    EXPECT_GT(linear, 0) << "depth " << depth;
    std::printf("depth %.0f m: linear radius %.3g m\n", depth, r_global);
  }
}

// Expansions across times (the default): a node's reference stays put while the node moves within
// its expansion radius of it, and the sums there are taken afresh at each new time. Nodes of a
// deep line (1860 m, the A.2 storm, 400 components) from the surface down to 1500 m, each moving
// on an orbit of its own over 60 s in steps of 0.1 s, and a second evaluation within the step
// (a Newton iterate): every value within kLinearTolerance of the direct sum, most of the deep
// evaluations made about a kept reference, and none of those near the surface, where the radius
// is centimetres and the orbit metres.
TEST(Waves, VelocityCacheExpandsAcrossTimes) {
  constexpr double kRoundTol = 1e-12;  // of the largest velocity: reordered rounding only
  WaveSpec spec = storm(0.0);
  spec.components = 400;
  const WaveField field(spec, 1860.0, kG);
  const double z0[] = {-0.5, -5.0, -40.0, -150.0, -400.0, -800.0, -1500.0};
  constexpr std::size_t kPoints = sizeof z0 / sizeof z0[0];
  WaveVelocityCache cache(&field, kPoints);
  double worst = 0.0;
  int kept_deep = 0, deep = 0, kept_shallow = 0;
  // The cache's rule, mirrored: about its reference within the radius (below the surface), else
  // an exact sum that becomes the reference.
  double x_ref[kPoints] = {}, z_ref[kPoints] = {};
  for (int step = 0; step < 600; ++step) {
    const double t = 0.1 * step;
    cache.setTime(t);
    for (std::size_t p = 0; p < kPoints; ++p) {
      // Orbits shrinking with depth as the waves' do (4 m at the surface), plus a slow drift.
      const double a = 4.0 * std::exp(z0[p] / 150.0) + 0.05;
      for (int iterate = 0; iterate < 2; ++iterate) {
        const double x = 10.0 * p + 0.002 * step + a * std::sin(0.4 * t + p) + 0.003 * iterate;
        const double z = std::min(-0.1, z0[p] + a * std::cos(0.4 * t + p) - 0.002 * iterate);
        const double r = cache.expansionRadius(p);
        const bool kept = r > 0.0 && std::hypot(x - x_ref[p], z - z_ref[p]) <= r;
        double vx, vz, ex, ey, ez;
        cache.velocity(p, x, z, vx, vz);
        field.velocity(x, 0.0, z, t, ex, ey, ez);
        const double scale = std::max({1e-3, std::abs(ex), std::abs(ez)});
        const double err = std::max(std::abs(vx - ex), std::abs(vz - ez));
        EXPECT_LE(err, WaveVelocityCache::kLinearTolerance + kRoundTol * scale) << "p " << p << " t " << t;
        if (kept) worst = std::max(worst, err);
        else EXPECT_LE(err, kRoundTol * scale + kNegligibleSum) << "exact sum, p " << p << " t " << t;
        if (!kept) {
          x_ref[p] = x;
          z_ref[p] = z;
        }
        if (iterate > 0) continue;  // (counted: the first evaluation at each time)
        if (z0[p] <= -400.0) {
          ++deep;
          kept_deep += kept;
        }
        if (z0[p] >= -5.0) kept_shallow += kept;
      }
    }
  }
  EXPECT_GT(kept_deep, deep * 9 / 10);
  EXPECT_EQ(kept_shallow, 0);
  std::printf("largest difference %.2e m/s; deep evaluations about a kept reference: %d of %d\n", worst, kept_deep,
              deep);
}

// A node that creeps for thousands of evaluations (its reference carried by the Taylor factors
// each time, computed afresh only every few hundred moves) keeps the direct sum's value: the
// rounding of the carried values does not build up.
TEST(Waves, VelocityCacheCarriedReferenceDoesNotDrift) {
  // Relative to the larger of the velocity and 0.1 m/s (a tenth of the sea's velocities at that
  // depth): reordered rounding only. A drift would grow with the moves; 32 and 512 moves between
  // fresh references give the same largest difference.
  constexpr double kRelTol = 1e-12;
  constexpr double kFloor = 0.1;  // [m/s]
  WaveSpec spec;
  spec.type = WaveSpec::Type::PiersonMoskowitz;
  spec.hs = 9.8;
  spec.tp = 16.0;
  spec.components = 400;
  const WaveField field(spec, 1860.0, 9.81);
  WaveVelocityCache cache(&field, 1, false, false);
  double worst = 0.0;
  for (int step = 0; step < 3000; ++step) {
    const double t = 0.1 * step;
    cache.setTime(t);
    // A node heaving 3 m and surging 1 m with the sea, 10 m down.
    const double x = 5.0 + std::sin(0.35 * t), z = -10.0 + 3.0 * std::sin(0.39 * t);
    double vx, vz, ex, ey, ez;
    cache.velocity(0, x, z, vx, vz);
    field.velocity(x, 0.0, z, t, ex, ey, ez);
    const double scale = std::max({kFloor, std::abs(ex), std::abs(ez)});
    worst = std::max({worst, std::abs(vx - ex) / scale, std::abs(vz - ez) / scale});
  }
  EXPECT_LT(worst, kRelTol);
  std::printf("largest relative difference over 3000 carried evaluations: %.2e\n", worst);
}

// The carried reference's two Taylor series (to u^7 below kShortTaylorRadius, to u^11 up to
// kTaylorRadius) on a single regular component, where k is known and nothing else rounds: moves
// whose largest argument k |dx| or k |dz| sits just below and just above each radius, from a
// reference carried along (each evaluation at a new time, so none is an expansion). The short
// series used at 0.2 would be off by 0.2^8 / 8! = 6e-11, a series to u^3 at 0.02 by
// 0.02^4 / 4! = 7e-9: far above the tolerance.
TEST(Waves, VelocityCacheTaylorSeriesAtTheirRadii) {
  constexpr double kRelTol = 1e-14;  // of a omega: one component's rounding only
  const double depth = 1000.0, T = 5.0;
  const WaveField field(regular(2.0, T), depth, kG);
  const double k = field.components()[0].k, aw = 1.0 * 2.0 * kPi / T;
  const double r7 = WaveVelocityCache::kShortTaylorRadius, r11 = WaveVelocityCache::kTaylorRadius;
  const double args[] = {0.99 * r7, 1.01 * r7, 0.5 * r11, 0.99 * r11};
  WaveVelocityCache cache(&field, 1, false, false);
  double t = 0.0, x = 3.0, z = -2.0;
  int evaluations = 0;
  for (double u : args) {
    for (int axis = 0; axis < 2; ++axis) {
      for (double sign : {1.0, -1.0}) {
        (axis == 0 ? x : z) += sign * u / k;
        t += 0.77;
        cache.setTime(t);
        double vx, vz, ex, ey, ez;
        cache.velocity(0, x, z, vx, vz);
        field.velocity(x, 0.0, z, t, ex, ey, ez);
        EXPECT_NEAR(vx, ex, kRelTol * aw) << "argument " << u << " axis " << axis;
        EXPECT_NEAR(vz, ez, kRelTol * aw) << "argument " << u << " axis " << axis;
        ++evaluations;
      }
    }
  }
  EXPECT_EQ(evaluations, 16);
}

// A cache for points anywhere in the horizontal plane (the 3-D solver's) against
// WaveField::velocity(x, y, z, t): seas travelling toward 17 and 115 degrees, in deep water and in
// 60 m, at points that creep and jump in x, y and z, above and below the surface. Same sums up to
// rounding. A cache for the x-z plane refuses points off it.
TEST(Waves, VelocityCacheInTheHorizontalPlaneMatchesDirectEvaluation) {
  constexpr double kRelTol = 1e-12;  // of the largest velocity: reordered rounding only
  int compared = 0;
  for (double direction : {0.3, 2.0})
    for (double depth : {1860.0, 60.0}) {
      const WaveField field(storm(direction), depth, 9.81);
      constexpr std::size_t kPoints = 3;
      WaveVelocityCache cache(&field, kPoints, true, false);
      const double x0[kPoints] = {0.0, 150.0, -40.0}, y0[kPoints] = {0.0, -70.0, 25.0};
      const double z0[kPoints] = {-1.0, -15.0, 0.5};
      for (int step = 0; step < 40; ++step) {
        const double t = 0.41 * step;
        cache.setTime(t);
        for (std::size_t p = 0; p < kPoints; ++p) {
          const double jump = step % 10 == 9 ? 6.0 : 0.0;
          const double x = x0[p] + 0.004 * step + jump, y = y0[p] - 0.003 * step + jump;
          const double z = z0[p] + 0.2 * std::sin(0.1 * step);
          double vx, vy, vz, ex, ey, ez;
          cache.velocity3(p, x, y, z, vx, vy, vz);
          field.velocity(x, y, z, t, ex, ey, ez);
          const double scale = std::max({1e-3, std::abs(ex), std::abs(ey), std::abs(ez)});
          EXPECT_NEAR(vx, ex, kRelTol * scale + kNegligibleSum) << "direction " << direction << " depth " << depth << " t " << t;
          EXPECT_NEAR(vy, ey, kRelTol * scale + kNegligibleSum) << "direction " << direction << " depth " << depth << " t " << t;
          EXPECT_NEAR(vz, ez, kRelTol * scale + kNegligibleSum) << "direction " << direction << " depth " << depth << " t " << t;
          ++compared;
        }
      }
      WaveVelocityCache xz(&field, 1);
      double vx, vy, vz;
      EXPECT_THROW(xz.velocity3(0, 1.0, 2.0, -3.0, vx, vy, vz), std::logic_error);
    }
  EXPECT_EQ(compared, 480);
}

// componentsAt(z), the cost of an exact evaluation that the dynamic solver shares between its
// threads by: every component at the surface (and above it: the surface values), whole groups
// of eight, fewer with depth (the short waves die out first), none where every component is
// below the negligible velocity (1e-12 m/s), and none without a sea.
TEST(Waves, VelocityCacheComponentsSummedFallWithDepth) {
  WaveSpec s = storm(0.0);
  s.components = 100;
  const WaveField field(s, 1860.0, kG);
  const WaveVelocityCache cache(&field, 1);
  EXPECT_EQ(cache.componentsAt(0.0), 104u);  // 100 rounded up to whole groups of eight
  EXPECT_EQ(cache.componentsAt(5.0), 104u);
  std::size_t above = cache.componentsAt(0.0);
  for (double z = -10.0; z >= -1860.0; z -= 10.0) {
    const std::size_t n = cache.componentsAt(z);
    EXPECT_EQ(n % 8, 0u) << "z " << z;
    EXPECT_LE(n, above) << "z " << z;
    above = n;
  }
  EXPECT_LT(cache.componentsAt(-300.0), cache.componentsAt(-30.0));  // short waves gone at 300 m
  // The longest component (f_min_factor 0.5 of fp: k = 0.004 1/m) is still felt at the bottom of
  // 1860 m (e^{-k 1860} ~ 7e-4 times its velocity at the surface), so the bottom still sums a group.
  EXPECT_GT(cache.componentsAt(-1860.0), 0u);
  const WaveVelocityCache none(nullptr, 1);
  EXPECT_EQ(none.componentsAt(-10.0), 0u);
}

// balancedWaterSplit: equal work per point splits at the meeting node; a line rising from the
// bottom to the surface (top last) gives the second thread fewer points, the ones that sum all
// the components, and the two parts' work then differs by less than one point's; no sea: the
// meeting node.
TEST(Waves, BalancedWaterSplitEvensTheWaveSums) {
  const WaveField field(storm(0.0), 1860.0, kG);
  const WaveVelocityCache cache(&field, 1);
  constexpr int kPoints = 200, kMeeting = 100;
  constexpr double kWaterWork = 40.0, kRestWork = 8.0;
  const std::vector<double> level(kPoints, -10.0);
  EXPECT_EQ(balancedWaterSplit(cache, level, kMeeting, kWaterWork, kRestWork), kMeeting);
  std::vector<double> rising(kPoints);
  for (int j = 0; j < kPoints; ++j) rising[static_cast<std::size_t>(j)] = -1860.0 * (1.0 - j / (kPoints - 1.0));
  const int w = balancedWaterSplit(cache, rising, kMeeting, kWaterWork, kRestWork);
  EXPECT_GT(w, kMeeting + 20);
  double first = kRestWork * kMeeting, second = kRestWork * (kPoints - kMeeting), largest = 0.0;
  for (int j = 0; j < kPoints; ++j) {
    const double work = static_cast<double>(cache.componentsAt(rising[static_cast<std::size_t>(j)])) + kWaterWork;
    (j < w ? first : second) += work;
    largest = std::max(largest, work);
  }
  EXPECT_LE(std::abs(first - second), largest);
  const WaveVelocityCache none(nullptr, 1);
  EXPECT_EQ(balancedWaterSplit(none, rising, kMeeting, kWaterWork, kRestWork), kMeeting);
}
