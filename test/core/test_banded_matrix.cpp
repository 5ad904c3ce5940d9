// BandedMatrix (LAPACK band storage, dgbtrf/dgbtrs; the block elimination and its solves) against
// dense Eigen linear algebra.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"

using mooring_dynamics::core::BandedMatrix;

namespace {

// Random O(1) entries, n <= 60: condition numbers stay well below 1e6, so two backward-stable
// LU solves agree to ~cond * 1e-16 relative.
constexpr double kSolveRelTol = 1e-9;
// A product of O(1) entries summed over at most (kl + ku + 1) terms: only rounding differs.
constexpr double kMultiplyAbsTol = 1e-13;

/// Fills the band of A with uniform random entries in [-1, 1] and returns the dense copy.
Eigen::MatrixXd fillRandom(BandedMatrix& A, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = A.size();
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (A.inBand(i, j)) D(i, j) = A.at(i, j) = u(rng);
  return D;
}

Eigen::VectorXd randomVector(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

// (n, kl, ku): square, tridiagonal, unequal bands both ways, diagonal only, band wider than n;
// the last rows are the bandwidths with a compiled kernel, (12, 10) dynamics and (8, 8) statics,
// from smaller than the band to many times it.
const std::vector<std::tuple<int, int, int>> kShapes = {
    {1, 0, 0}, {5, 1, 1}, {7, 2, 0}, {7, 0, 3}, {12, 3, 1}, {12, 1, 4},
    {30, 4, 7}, {30, 7, 2}, {60, 5, 5}, {60, 9, 3}, {6, 8, 8}, {40, 0, 0},
    {1, 12, 10}, {9, 12, 10}, {23, 12, 10}, {60, 12, 10}, {3, 8, 8}, {17, 8, 8}, {60, 8, 8}};

}  // namespace

TEST(BandedMatrix, DimensionsAndBandStorage) {
  BandedMatrix A(6, 2, 1);
  EXPECT_EQ(A.size(), 6);
  EXPECT_EQ(A.lower(), 2);
  EXPECT_EQ(A.upper(), 1);
  EXPECT_TRUE(A.inBand(3, 1));   // two below the diagonal
  EXPECT_FALSE(A.inBand(4, 1));  // three below
  EXPECT_TRUE(A.inBand(2, 3));   // one above
  EXPECT_FALSE(A.inBand(2, 4));  // two above
  // Every in-band element is stored separately: write distinct values, read them all back.
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (A.inBand(i, j)) A.at(i, j) = 10.0 * i + j;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_EQ(A.get(i, j), A.inBand(i, j) ? 10.0 * i + j : 0.0) << i << "," << j;
  A.setZero();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_EQ(A.get(i, j), 0.0);
}

TEST(BandedMatrix, BadDimensionsThrow) {
  EXPECT_THROW(BandedMatrix(0, 1, 1), std::invalid_argument);
  EXPECT_THROW(BandedMatrix(4, -1, 1), std::invalid_argument);
  EXPECT_THROW(BandedMatrix(4, 1, -1), std::invalid_argument);
}

TEST(BandedMatrix, MultiplyMatchesDense) {
  std::mt19937 rng(12345);
  for (const auto& [n, kl, ku] : kShapes) {
    BandedMatrix A(n, kl, ku);
    const Eigen::MatrixXd D = fillRandom(A, rng);
    const Eigen::VectorXd x = randomVector(n, rng);
    const Eigen::VectorXd y = A.multiply(x);
    const Eigen::VectorXd yd = D * x;
    ASSERT_EQ(y.size(), n);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(y[i], yd[i], kMultiplyAbsTol) << "n=" << n << " kl=" << kl << " ku=" << ku << " row " << i;
  }
}

TEST(BandedMatrix, SolveMatchesDensePartialPivLU) {
  std::mt19937 rng(2024);
  for (const auto& [n, kl, ku] : kShapes) {
    for (int trial = 0; trial < 3; ++trial) {
      BandedMatrix A(n, kl, ku);
      const Eigen::MatrixXd D = fillRandom(A, rng);
      const Eigen::VectorXd b = randomVector(n, rng);
      const Eigen::VectorXd x_dense = D.partialPivLu().solve(b);
      ASSERT_EQ(A.factorize(), 0) << "n=" << n << " kl=" << kl << " ku=" << ku;
      EXPECT_TRUE(A.factorized());
      Eigen::VectorXd x = b;
      A.solve(x);
      EXPECT_LE((x - x_dense).norm(), kSolveRelTol * x_dense.norm())
          << "n=" << n << " kl=" << kl << " ku=" << ku << " trial " << trial;
      // Independent of the reference solver: the residual of the original dense matrix.
      EXPECT_LE((D * x - b).norm(), kSolveRelTol * (D.norm() * x.norm() + b.norm()));
    }
  }
}

TEST(BandedMatrix, SolveNeedsPivoting) {
  // Zero leading diagonal: LU without row exchanges breaks down at the first pivot.
  // A = [0 2 0; 1 0 3; 0 4 5] (kl = ku = 1), det = -10. With x = (1, 2, 3), b = A x = (4, 10, 23).
  BandedMatrix A(3, 1, 1);
  A.at(0, 1) = 2.0;
  A.at(1, 0) = 1.0;
  A.at(1, 2) = 3.0;
  A.at(2, 1) = 4.0;
  A.at(2, 2) = 5.0;
  ASSERT_EQ(A.factorize(), 0);
  Eigen::VectorXd b(3);
  b << 4.0, 10.0, 23.0;
  A.solve(b);
  constexpr double kTol = 1e-14;  // 3x3, O(1) entries: rounding only
  EXPECT_NEAR(b[0], 1.0, kTol);
  EXPECT_NEAR(b[1], 2.0, kTol);
  EXPECT_NEAR(b[2], 3.0, kTol);
}

TEST(BandedMatrix, FactorizedMatrixSolvesSeveralRightHandSides) {
  std::mt19937 rng(7);
  BandedMatrix A(25, 3, 5);
  const Eigen::MatrixXd D = fillRandom(A, rng);
  ASSERT_EQ(A.factorize(), 0);
  for (int k = 0; k < 4; ++k) {
    const Eigen::VectorXd b = randomVector(25, rng);
    Eigen::VectorXd x = b;
    A.solve(x);
    const Eigen::VectorXd x_dense = D.partialPivLu().solve(b);
    EXPECT_LE((x - x_dense).norm(), kSolveRelTol * x_dense.norm()) << "rhs " << k;
  }
}

TEST(BandedMatrix, SingularMatrixReportsZeroPivotColumn) {
  // A zero column c stays zero through elimination, so U(c, c) == 0 exactly and dgbtrf reports
  // k = c + 1 (unless an earlier column is already singular, which it is not here).
  std::mt19937 rng(99);
  for (const auto& [n, kl, ku] : {std::tuple<int, int, int>{8, 2, 3}, {40, 12, 10}, {30, 8, 8}})
    for (int c : {0, 3, 7, n - 1}) {
      BandedMatrix A(n, kl, ku);
      fillRandom(A, rng);
      for (int i = 0; i < n; ++i)
        if (A.inBand(i, c)) A.at(i, c) = 0.0;
      const int k = A.factorize();
      EXPECT_EQ(k, c + 1) << "zero column " << c << " n=" << n << " kl=" << kl << " ku=" << ku;
      EXPECT_FALSE(A.factorized());
      Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
      EXPECT_THROW(A.solve(b), std::logic_error);
    }
  // Two equal rows of small integers: elimination of the second by the first is exact.
  BandedMatrix B(3, 1, 1);
  B.at(0, 0) = 1.0; B.at(0, 1) = 2.0;
  B.at(1, 0) = 1.0; B.at(1, 1) = 2.0;
  B.at(1, 2) = 0.0; B.at(2, 1) = 3.0; B.at(2, 2) = 4.0;
  EXPECT_GT(B.factorize(), 0);
  EXPECT_FALSE(B.factorized());
}

TEST(BandedMatrix, SolveBeforeFactorizeThrows) {
  BandedMatrix A(4, 1, 1);
  for (int i = 0; i < 4; ++i) A.at(i, i) = 2.0;
  Eigen::VectorXd b = Eigen::VectorXd::Ones(4);
  EXPECT_FALSE(A.factorized());
  EXPECT_THROW(A.solve(b), std::logic_error);
  // setZero discards a factorization.
  ASSERT_EQ(A.factorize(), 0);
  A.setZero();
  EXPECT_FALSE(A.factorized());
  EXPECT_THROW(A.solve(b), std::logic_error);
}

// The sparsity of the dynamic Newton matrix inside its band (kl = 12, ku = 10): 5 anchor rows on
// node 0, 8 rows per interval on nodes j and j + 1, 3 top rows on the last node, with a quarter
// of the block entries zero at random and a few all-zero leading columns in the blocks, so that
// rows start and end at different columns and the pivots move rows with different extents.
// Band LU and the node-by-node block elimination (setBlockStructure(8, 5)) must both match
// dense LU on it.
TEST(BandedMatrix, BoxSchemeSparsityMatchesDensePartialPivLU) {
  constexpr int kN = 8, kAnchor = 5;
  // A random pattern with a quarter of its entries zero can be (nearly) singular: such draws
  // are skipped, the rest have determinants of order one or more.
  constexpr double kSingularDeterminant = 1e-8;
  // Sparse random matrices are less well conditioned than the full bands above (cond up to
  // ~1e8 here), so the two solvers agree to cond * 1e-16; the residual check stays at
  // kSolveRelTol.
  constexpr double kSparseAgreementTol = 1e-6;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::bernoulli_distribution zero(0.25);
  int solved = 0;
  for (bool blocks : {false, true})
  for (int nodes : {1, 2, 3, 10, 40}) {
    for (int trial = 0; trial < 5; ++trial) {
      const int n = kN * nodes;
      BandedMatrix A(n, 12, 10);
      if (blocks) A.setBlockStructure(kN, kAnchor);
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
      auto set = [&](int r, int c) {
        if (zero(rng)) return;
        D(r, c) = A.at(r, c) = u(rng);
      };
      for (int r = 0; r < kAnchor; ++r)
        for (int c = 0; c < kN; ++c) set(r, c);
      for (int j = 0; j + 1 < nodes; ++j)
        for (int q = 0; q < kN; ++q)
          for (int c = kN * j + (q % 3); c < kN * (j + 2); ++c) set(kAnchor + kN * j + q, c);
      for (int r = n - 3; r < n; ++r)
        for (int c = n - kN; c < n; ++c) set(r, c);
      if (std::abs(D.determinant()) < kSingularDeterminant) continue;
      const Eigen::VectorXd b = randomVector(n, rng);
      const Eigen::VectorXd x_dense = D.partialPivLu().solve(b);
      ASSERT_EQ(A.factorize(), 0) << "nodes " << nodes << " trial " << trial;
      Eigen::VectorXd x = b;
      A.solve(x);
      EXPECT_LE((D * x - b).norm(), kSolveRelTol * (D.norm() * x.norm() + b.norm()))
          << "nodes " << nodes << " trial " << trial;
      EXPECT_LE((x - x_dense).norm(), kSparseAgreementTol * x_dense.norm()) << "nodes " << nodes << " trial " << trial;
      ++solved;
    }
  }
  EXPECT_GT(solved, 40);  // most random patterns are regular
}

TEST(BandedMatrix, BlockStructureMustFitTheBand) {
  BandedMatrix A(80, 12, 10);
  EXPECT_NO_THROW(A.setBlockStructure(8, 5));
  EXPECT_NO_THROW(A.setBlockStructure(0, 0));  // back to the band LU
  BandedMatrix narrow(80, 11, 10);
  EXPECT_THROW(narrow.setBlockStructure(8, 5), std::invalid_argument);
  BandedMatrix odd(81, 12, 10);
  EXPECT_THROW(odd.setBlockStructure(8, 5), std::invalid_argument);
  EXPECT_THROW(A.setBlockStructure(6, 3), std::invalid_argument);  // no kernel for it
  // In the structure: rows by node, and nothing outside the pattern.
  A.setBlockStructure(8, 5);
  EXPECT_TRUE(A.inPattern(0, 7));
  EXPECT_FALSE(A.inPattern(0, 8));     // anchor rows: node 0 only
  EXPECT_TRUE(A.inPattern(5, 15));     // interval 0: nodes 0 and 1
  EXPECT_FALSE(A.inPattern(13, 7));    // interval 1 starts at node 1
  EXPECT_FALSE(A.inPattern(79, 71));   // top rows: the last node only
  EXPECT_TRUE(A.inPattern(79, 72));
  EXPECT_THROW(A.at(0, 8), std::out_of_range);
  A.at(5, 15) = 2.5;
  EXPECT_EQ(A.get(5, 15), 2.5);
  EXPECT_EQ(A.blockRow(5)[15], 2.5);
  EXPECT_EQ(A.get(0, 8), 0.0);
}

// A zero column of a node is reported as that unknown by the block elimination as well: in the
// lower sweep (nodes 0, 1), at the meeting node (2) and in the upper sweep (3, 4) of the
// two-ended elimination of five nodes.
TEST(BandedMatrix, BlockEliminationReportsZeroPivotColumn) {
  std::mt19937 rng(5);
  ASSERT_EQ(BandedMatrix::meetingNode(5), 2);
  for (int c : {0, 13, 20, 26, 39}) {
    BandedMatrix A(40, 12, 10);
    A.setBlockStructure(8, 5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int r = 0; r < 5; ++r)
      for (int k = 0; k < 8; ++k) A.at(r, k) = u(rng);
    for (int j = 0; j + 1 < 5; ++j)
      for (int q = 0; q < 8; ++q)
        for (int k = 8 * j; k < 8 * (j + 2); ++k) A.at(5 + 8 * j + q, k) = u(rng);
    for (int r = 37; r < 40; ++r)
      for (int k = 32; k < 40; ++k) A.at(r, k) = u(rng);
    for (int i = 0; i < 40; ++i)
      if (A.inPattern(i, c)) A.at(i, c) = 0.0;
    EXPECT_EQ(A.factorize(), c + 1) << "zero column " << c;
    EXPECT_FALSE(A.factorized());
  }
}

// The block elimination's kernels (see setBlockStructure: column-major in AVX-512 vectors where
// the processor has them, else row-major in place; this runs the one the machine picks) on every
// structure with a kernel, from one node to many, against dense LU: random entries in the
// pattern, rows scaled over six decades (so that the pivots move between the carried rows and
// the interval's), a third of the entries zero, and small integers (exact ties in the pivot
// search, exactly zero candidates). One factorization solves several right-hand sides, and a
// matrix assembled after an earlier factorization (the storage the kernels reuse) solves
// exactly as a fresh one.
TEST(BandedMatrix, BlockKernelsMatchDensePartialPivLU) {
  struct Structure {
    int block, lead;
  };
  // Random fills can be ill-conditioned: agreement with the dense solve is checked where Eigen's
  // reciprocal condition estimate is above kMinRcond (error ~ cond * 1e-16), the residual always.
  constexpr double kMinRcond = 1e-8;
  constexpr double kAgreementTol = 1e-6;
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0), decades(-3.0, 3.0);
  std::uniform_int_distribution<int> small(-2, 2);
  std::bernoulli_distribution zero(1.0 / 3.0);
  int compared = 0;
  for (const Structure s : {Structure{8, 5}, Structure{16, 10}, Structure{16, 7}})
    for (int nodes : {1, 2, 3, 7, 25})
      for (int fill = 0; fill < 4; ++fill) {
        const int n = s.block * nodes, kl = s.lead + s.block - 1, ku = 2 * s.block - 1 - s.lead;
        // Assembles a draw into A (block structure) and returns it dense.
        auto assemble = [&](BandedMatrix& A) {
          A.setZero();
          Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
          for (int i = 0; i < n; ++i) {
            const double scale = fill == 1 ? std::pow(10.0, decades(rng)) : 1.0;
            for (int j = 0; j < n; ++j) {
              if (!A.inBand(i, j) || !A.inPattern(i, j)) continue;
              double v = u(rng) * scale;
              if (fill == 2 && zero(rng)) v = 0.0;
              if (fill == 3) v = small(rng);
              D(i, j) = A.at(i, j) = v;
            }
          }
          return D;
        };
        BandedMatrix A(n, kl, ku);
        A.setBlockStructure(s.block, s.lead);
        assemble(A);
        (void)A.factorize();  // an earlier draw: the storage its factorization (or attempt) leaves
        const Eigen::MatrixXd D = assemble(A);
        if (A.factorize() != 0) continue;  // singular draw (integer entries)
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu(D);
        BandedMatrix fresh(n, kl, ku);
        fresh.setBlockStructure(s.block, s.lead);
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            if (fresh.inBand(i, j) && fresh.inPattern(i, j)) fresh.at(i, j) = D(i, j);
        ASSERT_EQ(fresh.factorize(), 0);
        for (int rhs = 0; rhs < 3; ++rhs) {
          const Eigen::VectorXd b = randomVector(n, rng);
          Eigen::VectorXd x = b, y = b;
          A.solve(x);
          fresh.solve(y);
          const std::string what = "block " + std::to_string(s.block) + " lead " + std::to_string(s.lead) +
                                   " nodes " + std::to_string(nodes) + " fill " + std::to_string(fill);
          for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], y[i]) << what << " row " << i;  // no state carried over
          EXPECT_LE((D * x - b).norm(), kSolveRelTol * (D.norm() * x.norm() + b.norm())) << what;
          if (lu.rcond() > kMinRcond) {
            const Eigen::VectorXd x_dense = lu.solve(b);
            EXPECT_LE((x - x_dense).norm(), kAgreementTol * x_dense.norm()) << what;
            ++compared;
          }
        }
      }
  EXPECT_GT(compared, 100);  // most draws are regular and well conditioned
}

