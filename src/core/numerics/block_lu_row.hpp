// The portable row kernel of the block LU: a part of block_lu.hpp (its helpers, macros and
// floating-point settings), included by it only. Row-major and in place, with GCC/Clang vector
// extensions (compiled twice on x86-64: baseline and AVX2, see MD_SIMD_CLONES); the kernel the
// build option MD_BLOCK_KERNEL=portable chooses, and the reference the other kernels match bit
// for bit.
#pragma once

namespace mooring_dynamics {
namespace core {
namespace block_lu {

/// The portable block LU: row-major, in place (see factor below).
namespace rowkernel {

/// The first of largest magnitude among the candidates [LO, LO + N) (raw: their bits): its
/// index, magnitude (the bits of |x|) and bits. A balanced tree (depth ceil(log2 N), 4 for 13
/// candidates) instead of a scan (depth N - 1), as the search is on the dependent chain of the
/// elimination. The left operand wins ties at every level, so the result is the scan's: the
/// first entry of largest magnitude (except with NaN entries, whose bits order above infinity).
template <int LO, int N>
MD_INLINE void firstLargest(const std::int64_t* raw, std::int64_t& best, std::int64_t& bits, int& at) {
  if constexpr (N == 1) {
    bits = raw[LO];
    best = bits & INT64_MAX;
    at = LO;
    opaque(at);
  } else {
    std::int64_t m0, m1, r0, r1;
    int i0, i1;
    firstLargest<LO, N / 2>(raw, m0, r0, i0);
    firstLargest<LO + N / 2, N - N / 2>(raw, m1, r1, i1);
    const bool right = m1 > m0;
    best = right ? m1 : m0;
    bits = right ? r1 : r0;
    at = right ? i1 : i0;
  }
}

/// Rows in VL-double vectors (GCC/Clang vector extensions: one AVX2 operation, or two SSE2
/// ones in the baseline clone, per vector); single doubles elsewhere. The helpers take and give
/// memory, not vectors (no vector crosses a function boundary, even before inlining).
#if defined(__GNUC__) || defined(__clang__)
constexpr int VL = 4;
typedef double Vec __attribute__((vector_size(VL * sizeof(double)), aligned(8), may_alias));
/// out[0 .. VL) = x - l p.
MD_INLINE void subtractScaled(double* out, const double* x, const double* p, double l) {
  *reinterpret_cast<Vec*>(out) = *reinterpret_cast<const Vec*>(x) - l * *reinterpret_cast<const Vec*>(p);
}
MD_INLINE void setZero(double* out) { *reinterpret_cast<Vec*>(out) = Vec{}; }
MD_INLINE void swapVectors(double* a, double* b) {
  const Vec x = *reinterpret_cast<const Vec*>(a);
  *reinterpret_cast<Vec*>(a) = *reinterpret_cast<const Vec*>(b);
  *reinterpret_cast<Vec*>(b) = x;
}
/// The vector of columns C0 .. C0 + VL - 1 of row r: right of column K r - l p, column K l, left
/// of it unchanged (a constant shuffle and an insertion; no vector built from scalars, which the
/// compiler would assemble lane by lane before the clones exist).
template <int C0, int K, std::size_t... E>
MD_INLINE void mergeUpdate(double* r, const double* p, double l, std::index_sequence<E...>) {
  const Vec old = *reinterpret_cast<const Vec*>(r);
  const Vec upd = old - l * *reinterpret_cast<const Vec*>(p);
  Vec m = __builtin_shufflevector(old, upd, static_cast<int>(C0 + static_cast<int>(E) > K ? VL + E : E)...);
  m[K - C0] = l;
  *reinterpret_cast<Vec*>(r) = m;
}
template <int C0, int K>
MD_INLINE void mergeUpdate(double* r, const double* p, double l) {
  mergeUpdate<C0, K>(r, p, l, std::make_index_sequence<VL>{});
}
#else
constexpr int VL = 1;
MD_INLINE void subtractScaled(double* out, const double* x, const double* p, double l) { *out = *x - l * *p; }
MD_INLINE void setZero(double* out) { *out = 0.0; }
MD_INLINE void swapVectors(double* a, double* b) { std::swap(*a, *b); }
template <int C0, int K>
MD_INLINE void mergeUpdate(double* r, const double* p, double l) {
  *r = C0 > K ? *r - l * *p : C0 == K ? l : *r;
}
#endif

/// A panel being eliminated. Its rows stay at fixed places, LAPACK's way: an interchange swaps
/// two rows' contents (with their multipliers), which keeps every other address a constant
/// offset from two bases. Positions 0 .. LEAD - 1 are carried rows, then the interval's.
template <int NB, int LEAD, int ROWS>
struct Panel {
  double* carried;
  double* interval;
  int in[ROWS];  ///< the panel row at each position (0 .. LEAD - 1 carried, then the interval's)
  MD_INLINE double* row(int i) const { return i < LEAD ? carried + i * 2 * NB : interval + (i - LEAD) * 2 * NB; }
};

/// The updates of elimination step K that the next pivot search does not need: the vectors right
/// of the one holding column K + 1, of the rows at positions K + 1 .. ROWS - 1 (their multiplier
/// is in column K), with the pivot row at position K.
template <int NB, int LEAD, int ROWS, int COLS, int K>
MD_INLINE void updateRest(const Panel<NB, LEAD, ROWS>& P) {
  constexpr int next = (K + 1) / VL * VL + VL;
  if constexpr (next < COLS) {
    const double* const pivot = P.row(K);
    for (int i = K + 1; i < ROWS; ++i) {
      double* const r = P.row(i);
      const double l = r[K];
      for (int c = next; c < COLS; c += VL) subtractScaled(r + c, r + c, pivot + c, l);
    }
  }
}

/// Elimination steps K .. NB - 1 of a panel of ROWS positions and COLS columns, in place in the
/// panel's rows (LAPACK's storage: after step K the rows below the pivot hold their multiplier
/// in column K, left of the entries still to be eliminated). cand: the bits of column K at
/// positions K .. ROWS - 1.
///
/// Step K: the pivot search over cand, the interchange, 1 / pivot, and the update of the rows
/// below. The dependent chain runs from one search to the next through the division and the
/// update of column K + 1, which is therefore computed twice, by the same operations: as scalars
/// that feed the next search directly (cand of step K + 1), and in the vector update. That is
/// split too: the vector holding column K + 1 now (its lanes left of column K keep the earlier
/// multipliers; whole vectors left of it are not touched again), the vectors right of it
/// (updateRest) in the next step, where they run while its division does. With carry (an inner
/// panel) the last step writes the updated node j + 1 part of the leftover rows (positions
/// NB .. ROWS - 1) straight into the next panel's carried rows (zeros after). Fixed lengths
/// throughout (K is a template parameter): the loops unroll and the vectors need no remainder.
/// Returns 0, or K + 1 for an exactly zero pivot.
template <int NB, int LEAD, int ROWS, int COLS, int K>
MD_INLINE int eliminate(Panel<NB, LEAD, ROWS>& P, const std::int64_t* cand, double* __restrict rd,
                        double* __restrict carry) {
  if constexpr (K == NB) {
    return 0;
  } else {
    
    constexpr int W = 2 * NB, C = ROWS - K;
    static_assert(COLS % VL == 0 && NB % VL == 0, "rows in whole vectors");
    std::int64_t best, bits;
    int p;
    firstLargest<0, C>(cand, best, bits, p);
    opaque(best);  // else the last merge becomes a branch on the zero test below
    opaque(bits);
    opaque(p);
    if (best == 0) return K + 1;
    p += K;
    double* const rp = P.row(p);
    double* const pivot = P.row(K);
    double pv;
    std::memcpy(&pv, &bits, sizeof pv);
    const double rcp = 1.0 / pv;
    rd[K] = rcp;
    // Interchange positions K and p (the same row when p = K).
    for (int c = 0; c < COLS; c += VL) swapVectors(rp + c, pivot + c);
    const int in_p = P.in[p];
    P.in[p] = P.in[K];
    P.in[K] = in_p;
    if constexpr (K > 0) updateRest<NB, LEAD, ROWS, COLS, K - 1>(P);
    constexpr int gk = K / VL * VL, gn = (K + 1) / VL * VL;  // the vectors holding columns K, K + 1
    std::int64_t next[C > 1 ? C - 1 : 1];                    // the next search's candidates
    const double u = K + 1 < COLS ? pivot[K + 1] : 0.0;
    for (int i = K + 1; i < ROWS; ++i) {
      double* const r = P.row(i);
      const double l = r[K] * rcp;
      if constexpr (K + 1 < NB) {
        next[i - K - 1] = bitsOf(r[K + 1] - l * u);
        opaque(next[i - K - 1]);
      }
      if constexpr (K + 1 == NB && COLS == W) {
        r[K] = l;
        double* const out = carry + (i - NB) * W;
        for (int c = 0; c < NB; c += VL) subtractScaled(out + c, r + NB + c, pivot + NB + c, l);
        for (int c = NB; c < W; c += VL) setZero(out + c);
      } else if constexpr (gk == gn) {
        mergeUpdate<gn, K>(r + gn, pivot + gn, l);
      } else {
        r[K] = l;
        if constexpr (gn < COLS) subtractScaled(r + gn, r + gn, pivot + gn, l);
      }
    }
    if constexpr (K + 1 == NB) updateRest<NB, LEAD, ROWS, COLS, K>(P);  // nothing for an inner panel
    return eliminate<NB, LEAD, ROWS, COLS, K + 1>(P, next, rd, carry);
  }
}

/// Eliminates the panel P (ROWS positions, COLS columns) from its first column.
template <int NB, int LEAD, int ROWS, int COLS>
MD_INLINE int eliminatePanel(Panel<NB, LEAD, ROWS>& P, double* rd, double* carry) {
  std::int64_t cand[ROWS];
  for (int i = 0; i < ROWS; ++i) {
    P.in[i] = i;
    cand[i] = bitsOf(P.row(i)[0]);
    opaque(cand[i]);
  }
  return eliminate<NB, LEAD, ROWS, COLS, 0>(P, cand, rd, carry);
}

/// Node-by-node elimination of the box scheme's block structure (see setBlockStructure). Panel j
/// has M = LEAD + NB rows of W = 2 NB columns: the LEAD rows left over from node j - 1 (the
/// anchor rows for j = 0), restricted to node j's columns, and the NB rows of interval j on nodes
/// j and j + 1. Its NB columns of node j are eliminated with partial pivoting over the panel
/// rows; the rows not chosen as pivots carry their node j + 1 part (the Schur complement) into
/// panel j + 1. The last panel holds the leftover rows and the NB - LEAD rows of the last node,
/// on NB columns.
///
/// In place: the interval rows in rows (the assembled matrix is overwritten), panel j's carried
/// rows in rows j LEAD .. (j + 1) LEAD - 1 of carried (written by panel j - 1: node j part first,
/// zeros after). At the end position i of panel j holds U's row i (i < NB) or a leftover row,
/// with its multipliers left of that; perm records the panel row at each position, for the
/// right-hand side, and inv_diag U's reciprocal diagonal. Returns 0, or the 1-based unknown of
/// the first zero pivot.
template <int NB, int LEAD>
MD_SIMD_CLONES int factor(int n, double* rows, double* carried, double* inv_diag, int* perm, Panels part) {
  constexpr int M = LEAD + NB, W = 2 * NB;
  const int nodes = n / NB;
  if (part != Panels::kLast) {
    for (int r = 0; r < LEAD; ++r)
      for (int c = 0; c < W; ++c) carried[r * W + c] = c < NB ? rows[r * W + c] : 0.0;  // anchor rows: node 0
    for (int j = 0; j + 1 < nodes; ++j) {
      Panel<NB, LEAD, M> P{carried + static_cast<std::size_t>(LEAD * j) * W,
                           rows + static_cast<std::size_t>(LEAD + NB * j) * W, {}};
      if (const int k = eliminatePanel<NB, LEAD, M, W>(P, inv_diag + NB * j, P.carried + LEAD * W))
        return NB * j + k;
      for (int r = 0; r < M; ++r) perm[M * j + r] = P.in[r];
    }
    if (part == Panels::kInner) return 0;
  }
  // The last node: the leftover rows and the node's own NB - LEAD rows, on its NB columns.
  const int j = nodes - 1;
  Panel<NB, LEAD, NB> P{carried + static_cast<std::size_t>(LEAD * j) * W, rows + static_cast<std::size_t>(LEAD + NB * j) * W,
                        {}};
  if (const int k = eliminatePanel<NB, LEAD, NB, NB>(P, inv_diag + NB * j, nullptr)) return NB * j + k;
  for (int r = 0; r < NB; ++r) perm[M * j + r] = P.in[r];
  return 0;
}

}  // namespace rowkernel

}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics
