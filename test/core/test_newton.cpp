// solveNewton (paper section 6, eqs. 38-41) on small systems with known behaviour: a banded
// nonlinear system with a known root, the adaptive relaxation rule checked step by step from the
// recorded iterates, the clamps of mu to [mu0/1000, mu0], and the failure reports.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "mooring_dynamics/core/numerics/newton.hpp"

using namespace mooring_dynamics::core;

namespace {

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

/// x_i^3 + x_i - b_i + c (x_{i-1} + x_{i+1}) = 0 with b chosen so that `root` solves it.
/// Tridiagonal Jacobian: 3 x_i^2 + 1 on the diagonal, c beside it. Records every iterate.
class CubicChain : public NewtonSystem {
 public:
  static constexpr double c = 0.1;
  explicit CubicChain(const Eigen::VectorXd& root) : b_(root.size()) {
    for (int i = 0; i < root.size(); ++i) b_[i] = std::pow(root[i], 3) + root[i] + c * neighbours(root, i);
  }
  int size() const override { return static_cast<int>(b_.size()); }
  int lowerBandwidth() const override { return 1; }
  int upperBandwidth() const override { return 1; }
  void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override {
    iterates.push_back(Y);
    for (int i = 0; i < size(); ++i) R[i] = std::pow(Y[i], 3) + Y[i] - b_[i] + c * neighbours(Y, i);
    if (!J) return;
    for (int i = 0; i < size(); ++i) {
      J->at(i, i) = 3.0 * Y[i] * Y[i] + 1.0;
      if (i > 0) J->at(i, i - 1) = c;
      if (i + 1 < size()) J->at(i, i + 1) = c;
    }
  }
  double scale(int) const override { return 1.0; }
  std::string describe(int i) const override { return "x[" + std::to_string(i) + "]"; }
  std::vector<Eigen::VectorXd> iterates;

 private:
  double neighbours(const Eigen::VectorXd& x, int i) const {
    return (i > 0 ? x[i - 1] : 0.0) + (i + 1 < x.size() ? x[i + 1] : 0.0);
  }
  Eigen::VectorXd b_;
};

/// One unknown: R = f(x), J = f'(x). Records every iterate.
class Scalar : public NewtonSystem {
 public:
  Scalar(std::function<double(double)> f, std::function<double(double)> df, double chi = 1.0)
      : f_(std::move(f)), df_(std::move(df)), chi_(chi) {}
  int size() const override { return 1; }
  int lowerBandwidth() const override { return 0; }
  int upperBandwidth() const override { return 0; }
  void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override {
    iterates.push_back(Y[0]);
    R[0] = f_(Y[0]);
    if (J) J->at(0, 0) = df_(Y[0]);
  }
  double scale(int) const override { return chi_; }
  std::string describe(int) const override { return "the scalar unknown"; }
  /// The Newton update at x, computed as the 1x1 LU solve does: -R / J.
  double update(double x) const { return -f_(x) / df_(x); }
  std::vector<double> iterates;

 private:
  std::function<double(double)> f_, df_;
  double chi_;
};

Scalar atanSystem() {
  return Scalar([](double x) { return std::atan(x); }, [](double x) { return 1.0 / (1.0 + x * x); });
}

/// Relaxation factors actually applied, recovered from consecutive iterates: mu_k = dx_k / dY_k
/// (NaN where the update is exactly zero and mu cannot be observed).
std::vector<double> appliedRelaxation(const Scalar& s, double final_x) {
  std::vector<double> x = s.iterates;
  x.push_back(final_x);
  std::vector<double> mu;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const double dY = s.update(x[k]);
    mu.push_back(dY != 0.0 ? (x[k + 1] - x[k]) / dY : std::nan(""));
  }
  return mu;
}

// mu recovered from iterates of magnitude <= ~10 and updates >= ~1e-9: rounding only.
constexpr double kMuTol = 1e-6;

