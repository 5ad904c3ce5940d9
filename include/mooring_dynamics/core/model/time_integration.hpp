// Generalized-alpha parameters for the first-order cable equations (paper section 4): the
// one-parameter family of eq. 29, the named algorithms of Table 1, and the spectral radius of
// eq. 28.
#pragma once

#include <string>

namespace mooring_dynamics {
namespace core {

struct GeneralizedAlpha {
  double alpha_m = 1.0 / 6.0;  ///< weight of the previous step on the inertia terms [-]
  double alpha_k = 1.0 / 3.0;  ///< weight of the previous step on the stiffness and force terms [-]
  double gamma = 2.0 / 3.0;    ///< trapezoidal weight of eq. 26 [-]

  /// Eq. 29: second-order accurate, double eigenvalue lambda_inf at infinite frequency.
  static GeneralizedAlpha fromLambdaInf(double lambda_inf);
  /// Table 1 by name: "box", "trapezoidal", "backward", "lambda0" (lambda_inf = 0, second order),
  /// "lambda-0.5", "lambda0.75". Throws std::invalid_argument for an unknown name.
  static GeneralizedAlpha preset(const std::string& name);

  /// True when alpha_m - alpha_k + gamma = 1/2 (eq. 27).
  bool secondOrder(double tol = 1e-12) const;
  /// Spectral radius rho(omega dt) of the amplification matrix (eq. 28).
  double spectralRadius(double omega_dt) const;
  /// Empty when usable (gamma > 0, alpha_m != 1, ...), else a message naming the parameter.
  std::string validate() const;
};

}  // namespace core
}  // namespace mooring_dynamics
