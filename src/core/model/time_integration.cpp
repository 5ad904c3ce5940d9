#include "mooring_dynamics/core/model/time_integration.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {

GeneralizedAlpha GeneralizedAlpha::fromLambdaInf(double l) {
  if (!(l >= -1.0 && l <= 1.0) || l == 1.0)
    throw std::invalid_argument("lambda_inf = " + std::to_string(l) + ": must be in [-1, 1)");
  GeneralizedAlpha g;
  g.alpha_k = l / (l - 1.0);                      // eq. 29
  g.alpha_m = (3.0 * l + 1.0) / (2.0 * l - 2.0);
  g.gamma = -1.0 / (l - 1.0);
  return g;
}

GeneralizedAlpha GeneralizedAlpha::preset(const std::string& name) {
  GeneralizedAlpha g;
  if (name == "box") { g.alpha_m = 0.5; g.alpha_k = 0.5; g.gamma = 0.5; }
  else if (name == "trapezoidal") { g.alpha_m = 0.0; g.alpha_k = 0.0; g.gamma = 0.5; }
  else if (name == "backward") { g.alpha_m = 0.0; g.alpha_k = 0.0; g.gamma = 1.0; }
  else if (name == "lambda0") { g = fromLambdaInf(0.0); }
  else if (name == "lambda-0.5") { g = fromLambdaInf(-0.5); }
  // Table 1 prints alpha_k = +3.0 for this row (and swaps alpha_m and alpha_k in the lambda_inf = 0
  // row); eq. 29 gives alpha_k = -3.0, which makes the scheme second order (eq. 27).
  else if (name == "lambda0.75") { g = fromLambdaInf(0.75); }
  else
    throw std::invalid_argument("scheme = \"" + name +
                                "\": unknown (known: box, trapezoidal, backward, lambda0, lambda-0.5, lambda0.75)");
  return g;
}

bool GeneralizedAlpha::secondOrder(double tol) const {
  return std::abs(alpha_m - alpha_k + gamma - 0.5) <= tol;  // eq. 27
}

double GeneralizedAlpha::spectralRadius(double x) const {
  // Eq. 28 with x = omega dt; the square root may be imaginary (complex conjugate pair).
  const double am = alpha_m, ak = alpha_k, g = gamma;
  const std::complex<double> disc(x * x * ((g - 1.0) * (g - 1.0) + ak * (ak + 2.0 * g - 2.0)) +
                                  2.0 * x * (g + 2.0 * am - ak - 1.0) + 1.0);
  const std::complex<double> root = std::sqrt(disc);
  const double b = 2.0 * am - 1.0 + (1.0 - g - ak + 2.0 * g * ak) * x;
  const double d = 2.0 * (g * x * (ak - 1.0) + am - 1.0);
  return std::max(std::abs((b + root) / d), std::abs((b - root) / d));
}

std::string GeneralizedAlpha::validate() const {
  std::ostringstream os;
  if (!std::isfinite(alpha_m) || !std::isfinite(alpha_k) || !std::isfinite(gamma)) {
    os << "dynamics.alpha_m/alpha_k/gamma = (" << alpha_m << ", " << alpha_k << ", " << gamma << "): must be finite";
    return os.str();
  }
  if (!(gamma > 0.0)) {
    os << "dynamics.gamma = " << gamma << ": must be > 0";
    return os.str();
  }
  if (alpha_m == 1.0 || alpha_k == 1.0) {
    os << "dynamics.alpha_m = " << alpha_m << ", alpha_k = " << alpha_k << ": neither may be 1 (no new-step terms)";
    return os.str();
  }
  return {};
}

}  // namespace core
}  // namespace mooring_dynamics
