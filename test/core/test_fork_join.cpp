#include "mooring_dynamics/core/numerics/fork_join.hpp"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

using mooring_dynamics::core::balancedSplit;
using mooring_dynamics::core::ForkJoin;
using mooring_dynamics::core::sharedHalves;
using mooring_dynamics::core::TwoEndedClaims;

// Both halves run, the second on another thread, and run() returns only when both are done:
// every result is visible to the caller right after it (no half left running).
TEST(ForkJoin, RunsBothHalvesOnTwoThreadsAndJoins) {
  ForkJoin fork;
  constexpr int kRounds = 20000;  // enough handovers to catch a lost or early join
  std::vector<long> a(64), b(64);
  std::thread::id caller = std::this_thread::get_id(), worker;
  for (int k = 1; k <= kRounds; ++k) {
    fork.run([&] { for (long& v : a) v += 1; },
             [&] {
               worker = std::this_thread::get_id();
               for (long& v : b) v += 2;
             });
    ASSERT_EQ(a.back(), k);
    ASSERT_EQ(b.back(), 2L * k);
  }
  EXPECT_NE(worker, caller);
}

// A worker that has slept (idle longer than it polls) wakes for the next job.
TEST(ForkJoin, WakesAfterSleeping) {
  ForkJoin fork;
  const auto idle = std::chrono::duration<double>(20 * ForkJoin::kSpinSeconds);
  for (int k = 0; k < 5; ++k) {
    std::this_thread::sleep_for(idle);
    std::atomic<int> done{0};
    fork.run([&] { ++done; }, [&] { ++done; });
    EXPECT_EQ(done.load(), 2);
  }
}

// An exception in either half reaches the caller after both halves finished, and the object
// stays usable.
TEST(ForkJoin, RethrowsEitherHalfsExceptionAfterBothFinish) {
  ForkJoin fork;
  std::atomic<bool> other_done{false};
  EXPECT_THROW(fork.run([] { throw std::runtime_error("caller half"); }, [&] { other_done = true; }),
               std::runtime_error);
  EXPECT_TRUE(other_done.load());
  other_done = false;
  EXPECT_THROW(fork.run([&] { other_done = true; }, [] { throw std::logic_error("worker half"); }),
               std::logic_error);
  EXPECT_TRUE(other_done.load());
  int x = 0;
  fork.run([&] { x += 1; }, [] {});
  EXPECT_EQ(x, 1);
}

// The split balances the two halves' costs: uniform costs split in the middle, a few costly
// items at one end move the split towards them, and too few items are not split.
TEST(BalancedSplit, BalancesTheHalvesCosts) {
  EXPECT_EQ(balancedSplit({}), 0);
  EXPECT_EQ(balancedSplit({3.0}), 0);
  EXPECT_EQ(balancedSplit({1.0, 1.0}), 1);
  EXPECT_EQ(balancedSplit(std::vector<double>(10, 1.0)), 5);
  // Ten unit items then two of cost 5.5 (as the 2-D solver's junctions): split 10 leaves 10
  // against 11, split 9 9 against 12, split 11 15.5 against 5.5.
  std::vector<double> c(10, 1.0);
  c.push_back(5.5);
  c.push_back(5.5);
  EXPECT_EQ(balancedSplit(c), 10);
  // The costly items first: the split moves to the left of the middle.
  EXPECT_EQ(balancedSplit({4.0, 1.0, 1.0, 1.0, 1.0}), 1);
  // Exact ties: the first.
  EXPECT_EQ(balancedSplit({1.0, 0.0, 1.0}), 1);
  // Other work on the first thread moves the split down, on the second (negative) up.
  EXPECT_EQ(balancedSplit(std::vector<double>(10, 1.0), 4.0), 3);
  EXPECT_EQ(balancedSplit(std::vector<double>(10, 1.0), -4.0), 7);
}

