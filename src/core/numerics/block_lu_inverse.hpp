// The block LU's solve with inverted diagonal blocks (BandedMatrix::solve on a factor solved three
// times or more, as modified Newton does): per node the inverse of the unit lower block L11 and of
// the upper block U11 are formed once after the factorization, so that each solve multiplies by
// them instead of substituting. Substitution is a chain of dependent multiply-and-subtracts, one
// unknown after the other (16 of them per node in 3-D); a product by a stored inverse is
// independent sums that the processor's vector units take eight or four rows at a time.
// `bench_banded` (BM_BlockSolve16 against BM_BlockSolveInverse16) and the whole runs of the
// paper's cases (docs/performance.md, "Linear algebra against the flop limit") measure the
// gain. Internal to banded_matrix.cpp, after block_lu.hpp; not installed.
#pragma once

#include <cstddef>

namespace mooring_dynamics {
namespace core {
namespace block_lu {

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

// The products below are compiled for AVX-512 too: each does the same operations in the same
// order whatever the width (sums over columns in a fixed order, rows side by side), and no
// fused multiply-adds (contraction off above), so the results do not depend on the processor.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_INVERSE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MD_INVERSE_CLONES
#endif

/// Rows rounded up to a multiple of eight (one AVX-512 register of doubles).
constexpr int padded(int rows) { return (rows + 7) / 8 * 8; }

/// A node's solve form, column-major blocks of padded rows: the inverse of the unit lower
/// block L11, the inverse of the upper block U11 (with its diagonal), U12 (the node's coupling
/// to the node above), and L21 (the panel's LEAD leftover rows on the node's columns).
template <int NB, int LEAD>
struct InverseForm {
  static constexpr int kRows = padded(NB), kLeadRows = padded(LEAD);
  static constexpr std::size_t kLinv = 0, kUinv = kLinv + NB * kRows, kU12 = kUinv + NB * kRows,
                               kL21 = kU12 + NB * kRows, kSize = kL21 + NB * kLeadRows;
};

#if defined(__GNUC__) || defined(__clang__)
/// Eight doubles (one AVX-512 register, two AVX2 ones, four SSE2 ones: the same operations on
/// each double whatever the width).
typedef double Lane8 __attribute__((vector_size(64), aligned(64)));
#endif

/// y = A x (Accumulate false) or y -= A x (true) for a column-major A of R rows (padded, a
/// multiple of eight; A 64-byte aligned) and C columns (even): two partial sums per row, over
/// the even and the odd columns in order.
template <int R, int C, bool Accumulate>
MD_INLINE void product(const double* A, const double* x, double* y) {
  static_assert(R % 8 == 0 && C % 2 == 0, "padded rows, pairs of columns");
#if defined(__GNUC__) || defined(__clang__)
  constexpr int V = R / 8;
  const Lane8* const a = reinterpret_cast<const Lane8*>(__builtin_assume_aligned(A, 64));
  Lane8 s0[V], s1[V];
  for (int i = 0; i < V; ++i) s0[i] = s1[i] = Lane8{} ;
#pragma GCC unroll 16
  for (int c = 0; c < C; c += 2) {
    const double x0 = x[c], x1 = x[c + 1];
#pragma GCC unroll 4
    for (int i = 0; i < V; ++i) {
      s0[i] += a[c * V + i] * x0;
      s1[i] += a[(c + 1) * V + i] * x1;
    }
  }
#pragma GCC unroll 4
  for (int i = 0; i < V; ++i) {
    const Lane8 s = s0[i] + s1[i];
#pragma GCC unroll 8
    for (int k = 0; k < 8; ++k) y[8 * i + k] = Accumulate ? y[8 * i + k] - s[k] : s[k];
  }
#else
  double s0[R] = {}, s1[R] = {};
  for (int c = 0; c < C; c += 2)
    for (int i = 0; i < R; ++i) {
      s0[i] += A[c * R + i] * x[c];
      s1[i] += A[(c + 1) * R + i] * x[c + 1];
    }
  for (int i = 0; i < R; ++i) y[i] = Accumulate ? y[i] - (s0[i] + s1[i]) : s0[i] + s1[i];
#endif
}

/// The solve forms of nodes [0, count) of a factor (Layout: its kernel's panels, see
/// block_lu.hpp), `nodes` nodes in all: L21 for every node but the last (whose panel has no
/// leftover rows). Entries the blocks do not have (above L11's diagonal, below U11's, the
/// padding) are zero.
///
/// The inverses are formed a column at a time as rows of their transposes, eight columns of the
/// identity side by side: column c of U11^{-1} is row c of Z = (U11^T)^{-1},
/// Z(c, :) = (e_c - sum_{k < c} U(k, c) Z(k, :)) / U(c, c), and column c of L11^{-1} is row c of
/// (L11^T)^{-1}, from the last row up: Z(c, :) = e_c - sum_{k > c} L(k, c) Z(k, :).
template <int NB, int LEAD, class Layout>
MD_INVERSE_CLONES void buildInverseForms(int count, int nodes, const Layout& layout, const int* perm,
                                         const double* inv_diag, double* form) {
  using F = InverseForm<NB, LEAD>;
  constexpr int M = LEAD + NB, S = Layout::stride, RP = F::kRows, LP = F::kLeadRows;
#if defined(__GNUC__) || defined(__clang__)
  static_assert(RP == NB, "blocks of a multiple of eight unknowns: a column of an inverse is whole lanes");
  constexpr int V = RP / 8;
#endif
  for (int j = 0; j < count; ++j) {
    const int* const pj = perm + M * j;
    const double* const rd = inv_diag + NB * j;
    double* const f = form + F::kSize * static_cast<std::size_t>(j);
    const double* R[M];
    const int rows = j + 1 < nodes ? M : NB;
    for (int i = 0; i < rows; ++i) R[i] = layout.row(j, pj, i);
#if defined(__GNUC__) || defined(__clang__)
    Lane8* const Ui = reinterpret_cast<Lane8*>(__builtin_assume_aligned(f + F::kUinv, 64));
    Lane8* const Li = reinterpret_cast<Lane8*>(__builtin_assume_aligned(f + F::kLinv, 64));
    for (int c = 0; c < NB; ++c) {
      Lane8 z[V];
      for (int v = 0; v < V; ++v) z[v] = Lane8{};
      z[c / 8][c % 8] = 1.0;
      for (int k = 0; k < c; ++k) {
        const double u = R[k][c * S];
        for (int v = 0; v < V; ++v) z[v] -= u * Ui[k * V + v];
      }
      for (int v = 0; v < V; ++v) Ui[c * V + v] = z[v] * rd[c];
    }
    for (int c = NB - 1; c >= 0; --c) {
      Lane8 z[V];
      for (int v = 0; v < V; ++v) z[v] = Lane8{};
      z[c / 8][c % 8] = 1.0;
      for (int k = c + 1; k < NB; ++k) {
        const double l = R[k][c * S];
        for (int v = 0; v < V; ++v) z[v] -= l * Li[k * V + v];
      }
      for (int v = 0; v < V; ++v) Li[c * V + v] = z[v];
    }
#else
    double* const Ui = f + F::kUinv;
    double* const Li = f + F::kLinv;
    for (int c = 0; c < NB; ++c) {
      for (int r = 0; r < RP; ++r) Ui[c * RP + r] = r == c ? 1.0 : 0.0;
      for (int k = 0; k < c; ++k)
        for (int r = 0; r < RP; ++r) Ui[c * RP + r] -= R[k][c * S] * Ui[k * RP + r];
      for (int r = 0; r < RP; ++r) Ui[c * RP + r] *= rd[c];
    }
    for (int c = NB - 1; c >= 0; --c) {
      for (int r = 0; r < RP; ++r) Li[c * RP + r] = r == c ? 1.0 : 0.0;
      for (int k = c + 1; k < NB; ++k)
        for (int r = 0; r < RP; ++r) Li[c * RP + r] -= R[k][c * S] * Li[k * RP + r];
    }
#endif
    // Z above is the transpose: Z(c, r) = X(r, c), stored at X's column-major place c RP + r.
    for (int c = 0; c < NB; ++c)
      for (int i = 0; i < NB; ++i) f[F::kU12 + c * RP + i] = R[i][(NB + c) * S];
    if (rows == M)
      for (int c = 0; c < NB; ++c)
        for (int r = 0; r < LP; ++r) f[F::kL21 + c * LP + r] = r < LEAD ? R[NB + r][c * S] : 0.0;
  }
}

/// blockForward (block_lu.hpp) with the solve forms: per panel the right-hand side by position,
/// then L11^{-1} times its first NB values and, for an inner panel, its leftover rows less L21
/// times those.
template <int NB, int LEAD, class Layout>
MD_INVERSE_CLONES void inverseForward(int n, const double* form, const int* perm, double* b, Panels part,
                                      double* carried) {
  using F = InverseForm<NB, LEAD>;
  constexpr int M = LEAD + NB, RP = F::kRows, LP = F::kLeadRows;
  const int nodes = n / NB;
  double in[M];
  auto forward = [&](auto rowsc, int j) MD_LAMBDA_INLINE {
    constexpr int ROWS = decltype(rowsc)::value;
    const int* const pj = perm + M * j;
    const double* const f = form + F::kSize * static_cast<std::size_t>(j);
    for (int q = 0; q < ROWS - LEAD; ++q) in[Layout::intervalSlot(q)] = b[LEAD + NB * j + q];
    double v[RP] = {}, y[RP];
#pragma GCC unroll 16
    for (int i = 0; i < NB; ++i) v[i] = in[pj[i]];
    product<RP, NB, false>(f + F::kLinv, v, y);
#pragma GCC unroll 16
    for (int r = 0; r < NB; ++r) b[NB * j + r] = y[r];
    if constexpr (ROWS == M) {
      double w[LP] = {};
#pragma GCC unroll 16
      for (int r = 0; r < LEAD; ++r) w[r] = in[pj[NB + r]];
      product<LP, NB, true>(f + F::kL21, y, w);
#pragma GCC unroll 16
      for (int r = 0; r < LEAD; ++r) in[Layout::carriedSlot(r)] = w[r];
    }
  };
  forwardPanels<NB, LEAD, Layout>(nodes, in, b, part, carried, forward);
}

/// blockBackward (block_lu.hpp) with the solve forms: x_j = U11^{-1} (b_j - U12 x_{j+1}).
template <int NB, int LEAD>
MD_INVERSE_CLONES void inverseBackward(int from, int to, const double* form, double* b, const double* x_above) {
  using F = InverseForm<NB, LEAD>;
  constexpr int RP = F::kRows;
  double xn[RP] = {};
  if (x_above)
    for (int k = 0; k < NB; ++k) xn[k] = x_above[k];
  for (int j = from; j >= to; --j) {
    const double* const f = form + F::kSize * static_cast<std::size_t>(j);
    double t[RP] = {};
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) t[k] = b[NB * j + k];
    if (j < from || x_above) product<RP, NB, true>(f + F::kU12, xn, t);
    product<RP, NB, false>(f + F::kUinv, t, xn);
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) b[NB * j + k] = xn[k];
  }
}

#if !defined(__clang__) && defined(__GNUC__)
#pragma GCC pop_options
#endif

}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics
