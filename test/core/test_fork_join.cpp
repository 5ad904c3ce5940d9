#include "mooring_dynamics/core/fork_join.hpp"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

using mooring_dynamics::core::balancedSplit;
using mooring_dynamics::core::ForkJoin;

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
