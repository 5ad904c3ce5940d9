// The Eigen kernel of the block LU: a part of block_lu.hpp (its helpers, macros and
// floating-point settings), included by it only. Written with Eigen fixed-size blocks and left to
// Eigen's own vectorization (SSE2 on a baseline x86-64 build, NEON on ARM), it is the kernel of
// every processor without AVX-512 (see blockKernel in block_lu.hpp).
#pragma once

#include <Eigen/Core>

namespace mooring_dynamics {
namespace core {
namespace block_lu {
namespace eigenkernel {

/// Node-by-node block LU of the box scheme's structure (see setBlockStructure), LAPACK's
/// right-looking unblocked LU on each node's dense panel. Panel j is a row-major M x W matrix
/// (M = LEAD + NB rows, W = 2 NB columns: nodes j and j + 1) of its own, contiguous: rows
/// 0 .. LEAD - 1 the rows left over from node j - 1 (the anchor rows for j = 0) restricted to
/// node j's columns, then the NB rows of interval j (copied from the matrix, which stays as
/// assembled). The last panel holds the leftover rows and the node's own NB - LEAD rows on NB
/// columns.
///
/// Step K: the first entry of largest magnitude in column K at positions K .. (the pivot), the
/// interchange of the two whole rows (multipliers included), l = a * (1 / pivot) into column K
/// below the pivot, and the rank-one update x - l * u of the block below and right of the pivot.
/// The arithmetic is the other kernels' op for op (no fused multiply-add: see block_lu.hpp), so
/// the factor is the same bit for bit. After an inner panel the leftover rows' node j + 1 part
/// is copied into the next panel's first rows. The factor is read by the shared solve through
/// PanelLayout (position i of panel j is row i of panel j; perm: the panel row at each position,
/// the leftover rows first as in the row kernel).
template <int NB, int LEAD>
struct EigenLU {
  static constexpr int M = LEAD + NB, W = 2 * NB;
  /// Rows ROWS x COLS of a panel (row stride W).
  template <int ROWS, int COLS>
  using Block = Eigen::Map<Eigen::Matrix<double, ROWS, COLS, Eigen::RowMajor>, Eigen::Unaligned, Eigen::OuterStride<W>>;
  template <int ROWS, int COLS>
  using ConstBlock =
      Eigen::Map<const Eigen::Matrix<double, ROWS, COLS, Eigen::RowMajor>, Eigen::Unaligned, Eigen::OuterStride<W>>;

  /// Steps K .. NB - 1 of a panel of ROWS rows and COLS columns. Returns 0, or K + 1 for an
  /// exactly zero pivot column.
  template <int ROWS, int COLS, int K>
  static MD_INLINE int eliminate(double* p, double* rd, int* in) {
    if constexpr (K == NB) {
      return 0;
    } else {
      constexpr int R = ROWS - K - 1, C = COLS - K - 1;  // the rows below, the columns right of the pivot
      Block<ROWS, COLS> P(p);
      Eigen::Index q = 0;
      const double best = P.col(K).template tail<ROWS - K>().cwiseAbs().maxCoeff(&q);  // the first largest
      if (best == 0.0) return K + 1;
      const int at = K + static_cast<int>(q);
      P.row(K).swap(P.row(at));  // (itself when at = K)
      std::swap(in[K], in[at]);
      const double rcp = 1.0 / P(K, K);
      rd[K] = rcp;
      if constexpr (R > 0) {
        auto l = P.col(K).template tail<R>();
        l *= rcp;
        if constexpr (C > 0)
          P.template bottomRightCorner<R, C>().noalias() -= l * P.row(K).template tail<C>();
      }
      return eliminate<ROWS, COLS, K + 1>(p, rd, in);
    }
  }

  /// Interval j's NB rows (all W columns; a mirror's with its two nodes swapped) into rows
  /// LEAD .. M - 1 of panel P.
  static MD_INLINE void loadInterval(double* P, const RowSource& src, int j) {
    ConstBlock<NB, W> S(src.interval0 + src.step * j);
    Block<NB, W> D(P + LEAD * W);
    if (src.swap) {
      D.template leftCols<NB>() = S.template rightCols<NB>();
      D.template rightCols<NB>() = S.template leftCols<NB>();
    } else {
      D = S;
    }
  }
};

template <int NB, int LEAD>
MD_SIMD_CLONES int factor(int n, const RowSource& src, double* panels, double* inv_diag, int* perm, Panels part) {
  typedef EigenLU<NB, LEAD> E;
  constexpr int M = E::M, W = E::W;
  const int nodes = n / NB;
  auto panel = [&](int j) { return panels + static_cast<std::size_t>(j) * M * W; };
  int in[M];
  if (part != Panels::kLast) {
    // Panel 0's first rows: the anchor rows, on node 0.
    typename E::template Block<LEAD, W> lead(panel(0));
    lead.template leftCols<NB>() = typename E::template ConstBlock<LEAD, NB>(src.lead);
    lead.template rightCols<NB>().setZero();
    for (int i = 0; i + 1 < nodes; ++i) {
      double* const P = panel(i);
      E::loadInterval(P, src, i);
      for (int r = 0; r < M; ++r) in[r] = r;
      if (const int k = E::template eliminate<M, W, 0>(P, inv_diag + NB * i, in)) return NB * i + k;
      for (int r = 0; r < M; ++r) perm[M * i + r] = in[r];
      // The leftover rows' node i + 1 part into panel i + 1's first rows, zeros after.
      typename E::template Block<LEAD, W> next(panel(i + 1));
      next.template leftCols<NB>() = typename E::template Block<LEAD, NB>(P + NB * W + NB);
      next.template rightCols<NB>().setZero();
    }
    if (part == Panels::kInner) return 0;
  }
  // The last node: the leftover rows and the node's own NB - LEAD rows, on its NB columns.
  const int j = nodes - 1;
  double* const P = panel(j);
  typename E::template Block<NB - LEAD, NB>(P + LEAD * W) = typename E::template ConstBlock<NB - LEAD, NB>(src.own);
  for (int r = 0; r < NB; ++r) in[r] = r;
  if (const int k = E::template eliminate<NB, NB, 0>(P, inv_diag + NB * j, in)) return NB * j + k;
  for (int r = 0; r < NB; ++r) perm[M * j + r] = in[r];
  return 0;
}

}  // namespace eigenkernel
}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics
