// The Newton options of a dynamic time step (dynamic_run.hpp: stepNewtonOptions, sameStepSize)
// on the shipped 2-D problems: modified Newton (dynamics.jacobian_reuse) keeps its factorization
// across output samples and gives plain Newton's series with fewer assemblies; two-cycle damping
// (dynamics.damp_two_cycles) saves iterations at touchdown and keeps the series.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mooring_dynamics/core/solvers/dynamic_run.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"

using namespace mooring_dynamics::core;

// Modified Newton (dynamics.jacobian_reuse) keeps the factorization from step to step of the
// same size, also when a step lands on an output sample and its size t_end - t differs from
// dt = 0.1 s in the last bits (it used to reassemble at most of those steps: 60 Jacobians in the
// 100 steps below, now 4).
TEST(DynamicRun, JacobianReuseKeepsTheFactorizationAcrossOutputSamples) {
  Problem p = loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/s_tether.yaml");
  p.dynamics.duration = 10.0;
  p.dynamics.dt = 0.1;  // not a binary fraction: the sample times round
  p.dynamics.output_interval = 0.0;
  p.dynamics.jacobian_reuse = true;
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_EQ(r.cuts, 0);
  constexpr double kMaxJacobiansPerStep = 0.2;  // a smooth sea state: a fresh one now and then
  EXPECT_LT(static_cast<double>(r.jacobians), kMaxJacobiansPerStep * static_cast<double>(r.steps))
      << r.jacobians << " Jacobians in " << r.steps << " steps";
}

namespace {

/// Largest difference between the top tensions of two completed runs of the same problem [N]
/// (fatal failures when either did not complete or their samples differ in number).
double largestTopTensionDifference(const DynamicSeries& a, const DynamicSeries& b) {
  double worst = 0.0;
  [&] {
    ASSERT_TRUE(a.completed) << a.message;
    ASSERT_TRUE(b.completed) << b.message;
    ASSERT_EQ(a.top_tension.size(), b.top_tension.size());
    for (std::size_t i = 0; i < a.top_tension.size(); ++i)
      worst = std::max(worst, std::abs(a.top_tension[i] - b.top_tension[i]));
  }();
  return worst;
}

}  // namespace

// Modified Newton stops on the same tolerance as plain Newton, so the series agree to well within
// what the tolerance allows; with a kept Jacobian the rate's change over the last step is
// extrapolated as well (second-order predictor, as in 3-D), which starts the linear iteration
// closer: on the first 30 s below 3.0 iterations per step instead of 3.26 with the constant-rate
// predictor (over the whole 600 s 3.50 against 3.75; plain Newton 2.05).
TEST(DynamicRun, JacobianReuseGivesPlainNewtonsSeries) {
  Problem p = loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/s_tether.yaml");
  p.dynamics.duration = 30.0;
  p.dynamics.dt = 0.1;
  p.dynamics.snapshot_interval = 0.0;
  p.dynamics.jacobian_reuse = false;  // (the shipped file keeps its Jacobians)
  const DynamicSeries plain = runDynamic(p);
  p.dynamics.jacobian_reuse = true;
  const DynamicSeries kept = runDynamic(p);
  double worst = 0.0;
  ASSERT_NO_FATAL_FAILURE(worst = largestTopTensionDifference(plain, kept));
  // A converged step is within about the tolerance 1e-6 of chi (eq. 39) of the exact step
  // solution; over these 300 steps the top tension (9 kN) moved by 0.006 N at most.
  constexpr double kTensionAgreement = 0.1;  // [N], against 2.5 kN of wave-driven std
  EXPECT_LT(worst, kTensionAgreement);
  constexpr double kMaxIterationsPerStep = 3.15;  // second-order predictor 3.00, constant rate 3.26
  EXPECT_LT(static_cast<double>(kept.newton_iterations), kMaxIterationsPerStep * static_cast<double>(kept.steps))
      << kept.newton_iterations << " iterations in " << kept.steps << " steps";
}

// dynamics.damp_two_cycles on the shipped chain mooring (A.3): touchdown nodes that cycle in and
// out of contact are settled by halving the update that undoes the one before, so the steps take
// fewer iterations to the same tolerance and the top tension stays where plain Newton puts it.
TEST(DynamicRun, TwoCycleDampingSavesIterationsAtTouchdown) {
  Problem p = loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/chain_mooring.yaml");
  p.dynamics.duration = 40.0;
  p.dynamics.snapshot_interval = 0.0;
  p.dynamics.record_s.clear();
  const DynamicSeries plain = runDynamic(p);
  p.dynamics.damp_two_cycles = true;
  const DynamicSeries damped = runDynamic(p);
  double worst = 0.0;
  ASSERT_NO_FATAL_FAILURE(worst = largestTopTensionDifference(plain, damped));
  // Measured: 1652 -> 1591 iterations, the same 2 cuts, 0.07 N at most apart. For scale, halving
  // A.3's base step moves this series by some 200 N rms (docs/validation.md).
  constexpr double kTensionAgreement = 1.0;  // [N]
  EXPECT_LT(worst, kTensionAgreement);
  EXPECT_EQ(damped.cuts, plain.cuts);
  EXPECT_LT(static_cast<double>(damped.newton_iterations), 0.98 * static_cast<double>(plain.newton_iterations));
}

// A kept Jacobian stops on the estimated error left only where the scheme damps the highest
// frequencies: box (spectral radius 1 at infinity) keeps what each step leaves, and on A.2 at
// 0.1 s took 34 001 iterations with the estimate against 29 325 without (method.md, "Stopping a
// time step's iteration").
TEST(DynamicRun, KeptJacobianEstimateOnlyWithADampingScheme) {
  DynamicOptions o;
  o.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  EXPECT_GT(stepNewtonOptions(o).estimate_kept_margin, 0.0);
  EXPECT_TRUE(stepNewtonOptions(o).estimate_convergence);
  o.scheme = GeneralizedAlpha::preset("box");
  EXPECT_EQ(stepNewtonOptions(o).estimate_kept_margin, 0.0);
  EXPECT_TRUE(stepNewtonOptions(o).estimate_convergence);  // fresh Jacobians still stop on it
}