// The two sweeps of the two-ended elimination on a second thread (setParallel): the factor and
// the solutions are those of the one-thread elimination bit for bit, for every structure, and a
// matrix with fewer than four nodes (one-ended) is unaffected.
TEST(BandedMatrix, ParallelSweepsSolveBitForBitAsOneThread) {
  struct Structure {
    int block, lead;
  };
  mooring_dynamics::core::ForkJoin fork;
  std::mt19937 rng(47);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Structure s : {Structure{8, 5}, Structure{16, 10}, Structure{16, 7}})
    for (int nodes : {3, 4, 9, 60}) {
      const int n = s.block * nodes, kl = s.lead + s.block - 1, ku = 2 * s.block - 1 - s.lead;
      BandedMatrix A(n, kl, ku), B(n, kl, ku);
      A.setBlockStructure(s.block, s.lead);
      B.setBlockStructure(s.block, s.lead);
      B.setParallel(&fork);
      for (int round = 0; round < 3; ++round) {  // reassembled: the storage is reused
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            if (A.inBand(i, j) && A.inPattern(i, j)) A.at(i, j) = B.at(i, j) = u(rng);
        ASSERT_EQ(A.factorize(), 0);
        ASSERT_EQ(B.factorize(), 0);
        const Eigen::VectorXd b = randomVector(n, rng);
        Eigen::VectorXd x = b, y = b;
        A.solve(x);
        B.solve(y);
        for (int i = 0; i < n; ++i)
          ASSERT_EQ(x[i], y[i]) << "block " << s.block << " lead " << s.lead << " nodes " << nodes << " row " << i;
      }
    }
}

