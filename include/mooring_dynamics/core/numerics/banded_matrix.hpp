// Square banded matrix in LAPACK band storage with LU factorization (dgbtf2's algorithm; LAPACK's
// dgbtrf for bandwidths without a compiled kernel) and solves (dgbtrs's). The box scheme couples
// only neighbouring nodes, so the Newton matrix of an n-node line is banded with half-bandwidths
// of about 1.5 N; the cost of a factorization is linear in n. Optionally the matrix declares the
// box scheme's block structure and is then stored by rows and eliminated node by node
// (setBlockStructure).
#pragma once

#include <cassert>
#include <cstddef>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mooring_dynamics {
namespace core {

class ForkJoin;

/// Allocator of cache-line aligned storage: the rows of the block structure are 2 block doubles
/// (a multiple of 64 bytes), so that their vectors never straddle two lines.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const CacheLineAllocator<U>&) const { return false; }
};

class BandedMatrix {
 public:
  BandedMatrix() = default;
  /// n x n matrix with kl sub- and ku super-diagonals, all zero.
  BandedMatrix(int n, int kl, int ku);

  int size() const { return n_; }
  int lower() const { return kl_; }
  int upper() const { return ku_; }

  void setZero();
  /// Zero rows [first, first + count) only (all their entries in the band or pattern).
  void setZeroRows(int first, int count);
  /// Mark the matrix as being assembled anew without clearing it: for a caller that then writes
  /// every entry (NewtonSystem::writesEveryBlockEntry); factorized() is false afterwards.
  void beginAssembly() { factorized_ = false; }
  /// Element access; (i, j) must lie inside the band (checked in debug builds).
  /// LAPACK band storage: A(i, j) lives at AB(kl + ku + i - j, j) (0-based), column-major.
  /// With a block structure (setBlockStructure) the entries live in rows of 2 * block values
  /// starting at the row's first node, and (i, j) must lie in the pattern.
  double& at(int i, int j) {
    assert(i >= 0 && i < n_ && j >= 0 && j < n_ && inBand(i, j));
    if (block_ > 0) {
      if (!inPattern(i, j)) throwOutsidePattern(i, j);
      return rows_[static_cast<std::size_t>(i) * (2 * block_) + static_cast<std::size_t>(j - block_ * rowNode(i))];
    }
    return ab_[static_cast<std::size_t>(kl_ + ku_ + i - j) + static_cast<std::size_t>(j) * ldab_];
  }
  double get(int i, int j) const {
    if (!inBand(i, j)) return 0.0;
    if (block_ > 0)
      return inPattern(i, j)
                 ? rows_[static_cast<std::size_t>(i) * (2 * block_) + static_cast<std::size_t>(j - block_ * rowNode(i))]
                 : 0.0;
    return ab_[static_cast<std::size_t>(kl_ + ku_ + i - j) + static_cast<std::size_t>(j) * ldab_];
  }
  /// Block structure: row i's 2 * block entries, from the first column of its first node
  /// (block rows on a single node use the first half). Null without a block structure.
  double* blockRow(int i) {
    return block_ > 0 ? rows_.data() + static_cast<std::size_t>(i) * (2 * block_) : nullptr;
  }
  /// Block structure: the first column of row i's entries (blockRow), its first node's; block
  /// size 0 without a block structure.
  int blockRowFirstColumn(int i) const { return block_ * rowNode(i); }
  int blockSize() const { return block_; }
  bool inBand(int i, int j) const { return j - i <= ku_ && i - j <= kl_; }
  /// Block structure: whether (i, j) is one of the pattern's entries (always true without one).
  bool inPattern(int i, int j) const {
    if (block_ == 0) return inBand(i, j);
    const int first = block_ * rowNode(i);
    const bool pair = i >= lead_ && rowNode(i) + 1 < n_ / block_;  // an interval row: two nodes
    return j >= first && j < first + (pair ? 2 : 1) * block_;
  }

  /// Declare the box scheme's block structure: unknowns in blocks of `block` (one node), the
  /// first `lead` rows on block 0 only, then `block` rows at a time on blocks (j, j + 1) (one
  /// half-grid interval), the last block - lead rows on the last block. factorize() then
  /// eliminates node by node on dense panels (the candidate rows of a node's columns are the
  /// lead rows left over from the node before and the rows of its interval), with the same
  /// partial pivoting as the band LU (every other row of the band is zero in those columns),
  /// less than half of the multiply-adds and no stride-ldab access. The entries are then stored by rows (2 * block values from the row's first node)
  /// instead of the band, and at() throws std::out_of_range outside the pattern. Only
  /// (block, lead) = (8, 5) (2-D dynamics), (16, 10) and (16, 7) (3-D, anchored and with a free
  /// lower end) have a kernel; (0, 0) returns to the
  /// band. Changing the structure zeroes the matrix. Throws std::invalid_argument for another
  /// structure or one the band cannot hold.
  void setBlockStructure(int block, int lead);