/// f(x) = x - 0.5 solved from x = 1.5 (options `o`, reuse_jacobian on) with the factorization
/// that a solve of slope 1 / (1 - rate) leaves in the workspace: every update made with it shrinks
/// the error by exactly `rate`. Returns the error left, x - 0.5.
double solveWithKeptSlope(double rate, const NewtonOptions& o, NewtonWork* w, SolverSummary* summary) {
  Scalar seed([rate](double x) { return (x - 2.0) / (1.0 - rate); }, [rate](double) { return 1.0 / (1.0 - rate); });
  Scalar line([](double x) { return x - 0.5; }, [](double) { return 1.0; });
  BandedMatrix ws;
  Eigen::VectorXd Y(1);
  Y[0] = 0.0;
  EXPECT_TRUE(solveNewton(seed, Y, o, &ws).converged);  // leaves its factorization in ws
  Y[0] = 1.5;
  *summary = solveNewton(line, Y, o, &ws, w);
  return Y[0] - 0.5;
}

}  // namespace

TEST(Newton, BandedCubicSystemConvergesQuadraticallyToTheRoot) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  Eigen::VectorXd root(30);
  for (int i = 0; i < root.size(); ++i) root[i] = u(rng);
  for (const bool adaptive : {false, true}) {
    CubicChain sys(root);
    Eigen::VectorXd Y = Eigen::VectorXd::Zero(root.size());
    NewtonOptions o;
    o.tolerance = 1e-12;
    o.adaptive = adaptive;
    const SolverSummary s = solveNewton(sys, Y, o);
    ASSERT_TRUE(s.converged) << s.message;
    constexpr double kRootTol = 1e-11;  // last update < 1e-12 per unknown and shrinking quadratically
    EXPECT_LT((Y - root).cwiseAbs().maxCoeff(), kRootTol);
    // Newton from 0 on this well-conditioned system: a handful of iterations, not dozens.
    EXPECT_LE(s.iterations, 10);
    EXPECT_EQ(static_cast<std::size_t>(s.iterations), sys.iterates.size());
    EXPECT_LT(s.error, o.tolerance);
    EXPECT_EQ(s.relaxation, 1.0);
    EXPECT_TRUE(contains(s.message, "converged"));
    // sigma_k = mean |Y_{k+1} - Y_k| (mu = 1). Near the root it falls quadratically:
    // sigma_{k+1} <= C sigma_k^2, C ~ max|f''| / (2 min|f'|) = 9 / 2 for |x| <= 1.5.
    std::vector<double> sigma;
    for (std::size_t k = 0; k + 1 < sys.iterates.size(); ++k)
      sigma.push_back((sys.iterates[k + 1] - sys.iterates[k]).cwiseAbs().mean());
    int quadratic_steps = 0;
    for (std::size_t k = 0; k + 1 < sigma.size(); ++k) {
      if (sigma[k] > 1e-2 || sigma[k + 1] < 1e-14) continue;  // not yet near the root / at round-off
      EXPECT_LE(sigma[k + 1], 10.0 * sigma[k] * sigma[k]) << "step " << k;
      ++quadratic_steps;
    }
    EXPECT_GE(quadratic_steps, 1);
  }
}

TEST(Newton, SigmaIsTheScaledMeanUpdate) {
  // Linear R = Y - c from Y = 0: the first update is c exactly, so sigma (eq. 39) is
  // (|c0| / chi0 + |c1| / chi1) / 2 = (3 / 0.5 + 4 / 8) / 2 = 3.25.
  class Linear : public NewtonSystem {
   public:
    int size() const override { return 2; }
    int lowerBandwidth() const override { return 0; }
    int upperBandwidth() const override { return 0; }
    void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override {
      R[0] = Y[0] + 3.0;
      R[1] = Y[1] - 4.0;
      if (J) J->at(0, 0) = J->at(1, 1) = 1.0;
    }
    double scale(int i) const override { return i == 0 ? 0.5 : 8.0; }
    std::string describe(int i) const override { return "y" + std::to_string(i); }
  } sys;
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(2);
  NewtonOptions o;
  o.max_iterations = 1;
  const SolverSummary s = solveNewton(sys, Y, o);
  EXPECT_FALSE(s.converged);
  EXPECT_DOUBLE_EQ(s.error, 3.25);
  EXPECT_DOUBLE_EQ(Y[0], -3.0);
  EXPECT_DOUBLE_EQ(Y[1], 4.0);
  // The largest scaled update is y0 (3 / 0.5 = 6 against 0.5).
  EXPECT_TRUE(contains(s.message, "y0"));
}