// The AVX-512 kernel of the 8-unknown structures takes the pivots of the last factorization as
// guesses and checks each against the search (block_lu_avx512.hpp, ColumnLU::panel). Newton
// reassembles a matrix that changed a little: most pivots stay, some move. Such a sequence must
// give the factor of a fresh matrix (no guesses) bit for bit: nearby matrices (every guess
// right, or a few wrong), rows swapped in magnitude (guesses wrong at any step), and integer
// entries (exact ties, broken by position).
TEST(BandedMatrix, KeptPivotGuessesGiveTheSearchsFactorBitForBit) {
  std::mt19937 rng(53);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> small(-2, 2);
  std::bernoulli_distribution rare(0.02);
  for (int nodes : {4, 25, 60}) {
    const int block = 8, lead = 5, n = block * nodes, kl = lead + block - 1, ku = 2 * block - 1 - lead;
    BandedMatrix A(n, kl, ku);
    A.setBlockStructure(block, lead);
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (A.inBand(i, j) && A.inPattern(i, j)) D(i, j) = u(rng);
    for (int round = 0; round < 8; ++round) {
      if (round > 0 && round < 4) {  // nearby: relative changes of 1e-3, a few entries scaled up
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            if (D(i, j) != 0.0) D(i, j) *= rare(rng) ? 10.0 : 1.0 + 1e-3 * u(rng);
      } else if (round >= 4 && round < 6) {  // two rows of one interval trade magnitudes
        const int i = lead + block * static_cast<int>(rng() % static_cast<unsigned>(nodes - 1));
        D.row(i).swap(D.row(i + 1 + static_cast<int>(rng() % 7)));
      } else if (round >= 6) {  // integers: exact ties
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j)
            if (D(i, j) != 0.0) D(i, j) = small(rng) == 0 ? 1.0 : small(rng);
      }
      BandedMatrix fresh(n, kl, ku);
      fresh.setBlockStructure(block, lead);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (A.inBand(i, j) && A.inPattern(i, j)) A.at(i, j) = fresh.at(i, j) = D(i, j);
      const int info = A.factorize();
      ASSERT_EQ(info, fresh.factorize()) << "nodes " << nodes << " round " << round;
      if (info != 0) continue;
      const Eigen::VectorXd b = randomVector(n, rng);
      Eigen::VectorXd x = b, y = b;
      A.solve(x);
      fresh.solve(y);
      for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], y[i]) << "nodes " << nodes << " round " << round << " row " << i;
    }
  }
}

