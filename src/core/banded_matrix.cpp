#include "mooring_dynamics/core/banded_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

extern "C" {
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
             int* ipiv, int* info);
}

// The elimination kernels are compiled twice on x86-64 with GCC or Clang: for the baseline
// instruction set and with AVX2 (four doubles per operation); the loader picks the version the
// processor supports (function multiversioning: no change to the build flags or to the
// library's portability). Both do the same operations in the same order.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MD_SIMD_CLONES
#endif

namespace mooring_dynamics {
namespace core {

namespace {

/// r[0..len) -= l * p[0..len) for len a multiple of 4, in four-double vectors where the compiler
/// has them (GCC/Clang vector extensions: two SSE2 operations each in the baseline clone, one
/// AVX2 operation in the other); a plain loop elsewhere.
#if defined(__GNUC__) || defined(__clang__)
typedef double Vec4 __attribute__((vector_size(32), aligned(8), may_alias));
template <int LEN>
inline void subtractScaled(double* __restrict r, const double* __restrict p, double l) {
  static_assert(LEN % 4 == 0, "four doubles at a time");
  for (int c = 0; c < LEN; c += 4) {
    Vec4 a = *reinterpret_cast<Vec4*>(r + c);
    a -= l * *reinterpret_cast<const Vec4*>(p + c);
    *reinterpret_cast<Vec4*>(r + c) = a;
  }
}
/// The same from column c0 (a multiple of 4) on.
template <int LEN>
inline void subtractScaledFrom(double* __restrict r, const double* __restrict p, double l, int c0) {
  for (int c = c0; c < LEN; c += 4) {
    Vec4 a = *reinterpret_cast<Vec4*>(r + c);
    a -= l * *reinterpret_cast<const Vec4*>(p + c);
    *reinterpret_cast<Vec4*>(r + c) = a;
  }
}
#else
template <int LEN>
inline void subtractScaled(double* __restrict r, const double* __restrict p, double l) {
  for (int c = 0; c < LEN; ++c) r[c] -= l * p[c];
}
template <int LEN>
inline void subtractScaledFrom(double* __restrict r, const double* __restrict p, double l, int c0) {
  for (int c = c0; c < LEN; ++c) r[c] -= l * p[c];
}
#endif

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

/// Node-by-node elimination of the box scheme's block structure (see setBlockStructure). Panel
/// j (row-major, M x W) holds the LEAD rows left over from node j - 1 (the anchor rows for
/// j = 0) restricted to node j's columns, and the NB rows of interval j on nodes j and j + 1.
/// Its NB columns of node j are eliminated with partial pivoting over the panel rows; the rows
/// not chosen as pivots carry their node j + 1 part (the Schur complement) into panel j + 1.
/// The last panel holds the leftover rows and the NB - LEAD rows of the last node. ipiv holds
/// the panel row chosen at each elimination step. Returns 0, or the 1-based unknown of the first
/// zero pivot.
template <int NB, int LEAD>
MD_SIMD_CLONES int blockFactor(int n, const double* rowsA, double* panels, double* lower, int* ipiv,
                double* inv_diag, int* perm_out) {
  constexpr int M = LEAD + NB, W = 2 * NB, LP = (M + 3) / 4 * 4;
  // Row i of the matrix: W entries from the first column of its first node.
  auto A = [&](int i, int c) { return rowsA[static_cast<std::size_t>(i) * W + static_cast<std::size_t>(c)]; };
  const int nodes = n / NB;
  for (int j = 0; j < nodes; ++j) {
    double(*P)[W] = reinterpret_cast<double(*)[W]>(panels + static_cast<std::size_t>(j) * M * W);
    const bool last = j + 1 == nodes;
    const int rows = last ? NB : M, cols = last ? NB : W;
    for (int r = 0; r < LEAD; ++r) {
      for (int c = 0; c < NB; ++c) {
        if (j == 0) {
          P[r][c] = A(r, c);  // anchor rows: node 0
        } else {
          const double(*Q)[W] = reinterpret_cast<const double(*)[W]>(panels + static_cast<std::size_t>(j - 1) * M * W);
          P[r][c] = Q[NB + r][NB + c];
        }
      }
      for (int c = NB; c < W; ++c) P[r][c] = 0.0;
    }
    for (int r = LEAD; r < rows; ++r) {
      const int row = LEAD + NB * j + (r - LEAD);
      for (int c = 0; c < cols; ++c) P[r][c] = A(row, c);
      for (int c = cols; c < W; ++c) P[r][c] = 0.0;
    }
    int* piv = ipiv + NB * j;
    int perm[M];
    for (int r = 0; r < M; ++r) perm[r] = r;
    // Multipliers of column k in Lt[k][i] (rows i > k; zero elsewhere, padded to LP rows).
    double(*Lt)[LP] = reinterpret_cast<double(*)[LP]>(lower + static_cast<std::size_t>(j) * NB * LP);
    for (int k = 0; k < NB; ++k) {
      // First entry of largest magnitude (branch-free: the comparisons select, they do not jump).
      int p = k;
      double best = std::abs(P[k][k]);
      for (int i = k + 1; i < rows; ++i) {
        const double a = std::abs(P[i][k]);
        p = a > best ? i : p;
        best = a > best ? a : best;
      }
      piv[k] = p;
      if (P[p][k] == 0.0) return NB * j + k + 1;
      // Interchange whole rows, and the multipliers of the earlier columns with them (the
      // dense LU convention: the solve permutes the right-hand side once, then eliminates).
      if (p != k) {
        for (int c = 0; c < W; ++c) std::swap(P[p][c], P[k][c]);
        for (int q = 0; q < k; ++q) std::swap(Lt[q][p], Lt[q][k]);
        std::swap(perm[p], perm[k]);
      }
      const double rcp = 1.0 / P[k][k];
      inv_diag[NB * j + k] = rcp;
      for (int i = 0; i < LP; ++i) Lt[k][i] = 0.0;
      // Fixed-length row updates (vectorized, also for l = 0: cheaper than a branch on the data)
      // from the 4-column group holding column k + 1 on. Columns left of k + 1 are not read
      // again (the multipliers are in Lt), so what the update leaves there does not matter.
      const int c0 = (k + 1) / 4 * 4;
      for (int i = k + 1; i < rows; ++i) {
        const double l = P[i][k] * rcp;
        Lt[k][i] = l;
        subtractScaledFrom<W>(P[i], P[k], l, c0);
      }
    }
    // Panel rows in input order: rows 0..LEAD-1 the carried rows, then the node's own.
    for (int r = 0; r < M; ++r) perm_out[static_cast<std::size_t>(j) * M + r] = perm[r];
  }
  return 0;
}

/// Solve with the panels of blockFactor: forward through the panels (interchanges, unit lower
/// factor, leftover rows carried on), then back substitution node by node from the top.
template <int NB, int LEAD>
MD_SIMD_CLONES void blockSolve(int n, const double* panels, const double* lower, const int* perm_in, const double* inv_diag,
                               double* b) {
  static_assert(NB % 2 == 0, "the dot products below take two columns at a time");
  constexpr int M = LEAD + NB, W = 2 * NB, LP = (M + 3) / 4 * 4;
  const int nodes = n / NB;
  double carry[LEAD] = {};
  for (int j = 0; j < nodes; ++j) {
    const bool last = j + 1 == nodes;
    const int rows = last ? NB : M;
    double in[M];
    for (int r = 0; r < LEAD; ++r) in[r] = j == 0 ? b[r] : carry[r];
    for (int r = LEAD; r < rows; ++r) in[r] = b[LEAD + NB * j + (r - LEAD)];
    const int* perm = perm_in + static_cast<std::size_t>(j) * M;
    double v[LP] = {};
    for (int r = 0; r < rows; ++r) v[r] = in[perm[r]];  // the interchanges of the factorization
    const double(*Lt)[LP] = reinterpret_cast<const double(*)[LP]>(lower + static_cast<std::size_t>(j) * NB * LP);
    for (int k = 0; k < NB; ++k) subtractScaled<LP>(v, Lt[k], v[k]);  // Lt[k][i] = 0 for i <= k, i >= rows
    for (int r = 0; r < NB; ++r) b[NB * j + r] = v[r];  // rows of node j's panel are read
    if (!last)
      for (int r = 0; r < LEAD; ++r) carry[r] = v[NB + r];
  }
  for (int j = nodes - 1; j >= 0; --j) {
    const double(*P)[W] = reinterpret_cast<const double(*)[W]>(panels + static_cast<std::size_t>(j) * M * W);
    double* x = b + NB * j;
    const double* rd = inv_diag + NB * j;
    // U12 x_{j+1} first: eight independent dot products, then U11 by back substitution.
    double t[NB];
    for (int k = 0; k < NB; ++k) t[k] = x[k];
    if (j + 1 < nodes) {
      const double* xn = b + NB * (j + 1);
      for (int k = 0; k < NB; ++k) {
        double s0 = 0.0, s1 = 0.0;
        for (int c = 0; c < NB; c += 2) {
          s0 += P[k][NB + c] * xn[c];
          s1 += P[k][NB + c + 1] * xn[c + 1];
        }
        t[k] -= s0 + s1;
      }
    }
    // Column by column: x_k = t_k / U_kk, then x_k leaves the rows above (the dependent chain
    // is one multiply and one update per unknown).
    for (int k = NB - 1; k >= 0; --k) {
      const double xk = t[k] * rd[k];
      x[k] = xk;
      for (int i = 0; i < k; ++i) t[i] -= P[i][k] * xk;
    }
  }
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
  // Panels of M = lead + block rows by W = 2 block columns, multipliers padded to LP rows.
  const std::size_t nodes = static_cast<std::size_t>(n_ / block), M = static_cast<std::size_t>(lead + block),
                    W = static_cast<std::size_t>(2 * block), LP = (M + 3) / 4 * 4;
  rows_.assign(static_cast<std::size_t>(n_) * W, 0.0);
  panels_.assign(nodes * M * W, 0.0);
  lower_.assign(nodes * static_cast<std::size_t>(block) * LP, 0.0);
  inv_diag_.assign(static_cast<std::size_t>(n_), 0.0);
  perm_.assign(nodes * M, 0);
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
  if (block_ == 8 && lead_ == 5)
    info = blockFactor<8, 5>(n_, rows_.data(), panels_.data(), lower_.data(), ipiv_.data(), inv_diag_.data(), perm_.data());
  else if (block_ == 16 && lead_ == 10)  // 3-D, anchored
    info = blockFactor<16, 10>(n_, rows_.data(), panels_.data(), lower_.data(), ipiv_.data(), inv_diag_.data(), perm_.data());
  else if (block_ == 16 && lead_ == 7)   // 3-D, free lower end
    info = blockFactor<16, 7>(n_, rows_.data(), panels_.data(), lower_.data(), ipiv_.data(), inv_diag_.data(), perm_.data());
  else if (kl_ == 12 && ku_ == 10)
    info = bandFactor<12, 10>(n_, ab_.data(), ipiv_.data());
  else if (kl_ == 8 && ku_ == 8)
    info = bandFactor<8, 8>(n_, ab_.data(), ipiv_.data());
  else {
    dgbtrf_(&n_, &n_, &kl_, &ku_, ab_.data(), &ldab_, ipiv_.data(), &info);
    if (info < 0) throw std::logic_error("dgbtrf: illegal argument");
  }
  factorized_ = (info == 0);
  return info;
}

// dgbtrs ('N', one right-hand side) written out: the row interchanges and unit lower factor
// column by column, then the banded upper factor (bandwidth kl + ku) by back substitution.
void BandedMatrix::solve(Eigen::VectorXd& b) const {
  if (!factorized_) throw std::logic_error("BandedMatrix::solve before a successful factorize()");
  if (b.size() != n_) throw std::invalid_argument("BandedMatrix::solve: right-hand side of wrong size");
  if (block_ == 8 && lead_ == 5) {
    blockSolve<8, 5>(n_, panels_.data(), lower_.data(), perm_.data(), inv_diag_.data(), b.data());
    return;
  }
  if (block_ == 16 && lead_ == 10) {
    blockSolve<16, 10>(n_, panels_.data(), lower_.data(), perm_.data(), inv_diag_.data(), b.data());
    return;
  }
  if (block_ == 16 && lead_ == 7) {
    blockSolve<16, 7>(n_, panels_.data(), lower_.data(), perm_.data(), inv_diag_.data(), b.data());
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
