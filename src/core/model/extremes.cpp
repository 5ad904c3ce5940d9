// Gumbel fits of sample maxima (see extremes.hpp for the distribution and its moments).
#include "mooring_dynamics/core/model/extremes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEulerGamma = 0.57721566490153286061;

double mean(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

/// Sample standard deviation (n - 1 in the denominator).
double sampleStd(const std::vector<double>& x, double m) {
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

/// The maximum-likelihood scale equation g(beta) = beta - mean + sum x e^{-x/beta} / sum e^{-x/beta}
/// (the derivative of the log-likelihood in beta after mu is eliminated). The weights are taken
/// relative to the smallest value, so no exponential overflows. g < 0 as beta -> 0 (the weighted
/// mean tends to the smallest value) and g -> +inf as beta grows: one root.
double scaleEquation(const std::vector<double>& x, double m, double beta) {
  const double xmin = *std::min_element(x.begin(), x.end());
  double sw = 0.0, swx = 0.0;
  for (double v : x) {
    const double w = std::exp(-(v - xmin) / beta);
    sw += w;
    swx += w * (v - xmin);
  }
  return beta - (m - xmin) + swx / sw;
}

GumbelFit fitMoments(const std::vector<double>& x) {
  const double m = mean(x);
  GumbelFit f;
  f.samples = x.size();
  f.scale = sampleStd(x, m) * std::sqrt(6.0) / kPi;
  f.location = m - kEulerGamma * f.scale;
  return f;
}

GumbelFit fitMle(const std::vector<double>& x) {
  const double m = mean(x);
  GumbelFit f;
  f.samples = x.size();
  const double spread = *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
  if (!(spread > 0.0)) {  // all maxima equal: a degenerate distribution at that value
    f.location = x.front();
    return f;
  }
  // Bracket the root: g(lo) < 0 for lo small against the spread, g(hi) > 0 for hi >= the spread
  // (the weighted mean is at least the smallest value, so g(beta) >= beta - (mean - min) > 0).
  double lo = spread * 1e-6, hi = spread;
  while (scaleEquation(x, m, lo) > 0.0 && lo > spread * 1e-300) lo *= 0.5;
  // Bisection to the last bit: about 60 halvings of [lo, hi].
  for (int k = 0; k < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (scaleEquation(x, m, mid) < 0.0 ? lo : hi) = mid;
  }
  const double beta = 0.5 * (lo + hi);
  // mu = -beta ln(mean e^{-x/beta}), with the exponentials relative to the smallest value.
  const double xmin = *std::min_element(x.begin(), x.end());
  double sw = 0.0;
  for (double v : x) sw += std::exp(-(v - xmin) / beta);
  f.scale = beta;
  f.location = xmin - beta * std::log(sw / static_cast<double>(x.size()));
  return f;
}

}  // namespace

GumbelMethod gumbelMethodFromName(const std::string& name) {
  if (name == "moments") return GumbelMethod::Moments;
  if (name == "mle") return GumbelMethod::MaximumLikelihood;
  throw std::invalid_argument("'" + name + "': needs moments or mle");
}

const char* gumbelMethodName(GumbelMethod m) { return m == GumbelMethod::Moments ? "moments" : "mle"; }

GumbelFit fitGumbel(const std::vector<double>& maxima, GumbelMethod method) {
  if (maxima.size() < 2)
    throw std::invalid_argument("a Gumbel fit needs at least 2 maxima, got " + std::to_string(maxima.size()));
  for (double v : maxima)
    if (!std::isfinite(v)) throw std::invalid_argument("a Gumbel fit needs finite maxima");
  return method == GumbelMethod::Moments ? fitMoments(maxima) : fitMle(maxima);
}

double gumbelQuantile(const GumbelFit& f, double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("gumbelQuantile: p must be in (0, 1)");
  return f.location - f.scale * std::log(-std::log(p));
}

}  // namespace core
}  // namespace mooring_dynamics
