#include "mooring_dynamics/core/banded_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

// The block elimination has an AVX-512 kernel on x86-64 with GCC or Clang (see ColumnLU), chosen
// at run time when the processor has AVX-512F.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_AVX512_KERNEL 1
#include <immintrin.h>
#else
#define MD_AVX512_KERNEL 0
#endif

extern "C" {
void dgbtrf_(const int* m, const int* n, const int* kl, const int* ku, double* ab, const int* ldab,
             int* ipiv, int* info);
}

// The other elimination kernels are compiled twice on x86-64 with GCC or Clang: for the baseline
// instruction set and with AVX2 (four doubles per operation); the loader picks the version the
// processor supports (function multiversioning: no change to the build flags or to the
// library's portability). All kernels do the same operations in the same order, so the results
// do not depend on the processor: in particular no fused multiply-adds (AVX-512 has them; the
// contraction into them is switched off for the block kernels below).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MD_SIMD_CLONES
#endif

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

// The block kernels: no contraction of a * b + c into a fused multiply-add (one rounding
// instead of two, where the instruction set has it), and no warnings about passing vectors by
// value between the always-inlined helpers (no calls remain, so no ABI).
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#if defined(__GNUC__) || defined(__clang__)
#define MD_INLINE inline __attribute__((always_inline))
#define MD_LAMBDA_INLINE __attribute__((always_inline))
#else
#define MD_INLINE inline
#define MD_LAMBDA_INLINE
#endif

/// Hides v from the optimizer (GCC, Clang: an empty asm statement; v stays in a general
/// register). The pivot search below must be compiled to conditional moves: its comparisons are
/// data-dependent and a branch on them mispredicts about every other time. Without this GCC
/// turns the selections of constant indices, and of bits it knows were doubles, into branches.
template <class T>
MD_INLINE void opaque(T& v) {
#if defined(__GNUC__) || defined(__clang__)
  asm("" : "+r"(v));
#else
  (void)v;
#endif
}

