// Generalized-alpha time integration (paper section 4) against independent answers: the closed
// form of eq. 29 and Table 1, the second-order condition (eq. 27) checked by measuring the order,
// and the spectral radius of eq. 28 checked against eigenvalues of an amplification matrix that
// this file builds itself from the recurrence
//   (1 - am) Yd^i + am Yd^{i-1} + (1 - ak) K Y^i + ak K Y^{i-1} = 0,
//   Y^i = Y^{i-1} + dt ((1 - g) Yd^{i-1} + g Yd^i).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/time_integration.hpp"

using namespace mooring_dynamics::core;

namespace {

// Table 1 prints three decimals.
constexpr double kTableTol = 0.5e-3;
// Exact rationals from eq. 29 in double arithmetic.
constexpr double kExactTol = 1e-14;
// Eq. 28 against a numerical eigen-solve: near the cusp (a double eigenvalue) the eigenvalues of a
// 2x2 matrix are only sqrt(machine eps) ~ 1e-8 well conditioned; 1e-6 leaves margin.
constexpr double kSpectralTol = 1e-6;
// "As omega dt -> infinity": at omega dt = 1e6 the one-parameter family is within ~1/sqrt(1e6)
// of its limit (the discriminant of eq. 28 grows only linearly there); 2e-3 covers it.
constexpr double kLimitTol = 2e-3;
// Energy of a linear oscillator under the box (implicit midpoint) rule: round-off only, growing
// like sqrt(steps) * 1e-16; 1e-11 after 1e4 steps is far above that and far below any dissipation.
constexpr double kEnergyRoundOff = 1e-11;
// Measured order of accuracy: a least-squares slope over a factor-8 range of dt.
constexpr double kOrderBand = 0.1;

const char* const kPresets[] = {"box", "trapezoidal", "backward", "lambda0", "lambda-0.5", "lambda0.75"};

/// Amplification matrix of the scalar model problem y' + omega y = 0 (M = 1, "K" = omega) in the
/// state (y, dt * yd), written with x = omega dt:
///   (1 - am) v_i + x (1 - ak) y_i = -am v_{i-1} - x ak y_{i-1}
///   y_i - g v_i                   = y_{i-1} + (1 - g) v_{i-1}
Eigen::Matrix2d amplification(const GeneralizedAlpha& a, double x) {
  Eigen::Matrix2d L, R;
  L << x * (1.0 - a.alpha_k), 1.0 - a.alpha_m, 1.0, -a.gamma;
  R << -x * a.alpha_k, -a.alpha_m, 1.0, 1.0 - a.gamma;
  return L.inverse() * R;
}

double numericalSpectralRadius(const GeneralizedAlpha& a, double x) {
  Eigen::EigenSolver<Eigen::Matrix2d> es(amplification(a, x), false);
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

/// Generalized-alpha on the linear first-order system Y' + K Y = 0, Y = (y1, y2), K such that
/// y1' = y2, y2' = -w^2 y1 (undamped oscillator). Starts with the consistent rate Yd = -K Y.
struct Oscillator {
  GeneralizedAlpha a;
  double w;
  Eigen::Vector2d Y, Yd;
  Eigen::Matrix2d K;

  Oscillator(const GeneralizedAlpha& alpha, double omega, const Eigen::Vector2d& y0) : a(alpha), w(omega), Y(y0) {
    K << 0.0, -1.0, w * w, 0.0;
    Yd = -K * Y;
  }
  void step(double dt) {
    const double am = a.alpha_m, ak = a.alpha_k, g = a.gamma;
    // Yd_i = (Y_i - Y_{i-1}) / (g dt) - (1 - g) / g Yd_{i-1}, substituted into the weighted equation.
    const Eigen::Matrix2d A = ((1.0 - am) / (g * dt)) * Eigen::Matrix2d::Identity() + (1.0 - ak) * K;
    const Eigen::Vector2d b = ((1.0 - am) / (g * dt)) * Y + ((1.0 - am) * (1.0 - g) / g - am) * Yd - ak * (K * Y);
    const Eigen::Vector2d Yn = A.partialPivLu().solve(b);
    Yd = (Yn - Y) / (g * dt) - ((1.0 - g) / g) * Yd;
    Y = Yn;
  }
  double energy() const { return 0.5 * (Y[1] * Y[1] + w * w * Y[0] * Y[0]); }
};

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Order of accuracy on the oscillator (w = 2 pi, one period, y1(0) = 1): slope of the log of
/// the state error in the energy norm, |(y1 - cos wT, (y2 + w sin wT) / w)|, against log dt for
/// 160 .. 1280 steps (backward differences is pre-asymptotic below that: 40 steps lose 40% of the
/// amplitude). (The norm, not y1 alone: y1 at a full period sits on a crest, where a phase
/// error of O(dt^2) shows only as O(dt^4).)
double measuredOrder(const GeneralizedAlpha& a) {
  const double w = 2.0 * M_PI, T = 1.0;
  std::vector<double> logdt, logerr;
  for (int steps : {160, 320, 640, 1280}) {
    Oscillator o(a, w, Eigen::Vector2d(1.0, 0.0));
    const double dt = T / steps;
    for (int i = 0; i < steps; ++i) o.step(dt);
    logdt.push_back(std::log(dt));
    logerr.push_back(std::log(std::hypot(o.Y[0] - std::cos(w * T), (o.Y[1] + w * std::sin(w * T)) / w)));
  }
  return leastSquaresSlope(logdt, logerr);
}

}  // namespace

// --- Eq. 29 and Table 1 ---------------------------------------------------------------------

TEST(GeneralizedAlpha, Eq29ReproducesTable1LambdaMinusHalfRow) {
  const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(-0.5);
  EXPECT_NEAR(a.alpha_m, 0.167, kTableTol);
  EXPECT_NEAR(a.alpha_k, 0.333, kTableTol);
  EXPECT_NEAR(a.gamma, 0.667, kTableTol);
  // And exactly the rationals 1/6, 1/3, 2/3.
  EXPECT_NEAR(a.alpha_m, 1.0 / 6.0, kExactTol);
  EXPECT_NEAR(a.alpha_k, 1.0 / 3.0, kExactTol);
  EXPECT_NEAR(a.gamma, 2.0 / 3.0, kExactTol);
  // The struct's default is the paper's default scheme (section 4.1).
  const GeneralizedAlpha d;
  EXPECT_NEAR(d.alpha_m, a.alpha_m, kExactTol);
  EXPECT_NEAR(d.alpha_k, a.alpha_k, kExactTol);
  EXPECT_NEAR(d.gamma, a.gamma, kExactTol);
}

TEST(GeneralizedAlpha, Eq29LambdaZeroRow) {
  // Eq. 29 at lambda_inf = 0: alpha_k = 0, alpha_m = -1/2, gamma = 1. Table 1 as printed in the
  // seed text lists (alpha_m, alpha_k) = (0.0, -0.5): the two columns swapped. The printed row
  // violates eq. 27 (0 + 0.5 + 1 = 1.5) and its eigenvalues at infinity are (1/3, 0), not a
  // double 0, so eq. 29 is the consistent reading and it is what is checked here.
  const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(0.0);
  EXPECT_NEAR(a.alpha_m, -0.5, kExactTol);
  EXPECT_NEAR(a.alpha_k, 0.0, kExactTol);
  EXPECT_NEAR(a.gamma, 1.0, kExactTol);
  // The swapped (printed) row is not second order; eq. 29's is.
  GeneralizedAlpha printed;
  printed.alpha_m = 0.0;
  printed.alpha_k = -0.5;
  printed.gamma = 1.0;
  EXPECT_FALSE(printed.secondOrder());
  EXPECT_TRUE(a.secondOrder());
  // Preset "lambda0" is eq. 29's.
  const GeneralizedAlpha p = GeneralizedAlpha::preset("lambda0");
  EXPECT_NEAR(p.alpha_m, a.alpha_m, kExactTol);
  EXPECT_NEAR(p.alpha_k, a.alpha_k, kExactTol);
  EXPECT_NEAR(p.gamma, a.gamma, kExactTol);
}

TEST(GeneralizedAlpha, Eq29AtMinusOneIsTheBoxMethod) {
  const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(-1.0);
  const GeneralizedAlpha box = GeneralizedAlpha::preset("box");
  EXPECT_NEAR(a.alpha_m, 0.5, kExactTol);
  EXPECT_NEAR(a.alpha_k, 0.5, kExactTol);
  EXPECT_NEAR(a.gamma, 0.5, kExactTol);
  EXPECT_EQ(box.alpha_m, 0.5);
  EXPECT_EQ(box.alpha_k, 0.5);
  EXPECT_EQ(box.gamma, 0.5);
}

TEST(GeneralizedAlpha, Table1FixedPresets) {
  const GeneralizedAlpha trap = GeneralizedAlpha::preset("trapezoidal");
  EXPECT_EQ(trap.alpha_m, 0.0);
  EXPECT_EQ(trap.alpha_k, 0.0);
  EXPECT_EQ(trap.gamma, 0.5);
  const GeneralizedAlpha bd = GeneralizedAlpha::preset("backward");
  EXPECT_EQ(bd.alpha_m, 0.0);
  EXPECT_EQ(bd.alpha_k, 0.0);
  EXPECT_EQ(bd.gamma, 1.0);
  EXPECT_THROW(GeneralizedAlpha::preset("bogus"), std::invalid_argument);
}

TEST(GeneralizedAlpha, OneParameterFamilyIsSecondOrderBackwardIsNot) {
  // Eq. 27 checked by hand for every member, not only through secondOrder().
  for (double l : {-1.0, -0.9, -0.7, -0.5, -0.3, 0.0, 0.25, 0.5, 0.75, 0.9}) {
    const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(l);
    EXPECT_NEAR(a.alpha_m - a.alpha_k + a.gamma, 0.5, kExactTol) << "lambda_inf = " << l;
    EXPECT_TRUE(a.secondOrder()) << "lambda_inf = " << l;
  }
  EXPECT_TRUE(GeneralizedAlpha::preset("box").secondOrder());
  EXPECT_TRUE(GeneralizedAlpha::preset("trapezoidal").secondOrder());
  EXPECT_TRUE(GeneralizedAlpha::preset("lambda-0.5").secondOrder());
  EXPECT_TRUE(GeneralizedAlpha::preset("lambda0").secondOrder());
  const GeneralizedAlpha bd = GeneralizedAlpha::preset("backward");
  EXPECT_NEAR(bd.alpha_m - bd.alpha_k + bd.gamma, 1.0, kExactTol);  // 1, not 1/2
  EXPECT_FALSE(bd.secondOrder());
}

// Table 1 prints (alpha_m, alpha_k, gamma) = (-6.5, 3.0, 4.0) for lambda_inf = +0.75; eq. 29 gives
// alpha_k = 0.75 / (0.75 - 1) = -3.0. The printed +3.0 is a sign slip: it violates eq. 27
// (-6.5 - 3 + 4 = -5.5) and its eigenvalues at infinity are -ak/(1-ak) = 1.5 and -(1-g)/g = 0.75,
// i.e. unstable. The preset must follow eq. 29.
TEST(GeneralizedAlpha, PresetLambda075IsEq29) {
  const GeneralizedAlpha p = GeneralizedAlpha::preset("lambda0.75");
  const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(0.75);
  EXPECT_NEAR(a.alpha_m, -6.5, kExactTol);
  EXPECT_NEAR(a.alpha_k, -3.0, kExactTol);
  EXPECT_NEAR(a.gamma, 4.0, kExactTol);
  EXPECT_NEAR(p.alpha_m, a.alpha_m, kExactTol);
  EXPECT_NEAR(p.alpha_k, a.alpha_k, kExactTol);
  EXPECT_NEAR(p.gamma, a.gamma, kExactTol);
  EXPECT_TRUE(p.secondOrder());
  EXPECT_NEAR(p.spectralRadius(1e6), 0.75, kLimitTol);
}

// --- Eq. 28 against the amplification matrix -------------------------------------------------

TEST(GeneralizedAlpha, SpectralRadiusEq28MatchesEigenvaluesOfAmplificationMatrix) {
  std::vector<double> xs;
  for (double e = -2.0; e <= 3.0 + 1e-12; e += 0.125) xs.push_back(std::pow(10.0, e));  // 0.01 .. 1000
  std::vector<GeneralizedAlpha> schemes;
  for (const char* name : kPresets) schemes.push_back(GeneralizedAlpha::preset(name));
  for (double l : {-0.9, -0.3, 0.5}) schemes.push_back(GeneralizedAlpha::fromLambdaInf(l));
  for (const GeneralizedAlpha& a : schemes)
    for (double x : xs) {
      const double ref = numericalSpectralRadius(a, x);
      EXPECT_NEAR(a.spectralRadius(x), ref, kSpectralTol * std::max(1.0, ref))
          << "alpha_m = " << a.alpha_m << ", alpha_k = " << a.alpha_k << ", gamma = " << a.gamma
          << ", omega dt = " << x;
    }
}

TEST(GeneralizedAlpha, BoxIsAllPass) {
  const GeneralizedAlpha box = GeneralizedAlpha::preset("box");
  for (double e = -2.0; e <= 3.0 + 1e-12; e += 0.25) {
    const double x = std::pow(10.0, e);
    EXPECT_NEAR(box.spectralRadius(x), 1.0, kSpectralTol) << "omega dt = " << x;
    EXPECT_NEAR(numericalSpectralRadius(box, x), 1.0, kSpectralTol) << "omega dt = " << x;
  }
}

TEST(GeneralizedAlpha, SpectralRadiusLimitsOfTheLambdaFamily) {
  for (double l : {-0.9, -0.5, -0.3, 0.0, 0.5, 0.75}) {
    const GeneralizedAlpha a = GeneralizedAlpha::fromLambdaInf(l);
    EXPECT_NEAR(a.spectralRadius(1e6), std::abs(l), kLimitTol) << "lambda_inf = " << l;
    EXPECT_NEAR(numericalSpectralRadius(a, 1e6), std::abs(l), kLimitTol) << "lambda_inf = " << l;
    // Low frequencies are passed: rho -> 1 as omega dt -> 0 (consistency).
    EXPECT_NEAR(a.spectralRadius(1e-6), 1.0, 1e-5) << "lambda_inf = " << l;
    // Never amplifies.
    for (double e = -2.0; e <= 3.0 + 1e-12; e += 0.125)
      EXPECT_LE(a.spectralRadius(std::pow(10.0, e)), 1.0 + kSpectralTol) << "lambda_inf = " << l;
  }
  for (const char* name : {"lambda-0.5", "lambda0"}) {
    const GeneralizedAlpha p = GeneralizedAlpha::preset(name);
    const double l = std::string(name) == "lambda0" ? 0.0 : -0.5;
    EXPECT_NEAR(p.spectralRadius(1e6), std::abs(l), kLimitTol) << name;
  }
}

TEST(GeneralizedAlpha, BackwardDifferencesRollOff) {
  // Backward differences: y_i (1 + x) = y_{i-1}, so rho = 1 / (1 + omega dt), decreasing to 0.
  const GeneralizedAlpha bd = GeneralizedAlpha::preset("backward");
  double previous = 1.0;
  for (double e = -2.0; e <= 3.0 + 1e-12; e += 0.125) {
    const double x = std::pow(10.0, e);
    const double rho = bd.spectralRadius(x);
    EXPECT_NEAR(rho, 1.0 / (1.0 + x), kSpectralTol) << "omega dt = " << x;
    EXPECT_LT(rho, previous) << "omega dt = " << x;
    previous = rho;
  }
  EXPECT_LT(bd.spectralRadius(1000.0), 1e-3 + kSpectralTol);
}

// --- The oscillator --------------------------------------------------------------------------

TEST(GeneralizedAlpha, BoxKeepsOscillatorEnergyLambdaMinusHalfDissipatesHighFrequencies) {
  const double w = 1.0;
  constexpr int kSteps = 10000;
  {
    // Box over 1e4 steps at omega dt = 0.5 and at omega dt = 100: energy to round-off.
    for (double wdt : {0.5, 100.0}) {
      Oscillator o(GeneralizedAlpha::preset("box"), w, Eigen::Vector2d(1.0, 0.3));
      const double E0 = o.energy();
      double worst = 0.0;
      for (int i = 0; i < kSteps; ++i) {
        o.step(wdt / w);
        worst = std::max(worst, std::abs(o.energy() - E0) / E0);
      }
      EXPECT_LT(worst, kEnergyRoundOff) << "omega dt = " << wdt;
    }
  }
  {
    // lambda_inf = -0.5 at omega dt = 100: the eigenvalues are near the double -0.5, so the
    // energy falls by about 0.25 per step; 40 steps leave < 1e-12 of it (bound: 1e-10).
    Oscillator o(GeneralizedAlpha::fromLambdaInf(-0.5), w, Eigen::Vector2d(1.0, 0.3));
    const double E0 = o.energy();
    for (int i = 0; i < 40; ++i) o.step(100.0 / w);
    EXPECT_LT(o.energy() / E0, 1e-10);
  }
  {
    // ... while a well-resolved oscillation (omega dt = 0.01) loses little: the dissipation of a
    // second-order scheme is O((omega dt)^3) per step, ~1e-6 per step here; 1000 steps < 1%.
    Oscillator o(GeneralizedAlpha::fromLambdaInf(-0.5), w, Eigen::Vector2d(1.0, 0.3));
    const double E0 = o.energy();
    for (int i = 0; i < 1000; ++i) o.step(0.01 / w);
    EXPECT_GT(o.energy() / E0, 0.99);
    EXPECT_LT(o.energy() / E0, 1.0);
  }
}

TEST(GeneralizedAlpha, MeasuredOrderOnTheOscillator) {
  const double box = measuredOrder(GeneralizedAlpha::preset("box"));
  const double half = measuredOrder(GeneralizedAlpha::fromLambdaInf(-0.5));
  const double zero = measuredOrder(GeneralizedAlpha::preset("lambda0"));
  const double bd = measuredOrder(GeneralizedAlpha::preset("backward"));
  RecordProperty("order_box", std::to_string(box));
  RecordProperty("order_lambda_-0.5", std::to_string(half));
  RecordProperty("order_lambda0", std::to_string(zero));
  RecordProperty("order_backward", std::to_string(bd));
  EXPECT_NEAR(box, 2.0, kOrderBand);
  EXPECT_NEAR(half, 2.0, kOrderBand);
  EXPECT_NEAR(zero, 2.0, kOrderBand);
  EXPECT_NEAR(bd, 1.0, kOrderBand);
}
