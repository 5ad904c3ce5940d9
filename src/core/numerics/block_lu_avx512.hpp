// The AVX-512 column kernel of the block LU: a part of block_lu.hpp (its helpers, macros and
// floating-point settings), included by it only.
//
// Kept for 8 unknowns per node (2-D) only, against the Eigen kernel (block_lu_eigen.hpp: Eigen
// fixed-size blocks, same bits): the rule is to keep the intrinsics only where a whole run is
// more than 15 % faster with them. Whole runs of `cable_sim dynamic CONFIG --threads 1
// --no-progress`, the two kernels alternately on one build (MD_BLOCK_KERNEL=eigen in the
// environment, AVX-512 first in each pair), medians of three, on a shared 2-core AMD EPYC with
// AVX-512 at a load of 4 to 9 (two-thread runs were not measurable there: the threads wait):
//   A.3 chain_mooring             0.94 s  (Eigen 1.95 s: 2.08 times as long)   kept
//   A.2 s_tether                  1.01 s  (Eigen 1.10 s: 1.09)                 kept with A.3
//   A.2 s_tether --dt 0.1         2.63 s  (Eigen 2.72 s: 1.04)
//   A.1 towed_array (16 per node) 3.11 s  (Eigen 2.54 s: 0.82)                 not used
// A.1 again with the pair's order reversed (Eigen first; AVX-512 from the build before this
// change): AVX-512 3.51 s, Eigen 3.83 s (1.09). The order within a pair moves A.1 by about 20 %
// either way, so with 16 unknowns per node the kernel gains at most about 10 %: below the rule's
// 15 %, so block_lu.hpp uses it for blocks of 8 only (kColumnKernelBlock). A.3 is twice as fast
// with it, well beyond that noise. bench_banded (medians of three): BM_BlockFactor8/170 28 us
// (Eigen 91 us, row kernel 72 us), BM_BlockFactor16/170 252 us (Eigen 445 us, row kernel
// 349 us); the solves are shared. Elsewhere (16 unknowns per node, and without AVX-512: ARM,
// older x86) the portable row kernel runs, as before the Eigen kernel existed: it is faster than
// the Eigen one in bench_banded (above), and whole A.1 runs with the Eigen kernel took 2.25 s
// against 2.00 s with the row kernel (medians of three, quiet host). The Eigen kernel stays
// selectable (MD_BLOCK_KERNEL=eigen) and CI runs the dynamics tests with it.
#pragma once

namespace mooring_dynamics {
namespace core {
namespace block_lu {

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
  // 8 unknowns per node only (block_lu.hpp's kColumnKernelBlock; the header says why): the slots
  // fit two vectors.
  static_assert(NB == 8 && G == 2 && M < LANES, "8 unknowns per node: two vectors of slots, a padding lane");
  typedef std::uint32_t Slots;  // one bit per slot

  static MD_INLINE double* column(double* panel, int c) { return panel + static_cast<std::size_t>(c) * LANES; }

  /// An inner panel keeps its node j + 1 columns in registers through its NB steps (NB G = 16
  /// of the 32 vectors) instead of loading and storing each at every step: the updates were
  /// bound by the stores (one 512-bit store per vector and update, 184 of them per node;
  /// half-width store path on Zen 4). The same operations in the same order, so the same bits.
  static constexpr bool HELD = true;
  typedef __m512d Held[HELD ? NB : 1][G];