/// The bits of x as a signed integer. For x >= 0 (not NaN) the integers order as the values, so
/// magnitudes compare in general registers (one cycle) and selections are conditional moves.
MD_INLINE std::int64_t bitsOf(double x) {
  std::int64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
MD_INLINE double fromBits(std::int64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

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
MD_SIMD_CLONES int factor(int n, double* rows, double* carried, double* inv_diag, int* perm) {
  constexpr int M = LEAD + NB, W = 2 * NB;
  const int nodes = n / NB;
  for (int r = 0; r < LEAD; ++r)
    for (int c = 0; c < W; ++c) carried[r * W + c] = c < NB ? rows[r * W + c] : 0.0;  // anchor rows: node 0
  for (int j = 0; j + 1 < nodes; ++j) {
    Panel<NB, LEAD, M> P{carried + static_cast<std::size_t>(LEAD * j) * W,
                         rows + static_cast<std::size_t>(LEAD + NB * j) * W, {}};
    if (const int k = eliminatePanel<NB, LEAD, M, W>(P, inv_diag + NB * j, P.carried + LEAD * W))
      return NB * j + k;
    for (int r = 0; r < M; ++r) perm[M * j + r] = P.in[r];
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

#if MD_AVX512_KERNEL
// The AVX-512 kernel: every function in this region is compiled for AVX-512F (helpers included,
// which a target attribute on the caller alone would not do).
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f")
// GCC 12 reports its own _mm512_undefined_*() placeholders in the intrinsics as maybe
// uninitialized (GCC bug 105593).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace columnkernel {

/// Node-by-node block LU of the box scheme's structure (see setBlockStructure), one node's panel
/// at a time, column-major: the eight lanes of a vector are eight of the panel's rows. Panel j
/// has M = LEAD + NB rows of W = 2 NB columns (nodes j, j + 1): the NB rows of interval j in
/// slots 0 .. NB - 1, and in slots NB .. M - 1 the LEAD rows left over from node j - 1 (the
/// anchor rows for j = 0), restricted to node j's columns. A column is LANES doubles (M rounded
/// up to 8; the padding stays zero). The NB columns of node j are eliminated with partial
/// pivoting over the panel rows; the rows not chosen as pivots carry their node j + 1 part (the
/// Schur complement) into the carried slots of panel j + 1. The last panel holds the node's own
/// NB - LEAD rows (slots 0 ..) and the leftover rows, on NB columns.
///
/// Rows never move. The row interchanges of partial pivoting only renumber positions (pos: the
/// position of each slot, at: the slot at each position; carried rows first, as in the band),
/// which decide ties in the pivot search (the first entry of largest magnitude in position
/// order, as LAPACK's interchanges of whole rows make it) and the order of the leftover rows.
/// An elimination step is then: the largest magnitude of column K over the active rows (a
/// reduction across the lanes), 1 / |pivot| right away (the sign and the pivot's slot follow from
/// comparisons), and per column right of K two vectors of multiply and masked subtract (the rows
/// still active) where the row-major LU needs a dozen scalar and vector operations per row. The
/// arithmetic is the row-oriented LU's, op for op: multiplier l = a * (1 / pivot), update
/// x - l * u. Column K + 1 is kept in registers as the next step's candidates.
///
/// The factor stays in the panels, LAPACK's way: column k holds the multipliers of step k in the
/// rows still active then, and U's entries in the rows chosen before (row k of U is the slot at
/// position k). perm (M per node): the slot at each position; inv_diag: U's reciprocal diagonal.
template <int NB, int LEAD>
struct ColumnLU {
  static constexpr int M = LEAD + NB, W = 2 * NB, LANES = (M + 7) / 8 * 8, G = LANES / 8;
  static_assert(NB % 8 == 0 && LANES <= 32 && M < LANES, "slots in a 32-bit mask, a padding lane");
  typedef std::uint32_t Slots;  // one bit per slot

  static MD_INLINE double* column(double* panel, int c) { return panel + static_cast<std::size_t>(c) * LANES; }
  static MD_INLINE __mmask8 part(Slots s, int g) { return static_cast<__mmask8>(s >> (8 * g)); }

  /// dst[c * ds + r] = src[r * ss + c] for an 8 x 8 block (three stages of two-vector shuffles).
  static MD_INLINE void transpose8(const double* src, std::size_t ss, double* dst, std::size_t ds) {
    __m512d r[8], t[8];
    for (int i = 0; i < 8; ++i) r[i] = _mm512_loadu_pd(src + i * ss);
    for (int i = 0; i < 8; i += 2) {
      t[i] = _mm512_unpacklo_pd(r[i], r[i + 1]);      // rows i, i+1 at columns 0 2 4 6
      t[i + 1] = _mm512_unpackhi_pd(r[i], r[i + 1]);  // ... at columns 1 3 5 7
    }
    const __m512i lo2 = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0), hi2 = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
    for (int i = 0; i < 8; i += 4)
      for (int k = 0; k < 2; ++k) {
        r[i + k] = _mm512_permutex2var_pd(t[i + k], lo2, t[i + k + 2]);      // rows i..i+3, columns k, k+4
        r[i + k + 2] = _mm512_permutex2var_pd(t[i + k], hi2, t[i + k + 2]);  // ... columns k+2, k+6
      }
    const __m512i lo4 = _mm512_set_epi64(11, 10, 9, 8, 3, 2, 1, 0), hi4 = _mm512_set_epi64(15, 14, 13, 12, 7, 6, 5, 4);
    for (int k = 0; k < 4; ++k) {
      _mm512_storeu_pd(dst + k * ds, _mm512_permutex2var_pd(r[k], lo4, r[k + 4]));
      _mm512_storeu_pd(dst + (k + 4) * ds, _mm512_permutex2var_pd(r[k], hi4, r[k + 4]));
    }
  }

  /// Interval j's NB rows into slots 0 .. NB - 1 of its panel, all W columns.
  static MD_INLINE void loadInterval(double* panel, const double* rows, int j) {
    const double* const src = rows + static_cast<std::size_t>(LEAD + NB * j) * W;
    for (int q = 0; q < NB; q += 8)
      for (int c = 0; c < W; c += 8) transpose8(src + q * W + c, W, column(panel, c) + q, LANES);
  }

  /// Eliminates the NB columns of a panel: count interval rows (slots 0 ..) and the LEAD carried
  /// ones, on COLS columns. For an inner panel (COLS = W) the leftover rows' node j + 1 part goes
  /// into the carried slots of next. Returns 0, or the 1-based column of the first exactly zero
  /// pivot.
  template <int COLS>
  static MD_INLINE int panel(double* P, int count, double* rd, int* perm, double* next) {
    constexpr int ROWS = COLS == W ? M : NB;
    Slots active = ((Slots{1} << count) - 1) | (((Slots{1} << LEAD) - 1) << NB);
    std::int64_t at[LANES];  // the slot at each position (the padding lane past the rows)
    int pos[LANES];          // the position of each slot
    for (int i = 0; i < LANES; ++i) {
      at[i] = i < LEAD ? NB + i : i < ROWS ? i - LEAD : LANES - 1;
      pos[i] = i < NB ? LEAD + i : i - NB;
    }
    __m512d cand[G], none[G] = {};
    for (int g = 0; g < G; ++g) cand[g] = _mm512_loadu_pd(column(P, 0) + 8 * g);
    int info = 0;
    step<COLS, 0>(P, rd, next, active, at, pos, cand, none, 0, 0, info);
    if (info != 0) return info;
    for (int r = 0; r < ROWS; ++r) perm[r] = static_cast<int>(at[r]);
    return 0;
  }

  /// Column c of P minus l u (u: the pivot row's entry, in slot q) in the rows of upd, to out.
  static MD_INLINE void update(const double* P, int c, int q, Slots upd, const __m512d* l, double* out, __m512d* keep) {
    const double* const col = column(const_cast<double*>(P), c);
    const __m512d u = _mm512_set1_pd(col[q]);
    for (int g = 0; g < G; ++g) {
      const __m512d x = _mm512_loadu_pd(col + 8 * g);
      const __m512d y = _mm512_mask_sub_pd(x, part(upd, g), x, _mm512_mul_pd(l[g], u));
      if (keep) keep[g] = y;
      else _mm512_storeu_pd(out + 8 * g, y);
    }
  }

  /// Step K. cand: column K; (lp, qp, up): the previous step's multipliers, pivot slot and rows,
  /// for the part of its update deferred to here.
  template <int COLS, int K>
  static MD_INLINE void step(double* P, double* rd, double* next, Slots& active, std::int64_t* at, int* pos,
                             const __m512d* cand, const __m512d* lp, int qp, Slots up, int& info) {
    if constexpr (K < NB) {
      // The largest magnitude of the active rows (the bits of |x|, integers that order as the
      // values), in every lane; 1 / |pivot| from it.
      const __m512i abs_bits = _mm512_set1_epi64(INT64_MAX);
      __m512i mag[G], best;
      for (int g = 0; g < G; ++g) {
        mag[g] = _mm512_maskz_and_epi64(part(active, g), _mm512_castpd_si512(cand[g]), abs_bits);
        best = g == 0 ? mag[0] : _mm512_max_epi64(best, mag[g]);
      }
      best = _mm512_max_epi64(best, _mm512_shuffle_i64x2(best, best, 0x4e));
      best = _mm512_max_epi64(best, _mm512_shuffle_i64x2(best, best, 0xb1));
      best = _mm512_max_epi64(best, _mm512_permutex_epi64(best, 0xb1));
      if (_mm_cvtsi128_si64(_mm512_castsi512_si128(best)) == 0) {  // every candidate exactly zero
        info = K + 1;
        return;
      }
      const double rcp_abs = 1.0 / _mm_cvtsd_f64(_mm512_castpd512_pd128(_mm512_castsi512_pd(best)));
      // The rows holding it, and the negative candidates, one bit per slot.
      Slots tied = 0, negative = 0;
      for (int g = 0; g < G; ++g) {
        tied |= Slots{_mm512_cmpeq_epi64_mask(mag[g], best)} << (8 * g);
        negative |= Slots{_mm512_cmplt_epi64_mask(_mm512_castpd_si512(cand[g]), _mm512_setzero_si512())} << (8 * g);
      }
      int q = __builtin_ctz(tied);
      if (__builtin_expect((tied & (tied - 1)) != 0, 0))  // a tie: the first in position order
        for (Slots t = tied & (tied - 1); t != 0; t &= t - 1) {
          const int s = __builtin_ctz(t);
          if (pos[s] < pos[q]) q = s;
        }
      // 1 / pivot, broadcast: the sign bit of a negative pivot set by an exclusive or (exact:
      // rounding is symmetric), not a branch on the sign.
      const __m512d r = _mm512_castsi512_pd(_mm512_xor_si512(
          _mm512_castpd_si512(_mm512_set1_pd(rcp_abs)), _mm512_set1_epi64(static_cast<long long>((negative >> q) & 1) << 63)));
      _mm_store_sd(rd + K, _mm512_castpd512_pd128(r));
      // Interchange positions K and pos[q]: the slot at K takes q's position.
      const int p = pos[q], t = static_cast<int>(at[K]);
      at[p] = t;
      at[K] = q;
      pos[t] = p;
      pos[q] = K;
      active &= ~(Slots{1} << q);
      // The previous step's update of columns K + 2 .. (see below): it runs while this step's
      // division does, instead of holding the ports when this step's multipliers are ready.
      if constexpr (K > 0) {
#pragma GCC unroll 1
        for (int c = K + 2; c < COLS; ++c) update(P, c, qp, up, lp, column(P, c), nullptr);
      }
      // Multipliers into column K; columns K + 1 (the next candidates, kept in registers) and
      // K + 2 now, the rest in the next step. The last step of an inner panel stages the
      // leftover rows' node j + 1 part.
      __m512d l[G], nextCand[G];
      double* const colK = column(P, K);
      for (int g = 0; g < G; ++g) {
        l[g] = _mm512_mul_pd(cand[g], r);
        _mm512_storeu_pd(colK + 8 * g, _mm512_mask_mov_pd(cand[g], part(active, g), l[g]));
      }
      if constexpr (K + 1 < NB) {
        update(P, K + 1, q, active, l, nullptr, nextCand);
        if constexpr (K + 2 < COLS) update(P, K + 2, q, active, l, column(P, K + 2), nullptr);
        step<COLS, K + 1>(P, rd, next, active, at, pos, nextCand, l, q, active, info);
      } else if constexpr (COLS == W) {
#pragma GCC unroll 1
        for (int c = NB; c < W; ++c) update(P, c, q, active, l, column(next, c - NB), nullptr);
      }
    }
  }

  /// The leftover rows of an eliminated inner panel (staged: their node j + 1 columns by slot;
  /// at: the slot at each position) into the carried slots of panel Q in position order, zeros
  /// in Q's node j + 2 columns.
  static MD_INLINE void carry(const double* staged, const int* at_left, double* Q) {
    constexpr int first = NB / 8;  // the vectors of the carried slots
    __m512i idx[G];
    __mmask8 valid[G], high[G];
    for (int g = first; g < G; ++g) {
      auto slot = [&](int e) MD_LAMBDA_INLINE {  // the source slot of lane e (scalars: the
        const int r = 8 * (g - first) + e;       // positions were just stored one by one)
        return static_cast<long long>(r < LEAD ? at_left[r] : 0);
      };
      idx[g] = _mm512_set_epi64(slot(7), slot(6), slot(5), slot(4), slot(3), slot(2), slot(1), slot(0));
      valid[g] = static_cast<__mmask8>(((1u << LEAD) - 1) >> (8 * (g - first)));
      high[g] = _mm512_cmpge_epi64_mask(idx[g], _mm512_set1_epi64(16));
    }
    for (int c = 0; c < NB; ++c) {
      const double* const src = staged + static_cast<std::size_t>(c) * LANES;
      for (int g = first; g < G; ++g) {
        __m512d v = _mm512_maskz_permutex2var_pd(valid[g], _mm512_loadu_pd(src), idx[g], _mm512_loadu_pd(src + 8));
        if constexpr (G > 2)  // slots 16 .. LANES - 1 (indices 16 .. act by their low four bits)
          v = _mm512_mask_blend_pd(high[g] & valid[g], v,
                                   _mm512_permutex2var_pd(_mm512_loadu_pd(src + 16), idx[g],
                                                          _mm512_loadu_pd(src + (G > 3 ? 24 : 16))));
        _mm512_storeu_pd(column(Q, c) + 8 * g, v);
      }
    }
    for (int c = NB; c < W; ++c)
      for (int g = first; g < G; ++g) _mm512_storeu_pd(column(Q, c) + 8 * g, _mm512_setzero_pd());
  }
};

template <int NB, int LEAD>
int factor(int n, const double* rows, double* panels, double* inv_diag, int* perm) {
  typedef ColumnLU<NB, LEAD> B;
  constexpr int M = B::M, W = B::W, LANES = B::LANES;
  const int nodes = n / NB;
  auto panel = [&](int j) { return panels + static_cast<std::size_t>(j) * W * LANES; };
  // The last node's own rows (fewer than NB: no whole blocks, and not past the matrix).
  auto loadTop = [&](double* P, int j) {
    for (int c = 0; c < NB; ++c)
      for (int q = 0; q < NB - LEAD; ++q)
        B::column(P, c)[q] = rows[static_cast<std::size_t>(LEAD + NB * j + q) * W + static_cast<std::size_t>(c)];
  };
  // Panel 0's carried slots: the anchor rows, on node 0.
  for (int c = 0; c < W; ++c)
    for (int r = 0; r < LEAD; ++r)
      B::column(panel(0), c)[NB + r] = c < NB ? rows[static_cast<std::size_t>(r) * W + static_cast<std::size_t>(c)] : 0.0;
  if (nodes > 1) B::loadInterval(panel(0), rows, 0);
  else loadTop(panel(0), 0);
  alignas(64) double staged[NB * LANES];  // the leftover rows' node j + 1 part, by slot
  for (int j = 0; j + 1 < nodes; ++j) {
    double* const P = panel(j);
    double* const Q = panel(j + 1);
    if (j + 2 < nodes) B::loadInterval(Q, rows, j + 1);
    else loadTop(Q, j + 1);
    if (const int k = B::template panel<W>(P, NB, inv_diag + NB * j, perm + M * j, staged)) return NB * j + k;
    B::carry(staged, perm + M * j + NB, Q);
  }
  const int j = nodes - 1;
  if (const int k = B::template panel<NB>(panel(j), NB - LEAD, inv_diag + NB * j, perm + M * j, nullptr))
    return NB * j + k;
  return 0;
}

}  // namespace columnkernel

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
#endif  // MD_AVX512_KERNEL


/// Solve with a block factor of either kernel: forward through the panels (the interchanges,
/// the unit lower factor, the leftover rows carried on), then back substitution node by node from
/// the top. Layout gives panel j's row at position i (entry of column c at row[c * stride]) and
/// the slots of the right-hand side (slot s at position i: perm[i]; the interval's row q and the
/// carried row r). The loops have fixed lengths and unroll, so the dependent chains (one multiply
/// and one update per unknown, the carried values from node to node) run in registers.
template <int NB, int LEAD, class Layout>
MD_INLINE void blockSolve(int n, const Layout& layout, const int* perm, const double* inv_diag, double* b) {
  static_assert(NB % 2 == 0, "the dot products below take two columns at a time");
  constexpr int M = LEAD + NB, S = Layout::stride;
  const int nodes = n / NB;
  double in[M];  // the panel's right-hand side by slot
  for (int r = 0; r < LEAD; ++r) in[Layout::carriedSlot(r)] = b[r];
  auto forward = [&](auto rowsc, int j) MD_LAMBDA_INLINE {
    constexpr int ROWS = decltype(rowsc)::value;
    const int* const pj = perm + M * j;
    for (int q = 0; q < ROWS - LEAD; ++q) in[Layout::intervalSlot(q)] = b[LEAD + NB * j + q];
    double v[ROWS];
    const double* R[ROWS];
#pragma GCC unroll 32
    for (int i = 0; i < ROWS; ++i) {
      v[i] = in[pj[i]];
      R[i] = layout.row(j, pj, i);
    }
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) {
      const double vk = v[k];
#pragma GCC unroll 32
      for (int i = k + 1; i < ROWS; ++i) v[i] -= R[i][k * S] * vk;
    }
#pragma GCC unroll 16
    for (int r = 0; r < NB; ++r) b[NB * j + r] = v[r];
    if constexpr (ROWS == M)
#pragma GCC unroll 16
      for (int r = 0; r < LEAD; ++r) in[Layout::carriedSlot(r)] = v[NB + r];
  };
  for (int j = 0; j + 1 < nodes; ++j) forward(std::integral_constant<int, M>{}, j);
  forward(std::integral_constant<int, NB>{}, nodes - 1);
  double xn[NB] = {};  // x of the node above
  for (int j = nodes - 1; j >= 0; --j) {
    const int* const pj = perm + M * j;
    const double* U[NB];  // U's rows
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) U[k] = layout.row(j, pj, k);
    const double* const rd = inv_diag + NB * j;
    // U12 x_{j+1} first: NB independent dot products, then U11 by back substitution.
    double t[NB];
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) t[k] = b[NB * j + k];
    if (j + 1 < nodes)
#pragma GCC unroll 16
      for (int k = 0; k < NB; ++k) {
        double s0 = 0.0, s1 = 0.0;
#pragma GCC unroll 16
        for (int c = 0; c < NB; c += 2) {
          s0 += U[k][(NB + c) * S] * xn[c];
          s1 += U[k][(NB + c + 1) * S] * xn[c + 1];
        }
        t[k] -= s0 + s1;
      }
    // Column by column: x_k = t_k / U_kk, then x_k leaves the rows above (the dependent chain
    // is one multiply and one update per unknown).
#pragma GCC unroll 16
    for (int k = NB - 1; k >= 0; --k) {
      const double xk = t[k] * rd[k];
      xn[k] = xk;
#pragma GCC unroll 16
      for (int i = 0; i < k; ++i) t[i] -= U[i][k * S] * xk;
    }
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) b[NB * j + k] = xn[k];
  }
}

