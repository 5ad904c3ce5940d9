// Square banded matrix in LAPACK band storage with LU factorization (dgbtrf) and solves (dgbtrs).
// The box scheme couples only neighbouring nodes, so the Newton matrix of an n-node line is
// banded with half-bandwidths of about 1.5 N; the cost of a factorization is linear in n.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace mooring_dynamics {
namespace core {

class BandedMatrix {
 public:
  BandedMatrix() = default;
  /// n x n matrix with kl sub- and ku super-diagonals, all zero.
  BandedMatrix(int n, int kl, int ku);

  int size() const { return n_; }
  int lower() const { return kl_; }
  int upper() const { return ku_; }

  void setZero();
  /// Element access; (i, j) must lie inside the band (checked in debug builds).
  double& at(int i, int j);
  double get(int i, int j) const;
  bool inBand(int i, int j) const { return j - i <= ku_ && i - j <= kl_; }

  /// y = A x using the unfactored matrix.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

  /// LU-factorize in place (partial pivoting). Returns 0 on success, or k > 0 when U(k-1, k-1)
  /// is exactly zero (the matrix is singular; the 0-based column is k-1).
  int factorize();
  bool factorized() const { return factorized_; }
  /// Solve A x = b in place with the factorization.
  void solve(Eigen::VectorXd& b) const;

 private:
  int n_ = 0, kl_ = 0, ku_ = 0, ldab_ = 1;
  std::vector<double> ab_;
  std::vector<int> ipiv_;
  bool factorized_ = false;
};

}  // namespace core
}  // namespace mooring_dynamics
