// Extreme-value statistics of design runs: the Gumbel (type I largest) distribution fitted to
// the maxima of independent realisations of one storm (one maximum per random seed), and its
// most probable maximum (MPM), the mode of the fitted distribution, as mooring codes ask for
// (e.g. DNV-OS-E301, API RP 2SK: the most probable maximum line tension of a storm).
//
//   F(x) = exp(-exp(-(x - mu) / beta)),  mode = mu,  mean = mu + gamma_E beta,
//   variance = pi^2 beta^2 / 6  (gamma_E = 0.5772..., the Euler-Mascheroni constant).
#pragma once

#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

/// How the Gumbel parameters are estimated from the sample of maxima.
enum class GumbelMethod {
  Moments,  ///< method of moments: beta = s sqrt(6) / pi (s the sample standard deviation, n - 1), mu = mean - gamma_E beta
  MaximumLikelihood,  ///< maximum likelihood: the scale equation solved by bisection, then mu in closed form
};

/// "moments" or "mle"; throws std::invalid_argument naming the accepted values otherwise.
GumbelMethod gumbelMethodFromName(const std::string& name);
const char* gumbelMethodName(GumbelMethod m);

struct GumbelFit {
  double location = 0.0;  ///< mu [unit of the sample]: the mode, i.e. the most probable maximum
  double scale = 0.0;     ///< beta > 0 [unit of the sample]; 0 when all maxima are equal
  std::size_t samples = 0;
};

/// Fit to `maxima` (at least 2 finite values, else std::invalid_argument naming the constraint).
GumbelFit fitGumbel(const std::vector<double>& maxima, GumbelMethod method);

/// Most probable maximum of the fitted distribution: its mode, mu.
inline double mostProbableMaximum(const GumbelFit& f) { return f.location; }

/// The value not exceeded with probability p in (0, 1): mu - beta ln(-ln p).
double gumbelQuantile(const GumbelFit& f, double p);

}  // namespace core
}  // namespace mooring_dynamics
