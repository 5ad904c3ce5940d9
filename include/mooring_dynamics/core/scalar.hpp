// Scalar helpers so that the governing equations can be written once and evaluated with double
// (residuals) or Eigen::AutoDiffScalar (exact Jacobians).
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

namespace mooring_dynamics {
namespace core {

inline double value(double x) { return x; }

template <class D>
double value(const Eigen::AutoDiffScalar<D>& x) {
  return x.value();
}

/// Signed square u|u| (quadratic drag), smooth enough for Newton (derivative 2|u|).
template <class S>
S signedSquare(const S& u) {
  using std::abs;
  return u * abs(u);
}

}  // namespace core
}  // namespace mooring_dynamics