TEST(Newton, PlainNewtonDivergesOnAtanAdaptiveRelaxationConverges) {
  // Plain Newton on atan(x) = 0 diverges for |x0| > 1.3917 (the iterates alternate in sign and
  // grow). From 1.45 the adaptive rule cuts mu fast enough (mu / 1.1 per growing step) to recover.
  // (From x0 = 2 the iterates blow up within ~10 steps, too fast for R1 = 1.1 to catch.)
  {
    Scalar sys = atanSystem();
    Eigen::VectorXd Y(1);
    Y[0] = 1.45;
    NewtonOptions o;
    o.adaptive = false;
    const SolverSummary s = solveNewton(sys, Y, o);
    EXPECT_FALSE(s.converged);
    EXPECT_FALSE(s.message.empty());
    // It genuinely diverged: the iterates grew in magnitude step after step.
    ASSERT_GE(sys.iterates.size(), 4u);
    for (std::size_t k = 0; k + 1 < 4; ++k) EXPECT_GT(std::abs(sys.iterates[k + 1]), std::abs(sys.iterates[k]));
  }
  {
    Scalar sys = atanSystem();
    Eigen::VectorXd Y(1);
    Y[0] = 1.45;
    NewtonOptions o;  // adaptive, R1 = 1.1, R2 = 1.02, mu0 = 1
    const SolverSummary s = solveNewton(sys, Y, o);
    ASSERT_TRUE(s.converged) << s.message;
    constexpr double kRootTol = 1e-9;  // the last update was below the tolerance 1e-9
    EXPECT_NEAR(Y[0], 0.0, kRootTol);
    EXPECT_LE(s.iterations, 30);
    // The rule had to act: at least one step was taken with mu < mu0.
    const std::vector<double> mu = appliedRelaxation(sys, Y[0]);
    double smallest = 1.0;
    for (double m : mu)
      if (!std::isnan(m)) smallest = std::min(smallest, m);
    EXPECT_LT(smallest, 0.95);
  }
}

TEST(Newton, AdaptiveRuleFollowsEquations40And41) {
  // Replay the rule independently: mu_0 = mu0; then mu_k = mu_{k-1} / R1 when sigma_k > sigma_{k-1}
  // (eq. 40), mu_{k-1} * R2 otherwise (eq. 41), clamped to [mu0 / 1000, mu0].
  struct Case { double x0, mu0, R1, R2; };
  for (const Case c : {Case{1.45, 1.0, 1.1, 1.02}, Case{1.42, 1.0, 1.1, 1.02}, Case{1.6, 1.0, 1.3, 1.05},
                       Case{1.5, 0.95, 1.3, 1.05}, Case{1.6, 1.0, 1.5, 1.1}}) {
    const double x0 = c.x0;
    Scalar sys = atanSystem();
    Eigen::VectorXd Y(1);
    Y[0] = x0;
    NewtonOptions o;
    o.mu0 = c.mu0;
    o.R1 = c.R1;
    o.R2 = c.R2;
    o.max_iterations = 60;
    const SolverSummary s = solveNewton(sys, Y, o);
    const std::vector<double> mu = appliedRelaxation(sys, Y[0]);
    ASSERT_EQ(mu.size(), sys.iterates.size());
    ASSERT_GE(mu.size(), 3u);
    double expected = o.mu0;
    bool reduced = false, increased = false;
    for (std::size_t k = 0; k < mu.size(); ++k) {
      if (k > 0) {
        const double sk = std::abs(sys.update(sys.iterates[k]));
        const double sp = std::abs(sys.update(sys.iterates[k - 1]));
        if (sk > sp) { expected /= o.R1; reduced = true; }
        else {
          expected *= o.R2;
          if (expected < o.mu0) increased = true;  // eq. 41 visible below the cap
        }
        expected = std::min(std::max(expected, o.mu0 / 1000.0), o.mu0);
      }
      if (!std::isnan(mu[k])) {
        EXPECT_NEAR(mu[k], expected, kMuTol) << "x0 " << x0 << " iteration " << k;
      }
    }
    EXPECT_NEAR(s.relaxation, expected, kMuTol);
    EXPECT_TRUE(reduced) << "x0 " << x0 << ": the test never exercised eq. 40";
    EXPECT_TRUE(increased) << "x0 " << x0 << ": the test never exercised eq. 41 below the cap";
    EXPECT_TRUE(s.converged) << s.message;
  }
}

