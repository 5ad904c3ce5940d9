// Node-by-node block LU of the box scheme's Newton matrix (BandedMatrix::setBlockStructure):
// the helpers of the kernels, the kernels in their own files (block_lu_row.hpp: portable,
// row-major, in place; block_lu_avx512.hpp: the AVX-512 column kernel; block_lu_eigen.hpp), and
// the solve shared by all. Internal to banded_matrix.cpp, which includes it once; not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <utility>

// The block elimination has an AVX-512 kernel on x86-64 with GCC or Clang (see ColumnLU), chosen
// at run time when the processor has AVX-512F; elsewhere it runs the Eigen kernel (EigenLU). The
// build option MD_BLOCK_KERNEL (CMakeLists.txt) can choose the Eigen kernel or the portable row
// kernel (rowkernel) everywhere instead, and MD_NO_MULTIVERSION leaves the AVX-512 kernel out.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION) && \
    !defined(MD_BLOCK_KERNEL_EIGEN) && !defined(MD_BLOCK_KERNEL_PORTABLE)
#define MD_AVX512_KERNEL 1
#include <immintrin.h>
#else
#define MD_AVX512_KERNEL 0
#endif

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
namespace block_lu {

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

/// The panels a factor call eliminates (two-ended elimination, see banded_matrix.cpp): all of
/// them; the inner ones only (every node but the last, whose carried rows the last inner panel
/// leaves in its storage); or, after kInner, the last one only (its own rows loaded then).
enum class Panels { kAll, kInner, kLast };

/// Where the column kernel reads a block structure's rows (2 NB values each): the LEAD lead
/// rows, interval j's NB rows at interval0 + step j, the last node's own rows. A mirror (the
/// two-ended elimination's upper sweep) reads the matrix's rows in reverse order of the
/// intervals (step < 0) with each interval's two nodes swapped.
struct RowSource {
  const double* lead;
  const double* interval0;
  std::ptrdiff_t step;
  bool swap;
  const double* own;
};
/// The rows of an n-unknown block structure in their own order.
template <int NB, int LEAD>
RowSource rowsInOrder(int n, const double* rows) {
  constexpr std::ptrdiff_t W = 2 * NB;
  return RowSource{rows, rows + LEAD * W, NB * W, false, rows + static_cast<std::ptrdiff_t>(n - NB + LEAD) * W};
}

}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics

#include "block_lu_row.hpp"
#include "block_lu_avx512.hpp"
#include "block_lu_eigen.hpp"

