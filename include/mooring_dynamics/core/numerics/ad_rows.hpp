// Helpers for assembling residual rows written once for double and AutoDiff scalars: AD
// variables and constants, and copying rows into the residual vector and the banded Jacobian.
#pragma once

#include <Eigen/Core>

#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/model/scalar.hpp"

namespace mooring_dynamics {
namespace core {

/// Rows r[0..rows) into R from row0 (double rows: no Jacobian).
inline void scatter(const double* r, int rows, int row0, int, int, Eigen::VectorXd& R, BandedMatrix*) {
  for (int q = 0; q < rows; ++q) R[row0 + q] = r[q];
}

/// AD rows into R, and their nonzero derivatives into J at columns col0 .. col0 + cols.
template <class AD>
void scatter(const AD* r, int rows, int row0, int col0, int cols, Eigen::VectorXd& R, BandedMatrix* J) {
  for (int q = 0; q < rows; ++q) {
    R[row0 + q] = r[q].value();
    if (!J || r[q].derivatives().size() == 0) continue;
    for (int k = 0; k < cols; ++k) {
      const double d = r[q].derivatives()[k];
      if (d != 0.0) J->at(row0 + q, col0 + k) = d;
    }
  }
}

/// A constant: an AD scalar with zero derivatives, or the plain value.
template <class AD>
AD constant(double v) {
  AD a(v);
  a.derivatives().setZero();
  return a;
}
template <>
inline double constant<double>(double v) {
  return v;
}

/// Unknown k of `size` (an AD variable), or its plain value for double.
template <class S>
S variable(double v, int size, int k) {
  return S(v, size, k);
}
template <>
inline double variable<double>(double v, int, int) {
  return v;
}

}  // namespace core
}  // namespace mooring_dynamics