TEST(Newton, RelaxationNeverExceedsMu0) {
  // Linear R = x - 1 from x = 2 with mu0 = 0.5: sigma halves every step, so eq. 41 keeps asking
  // for a larger mu, which the cap holds at 0.5. Then x_k = 1 + 2^-k and sigma_k = 2^-k exactly:
  // the first sigma below 1e-9 is 2^-30, at the 31st iteration.
  for (const bool adaptive : {true, false}) {
    Scalar sys([](double x) { return x - 1.0; }, [](double) { return 1.0; });
    Eigen::VectorXd Y(1);
    Y[0] = 2.0;
    NewtonOptions o;
    o.mu0 = 0.5;
    o.adaptive = adaptive;
    const SolverSummary s = solveNewton(sys, Y, o);
    ASSERT_TRUE(s.converged);
    EXPECT_EQ(s.iterations, 31);
    EXPECT_DOUBLE_EQ(s.error, std::ldexp(1.0, -30));
    EXPECT_DOUBLE_EQ(s.relaxation, 0.5);
    EXPECT_DOUBLE_EQ(Y[0], 1.0 + std::ldexp(1.0, -31));
    for (double m : appliedRelaxation(sys, Y[0])) EXPECT_DOUBLE_EQ(m, 0.5);
  }
}

TEST(Newton, RelaxationFloorIsMu0Over1000AndNonConvergenceIsReported) {
  // R = 1/x has its root at infinity: the Newton update is +x, so sigma grows every step and
  // eq. 40 divides mu by R1 = 1.1 each time, down to the floor mu0/1000 after 73 steps
  // (1.1^72 < 1000 < 1.1^73), where it stays.
  Scalar sys([](double x) { return 1.0 / x; }, [](double x) { return -1.0 / (x * x); });
  Eigen::VectorXd Y(1);
  Y[0] = 1.0;
  NewtonOptions o;
  o.max_iterations = 100;
  SolverSummary s;
  ASSERT_NO_THROW(s = solveNewton(sys, Y, o));
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, 100);
  EXPECT_DOUBLE_EQ(s.relaxation, 1e-3);
  const std::vector<double> mu = appliedRelaxation(sys, Y[0]);
  ASSERT_EQ(mu.size(), 100u);
  EXPECT_GT(mu[72], 1e-3 * (1.0 + 1e-9));
  for (std::size_t k = 73; k < mu.size(); ++k) EXPECT_NEAR(mu[k], 1e-3, 1e-3 * kMuTol) << "iteration " << k;
  EXPECT_TRUE(contains(s.message, "did not converge"));
  EXPECT_TRUE(contains(s.message, "100"));
  EXPECT_TRUE(contains(s.message, "the scalar unknown"));
  // Y holds the last iterate, not the initial guess.
  EXPECT_GT(Y[0], 1.0);
}

TEST(Newton, IterationLimitOnAConvergentSystem) {
  Eigen::VectorXd root = Eigen::VectorXd::Constant(8, 0.7);
  CubicChain sys(root);
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(8);
  NewtonOptions o;
  o.max_iterations = 2;
  SolverSummary s;
  ASSERT_NO_THROW(s = solveNewton(sys, Y, o));
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, 2);
  EXPECT_GT(s.error, o.tolerance);
  EXPECT_TRUE(contains(s.message, "did not converge"));
  EXPECT_TRUE(contains(s.message, "x["));
}