  /// y = A x using the unfactored matrix.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

  /// LU-factorize in place (partial pivoting, LAPACK's dgbtf2 algorithm and storage). Returns 0
  /// on success, or k > 0 when U(k-1, k-1) is exactly zero (the matrix is singular; the 0-based
  /// column is k-1). The bandwidths of the solvers, (12, 10) for dynamics and (8, 8) for
  /// statics, are compiled with fixed loop lengths: at these widths LAPACK's unblocked dgbtf2
  /// spends most of its time in the per-column BLAS calls (idamax, dswap, dscal, dger); other
  /// bandwidths call dgbtrf.
  ///
  /// With a block structure of four nodes or more the elimination runs from both ends and meets
  /// in the middle (twisted): node by node from the first node up to the middle one, and from
  /// the last node down to the one above it (the mirror: the same kernel on the upper nodes in
  /// reverse order), whose leftover rows join the middle node's. The two sweeps are independent
  /// and run at the same time when setParallel() gave a ForkJoin; they do the same operations
  /// either way, so the factor and the solutions do not depend on it.
  int factorize();
  bool factorized() const { return factorized_; }
  /// Solve A x = b in place with the factorization (not reentrant: the two-ended solve keeps
  /// its mirror's right-hand side in the matrix).
  void solve(Eigen::VectorXd& b) const;
  /// Run the two sweeps of the block elimination and of its solves on `fork` (null: one after
  /// the other). Not owned; must outlive its use here.
  void setParallel(ForkJoin* fork) { fork_ = fork; }
  ForkJoin* parallel() const { return fork_; }
  /// The node where the two sweeps of a block structure of `nodes` nodes meet, or 0 when its
  /// elimination is one-ended (fewer than four nodes: the mirror needs an inner node).
  static int meetingNode(int nodes) { return nodes >= 4 ? nodes / 2 : 0; }

 private:
  int n_ = 0, kl_ = 0, ku_ = 0, ldab_ = 1;
  std::vector<double> ab_;
  std::vector<int> ipiv_;
  bool factorized_ = false;
  int block_ = 0, lead_ = 0;     ///< block structure (setBlockStructure), 0: plain band
  int rowNode(int i) const { return i < lead_ ? 0 : (i - lead_) / block_; }
  [[noreturn]] void throwOutsidePattern(int i, int j) const;
  /// Block structure: the matrix, 2 * block entries per row (the factor after factorize()).
  std::vector<double, CacheLineAllocator<double>> rows_;
  int kernel_ = 0;  ///< block structure: its kernel (block_lu::Kernel, see banded_matrix.cpp)
  /// Block elimination, row kernel: the carried rows of every panel (lead per node).
  std::vector<double, CacheLineAllocator<double>> carried_;
  /// Block elimination, column and Eigen kernels: the factored panels.
  std::vector<double, CacheLineAllocator<double>> panels_;
  std::vector<double> inv_diag_; ///< reciprocals of U's diagonal (block elimination)
  std::vector<int> perm_;        ///< block elimination: panel row at each position
  /// Two-ended block elimination (factorize): the meeting node (0: one-ended) and the mirror,
  /// the nodes meet_ .. last in reverse order as a block structure of its own (its lead rows
  /// the last node's rows, its intervals with their two nodes swapped), with its storage.
  int meet_ = 0;
  std::vector<double, CacheLineAllocator<double>> mirror_rows_, mirror_carried_, mirror_panels_;
  std::vector<double> mirror_inv_diag_;
  std::vector<int> mirror_perm_;
  mutable std::vector<double> mirror_b_;  ///< solve: the mirror's right-hand side
  /// Block structure: solves since the last factorize(); from the kSolvesForInverse-th on, the
  /// solves use the nodes' inverse diagonal blocks (form_, mirror_form_; see solve()).
  static constexpr int kSolvesForInverse = 3;
  mutable int solves_ = 0;
  mutable std::vector<double, CacheLineAllocator<double>> form_, mirror_form_;
  ForkJoin* fork_ = nullptr;

};

}  // namespace core
}  // namespace mooring_dynamics