/// The row kernel's factor: rows in place at their positions (see rowkernel::factor), the
/// right-hand side by panel row (the carried rows first).
template <int NB, int LEAD>
struct RowLayout {
  static constexpr int stride = 1;
  const double* rows;
  const double* carried;
  MD_INLINE const double* row(int j, const int*, int i) const {
    return i < LEAD ? carried + static_cast<std::size_t>(LEAD * j + i) * 2 * NB
                    : rows + static_cast<std::size_t>(LEAD + NB * j + i - LEAD) * 2 * NB;
  }
  static constexpr int intervalSlot(int q) { return LEAD + q; }
  static constexpr int carriedSlot(int r) { return r; }
};

/// The column kernel's factor: panels of columns, a row per slot (see columnkernel::ColumnLU).
template <int NB, int LEAD>
struct ColumnLayout {
  static constexpr int lanes = (LEAD + NB + 7) / 8 * 8, stride = lanes;
  const double* panels;
  MD_INLINE const double* row(int j, const int* pj, int i) const {
    return panels + static_cast<std::size_t>(j) * 2 * NB * lanes + static_cast<std::size_t>(pj[i]);
  }
  static constexpr int intervalSlot(int q) { return q; }
  static constexpr int carriedSlot(int r) { return NB + r; }
};