  /// Lane q of the two vectors v in every lane.
  static MD_INLINE __m512d broadcastLane(const __m512d* v, int q) {
    return _mm512_permutex2var_pd(v[0], _mm512_set1_epi64(q), v[1]);
  }
  /// update() of a column held in registers, in place.
  static MD_INLINE void updateHeld(__m512d* v, int q, Slots upd, const __m512d* l) {
    const __m512d u = broadcastLane(v, q);
    for (int g = 0; g < G; ++g) v[g] = _mm512_mask_sub_pd(v[g], part(upd, g), v[g], _mm512_mul_pd(l[g], u));
  }
  /// Column c (>= NB) of an inner panel minus l u: held (in registers) or in P.
  template <int COLS, int C>
  static MD_INLINE void updateRight(double* P, Held& held, int q, Slots upd, const __m512d* l) {
    if constexpr (COLS == W && HELD && C >= NB) updateHeld(held[C - NB], q, upd, l);
    else update(P, C, q, upd, l, column(P, C), nullptr);
  }
  /// updateRight of columns C .. COLS - 1.
  template <int COLS, int C>
  static MD_INLINE void updateFrom(double* P, Held& held, int q, Slots upd, const __m512d* l) {
    if constexpr (C < COLS) {
      updateRight<COLS, C>(P, held, q, upd, l);
      updateFrom<COLS, C + 1>(P, held, q, upd, l);
    }
  }
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
  static MD_INLINE void loadInterval(double* panel, const RowSource& in, int j) {
    const double* const src = in.interval0 + in.step * j;
    for (int q = 0; q < NB; q += 8)
      for (int c = 0; c < W; c += 8)
        transpose8(src + q * W + (in.swap ? (c + NB) % W : c), W, column(panel, c) + q, LANES);
  }

  /// Eliminates the NB columns of a panel: count interval rows (slots 0 ..) and the LEAD carried
  /// ones, on COLS columns. For an inner panel (COLS = W) the leftover rows' node j + 1 part goes
  /// into the carried slots of next. Returns 0, or the 1-based column of the first exactly zero
  /// pivot. With GUESS the pivot slots are taken from perm as the last factorization left it
  /// (its pivot slot of step K at position K), so that the pivot's reciprocal does not wait for
  /// the search; the search still runs beside the chain and checks every guess, and a wrong
  /// one is replaced by the search's choice (see step). A right guess is the search's choice,
  /// so the factor is the same bit for bit either way.
  template <int COLS, bool GUESS>
  static MD_INLINE int panel(double* P, int count, double* rd, int* perm, double* next) {
    constexpr int ROWS = COLS == W ? M : NB;
    Slots active = ((Slots{1} << count) - 1) | (((Slots{1} << LEAD) - 1) << NB);
    std::int64_t at[LANES];  // the slot at each position (the padding lane past the rows)
    int pos[LANES];          // the position of each slot
    for (int i = 0; i < LANES; ++i) {
      at[i] = i < LEAD ? NB + i : i < ROWS ? i - LEAD : LANES - 1;
      pos[i] = i < NB ? LEAD + i : i - NB;
    }
    int guess[NB] = {};
    if constexpr (GUESS)
      for (int k = 0; k < NB; ++k) guess[k] = perm[k] & (LANES - 1);  // (in range whatever perm holds)
    __m512d cand[G], none[G] = {};
    for (int g = 0; g < G; ++g) cand[g] = _mm512_loadu_pd(column(P, 0) + 8 * g);
    Held held;
    if constexpr (COLS == W && HELD)
      for (int c = NB; c < W; ++c)
        for (int g = 0; g < G; ++g) held[c - NB][g] = _mm512_loadu_pd(column(P, c) + 8 * g);
    int info = 0;
    step<COLS, 0, GUESS>(P, rd, next, active, at, pos, cand, none, 0, 0, info, guess, held);
    if (info != 0) return info;
    for (int r = 0; r < ROWS; ++r) perm[r] = static_cast<int>(at[r]);
    return 0;
  }

  /// 1 / pivot, broadcast, for a missed guess: out of line (cold), so that the compiler keeps
  /// the branch instead of selecting between the guess and the search, which would make the
  /// chain wait for the search again.
  __attribute__((noinline, cold)) static __m512d missedPivot(const __m512d* cand, int q) {
    return _mm512_set1_pd(1.0 / lane(cand, q));
  }