// Claims from both ends hand out every item once, in pieces of a quarter of what is left (at
// least kMinPiece), and stop when the ends meet.
TEST(TwoEndedClaims, HandsOutEveryItemOnceFromBothEnds) {
  TwoEndedClaims c(10, 30);  // 20 items
  int j0 = 0, j1 = 0;
  ASSERT_TRUE(c.fromBelow(j0, j1));
  EXPECT_EQ(j0, 10);
  EXPECT_EQ(j1, 15);  // 20 / 4
  ASSERT_TRUE(c.fromAbove(j0, j1));
  EXPECT_EQ(j0, 27);  // 15 left: 3
  EXPECT_EQ(j1, 30);
  std::vector<int> seen(40, 0);
  for (int j = 10; j < 15; ++j) ++seen[static_cast<std::size_t>(j)];
  for (int j = 27; j < 30; ++j) ++seen[static_cast<std::size_t>(j)];
  bool below = true;
  int pieces = 0;
  while (below ? c.fromBelow(j0, j1) : c.fromAbove(j0, j1)) {
    ASSERT_LT(j0, j1);
    EXPECT_LE(j1 - j0, 3);  // 12 left: 3, then 2 (at least kMinPiece), and 1 last
    for (int j = j0; j < j1; ++j) ++seen[static_cast<std::size_t>(j)];
    below = !below;
    ++pieces;
  }
  EXPECT_EQ(pieces, 6);  // [15, 27): 3, 2, 2, 2, 2, 1
  for (int j = 0; j < 40; ++j) EXPECT_EQ(seen[static_cast<std::size_t>(j)], j >= 10 && j < 30 ? 1 : 0) << j;
  EXPECT_FALSE(c.fromBelow(j0, j1));
  EXPECT_FALSE(c.fromAbove(j0, j1));
}

namespace {
/// Runs sharedHalves over [0, n) and checks that every item is done once and that a piece is
/// `continued` exactly when it starts where the same thread's previous piece ended. Returns the
/// items the calling thread did; worker_delay is slept by the worker at the start of each piece.
int checkSharedHalves(ForkJoin* fork, int guess, int n, std::chrono::milliseconds worker_delay) {
  std::vector<std::atomic<int>> done(static_cast<std::size_t>(n));
  for (auto& d : done) d = 0;
  const std::thread::id caller = std::this_thread::get_id();
  int caller_end = -1, worker_end = -1, caller_items = 0;  // each written by its own thread
  bool consistent = true;
  sharedHalves(fork, guess, n, [&](int j0, int j1, bool continued) {
    const bool mine = std::this_thread::get_id() == caller;
    if (!mine) std::this_thread::sleep_for(worker_delay);
    int& end = mine ? caller_end : worker_end;
    if (continued != (end == j0)) consistent = false;
    for (int j = j0; j < j1; ++j) ++done[static_cast<std::size_t>(j)];
    if (mine) caller_items += j1 - j0;
    end = j1;
  });
  EXPECT_TRUE(consistent);
  for (int j = 0; j < n; ++j) EXPECT_EQ(done[static_cast<std::size_t>(j)].load(), 1) << j;
  return caller_items;
}
}  // namespace

// sharedHalves covers the items once with one thread or two; with two, a worker slowed down
// (here by a sleep of 50 ms before each of its pieces) leaves the middle to the calling
// thread, which then does more than its guessed share.
TEST(SharedHalves, CoversEveryItemOnceAndFollowsTheThreadsSpeed) {
  using std::chrono::milliseconds;
  EXPECT_EQ(checkSharedHalves(nullptr, 50, 100, milliseconds(0)), 100);
  ForkJoin fork;
  EXPECT_EQ(checkSharedHalves(&fork, 0, 100, milliseconds(0)), 100);  // no guess: not split
  for (int n : {2, 3, 7, 100, 273}) checkSharedHalves(&fork, n / 2, n, milliseconds(0));
  // Guess 60 of 100: the calling thread's bulk is [0, 47), the middle [47, 73).
  const int caller_items = checkSharedHalves(&fork, 60, 100, milliseconds(50));
  EXPECT_GT(caller_items, 60);
}