// A factor solved again and again (modified Newton keeps one across iterations) solves with its
// nodes' inverse diagonal blocks from its third solve on (banded_matrix.cpp,
// block_lu_inverse.hpp): the same solution as the first solves' substitution to rounding, the
// residual of a backward-stable solve, and bit for bit the same with the sweeps on two threads,
// for every structure, one-ended (fewer than four nodes) and two-ended.
TEST(BandedMatrix, RepeatedSolvesWithInverseBlocksAgreeWithSubstitution) {
  struct Structure {
    int block, lead;
  };
  // Random O(1) entries, nodes <= 60: well conditioned (kSolveRelTol's reasoning); the two
  // solutions differ by the rounding of two backward-stable solves.
  constexpr double kAgreementTol = 1e-9;
  constexpr int kSolves = 5;  // the first by substitution, the last with the inverse blocks
  mooring_dynamics::core::ForkJoin fork;
  std::mt19937 rng(59);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Structure s : {Structure{8, 5}, Structure{16, 10}, Structure{16, 7}})
    for (int nodes : {1, 2, 3, 4, 9, 60}) {
      const int n = s.block * nodes, kl = s.lead + s.block - 1, ku = 2 * s.block - 1 - s.lead;
      BandedMatrix A(n, kl, ku), B(n, kl, ku);
      A.setBlockStructure(s.block, s.lead);
      B.setBlockStructure(s.block, s.lead);
      B.setParallel(&fork);
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (A.inBand(i, j) && A.inPattern(i, j)) D(i, j) = A.at(i, j) = B.at(i, j) = u(rng);
      ASSERT_EQ(A.factorize(), 0);
      ASSERT_EQ(B.factorize(), 0);
      const std::string what = "block " + std::to_string(s.block) + " lead " + std::to_string(s.lead) +
                               " nodes " + std::to_string(nodes);
      const Eigen::VectorXd b = randomVector(n, rng);
      Eigen::VectorXd first, last;
      bool differs = false;  // some solve took the other method (its rounding differs)
      for (int k = 0; k < kSolves; ++k) {
        Eigen::VectorXd x = b, y = b;
        A.solve(x);
        B.solve(y);
        for (int i = 0; i < n; ++i) ASSERT_EQ(x[i], y[i]) << what << " solve " << k << " row " << i;
        EXPECT_LE((D * x - b).norm(), kSolveRelTol * (D.norm() * x.norm() + b.norm())) << what;
        if (k == 0) first = x;
        differs = differs || x != first;
        last = x;
      }
      EXPECT_LE((last - first).norm(), kAgreementTol * first.norm()) << what;
      if (nodes >= 9) {
        EXPECT_TRUE(differs) << what << ": every solve took the same path";
      }
    }
}
