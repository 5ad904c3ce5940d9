#include "mooring_dynamics/core/numerics/banded_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "block_lu.hpp"
#include "block_lu_inverse.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"

extern "C" {
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
             int* ipiv, int* info);
}

namespace mooring_dynamics {
namespace core {

namespace {

/// In-place band LU with partial pivoting of an n x n matrix in LAPACK band storage (leading
/// dimension 2 kl + ku + 1), the algorithm of LAPACK's dgbtf2 step by step (same pivots: the
/// first entry of largest magnitude; same fill-in bookkeeping), with the half-bandwidths as
/// compile-time constants so that the column loops have fixed lengths. ipiv is 1-based as in
/// LAPACK. Returns 0, or the 1-based column of the first exactly zero pivot.
template <int KL, int KU>
MD_SIMD_CLONES int bandFactor(int n, double* ab, int* ipiv) {
  constexpr int KV = KL + KU;
  constexpr int LD = 2 * KL + KU + 1;
  // Element A(i, c) of the band: ab[KV + i - c + c LD] = ab[KV + i + c (LD - 1)].
  auto idx = [](int i, int c) { return static_cast<std::size_t>(KV + i) + static_cast<std::size_t>(c) * (LD - 1); };
  // Fill-in rows of columns KU + 1 .. KV - 1 start zero (dgbtf2).
  for (int j = KU + 1; j < std::min(KV, n); ++j)
    for (int i = KV - j; i < KL; ++i) ab[i + static_cast<std::size_t>(j) * LD] = 0.0;
  int ju = 0, info = 0;
  for (int j = 0; j < n; ++j) {
    if (j + KV < n)
      for (int i = 0; i < KL; ++i) ab[i + static_cast<std::size_t>(j + KV) * LD] = 0.0;
    const int km = std::min(KL, n - 1 - j);
    double* col = ab + KV + static_cast<std::size_t>(j) * LD;  // col[0] diagonal, col[1..km] below
    int jp = 0;
    double best = std::abs(col[0]);
    for (int i = 1; i <= km; ++i)
      if (std::abs(col[i]) > best) {
        best = std::abs(col[i]);
        jp = i;
      }
    ipiv[j] = j + jp + 1;
    if (col[jp] == 0.0) {
      if (info == 0) info = j + 1;
      continue;
    }
    ju = std::max(ju, std::min(j + KU + jp, n - 1));
    if (jp != 0)
      for (int c = j; c <= ju; ++c) std::swap(ab[idx(j + jp, c)], ab[idx(j, c)]);
    if (km == 0) continue;
    const double r = 1.0 / col[0];
    if (km == KL) {
      for (int i = 1; i <= KL; ++i) col[i] *= r;
      for (int c = j + 1; c <= ju; ++c) {
        const double u = ab[idx(j, c)];
        if (u == 0.0) continue;
        double* __restrict t = ab + idx(j + 1, c);
        const double* __restrict l = col + 1;
        for (int i = 0; i < KL; ++i) t[i] -= l[i] * u;
      }
    } else {
      for (int i = 1; i <= km; ++i) col[i] *= r;
      for (int c = j + 1; c <= ju; ++c) {
        const double u = ab[idx(j, c)];
        if (u == 0.0) continue;
        double* t = ab + idx(j + 1, c);
        for (int i = 0; i < km; ++i) t[i] -= col[1 + i] * u;
      }
    }
  }
  return info;
}

}  // namespace

using block_lu::blockBackward;
using block_lu::blockFactor;
using block_lu::blockForward;
using block_lu::BlockStorage;
using block_lu::blockKernel;
using block_lu::Kernel;
using block_lu::leftoverRows;
using block_lu::Panels;

namespace {

// The two-ended block elimination (BandedMatrix::factorize): the lower sweep is the one-ended
// kernel on nodes 0 .. meet, whose last node's own rows are the leftover rows of the upper
// sweep (written where interval meet's first rows were, once the upper sweep has read them);
// the upper sweep eliminates the mirror of nodes meet .. last (block_lu::mirrorFactor) up to
// the meeting node.

template <int NB, int LEAD>
int twistedFactor(Kernel kernel, int nodes, int meet, const BlockStorage& lower, const BlockStorage& mirror,
                  ForkJoin* fork) {
  constexpr int LM = NB - LEAD, W = 2 * NB;
  const int mirror_nodes = nodes - meet;
  int lower_info = 0, upper_info = 0;
  auto lowerSweep = [&] { lower_info = blockFactor<NB, LEAD>(kernel, NB * (meet + 1), lower, Panels::kInner); };
  auto upperSweep = [&] {
    const int k = block_lu::mirrorFactor<NB, LM>(kernel, nodes, meet, lower.rows, mirror);
    if (k != 0) {  // mirror node (k - 1) / NB is node nodes - 1 - (k - 1) / NB
      upper_info = NB * (nodes - 1 - (k - 1) / NB) + (k - 1) % NB + 1;
      return;
    }
    double left[LM * NB];
    leftoverRows<NB, LM>(kernel, NB * mirror_nodes, mirror, left);
    double* const own = lower.rows + static_cast<std::size_t>(LEAD + NB * meet) * W;
    for (int r = 0; r < LM; ++r)
      for (int c = 0; c < NB; ++c) own[r * W + c] = left[r * NB + c];
  };
  runBoth(fork, lowerSweep, upperSweep);
  if (lower_info != 0) return lower_info;
  if (upper_info != 0) return upper_info;
  return blockFactor<NB, LEAD>(kernel, NB * (meet + 1), lower, Panels::kLast);
}

/// A factor's storage for the solve: the kernel's (s) and, once built, the nodes' inverse
/// forms (block_lu_inverse.hpp; null: substitution).
struct SolveStorage {
  const BlockStorage& s;
  const double* form;
};

/// The solve forms of nodes [0, count) of a factor of `nodes` nodes, from its kernel's storage.
template <int NB, int LEAD>
void buildForms(Kernel kernel, int count, int nodes, const BlockStorage& s, double* form) {
  using namespace block_lu;
  if (kernel == Kernel::kColumns)
    buildInverseForms<NB, LEAD>(count, nodes, ColumnLayout<NB, LEAD>{s.panels}, s.perm, s.inv_diag, form);
  else if (kernel == Kernel::kEigen)
    buildInverseForms<NB, LEAD>(count, nodes, PanelLayout<NB, LEAD>{s.panels}, s.perm, s.inv_diag, form);
  else
    buildInverseForms<NB, LEAD>(count, nodes, RowLayout<NB, LEAD>{s.rows, s.carried}, s.perm, s.inv_diag, form);
}

template <int NB, int LEAD>
void forward(Kernel kernel, int n, const SolveStorage& st, double* b, Panels part, double* carry) {
  using namespace block_lu;
  if (!st.form) return blockForward<NB, LEAD>(kernel, n, st.s, b, part, carry);
  if (kernel == Kernel::kColumns)
    inverseForward<NB, LEAD, ColumnLayout<NB, LEAD>>(n, st.form, st.s.perm, b, part, carry);
  else if (kernel == Kernel::kEigen)
    inverseForward<NB, LEAD, PanelLayout<NB, LEAD>>(n, st.form, st.s.perm, b, part, carry);
  else
    inverseForward<NB, LEAD, RowLayout<NB, LEAD>>(n, st.form, st.s.perm, b, part, carry);
}

template <int NB, int LEAD>
void backward(Kernel kernel, int from, int to, const SolveStorage& st, double* b, const double* x_above) {
  if (!st.form) return blockBackward<NB, LEAD>(kernel, from, to, st.s, b, x_above);
  block_lu::inverseBackward<NB, LEAD>(from, to, st.form, b, x_above);
}

template <int NB, int LEAD>
void twistedSolve(Kernel kernel, int nodes, int meet, const SolveStorage& lower, const SolveStorage& mirror,
                  double* b, double* mb, ForkJoin* fork) {
  constexpr int LM = NB - LEAD;
  const int mirror_nodes = nodes - meet;
  double carry_lower[LEAD], carry_upper[LM];
  auto lowerForward = [&] { forward<NB, LEAD>(kernel, NB * (meet + 1), lower, b, Panels::kInner, carry_lower); };
  auto upperForward = [&] {
    for (int q = 0; q < LM; ++q) mb[q] = b[LEAD + NB * (nodes - 1) + q];
    for (int i = 0; i + 1 < mirror_nodes; ++i)
      for (int r = 0; r < NB; ++r) mb[LM + NB * i + r] = b[LEAD + NB * (nodes - 2 - i) + r];
    forward<NB, LM>(kernel, NB * mirror_nodes, mirror, mb, Panels::kInner, carry_upper);
  };
  runBoth(fork, lowerForward, upperForward);
  // The meeting node: its own rows' right-hand side from the mirror, then its x.
  for (int q = 0; q < LM; ++q) b[LEAD + NB * meet + q] = carry_upper[q];
  forward<NB, LEAD>(kernel, NB * (meet + 1), lower, b, Panels::kLast, carry_lower);
  backward<NB, LEAD>(kernel, meet, meet, lower, b, nullptr);
  const double* const x_meet = b + NB * meet;
  auto lowerBack = [&] { backward<NB, LEAD>(kernel, meet - 1, 0, lower, b, x_meet); };
  auto upperBack = [&] {
    backward<NB, LM>(kernel, mirror_nodes - 2, 0, mirror, mb, x_meet);
    for (int i = 0; i + 1 < mirror_nodes; ++i)
      for (int k = 0; k < NB; ++k) b[NB * (nodes - 1 - i) + k] = mb[NB * i + k];
  };
  runBoth(fork, lowerBack, upperBack);
}

/// The factor storage of a block structure, from the vectors BandedMatrix keeps (the solve reads
/// it through a const matrix; the kernels take it by pointer).
template <class V>
BlockStorage storageOf(const V& rows, const V& carried, const V& panels, const std::vector<double>& inv_diag,
                       const std::vector<int>& perm) {
  return BlockStorage{const_cast<double*>(rows.data()), const_cast<double*>(carried.data()),
                      const_cast<double*>(panels.data()), const_cast<double*>(inv_diag.data()),
                      const_cast<int*>(perm.data())};
}

template <int NB, int LEAD>
int factorBlocks(Kernel kernel, int n, int meet, const BlockStorage& s, const BlockStorage& mirror, ForkJoin* fork) {
  if (meet == 0) return blockFactor<NB, LEAD>(kernel, n, s);
  return twistedFactor<NB, LEAD>(kernel, n / NB, meet, s, mirror, fork);
}

template <int NB, int LEAD>
void solveBlocks(Kernel kernel, int n, int meet, const SolveStorage& s, const SolveStorage& mirror, double* b,
                 double* mb, ForkJoin* fork) {
  if (meet == 0) {
    forward<NB, LEAD>(kernel, n, s, b, Panels::kAll, nullptr);
    backward<NB, LEAD>(kernel, n / NB - 1, 0, s, b, nullptr);
    return;
  }
  twistedSolve<NB, LEAD>(kernel, n / NB, meet, s, mirror, b, mb, fork);
}

/// The solve forms of a factor: one-ended, of all nodes; two-ended, of the lower sweep's nodes
/// 0 .. meet and of the mirror's inner nodes (each sweep on its own thread when there is a fork).
template <int NB, int LEAD>
void buildAllForms(Kernel kernel, int n, int meet, const BlockStorage& s, const BlockStorage& mirror, double* form,
                   double* mirror_form, ForkJoin* fork) {
  const int nodes = n / NB;
  if (meet == 0) return buildForms<NB, LEAD>(kernel, nodes, nodes, s, form);
  runBoth(fork, [&] { buildForms<NB, LEAD>(kernel, meet + 1, meet + 1, s, form); },
          [&] { buildForms<NB, NB - LEAD>(kernel, nodes - meet - 1, nodes - meet, mirror, mirror_form); });
}

}  // namespace

void BandedMatrix::setBlockStructure(int block, int lead) {
  if (block == block_ && lead == lead_) return;
  factorized_ = false;
  if (block == 0 && lead == 0) {
    block_ = lead_ = 0;
    std::fill(ab_.begin(), ab_.end(), 0.0);
    return;
  }
  const bool kernel = (block == 8 && lead == 5) || (block == 16 && (lead == 10 || lead == 7));
  if (!kernel || n_ % block != 0 || kl_ < lead + block - 1 || ku_ < 2 * block - 1 - lead)
    throw std::invalid_argument("BandedMatrix::setBlockStructure(" + std::to_string(block) + ", " +
                                std::to_string(lead) + "): does not fit n = " + std::to_string(n_) +
                                ", kl = " + std::to_string(kl_) + ", ku = " + std::to_string(ku_));
  block_ = block;
  lead_ = lead;
  // The kernel's storage (see rowkernel::factor, columnkernel::ColumnLU, eigenkernel::EigenLU):
  // the row kernel eliminates in place in rows_ and the carried rows of every panel (lead per
  // node), the column kernel in panels of 2 block columns of the panel rows (rounded up to 8) per
  // node, the Eigen kernel in panels of the M = lead + block panel rows of 2 block columns. All:
  // per node the permutation (M) and U's reciprocal diagonal.
  kernel_ = static_cast<int>(blockKernel(block));
  const bool in_place = kernel_ == static_cast<int>(Kernel::kRows);
  const std::size_t nodes = static_cast<std::size_t>(n_ / block), M = static_cast<std::size_t>(lead + block),
                    W = static_cast<std::size_t>(2 * block), lanes = (M + 7) / 8 * 8;
  rows_.assign(static_cast<std::size_t>(n_) * W, 0.0);
  carried_.assign(in_place ? nodes * static_cast<std::size_t>(lead) * W : 0, 0.0);
  panels_.assign(in_place ? 0 : nodes * W * (kernel_ == static_cast<int>(Kernel::kColumns) ? lanes : M), 0.0);
  inv_diag_.assign(static_cast<std::size_t>(n_), 0.0);
  perm_.assign(nodes * M, 0);
  // The mirror of the two-ended elimination: nodes meet_ .. last, with lead block - lead.
  meet_ = meetingNode(static_cast<int>(nodes));
  const std::size_t mnodes = meet_ > 0 ? nodes - static_cast<std::size_t>(meet_) : 0,
                    mlead = static_cast<std::size_t>(block - lead), mM = mlead + static_cast<std::size_t>(block),
                    mlanes = (mM + 7) / 8 * 8;
  mirror_rows_.assign(in_place ? mnodes * static_cast<std::size_t>(block) * W : 0, 0.0);
  mirror_carried_.assign(in_place ? mnodes * mlead * W : 0, 0.0);
  mirror_panels_.assign(in_place ? 0 : mnodes * W * (kernel_ == static_cast<int>(Kernel::kColumns) ? mlanes : mM), 0.0);
  mirror_inv_diag_.assign(mnodes * static_cast<std::size_t>(block), 0.0);
  mirror_perm_.assign(mnodes * mM, 0);
  mirror_b_.assign(mnodes * static_cast<std::size_t>(block), 0.0);
}

void BandedMatrix::throwOutsidePattern(int i, int j) const {
  throw std::out_of_range("BandedMatrix::at(" + std::to_string(i) + ", " + std::to_string(j) +
                          "): outside the block structure (" + std::to_string(block_) + ", " +
                          std::to_string(lead_) + ")");
}

BandedMatrix::BandedMatrix(int n, int kl, int ku) : n_(n), kl_(kl), ku_(ku), ldab_(2 * kl + ku + 1) {
  if (n <= 0 || kl < 0 || ku < 0)
    throw std::invalid_argument("BandedMatrix: n = " + std::to_string(n) + ", kl = " + std::to_string(kl) +
                                ", ku = " + std::to_string(ku) + ": need n > 0, kl >= 0, ku >= 0");
  ab_.assign(static_cast<std::size_t>(ldab_) * static_cast<std::size_t>(n), 0.0);
  ipiv_.assign(static_cast<std::size_t>(n), 0);
}

void BandedMatrix::setZero() {
  if (block_ > 0)
    std::fill(rows_.begin(), rows_.end(), 0.0);
  else
    std::fill(ab_.begin(), ab_.end(), 0.0);
  factorized_ = false;
}

void BandedMatrix::setZeroRows(int first, int count) {
  assert(first >= 0 && count >= 0 && first + count <= n_);
  if (block_ > 0) {
    const std::size_t w = 2 * static_cast<std::size_t>(block_);
    std::fill(rows_.begin() + static_cast<std::ptrdiff_t>(first * w),
              rows_.begin() + static_cast<std::ptrdiff_t>((first + count) * w), 0.0);
    return;
  }
  for (int i = first; i < first + count; ++i)
    for (int j = std::max(0, i - kl_); j <= std::min(n_ - 1, i + ku_); ++j)
      ab_[static_cast<std::size_t>(kl_ + ku_ + i - j) + static_cast<std::size_t>(j) * ldab_] = 0.0;
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
  const BlockStorage st = storageOf(rows_, carried_, panels_, inv_diag_, perm_);
  const BlockStorage mirror = storageOf(mirror_rows_, mirror_carried_, mirror_panels_, mirror_inv_diag_, mirror_perm_);
  if (block_ == 8 && lead_ == 5)  // 2-D
    info = factorBlocks<8, 5>(static_cast<Kernel>(kernel_), n_, meet_, st, mirror, fork_);
  else if (block_ == 16 && lead_ == 10)  // 3-D, anchored
    info = factorBlocks<16, 10>(static_cast<Kernel>(kernel_), n_, meet_, st, mirror, fork_);
  else if (block_ == 16 && lead_ == 7)  // 3-D, free lower end
    info = factorBlocks<16, 7>(static_cast<Kernel>(kernel_), n_, meet_, st, mirror, fork_);
  else if (kl_ == 12 && ku_ == 10)
    info = bandFactor<12, 10>(n_, ab_.data(), ipiv_.data());
  else if (kl_ == 8 && ku_ == 8)
    info = bandFactor<8, 8>(n_, ab_.data(), ipiv_.data());
  else {
    dgbtrf_(&n_, &n_, &kl_, &ku_, ab_.data(), &ldab_, ipiv_.data(), &info);
    if (info < 0) throw std::logic_error("dgbtrf: illegal argument");
  }
  factorized_ = (info == 0);
  solves_ = 0;
  return info;
}

// dgbtrs ('N', one right-hand side) written out: the row interchanges and unit lower factor
// column by column, then the banded upper factor (bandwidth kl + ku) by back substitution.
void BandedMatrix::solve(Eigen::VectorXd& b) const {
  if (!factorized_) throw std::logic_error("BandedMatrix::solve before a successful factorize()");
  if (b.size() != n_) throw std::invalid_argument("BandedMatrix::solve: right-hand side of wrong size");
  if (block_ > 0) {
    const BlockStorage st = storageOf(rows_, carried_, panels_, inv_diag_, perm_);
    const BlockStorage mirror = storageOf(mirror_rows_, mirror_carried_, mirror_panels_, mirror_inv_diag_, mirror_perm_);
    const Kernel kernel = static_cast<Kernel>(kernel_);
    // The kSolvesForInverse-th solve with a factor builds its inverse forms (block_lu_inverse.hpp),
    // which that solve and the later ones use. A factor solved once or twice (plain Newton;
    // modified Newton through a front) does not repay them: built at the second solve, they made
    // the spread mooring's Hs 4 storm (about three solves a factor) 5 % slower.
    if (++solves_ == kSolvesForInverse) {
      const std::size_t nodes = static_cast<std::size_t>(n_ / block_);
      if (block_ == 8 && lead_ == 5) {
        form_.resize(nodes * block_lu::InverseForm<8, 5>::kSize);
        mirror_form_.resize(nodes * block_lu::InverseForm<8, 3>::kSize);
        buildAllForms<8, 5>(kernel, n_, meet_, st, mirror, form_.data(), mirror_form_.data(), fork_);
      } else if (block_ == 16 && lead_ == 10) {
        form_.resize(nodes * block_lu::InverseForm<16, 10>::kSize);
        mirror_form_.resize(nodes * block_lu::InverseForm<16, 6>::kSize);
        buildAllForms<16, 10>(kernel, n_, meet_, st, mirror, form_.data(), mirror_form_.data(), fork_);
      } else {
        form_.resize(nodes * block_lu::InverseForm<16, 7>::kSize);
        mirror_form_.resize(nodes * block_lu::InverseForm<16, 9>::kSize);
        buildAllForms<16, 7>(kernel, n_, meet_, st, mirror, form_.data(), mirror_form_.data(), fork_);
      }
    }
    const bool inverse = solves_ >= kSolvesForInverse;
    const SolveStorage s{st, inverse ? form_.data() : nullptr}, m{mirror, inverse ? mirror_form_.data() : nullptr};
    if (block_ == 8 && lead_ == 5)
      solveBlocks<8, 5>(kernel, n_, meet_, s, m, b.data(), mirror_b_.data(), fork_);
    else if (block_ == 16 && lead_ == 10)
      solveBlocks<16, 10>(kernel, n_, meet_, s, m, b.data(), mirror_b_.data(), fork_);
    else
      solveBlocks<16, 7>(kernel, n_, meet_, s, m, b.data(), mirror_b_.data(), fork_);
    return;
  }
  const int kv = kl_ + ku_;
  const double* ab = ab_.data();
  double* x = b.data();
  for (int j = 0; j + 1 < n_; ++j) {
    const int l = ipiv_[static_cast<std::size_t>(j)] - 1;
    if (l != j) std::swap(x[l], x[j]);
    const double xj = x[j];
    if (xj == 0.0) continue;
    const int lm = std::min(kl_, n_ - 1 - j);
    const double* col = ab + kv + 1 + static_cast<std::size_t>(j) * ldab_;
    for (int i = 0; i < lm; ++i) x[j + 1 + i] -= col[i] * xj;
  }
  for (int j = n_ - 1; j >= 0; --j) {
    if (x[j] == 0.0) continue;
    const double* col = ab + static_cast<std::size_t>(j) * ldab_;  // A(i, j) = col[kv + i - j]
    x[j] /= col[kv];
    const double t = x[j];
    const int i0 = std::max(0, j - kv);
    for (int i = j - 1; i >= i0; --i) x[i] -= t * col[kv + i - j];
  }
}

}  // namespace core
}  // namespace mooring_dynamics