  /// Lane q of the two vectors v (q < LANES = 16).
  static MD_INLINE double lane(const __m512d* v, int q) {
    return _mm512_cvtsd_f64(_mm512_permutex2var_pd(v[0], _mm512_set1_epi64(q), v[1]));
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
  template <int COLS, int K, bool GUESS>
  static MD_INLINE void step(double* P, double* rd, double* next, Slots& active, std::int64_t* at, int* pos,
                             const __m512d* cand, const __m512d* lp, int qp, Slots up, int& info,
                             const int* guess, Held& held) {
    if constexpr (K < NB) {
      // With a guess, 1 / pivot from the guessed slot right away (1 / p is the search path's
      // 1 / |p| with p's sign: IEEE division rounds the magnitude alike).
      int qg = 0;
      __m512d rg = _mm512_setzero_pd();
      if constexpr (GUESS) {
        qg = guess[K];
        rg = _mm512_set1_pd(1.0 / lane(cand, qg));
      }
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
      const bool zero = _mm_cvtsi128_si64(_mm512_castsi512_si128(best)) == 0;  // every candidate exactly zero
      if (!GUESS && zero) {
        info = K + 1;
        return;
      }
      // The rows holding it, and the negative candidates, one bit per slot.
      Slots tied = 0, negative = 0;
      for (int g = 0; g < G; ++g) {
        tied |= Slots{_mm512_cmpeq_epi64_mask(mag[g], best)} << (8 * g);
        if constexpr (!GUESS)
          negative |= Slots{_mm512_cmplt_epi64_mask(_mm512_castpd_si512(cand[g]), _mm512_setzero_si512())} << (8 * g);
      }
      int q = __builtin_ctz(tied);
      if (__builtin_expect((tied & (tied - 1)) != 0, 0))  // a tie: the first in position order
        for (Slots t = tied & (tied - 1); t != 0; t &= t - 1) {
          const int s = __builtin_ctz(t);
          if (pos[s] < pos[q]) q = s;
        }
      // With a guess, the search's choice must be the guess (an active slot, nonzero). A
      // branch, not a data dependency: the processor runs on with the guess while the search
      // completes; a miss (its branch mispredicted) takes this step's pivot from the search, and
      // the next steps again from their guesses.
      __m512d r;
      if constexpr (GUESS) {
        if (__builtin_expect(zero || q != qg, 0)) {
          if (zero) {
            info = K + 1;
            return;
          }
          r = missedPivot(cand, q);
        } else {
          q = qg;
          r = rg;
        }
      } else {
        const double rcp_abs = 1.0 / _mm_cvtsd_f64(_mm512_castpd512_pd128(_mm512_castsi512_pd(best)));
        // 1 / pivot, broadcast: the sign bit of a negative pivot set by an exclusive or (exact:
        // rounding is symmetric), not a branch on the sign.
        r = _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(_mm512_set1_pd(rcp_abs)),
                                                 _mm512_set1_epi64(static_cast<long long>((negative >> q) & 1) << 63)));
      }
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
        if constexpr (COLS == W && HELD) {
#pragma GCC unroll 1
          for (int c = K + 2; c < NB; ++c) update(P, c, qp, up, lp, column(P, c), nullptr);
          updateFrom<COLS, std::max(K + 2, NB)>(P, held, qp, up, lp);
        } else {
#pragma GCC unroll 1
          for (int c = K + 2; c < COLS; ++c) update(P, c, qp, up, lp, column(P, c), nullptr);
        }
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
        if constexpr (K + 2 < COLS) updateRight<COLS, K + 2>(P, held, q, active, l);
        step<COLS, K + 1, GUESS>(P, rd, next, active, at, pos, nextCand, l, q, active, info, guess, held);
      } else if constexpr (COLS == W) {
        if constexpr (HELD) {
          // The held columns as the panel keeps them (U's rows: their state before this last
          // step), then this step's update of the leftover rows, staged.
          for (int c = NB; c < W; ++c) {
            for (int g = 0; g < G; ++g) _mm512_storeu_pd(column(P, c) + 8 * g, held[c - NB][g]);
            updateHeld(held[c - NB], q, active, l);
            for (int g = 0; g < G; ++g) _mm512_storeu_pd(column(next, c - NB) + 8 * g, held[c - NB][g]);
          }
        } else {
#pragma GCC unroll 1
          for (int c = NB; c < W; ++c) update(P, c, q, active, l, column(next, c - NB), nullptr);
        }
      }
    }
  }

