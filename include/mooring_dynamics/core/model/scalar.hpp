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

/// sin x and cos x in one call where the compiler has one (glibc's sincos gives the values of its
/// sin and cos: the same bits as the two calls, in about the time of one).
inline void sinCos(double x, double& s, double& c) {
#if defined(__GNUC__) && !defined(__clang__)
  __builtin_sincos(x, &s, &c);
#elif defined(__clang__) && defined(__GLIBC__)
  ::sincos(x, &s, &c);  // clang has no __builtin_sincos; glibc's sincos (scripts/fuzz builds with clang)
#else
  s = std::sin(x);
  c = std::cos(x);
#endif
}

/// Signed square u|u| (quadratic drag), smooth enough for Newton (derivative 2|u|).
template <class S>
S signedSquare(const S& u) {
  using std::abs;
  return u * abs(u);
}

}  // namespace core
}  // namespace mooring_dynamics