template <int NB, int LEAD>
MD_SIMD_CLONES void rowSolve(int n, const double* rows, const double* carried, const int* perm,
                             const double* inv_diag, double* b) {
  blockSolve<NB, LEAD>(n, RowLayout<NB, LEAD>{rows, carried}, perm, inv_diag, b);
}
template <int NB, int LEAD>
MD_SIMD_CLONES void columnSolve(int n, const double* panels, const int* perm, const double* inv_diag, double* b) {
  blockSolve<NB, LEAD>(n, ColumnLayout<NB, LEAD>{panels}, perm, inv_diag, b);
}

/// Whether this processor runs the AVX-512 block kernel (a test of the processor model that the
/// runtime library fills in at start-up).
bool columnKernel() {
#if MD_AVX512_KERNEL
  return __builtin_cpu_supports("avx512f");
#else
  return false;
#endif
}

/// The block LU with the structure's kernel (setBlockStructure chose it and sized its storage).
template <int NB, int LEAD>
int blockFactor(bool columns, int n, double* rows, double* carried, double* panels, double* inv_diag, int* perm) {
#if MD_AVX512_KERNEL
  if (columns) return columnkernel::factor<NB, LEAD>(n, rows, panels, inv_diag, perm);
#endif
  (void)columns;
  (void)panels;
  return rowkernel::factor<NB, LEAD>(n, rows, carried, inv_diag, perm);
}
template <int NB, int LEAD>
void blockSolve(bool columns, int n, const double* rows, const double* carried, const double* panels,
                const double* inv_diag, const int* perm, double* b) {
  if (columns) columnSolve<NB, LEAD>(n, panels, perm, inv_diag, b);
  else rowSolve<NB, LEAD>(n, rows, carried, perm, inv_diag, b);
}

#if !defined(__clang__) && defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

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
  // The kernel's storage (see rowkernel::factor, columnkernel::ColumnLU): the row kernel
  // eliminates in place in rows_ and the carried rows of every panel (lead per node), the column
  // kernel in panels of 2 block columns of the panel rows (rounded up to 8) per node. Both: per
  // node the permutation (M = lead + block) and U's reciprocal diagonal.
  columns_ = columnKernel();
  const std::size_t nodes = static_cast<std::size_t>(n_ / block), M = static_cast<std::size_t>(lead + block),
                    W = static_cast<std::size_t>(2 * block), lanes = (M + 7) / 8 * 8;
  rows_.assign(static_cast<std::size_t>(n_) * W, 0.0);
  carried_.assign(columns_ ? 0 : nodes * static_cast<std::size_t>(lead) * W, 0.0);
  panels_.assign(columns_ ? nodes * W * lanes : 0, 0.0);
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
    info = blockFactor<8, 5>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(),
                                  perm_.data());
  else if (block_ == 16 && lead_ == 10)  // 3-D, anchored
    info = blockFactor<16, 10>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(),
                                  perm_.data());
  else if (block_ == 16 && lead_ == 7)   // 3-D, free lower end
    info = blockFactor<16, 7>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(),
                                  perm_.data());
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
    blockSolve<8, 5>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(), perm_.data(),
                           b.data());
    return;
  }
  if (block_ == 16 && lead_ == 10) {
    blockSolve<16, 10>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(), perm_.data(),
                           b.data());
    return;
  }
  if (block_ == 16 && lead_ == 7) {
    blockSolve<16, 7>(columns_, n_, rows_.data(), carried_.data(), panels_.data(), inv_diag_.data(), perm_.data(),
                           b.data());
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
