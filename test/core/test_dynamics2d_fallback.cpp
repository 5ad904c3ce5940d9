// The fallback step of the 2-D solver (src/core/solvers/dynamics2d_fallback.cpp): runs that the
// implicit step alone cannot finish go through with the fallback steps counted; the snap of a
// weight dropped onto a slack rope meets its closed form; tensions of lines without compression
// never go below zero; the planar 3-D solver with its own fallback gives the same snaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"

using namespace mooring_dynamics::core;

namespace {

/// The snap-load closed form's tolerance (as docs/validation.md "Slack lines and snap loads" for
/// 3-D): the lumped fallback and the implicit steps resolve the snap on the rope's mesh.
constexpr double kSnapRelTol = 0.005;
/// Top-tension peaks per heave cycle, 2-D against the planar 3-D run: the implicit steps agree to
/// 2e-6 of the tension (docs/method.md "3-D model") and both fall back on the same lumped model,
/// but their box-to-lumped conversions differ (angles against frames) and the fallback takes
/// different steps; measured 0.2 % on ten cycles.
constexpr double kPlanarPeakRelTol = 0.02;

/// config/heaved_slack.yaml with `compression: false` on its chain too (issue case: the 2-D run
/// stopped at t = 0.58 s before the fallback).
Problem heavedSlackNoCompression(double duration) {
  Problem p = loadProblemFromFile("config/heaved_slack.yaml");
  for (Material& m : p.materials) m.compression = false;
  p.dynamics.duration = duration;
  return p;
}

double smallest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

double peakIn(const DynamicSeries& r, double t0, double t1) {
  double hi = -1e300;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] >= t0 && r.t[i] < t1) hi = std::max(hi, r.top_tension[i]);
  return hi;
}

}  // namespace

TEST(Dynamics2DFallback, SnapOfAWeightDroppedOnASlackRopeMeetsTheClosedForm) {
  // test/data/snap_inline_weight.yaml: the weight inline above a light tail (no free end in 2-D).
  const Problem p = loadProblemFromFile("test/data/snap_inline_weight.yaml");
  ASSERT_EQ(p.formulation, Formulation::TwoD);
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_GT(r.fallback_steps, 0) << "the rope folds under the dropping point";
  const double W = 981.0, k = 1e5 / 10.0, h = 0.5;
  const double closed = W * (1.0 + std::sqrt(1.0 + 2.0 * k * h / W));
  const double peak = *std::max_element(r.top_tension.begin(), r.top_tension.end());
  std::printf("2-D snap: peak %.1f N against %.1f N (%+.2f %%), %ld fallback steps\n", peak, closed,
              100.0 * (peak / closed - 1.0), r.fallback_steps);
  EXPECT_NEAR(peak, closed, kSnapRelTol * closed);
  EXPECT_EQ(smallest(r.top_tension), 0.0) << "the rope is slack while the weight falls";
  // Without the fallback the implicit step alone stops while the rope is folded.
  Problem off = p;
  off.dynamics.fallback = false;
  const DynamicSeries s = runDynamic(off);
  EXPECT_FALSE(s.completed);
  EXPECT_EQ(s.fallback_steps, 0);
}

TEST(Dynamics2DFallback, HeavedSlackLineWithoutCompressionRunsThroughLikeThePlanar3DSolver) {
  const Problem p = heavedSlackNoCompression(12.0);  // four heave cycles, each slack then snapped
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_GT(r.fallback_steps, 0);
  EXPECT_GE(r.fallback_substeps, r.fallback_steps);
  // Neither chain nor rope pushes: every published tension >= 0, exactly.
  EXPECT_GE(smallest(r.top_tension), 0.0);
  EXPECT_GE(smallest(r.anchor_tension), 0.0);
  for (const auto& series : r.node_tension) EXPECT_GE(smallest(series), 0.0);
  EXPECT_EQ(smallest(r.top_tension), 0.0) << "the top goes slack in every cycle";
  // The same line on the 3-D equations in its plane, with the 3-D fallback.
  Problem p3 = p;
  p3.formulation = Formulation::ThreeD;
  const DynamicSeries r3 = runDynamic3D(p3);
  ASSERT_TRUE(r3.completed) << r3.message;
  const double T0 = r.initial_static.nodes.back().tension;
  for (int c = 0; c < 4; ++c) {
    const double a = peakIn(r, 3.0 * c, 3.0 * (c + 1)), b = peakIn(r3, 3.0 * c, 3.0 * (c + 1));
    std::printf("cycle %d: top tension peak 2-D %.1f N, 3-D %.1f N (static %.1f N)\n", c, a, b, T0);
    EXPECT_NEAR(a, b, kPlanarPeakRelTol * b) << "cycle " << c;
    EXPECT_GT(a, T0) << "it snaps above its static tension";
  }
}

