#include "mooring_dynamics/core/banded_matrix.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>

extern "C" {
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
             int* ipiv, int* info);
void dgbtrs_(const char* trans, const int* n, const int* kl, const int* ku, const int* nrhs,
             const double* ab, const int* ldab, const int* ipiv, double* b, const int* ldb, int* info,
             std::size_t trans_len);
}

namespace mooring_dynamics {
namespace core {

BandedMatrix::BandedMatrix(int n, int kl, int ku) : n_(n), kl_(kl), ku_(ku), ldab_(2 * kl + ku + 1) {
  if (n <= 0 || kl < 0 || ku < 0)
    throw std::invalid_argument("BandedMatrix: n = " + std::to_string(n) + ", kl = " + std::to_string(kl) +
                                ", ku = " + std::to_string(ku) + ": need n > 0, kl >= 0, ku >= 0");
  ab_.assign(static_cast<std::size_t>(ldab_) * static_cast<std::size_t>(n), 0.0);
  ipiv_.assign(static_cast<std::size_t>(n), 0);
}

void BandedMatrix::setZero() {
  std::fill(ab_.begin(), ab_.end(), 0.0);
  factorized_ = false;
}

// LAPACK band storage: A(i, j) lives at AB(kl + ku + i - j, j) (0-based), column-major.
double& BandedMatrix::at(int i, int j) {
  assert(i >= 0 && i < n_ && j >= 0 && j < n_ && inBand(i, j));
  return ab_[static_cast<std::size_t>(kl_ + ku_ + i - j) + static_cast<std::size_t>(j) * ldab_];
}

double BandedMatrix::get(int i, int j) const {
  if (!inBand(i, j)) return 0.0;
  return ab_[static_cast<std::size_t>(kl_ + ku_ + i - j) + static_cast<std::size_t>(j) * ldab_];
}

Eigen::VectorXd BandedMatrix::multiply(const Eigen::VectorXd& x) const {
  assert(!factorized_);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n_);
  for (int j = 0; j < n_; ++j) {
    const int i0 = std::max(0, j - ku_), i1 = std::min(n_ - 1, j + kl_);
    for (int i = i0; i <= i1; ++i) y[i] += get(i, j) * x[j];
  }
  return y;
}

int BandedMatrix::factorize() {
  int info = 0;
  dgbtrf_(&n_, &n_, &kl_, &ku_, ab_.data(), &ldab_, ipiv_.data(), &info);
  if (info < 0) throw std::logic_error("dgbtrf: illegal argument");
  factorized_ = (info == 0);
  return info;
}

void BandedMatrix::solve(Eigen::VectorXd& b) const {
  if (!factorized_) throw std::logic_error("BandedMatrix::solve before a successful factorize()");
  const char trans = 'N';
  const int nrhs = 1;
  int info = 0;
  dgbtrs_(&trans, &n_, &kl_, &ku_, &nrhs, ab_.data(), &ldab_, ipiv_.data(), b.data(), &n_, &info, 1);
  if (info != 0) throw std::logic_error("dgbtrs: illegal argument");
}

}  // namespace core
}  // namespace mooring_dynamics