TEST(Newton, SingularJacobianNamesTheUnknown) {
  // Unknown 2 of 4 appears in no residual: its Jacobian column is zero, so elimination meets an
  // exactly zero pivot in column 2.
  class Decoupled : public NewtonSystem {
   public:
    int size() const override { return 4; }
    int lowerBandwidth() const override { return 1; }
    int upperBandwidth() const override { return 1; }
    void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override {
      R[0] = Y[0] - 1.0;
      R[1] = Y[1] + Y[0];
      R[2] = Y[3] - Y[1];
      R[3] = Y[3] - 2.0;
      if (!J) return;
      J->at(0, 0) = 1.0;
      J->at(1, 1) = 1.0;
      J->at(1, 0) = 1.0;
      J->at(2, 3) = 1.0;
      J->at(2, 1) = -1.0;
      J->at(3, 3) = 1.0;
    }
    double scale(int) const override { return 1.0; }
    std::string describe(int i) const override { return "unknown #" + std::to_string(i) + " (tension)"; }
  } sys;
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(4);
  SolverSummary s;
  ASSERT_NO_THROW(s = solveNewton(sys, Y, NewtonOptions()));
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, 0);
  EXPECT_TRUE(contains(s.message, "singular"));
  EXPECT_TRUE(contains(s.message, "unknown #2 (tension)"));
  EXPECT_EQ(Y, Eigen::VectorXd::Zero(4));  // no update was applied
}

TEST(Newton, NonFiniteResidualIsReported) {
  Scalar sys([](double x) { return std::log(x); }, [](double x) { return 1.0 / x; });
  Eigen::VectorXd Y(1);
  Y[0] = -1.0;
  SolverSummary s;
  ASSERT_NO_THROW(s = solveNewton(sys, Y, NewtonOptions()));
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, 0);
  EXPECT_TRUE(contains(s.message, "not finite"));
}

TEST(Newton, ModifiedNewtonReachesTheSameRootWithFewerJacobians) {
  // Modified Newton (reuse_jacobian): the same root to the tolerance; a second solve from a
  // nearby start reuses the first call's factorization (none assembled unless it contracts
  // too slowly); plain Newton assembles at every iterate.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd root(30);
  for (int i = 0; i < root.size(); ++i) root[i] = u(rng);
  CubicChain sys(root);
  NewtonOptions plain;
  plain.tolerance = 1e-12;
  NewtonOptions kept = plain;
  kept.reuse_jacobian = true;
  BandedMatrix ws;
  NewtonWork wp, wk, wk2;
  Eigen::VectorXd Yp = Eigen::VectorXd::Constant(root.size(), 0.1), Yk = Yp;
  ASSERT_TRUE(solveNewton(sys, Yp, plain, nullptr, &wp).converged);
  ASSERT_TRUE(solveNewton(sys, Yk, kept, &ws, &wk).converged);
  constexpr double kRootTol = 1e-10;  // both stop on updates below 1e-12 per unknown
  EXPECT_LT((Yp - root).cwiseAbs().maxCoeff(), kRootTol);
  EXPECT_LT((Yk - root).cwiseAbs().maxCoeff(), kRootTol);
  EXPECT_EQ(wp.residuals, 0);
  EXPECT_LT(wk.assemblies, wp.assemblies);
  EXPECT_GT(wk.residuals, 0);
  // A nearby start: the kept factorization is used from the first iteration.
  Eigen::VectorXd Y2 = root + Eigen::VectorXd::Constant(root.size(), 1e-4);
  ASSERT_TRUE(solveNewton(sys, Y2, kept, &ws, &wk2).converged);
  EXPECT_EQ(wk2.assemblies, 0);
  EXPECT_LT((Y2 - root).cwiseAbs().maxCoeff(), kRootTol);
}