TEST(Dynamics2DFallback, StopsWithoutItAndCountsItsSteps) {
  // The issue's case without the fallback stops early (the implicit step alone, at its smallest
  // step), with the reason; with it, the solver's totals count the fallback steps.
  Problem p = heavedSlackNoCompression(3.0);
  p.dynamics.fallback = false;
  const DynamicSeries off = runDynamic(p);
  EXPECT_FALSE(off.completed);
  EXPECT_LT(off.t.back(), 1.0) << off.message;
  p.dynamics.fallback = true;
  DynamicSolver2D solver(p);
  const StepReport rep = solver.advanceTo(3.0);
  ASSERT_TRUE(rep.ok) << rep.message;
  EXPECT_EQ(solver.time(), 3.0);
  EXPECT_GT(solver.totals().fallback_steps, 0);
  EXPECT_LE(solver.totals().fallback_steps, solver.totals().steps);
}

TEST(Dynamics2DFallback, ATautWireHeldStillInTheFallbackKeepsItsTension) {
  // A taut wire (EA = 1e8 N, 10 kN) on a coarse mesh (11.1 m intervals, turning up to 0.29 rad
  // over one) held still, every step taken by the fallback (a Newton tolerance no step meets).
  // Measured against h, the lumped chords would start 1 % short of the box state's stretched
  // length: the first step took the anchor from 4 kN to 122 kN and the top swung between -41 and
  // +86 kN. Against h cos(dphi / 2) (lumped_line.hpp, kMaxChordCorrection) the line stays at its
  // tension: the lumped line settles to its own equilibrium (measured 4.6 % below the box's on
  // this mesh) with a swing of 0.3 % of the static tension.
  constexpr double kSwingRelTol = 0.01;    // rms swing of the top tension about its mean
  constexpr double kSettleRelTol = 0.06;   // the lumped equilibrium's distance from the box's
  const Problem p = loadProblemFromString(R"(
name: taut wire held still, every step by the fallback
environment: {depth: 80, seabed: {stiffness: 1.0e6}}
materials:
  wire: {EA: 1.0e8, EI: 1.0, GJ: 1.0, mass: 11.82, added_mass: 1.63, wet_weight: 100.0,
         diameter: 0.045, cdn: 1.2, cdt: 0.01}
line:
  - {material: wire, length: 100.0, spacing: 11.5}
anchor: {x: 0, z: -60}
top:
  position: {x: 70, z: 0}
dynamics:
  duration: 10
  dt: 0.1
  max_iterations: 1
  max_cut_levels: 0
  tolerance: 1.0e-300
  top_motion: {type: sinusoid, amplitude_z: 0.0, period: 5, prescribe: position}
)");
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_EQ(r.fallback_steps, r.steps) << "every step by the fallback";
  const double T0 = r.initial_static.nodes.back().tension;
  double mean = 0.0, sq = 0.0;
  for (double T : r.top_tension) mean += T / static_cast<double>(r.top_tension.size());
  for (double T : r.top_tension) sq += (T - mean) * (T - mean) / static_cast<double>(r.top_tension.size());
  std::printf("taut wire in the fallback: static %.1f N, mean %.1f N, rms swing %.1f N, anchor %.1f to %.1f N\n", T0,
              mean, std::sqrt(sq), smallest(r.anchor_tension),
              *std::max_element(r.anchor_tension.begin(), r.anchor_tension.end()));
  EXPECT_LT(std::sqrt(sq), kSwingRelTol * T0);
  EXPECT_NEAR(mean, T0, kSettleRelTol * T0);
  EXPECT_GT(smallest(r.anchor_tension), 0.0);
}

TEST(Dynamics2DFallback, PaperChainMooringWithoutCompressionRunsThroughWithTheSameStatistics) {
  // Paper A.3 (config/chain_mooring.yaml, a surface buoy heaved 2 m every 8 s, 300 s) with
  // `compression: false` on its chains: the implicit step alone stopped in the start transient at
  // t = 0.13 s (the top is a surface buoy, whose motion is prescribed in dynamics, which the
  // fallback now takes). The law through zero pushes only briefly and little in this case, so the
  // top tension's mean and standard deviation stay those of the paper case's run (validated
  // against the paper's figure in docs/validation.md): measured 0.2 % and 0.3 % apart.
  constexpr double kStatisticsRelTol = 0.01;
  Problem p = loadProblemFromFile("config/chain_mooring.yaml");
  const DynamicSeries ref = runDynamic(p);
  for (Material& m : p.materials) m.compression = false;
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(ref.completed) << ref.message;
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_GT(r.fallback_steps, 0);
  auto meanStd = [](const std::vector<double>& v) {
    double m = 0.0, q = 0.0;
    for (double x : v) m += x / static_cast<double>(v.size());
    for (double x : v) q += (x - m) * (x - m) / static_cast<double>(v.size());
    return std::make_pair(m, std::sqrt(q));
  };
  const auto [m0, s0] = meanStd(ref.top_tension);
  const auto [m1, s1] = meanStd(r.top_tension);
  std::printf("A.3 top tension: law through zero mean %.1f N std %.1f N; no compression mean %.1f N std %.1f N, %ld fallback steps\n",
              m0, s0, m1, s1, r.fallback_steps);
  EXPECT_NEAR(m1, m0, kStatisticsRelTol * m0);
  EXPECT_NEAR(s1, s0, kStatisticsRelTol * s0);
  EXPECT_GE(smallest(r.top_tension), 0.0);
  EXPECT_GE(smallest(r.anchor_tension), 0.0);
}
