// Tests of the Gumbel fits (model/extremes.hpp): the method of moments against hand sums, the
// maximum-likelihood fit against its own score equations and the log-likelihood, and both on
// large synthetic samples drawn from a Gumbel distribution with known parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "mooring_dynamics/core/model/extremes.hpp"

namespace md = mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEulerGamma = 0.57721566490153286061;

/// n draws of a Gumbel(mu, beta) by inverting its distribution function: x = mu - beta ln(-ln u).
std::vector<double> gumbelSample(double mu, double beta, std::size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x;
  for (std::size_t i = 0; i < n; ++i) {
    double p = u(gen);
    while (p <= 0.0) p = u(gen);
    x.push_back(mu - beta * std::log(-std::log(p)));
  }
  return x;
}

double logLikelihood(const std::vector<double>& x, double mu, double beta) {
  double l = 0.0;
  for (double v : x) {
    const double z = (v - mu) / beta;
    l += -std::log(beta) - z - std::exp(-z);
  }
  return l;
}

}  // namespace

TEST(Extremes, MomentsMatchHandSums) {
  // Five maxima 100, 110, 120, 130, 140 kN: mean 120, sample variance (400+100+0+100+400)/4 = 250,
  // s = 15.8113883; beta = s sqrt(6)/pi = 12.3280889; mu = 120 - 0.5772157 * 12.3280889 = 112.8840340.
  const md::GumbelFit f = md::fitGumbel({100, 110, 120, 130, 140}, md::GumbelMethod::Moments);
  constexpr double kHandRounding = 1e-6;  // the hand values are written to 9-10 digits
  EXPECT_NEAR(f.scale, 12.3280889, kHandRounding);
  EXPECT_NEAR(f.location, 112.8840340, kHandRounding);
  EXPECT_EQ(md::mostProbableMaximum(f), f.location);
  EXPECT_EQ(f.samples, 5u);
}

TEST(Extremes, MleSatisfiesItsScoreEquations) {
  const std::vector<double> x = {812.0, 905.5, 870.2, 1010.9, 845.1, 931.4, 888.8};
  const md::GumbelFit f = md::fitGumbel(x, md::GumbelMethod::MaximumLikelihood);
  ASSERT_GT(f.scale, 0.0);
  // d/dmu: sum e^{-z} = n; d/dbeta: sum z (1 - e^{-z}) = n, with z = (x - mu)/beta.
  double s1 = 0.0, s2 = 0.0;
  for (double v : x) {
    const double z = (v - f.location) / f.scale;
    s1 += std::exp(-z);
    s2 += z * (1.0 - std::exp(-z));
  }
  constexpr double kScoreTolerance = 1e-9;  // the bisection stops at a few ulps of beta
  EXPECT_NEAR(s1, static_cast<double>(x.size()), kScoreTolerance * x.size());
  EXPECT_NEAR(s2, static_cast<double>(x.size()), 1e-7 * x.size());
  // A maximum of the likelihood: any nearby parameters give less.
  const double l0 = logLikelihood(x, f.location, f.scale);
  for (double dm : {-1.0, 1.0})
    for (double db : {-1.0, 0.0, 1.0}) {
      EXPECT_LT(logLikelihood(x, f.location + dm, f.scale), l0);
      EXPECT_LT(logLikelihood(x, f.location + dm * 0.5, f.scale + db), l0);
    }
}

TEST(Extremes, BothFitsRecoverKnownParametersOfLargeSamples) {
  const double mu = 1.2e6, beta = 8.0e4;  // a tension maximum [N] and its spread
  const std::size_t n = 4000;
  const std::vector<double> x = gumbelSample(mu, beta, n, 20261204u);
  // Asymptotic standard errors of the MLE: sd(mu) = 1.053 beta / sqrt(n), sd(beta) = 0.780 beta /
  // sqrt(n); the method of moments is less efficient (sd(beta) about 1.05 beta / sqrt(n)). Five
  // standard errors: a correct fit fails this with probability below 1e-6.
  const double se = beta / std::sqrt(static_cast<double>(n));
  const md::GumbelFit mle = md::fitGumbel(x, md::GumbelMethod::MaximumLikelihood);
  EXPECT_NEAR(mle.location, mu, 5 * 1.053 * se);
  EXPECT_NEAR(mle.scale, beta, 5 * 0.780 * se);
  const md::GumbelFit mom = md::fitGumbel(x, md::GumbelMethod::Moments);
  EXPECT_NEAR(mom.location, mu, 5 * 1.2 * se);
  EXPECT_NEAR(mom.scale, beta, 5 * 1.1 * se);
  // The two estimates differ on a finite sample (the test would not see a fit that ignored its method).
  EXPECT_NE(mle.scale, mom.scale);
}

TEST(Extremes, QuantileInvertsTheDistribution) {
  md::GumbelFit f;
  f.location = 100.0;
  f.scale = 10.0;
  // F(mu) = exp(-1): the mode is the 36.8 % quantile; the median is mu - beta ln(ln 2).
  EXPECT_NEAR(md::gumbelQuantile(f, std::exp(-1.0)), 100.0, 1e-12);
  EXPECT_NEAR(md::gumbelQuantile(f, 0.5), 100.0 - 10.0 * std::log(std::log(2.0)), 1e-12);
  EXPECT_THROW(md::gumbelQuantile(f, 1.0), std::invalid_argument);
}

TEST(Extremes, DegenerateAndBadSamples) {
  const md::GumbelFit same = md::fitGumbel({5.0, 5.0, 5.0}, md::GumbelMethod::MaximumLikelihood);
  EXPECT_EQ(same.location, 5.0);
  EXPECT_EQ(same.scale, 0.0);
  const md::GumbelFit same_m = md::fitGumbel({5.0, 5.0}, md::GumbelMethod::Moments);
  EXPECT_EQ(same_m.location, 5.0);
  EXPECT_THROW(md::fitGumbel({1.0}, md::GumbelMethod::Moments), std::invalid_argument);
  EXPECT_THROW(md::fitGumbel({1.0, NAN}, md::GumbelMethod::Moments), std::invalid_argument);
  EXPECT_EQ(md::gumbelMethodFromName("mle"), md::GumbelMethod::MaximumLikelihood);
  EXPECT_THROW(md::gumbelMethodFromName("lsq"), std::invalid_argument);
  // The moments relations the header states: mean = mu + gamma beta, var = pi^2 beta^2 / 6.
  const md::GumbelFit f = md::fitGumbel({1.0, 2.0, 4.0}, md::GumbelMethod::Moments);
  EXPECT_NEAR(f.location + kEulerGamma * f.scale, 7.0 / 3.0, 1e-12);
  EXPECT_NEAR(kPi * kPi * f.scale * f.scale / 6.0, (std::pow(1 - 7.0 / 3, 2) + std::pow(2 - 7.0 / 3, 2) + std::pow(4 - 7.0 / 3, 2)) / 2.0, 1e-12);
}