TEST(Newton, KeptJacobianWhoseUpdateDivergesIsUndone) {
  // A factorization kept from another call (slope 0.1) makes the first update of the next call
  // (slope 1) ten times too long: the iteration grows, so that update is undone and redone from
  // the start with a fresh Jacobian, which then solves the linear problem exactly.
  Scalar shallow([](double x) { return 0.1 * (x - 2.0); }, [](double) { return 0.1; });
  Scalar steep([](double x) { return x - 0.5; }, [](double) { return 1.0; });
  NewtonOptions kept;
  kept.reuse_jacobian = true;
  kept.adaptive = false;
  BandedMatrix ws;
  Eigen::VectorXd Y(1);
  Y[0] = 0.0;
  ASSERT_TRUE(solveNewton(shallow, Y, kept, &ws).converged);
  Y[0] = 1.0;
  NewtonWork w;
  const SolverSummary s = solveNewton(steep, Y, kept, &ws, &w);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_DOUBLE_EQ(Y[0], 0.5);
  // Iterates: the start, the kept update's overshoot (1 - 0.5 / 0.1), the start again (undone),
  // the root.
  const std::vector<double> expected = {1.0, -4.0, 1.0, 0.5};
  EXPECT_EQ(steep.iterates, expected);
  EXPECT_EQ(w.assemblies, 1);
  EXPECT_EQ(s.iterations, 2);  // the undone update does not count
}

TEST(Newton, EstimatedConvergenceSavesTheConfirmingIteration) {
  // With estimate_convergence the iteration stops once theta / (1 - theta) sigma_k is below the
  // tolerance: one update earlier than eq. 39 alone on this quadratically converging problem,
  // and the iterate is still within the tolerance of the root (the measure of eq. 39, chi = 1).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd root(40);
  for (int i = 0; i < root.size(); ++i) root[i] = u(rng);
  CubicChain sys(root);
  NewtonOptions plain;
  plain.tolerance = 1e-8;
  NewtonOptions est = plain;
  est.estimate_convergence = true;
  Eigen::VectorXd Yp = Eigen::VectorXd::Constant(root.size(), 0.2), Ye = Yp;
  const SolverSummary sp = solveNewton(sys, Yp, plain);
  const SolverSummary se = solveNewton(sys, Ye, est);
  ASSERT_TRUE(sp.converged);
  ASSERT_TRUE(se.converged);
  EXPECT_EQ(se.iterations, sp.iterations - 1);
  EXPECT_LT((Ye - root).cwiseAbs().mean(), plain.tolerance);
  EXPECT_GT(se.error, plain.tolerance);  // stopped on the estimate, not on the last update
}

TEST(Newton, EstimatedConvergenceWithAKeptJacobianHoldsAMarginBelowTheTolerance) {
  // A kept Jacobian of slope 1 / (1 - r) on f(x) = x - 0.5 contracts the error by r = 0.05 at
  // every update: updates sigma_k = (1 - r) r^(k - 1) from an error of 1, and after update k the
  // error left is exactly the estimate theta / (1 - theta) sigma_k (theta = r). The estimate
  // stops the iteration once it is below estimate_kept_margin (0.1) times the tolerance.
  constexpr double kRate = 0.05;
  auto keptRun = [&](double tolerance, int* iterations) {
    NewtonOptions o;
    o.reuse_jacobian = true;
    o.adaptive = false;  // updates applied in full
    o.estimate_convergence = true;
    o.tolerance = tolerance;
    NewtonWork w;
    SolverSummary s;
    const double error = solveWithKeptSlope(kRate, o, &w, &s);
    EXPECT_TRUE(s.converged) << s.message;
    EXPECT_EQ(w.assemblies, 0);  // every update with the kept Jacobian
    *iterations = s.iterations;
    return error;
  };
  const double margin = NewtonOptions().estimate_kept_margin;
  ASSERT_EQ(margin, 0.1);
  int its = 0;
  // Tolerance 4e-6: sigma_5 = 5.9e-6 is above it, its estimate 3.1e-7 below 0.1 of it: five
  // updates where eq. 39 alone takes six (sigma_6 = 3.0e-7); the error left is the estimate.
  double error = keptRun(4e-6, &its);
  EXPECT_EQ(its, 5);
  EXPECT_LT(std::abs(error), margin * 4e-6);
  // Tolerance 8e-6: the estimate after update 4, 6.25e-6, is below the tolerance but not below
  // 0.1 of it: the iteration goes on to sigma_5 = 5.9e-6 (eq. 39), where an estimate held to the
  // tolerance itself would have stopped at an error of 6.25e-6.
  error = keptRun(8e-6, &its);
  EXPECT_EQ(its, 5);
  EXPECT_LT(std::abs(error), margin * 8e-6);
}