namespace mooring_dynamics {
namespace core {
namespace block_lu {


/// The forward part's sweep over the panels (blockForward; block_lu_inverse.hpp's
/// inverseForward): with Panels::kAll or kInner the inner panels from the anchor rows' b[0 ..
/// LEAD), kInner leaving the values carried into the last node in carried[0 .. LEAD); with
/// kLast the last panel only, from carried. forward(rows, j) eliminates panel j (its rows: an
/// std::integral_constant, M for an inner panel, NB for the last) and carries `in` on.
template <int NB, int LEAD, class Layout, class Forward>
MD_INLINE void forwardPanels(int nodes, double* in, const double* b, Panels part, double* carried,
                             const Forward& forward) {
  constexpr int M = LEAD + NB;
  if (part != Panels::kLast) {
    for (int r = 0; r < LEAD; ++r) in[Layout::carriedSlot(r)] = b[r];
    for (int j = 0; j + 1 < nodes; ++j) forward(std::integral_constant<int, M>{}, j);
    if (part == Panels::kInner) {
      for (int r = 0; r < LEAD; ++r) carried[r] = in[Layout::carriedSlot(r)];
      return;
    }
  } else {
    for (int r = 0; r < LEAD; ++r) in[Layout::carriedSlot(r)] = carried[r];
  }
  forward(std::integral_constant<int, NB>{}, nodes - 1);
}

/// Solve with a block factor of either kernel, in two parts: forward through the panels (the
/// interchanges, the unit lower factor, the leftover rows carried on), then back substitution
/// node by node from the top. Layout gives panel j's row at position i (entry of column c at
/// row[c * stride]) and the slots of the right-hand side (slot s at position i: perm[i]; the
/// interval's row q and the carried row r). The loops have fixed lengths and unroll, so the
/// dependent chains (one multiply and one update per unknown, the carried values from node to
/// node) run in registers.
///
/// Forward: with Panels::kAll or kInner the inner panels (from the anchor rows' b[0 .. LEAD));
/// with kInner the values carried into the last node are left in carried[0 .. LEAD); with
/// kLast the last panel only, from carried. b[NB j ..) receives node j's forward values.
template <int NB, int LEAD, class Layout>
MD_INLINE void blockForward(int n, const Layout& layout, const int* perm, double* b, Panels part, double* carried) {
  constexpr int M = LEAD + NB, S = Layout::stride;
  const int nodes = n / NB;
  double in[M];  // the panel's right-hand side by slot
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
  forwardPanels<NB, LEAD, Layout>(nodes, in, b, part, carried, forward);
}

/// Back substitution over nodes from, from - 1, .., to (after the forward part): b[NB j ..)
/// holds node j's forward values and receives its x. x_above: x of node from + 1, or null when
/// from is the last node.
template <int NB, int LEAD, class Layout>
MD_INLINE void blockBackward(int from, int to, const Layout& layout, const int* perm, const double* inv_diag,
                             double* b, const double* x_above) {
  static_assert(NB % 2 == 0, "the dot products below take two columns at a time");
  constexpr int M = LEAD + NB, S = Layout::stride;
  double xn[NB] = {};  // x of the node above
  if (x_above)
    for (int k = 0; k < NB; ++k) xn[k] = x_above[k];
  for (int j = from; j >= to; --j) {
    const int* const pj = perm + M * j;
    const double* U[NB];  // U's rows
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) U[k] = layout.row(j, pj, k);
    const double* const rd = inv_diag + NB * j;
    // U12 x_{j+1} first: NB independent dot products, then U11 by back substitution.
    double t[NB];
#pragma GCC unroll 16
    for (int k = 0; k < NB; ++k) t[k] = b[NB * j + k];
    if (j < from || x_above)
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

/// The Eigen kernel's factor: a contiguous row-major panel per node, rows in position order
/// (see eigenkernel::EigenLU), the right-hand side by panel row as in the row kernel.
template <int NB, int LEAD>
struct PanelLayout {
  static constexpr int stride = 1;
  const double* panels;
  MD_INLINE const double* row(int j, const int*, int i) const {
    return panels + static_cast<std::size_t>((LEAD + NB) * j + i) * 2 * NB;
  }
  static constexpr int intervalSlot(int q) { return LEAD + q; }
  static constexpr int carriedSlot(int r) { return r; }
};

template <int NB, int LEAD>
MD_SIMD_CLONES void rowForward(int n, const double* rows, const double* carried, const int* perm, double* b,
                               Panels part, double* carry) {
  blockForward<NB, LEAD>(n, RowLayout<NB, LEAD>{rows, carried}, perm, b, part, carry);
}
template <int NB, int LEAD>
MD_SIMD_CLONES void rowBackward(int from, int to, const double* rows, const double* carried, const int* perm,
                                const double* inv_diag, double* b, const double* x_above) {
  blockBackward<NB, LEAD>(from, to, RowLayout<NB, LEAD>{rows, carried}, perm, inv_diag, b, x_above);
}
template <int NB, int LEAD>
MD_SIMD_CLONES void columnForward(int n, const double* panels, const int* perm, double* b, Panels part,
                                  double* carry) {
  blockForward<NB, LEAD>(n, ColumnLayout<NB, LEAD>{panels}, perm, b, part, carry);
}
template <int NB, int LEAD>
MD_SIMD_CLONES void columnBackward(int from, int to, const double* panels, const int* perm, const double* inv_diag,
                                   double* b, const double* x_above) {
  blockBackward<NB, LEAD>(from, to, ColumnLayout<NB, LEAD>{panels}, perm, inv_diag, b, x_above);
}

template <int NB, int LEAD>
MD_SIMD_CLONES void panelForward(int n, const double* panels, const int* perm, double* b, Panels part,
                                 double* carry) {
  blockForward<NB, LEAD>(n, PanelLayout<NB, LEAD>{panels}, perm, b, part, carry);
}
template <int NB, int LEAD>
MD_SIMD_CLONES void panelBackward(int from, int to, const double* panels, const int* perm, const double* inv_diag,
                                  double* b, const double* x_above) {
  blockBackward<NB, LEAD>(from, to, PanelLayout<NB, LEAD>{panels}, perm, inv_diag, b, x_above);
}

/// The block elimination's kernels: the portable row kernel (in place, rowkernel), the AVX-512
/// column kernel (columnkernel) and the Eigen kernel (eigenkernel). All give the same bits.
enum class Kernel { kRows, kColumns, kEigen };

/// The block size (unknowns per node) the AVX-512 kernel is used for: 8 (2-D). With 16 (3-D)
/// it gains at most about 10 % (see block_lu_avx512.hpp's header), below the 15 % rule.
constexpr int kColumnKernelBlock = 8;

/// The kernel of this build and processor for blocks of `block` unknowns: AVX-512 when it is compiled in and the processor has
/// AVX-512F (a test of the processor model that the runtime library fills in at start-up), else
/// the row kernel, or the one the build option MD_BLOCK_KERNEL chose. The environment variable
/// MD_BLOCK_KERNEL=eigen or =portable chooses another at run time (tests and benchmarks of the
/// kernels on one build); anything else in it is ignored.
Kernel blockKernel(int block) {
  if (const char* env = std::getenv("MD_BLOCK_KERNEL")) {
    if (std::strcmp(env, "eigen") == 0) return Kernel::kEigen;
    if (std::strcmp(env, "portable") == 0) return Kernel::kRows;
  }
#if defined(MD_BLOCK_KERNEL_PORTABLE)
  (void)block;
  return Kernel::kRows;
#elif defined(MD_BLOCK_KERNEL_EIGEN)
  (void)block;
  return Kernel::kEigen;
#elif MD_AVX512_KERNEL
  return block == kColumnKernelBlock && __builtin_cpu_supports("avx512f") ? Kernel::kColumns : Kernel::kRows;
#else
  (void)block;
  return Kernel::kRows;  // the row kernel: faster than the Eigen one here (block_lu_avx512.hpp's figures)
#endif
}

/// A block-structured matrix's factor storage (setBlockStructure chose the kernel and sized it).
struct BlockStorage {
  double* rows;
  double* carried;   ///< row kernel
  double* panels;    ///< column kernel
  double* inv_diag;
  int* perm;
};

/// The block LU with the structure's kernel, of the panels `part` names.
template <int NB, int LEAD>
int blockFactor(Kernel kernel, int n, const BlockStorage& s, Panels part = Panels::kAll) {
#if MD_AVX512_KERNEL
  if constexpr (NB == kColumnKernelBlock)
    if (kernel == Kernel::kColumns)
      return columnkernel::factor<NB, LEAD>(n, rowsInOrder<NB, LEAD>(n, s.rows), s.panels, s.inv_diag, s.perm, part);
#endif
  if (kernel == Kernel::kEigen)
    return eigenkernel::factor<NB, LEAD>(n, rowsInOrder<NB, LEAD>(n, s.rows), s.panels, s.inv_diag, s.perm, part);
  return rowkernel::factor<NB, LEAD>(n, s.rows, s.carried, s.inv_diag, s.perm, part);
}
template <int NB, int LEAD>
void blockForward(Kernel kernel, int n, const BlockStorage& s, double* b, Panels part, double* carry) {
  if constexpr (NB == kColumnKernelBlock)
    if (kernel == Kernel::kColumns) return columnForward<NB, LEAD>(n, s.panels, s.perm, b, part, carry);
  if (kernel == Kernel::kEigen) panelForward<NB, LEAD>(n, s.panels, s.perm, b, part, carry);
  else rowForward<NB, LEAD>(n, s.rows, s.carried, s.perm, b, part, carry);
}
template <int NB, int LEAD>
void blockBackward(Kernel kernel, int from, int to, const BlockStorage& s, double* b, const double* x_above) {
  if constexpr (NB == kColumnKernelBlock)
    if (kernel == Kernel::kColumns) return columnBackward<NB, LEAD>(from, to, s.panels, s.perm, s.inv_diag, b, x_above);
  if (kernel == Kernel::kEigen) panelBackward<NB, LEAD>(from, to, s.panels, s.perm, s.inv_diag, b, x_above);
  else rowBackward<NB, LEAD>(from, to, s.rows, s.carried, s.perm, s.inv_diag, b, x_above);
}
/// The inner panels of the mirror of nodes meet .. nodes - 1 of a block structure with lead
/// NB - MLEAD (whose rows are `rows`): its node i is node nodes - 1 - i, its lead rows the last
/// node's own rows, its interval i interval nodes - 2 - i with the two nodes' columns swapped;
/// its last node, the meeting node, is left (Panels::kInner). The column and Eigen kernels read
/// the rows where they are; the row kernel, which works in place, copies them into mirror.rows.
template <int NB, int MLEAD>
int mirrorFactor(Kernel kernel, int nodes, int meet, const double* rows, const BlockStorage& mirror) {
  constexpr int LEAD = NB - MLEAD, W = 2 * NB;
  const int mirror_n = NB * (nodes - meet);
  const double* const own = rows + static_cast<std::size_t>(LEAD + NB * (nodes - 1)) * W;
  const double* const last_interval = rows + static_cast<std::size_t>(LEAD + NB * (nodes - 2)) * W;
  const RowSource source{own, last_interval, -NB * W, true, nullptr};
#if MD_AVX512_KERNEL
  if constexpr (NB == kColumnKernelBlock)
    if (kernel == Kernel::kColumns)
      return columnkernel::factor<NB, MLEAD>(mirror_n, source, mirror.panels, mirror.inv_diag, mirror.perm,
                                           Panels::kInner);
#endif
  if (kernel == Kernel::kEigen)
    return eigenkernel::factor<NB, MLEAD>(mirror_n, source, mirror.panels, mirror.inv_diag, mirror.perm,
                                          Panels::kInner);
  double* const out = mirror.rows;
  for (int q = 0; q < MLEAD; ++q)
    for (int c = 0; c < W; ++c) out[q * W + c] = c < NB ? own[q * W + c] : 0.0;
  for (int i = 0; i + 1 < nodes - meet; ++i) {
    const double* const src = last_interval - static_cast<std::ptrdiff_t>(NB * W) * i;
    double* const dst = out + static_cast<std::size_t>(MLEAD + NB * i) * W;
    for (int r = 0; r < NB; ++r)
      for (int c = 0; c < NB; ++c) {
        dst[r * W + c] = src[r * W + NB + c];
        dst[r * W + NB + c] = src[r * W + c];
      }
  }
  return rowkernel::factor<NB, MLEAD>(mirror_n, mirror.rows, mirror.carried, mirror.inv_diag, mirror.perm,
                                      Panels::kInner);
}

/// The LEAD rows the inner panels of an n-unknown factor leave for its last node, on that node's
/// NB columns, row-major into out (in carried order: the order the forward part carries their
/// right-hand sides in).
template <int NB, int LEAD>
void leftoverRows(Kernel kernel, int n, const BlockStorage& s, double* out) {
  const int j = n / NB - 1;
  if (kernel == Kernel::kColumns) {
    constexpr int lanes = (LEAD + NB + 7) / 8 * 8;
    const double* const P = s.panels + static_cast<std::size_t>(j) * 2 * NB * lanes;
    for (int r = 0; r < LEAD; ++r)
      for (int c = 0; c < NB; ++c) out[r * NB + c] = P[static_cast<std::size_t>(c) * lanes + NB + r];
  } else {
    const double* const C = kernel == Kernel::kEigen ? s.panels + static_cast<std::size_t>((LEAD + NB) * j) * 2 * NB
                                                     : s.carried + static_cast<std::size_t>(LEAD * j) * 2 * NB;
    for (int r = 0; r < LEAD; ++r)
      for (int c = 0; c < NB; ++c) out[r * NB + c] = C[r * 2 * NB + c];
  }
}

#if !defined(__clang__) && defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

}  // namespace block_lu
}  // namespace core
}  // namespace mooring_dynamics