  /// The leftover rows of an eliminated inner panel (staged: their node j + 1 columns by slot;
  /// at: the slot at each position) into the carried slots of panel Q in position order, zeros
  /// in Q's node j + 2 columns.
  static MD_INLINE void carry(const double* staged, const int* at_left, double* Q) {
    constexpr int first = NB / 8;  // the vectors of the carried slots
    __m512i idx[G];
    __mmask8 valid[G];
    for (int g = first; g < G; ++g) {
      auto slot = [&](int e) MD_LAMBDA_INLINE {  // the source slot of lane e (scalars: the
        const int r = 8 * (g - first) + e;       // positions were just stored one by one)
        return static_cast<long long>(r < LEAD ? at_left[r] : 0);
      };
      idx[g] = _mm512_set_epi64(slot(7), slot(6), slot(5), slot(4), slot(3), slot(2), slot(1), slot(0));
      valid[g] = static_cast<__mmask8>(((1u << LEAD) - 1) >> (8 * (g - first)));
    }
    for (int c = 0; c < NB; ++c) {
      const double* const src = staged + static_cast<std::size_t>(c) * LANES;
      for (int g = first; g < G; ++g) {
        const __m512d v = _mm512_maskz_permutex2var_pd(valid[g], _mm512_loadu_pd(src), idx[g], _mm512_loadu_pd(src + 8));
        _mm512_storeu_pd(column(Q, c) + 8 * g, v);
      }
    }
    for (int c = NB; c < W; ++c)
      for (int g = first; g < G; ++g) _mm512_storeu_pd(column(Q, c) + 8 * g, _mm512_setzero_pd());
  }
};

template <int NB, int LEAD>
int factor(int n, const RowSource& in, double* panels, double* inv_diag, int* perm, Panels part) {
  typedef ColumnLU<NB, LEAD> B;
  constexpr int M = B::M, W = B::W, LANES = B::LANES;
  const int nodes = n / NB;
  auto panel = [&](int j) { return panels + static_cast<std::size_t>(j) * W * LANES; };
  // The last node's own rows (fewer than NB: no whole blocks, and not past the matrix).
  auto loadTop = [&](double* P) {
    for (int c = 0; c < NB; ++c)
      for (int q = 0; q < NB - LEAD; ++q)
        B::column(P, c)[q] = in.own[static_cast<std::size_t>(q) * W + static_cast<std::size_t>(c)];
  };
  const int j = nodes - 1;
  // Panel 0's carried slots: the anchor rows, on node 0.
  auto loadLead = [&](double* P) {
    for (int c = 0; c < W; ++c)
      for (int r = 0; r < LEAD; ++r)
        B::column(P, c)[NB + r] = c < NB ? in.lead[static_cast<std::size_t>(r) * W + static_cast<std::size_t>(c)] : 0.0;
  };
  if (part != Panels::kLast) {
    loadLead(panel(0));
    if (nodes > 1) B::loadInterval(panel(0), in, 0);
    else loadTop(panel(0));
    alignas(64) double staged[NB * LANES];  // the leftover rows' node j + 1 part, by slot
    for (int i = 0; i + 1 < nodes; ++i) {
      double* const P = panel(i);
      double* const Q = panel(i + 1);
      if (i + 2 < nodes) B::loadInterval(Q, in, i + 1);
      else if (part == Panels::kAll) loadTop(Q);
      // The pivots of the last factorization as guesses (ColumnLU::panel): 40 -> 33 us a
      // factorization in bench_banded BM_BlockFactor8.
      const int k = B::template panel<W, true>(P, NB, inv_diag + NB * i, perm + M * i, staged);
      if (k != 0) return NB * i + k;
      B::carry(staged, perm + M * i + NB, Q);
    }
    if (part == Panels::kInner) return 0;
  } else {
    loadTop(panel(j));
  }
  if (const int k = B::template panel<NB, false>(panel(j), NB - LEAD, inv_diag + NB * j, perm + M * j, nullptr))
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

}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics
