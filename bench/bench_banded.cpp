// Node-by-node block LU of the box scheme (BandedMatrix::setBlockStructure, factorize, solve) on
// its own, without assembly: the hot spot of the dynamic solvers (2-D: block 8, 5 anchor rows;
// 3-D: block 16, 10 anchor rows).
//
// The matrix has the block pattern of the Newton matrix (lead rows on node 0, block rows per
// interval on nodes j and j + 1, block - lead rows on the last node) with uniform random entries
// in [-1, 1]: every entry of the pattern nonzero, and the pivots fall on carried and interval
// rows alike. The argument is the node count (170: config/chain_mooring.yaml, n = 1360 in 2-D).
//
// BM_BlockFactor<block>/<nodes>: one factorize() per iteration. factorize() may overwrite the
// assembled entries, so each iteration first copies them back (the dynamic solver assembles
// before each factorization; the copy leaves them in cache as the assembly does) and only the
// factorization is timed (manual time).
// BM_BlockSolve<block>/<nodes>: one solve() of a fixed factorization per iteration (the copy of
// the right-hand side is not timed): from the third solve of a factorization on, the solve
// multiplies by the nodes' inverse diagonal blocks (block_lu_inverse.hpp), as modified Newton's
// repeated solves do.
// BM_BlockSolveFirst<block>/<nodes>: the first solve() after each factorization (substitution,
// as plain Newton's one solve per factorization); the refactorization is not timed.
// BM_BlockSolveThird16/<nodes>: the third solve() after each factorization, which forms the
// inverse blocks and solves with them (the two solves before it are not timed).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/numerics/banded_matrix.hpp"

using mooring_dynamics::core::BandedMatrix;

namespace {

/// A block-structured matrix of `nodes` nodes with random entries in the pattern; the smallest
/// band that holds the structure.
BandedMatrix randomBlockMatrix(int block, int lead, int nodes, unsigned seed) {
  const int n = block * nodes;
  BandedMatrix A(n, lead + block - 1, 2 * block - 1 - lead);
  A.setBlockStructure(block, lead);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (A.inBand(i, j) && A.inPattern(i, j)) A.at(i, j) = u(rng);
  return A;
}

void blockFactor(benchmark::State& state, int block, int lead) {
  const int nodes = static_cast<int>(state.range(0));
  BandedMatrix A = randomBlockMatrix(block, lead, nodes, 1);
  const std::size_t entries = static_cast<std::size_t>(A.size()) * static_cast<std::size_t>(2 * block);
  const std::vector<double> assembled(A.blockRow(0), A.blockRow(0) + entries);
  for (auto _ : state) {
    std::memcpy(A.blockRow(0), assembled.data(), entries * sizeof(double));
    const auto t0 = std::chrono::steady_clock::now();
    const int info = A.factorize();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (info != 0) {
      state.SkipWithError(("singular matrix: info = " + std::to_string(info)).c_str());
      return;
    }
    benchmark::ClobberMemory();
  }
}

/// A random right-hand side for A.
Eigen::VectorXd randomRhs(const BandedMatrix& A) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(A.size());
  for (int i = 0; i < A.size(); ++i) b[i] = u(rng);
  return b;
}

/// One timed solve() of b (the copy into x is not timed).
void timedSolve(benchmark::State& state, const BandedMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x = b;
  const auto t0 = std::chrono::steady_clock::now();
  A.solve(x);
  state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  benchmark::DoNotOptimize(x.data());
  benchmark::ClobberMemory();
}

void blockSolve(benchmark::State& state, int block, int lead) {
  BandedMatrix A = randomBlockMatrix(block, lead, static_cast<int>(state.range(0)), 2);
  if (A.factorize() != 0) {
    state.SkipWithError("singular matrix");
    return;
  }
  const Eigen::VectorXd b = randomRhs(A);
  Eigen::VectorXd x;
  for (auto _ : state) timedSolve(state, A, b, x);
}

/// The solve() number `which` after each factorization (1: substitution; 3: the one that forms the
/// inverse blocks and uses them); the refactorization and the solves before are not timed.
void blockSolveNth(benchmark::State& state, int block, int lead, int which) {
  BandedMatrix A = randomBlockMatrix(block, lead, static_cast<int>(state.range(0)), 2);
  const std::size_t entries = static_cast<std::size_t>(A.size()) * static_cast<std::size_t>(2 * block);
  const std::vector<double> assembled(A.blockRow(0), A.blockRow(0) + entries);
  const Eigen::VectorXd b = randomRhs(A);
  Eigen::VectorXd x;
  for (auto _ : state) {
    std::memcpy(A.blockRow(0), assembled.data(), entries * sizeof(double));
    if (A.factorize() != 0) {
      state.SkipWithError("singular matrix");
      return;
    }
    for (int k = 1; k < which; ++k) A.solve(x = b);
    timedSolve(state, A, b, x);
  }
}

void BM_BlockFactor8(benchmark::State& state) { blockFactor(state, 8, 5); }
void BM_BlockSolveFirst8(benchmark::State& state) { blockSolveNth(state, 8, 5, 1); }
void BM_BlockSolveFirst16(benchmark::State& state) { blockSolveNth(state, 16, 10, 1); }
void BM_BlockSolveThird16(benchmark::State& state) { blockSolveNth(state, 16, 10, 3); }
void BM_BlockSolve8(benchmark::State& state) { blockSolve(state, 8, 5); }
void BM_BlockFactor16(benchmark::State& state) { blockFactor(state, 16, 10); }
void BM_BlockSolve16(benchmark::State& state) { blockSolve(state, 16, 10); }
void BM_BlockFactor16Free(benchmark::State& state) { blockFactor(state, 16, 7); }
void BM_BlockSolve16Free(benchmark::State& state) { blockSolve(state, 16, 7); }

}  // namespace

BENCHMARK(BM_BlockFactor8)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolveFirst8)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolve8)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockFactor16)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolveFirst16)->Arg(170)->Arg(1031)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolveThird16)->Arg(170)->Arg(1031)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolve16)->Arg(170)->Arg(1031)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockFactor16Free)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlockSolve16Free)->Arg(170)->UseManualTime()->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
