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

/// AD rows into R, and their nonzero derivatives into J at columns col0 .. col0 + cols. Where J
/// has a block structure whose rows start at col0 (BandedMatrix::blockRow), a row's derivatives
/// are copied whole, zeros as +0 (the entries the element-wise copy leaves as cleared).
template <class AD>
void scatter(const AD* r, int rows, int row0, int col0, int cols, Eigen::VectorXd& R, BandedMatrix* J) {
  using Der = typename AD::DerType;
  constexpr int kCols = Der::RowsAtCompileTime;
  if constexpr (kCols > 0) {
    if (J && cols == kCols && J->blockSize() > 0 && kCols <= 2 * J->blockSize() &&
        J->blockRowFirstColumn(row0) == col0 && J->blockRowFirstColumn(row0 + rows - 1) == col0) {
      for (int q = 0; q < rows; ++q) {
        R[row0 + q] = r[q].value();
        Eigen::Map<Eigen::Matrix<double, kCols, 1>>(J->blockRow(row0 + q)) = r[q].derivatives().array() + 0.0;
      }
      return;
    }
  }
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