// Newton on sign(x) sqrt|x| jumps from x to -x forever (the update is -2x): a two-cycle with
// sigma constant, which eq. 40 never sees. damp_two_cycles halves the second update, which lands
// on the root. A shrinking alternation (a Jacobian too small by 0.7: x -> -0.43 x) converges
// and is left alone: the same iterates with the option as without.
TEST(Newton, TwoCycleDampingLandsBetweenTheTwoIterates) {
  auto f = [](double x) { return std::copysign(std::sqrt(std::abs(x)), x); };
  auto df = [](double x) { return 0.5 / std::sqrt(std::max(std::abs(x), 1e-300)); };
  NewtonOptions o;
  o.tolerance = 1e-12;
  o.max_iterations = 40;
  {
    Scalar s(f, df);
    Eigen::VectorXd x(1);
    x[0] = 0.25;
    const SolverSummary r = solveNewton(s, x, o);
    EXPECT_FALSE(r.converged) << r.message;  // cycles between +-0.25 until the limit
    EXPECT_NEAR(std::abs(x[0]), 0.25, 1e-12);
  }
  o.damp_two_cycles = true;
  {
    Scalar s(f, df);
    Eigen::VectorXd x(1);
    x[0] = 0.25;
    const SolverSummary r = solveNewton(s, x, o);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_LE(r.iterations, 3);  // 0.25 -> -0.25 -> 0 (halved), then a zero update
    EXPECT_EQ(x[0], 0.0);
  }
  // Alternating but shrinking: x - x / 0.7 = -0.43 x per update.
  auto g = [](double x) { return x; };
  auto dg = [](double) { return 0.7; };
  std::vector<double> plain, damped;
  for (bool damp : {false, true}) {
    NewtonOptions q;
    q.tolerance = 1e-12;
    q.adaptive = false;
    q.damp_two_cycles = damp;
    Scalar s(g, dg);
    Eigen::VectorXd x(1);
    x[0] = 1.0;
    ASSERT_TRUE(solveNewton(s, x, q).converged);
    (damp ? damped : plain) = s.iterates;
  }
  EXPECT_EQ(plain, damped);
}

TEST(Newton, ReuseRateDecidesWhetherASlowKeptJacobianStays) {
  // A kept Jacobian of slope 1 / (1 - r) on f(x) = x - 0.5 contracts the error by exactly r = 0.3
  // at every update. Below reuse_rate (0.5) it stays to the end: no assembly, the updates shrink
  // by 0.3 each. Above it (the default 0.15) the second update is too slow, so a fresh Jacobian
  // is assembled, which solves this linear problem at once. Both end at the root within the
  // tolerance.
  constexpr double kRate = 0.3;
  constexpr double kTolerance = 1e-7;  // eq. 39 on the last update (chi = 1)
  auto run = [&](double reuse_rate, NewtonWork* w) {
    NewtonOptions o;
    o.reuse_jacobian = true;
    o.reuse_rate = reuse_rate;
    o.adaptive = false;  // updates applied in full
    o.tolerance = kTolerance;
    SolverSummary s;
    const double error = solveWithKeptSlope(kRate, o, w, &s);
    EXPECT_TRUE(s.converged) << s.message;
    return error;
  };
  ASSERT_EQ(NewtonOptions().reuse_rate, 0.15);
  NewtonWork slow_kept, fresh;
  EXPECT_LT(std::abs(run(0.5, &slow_kept)), kTolerance);
  EXPECT_EQ(slow_kept.assemblies, 0);
  // Updates (1 - r) r^(k - 1) from an error of 1 fall below 1e-7 at k = 15 (1.1e-7 at 14).
  EXPECT_EQ(slow_kept.residuals, 15);
  EXPECT_LT(std::abs(run(0.15, &fresh)), kTolerance);
  EXPECT_EQ(fresh.assemblies, 1);
  EXPECT_EQ(fresh.residuals, 3);  // the kept updates (the second redone fresh), the confirming one
}
