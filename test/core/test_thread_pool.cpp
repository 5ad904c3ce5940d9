#include "mooring_dynamics/core/numerics/thread_pool.hpp"

#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

using mooring_dynamics::core::ThreadPool;

TEST(ThreadPool, RunsEveryItemExactlyOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (std::size_t n : {0u, 1u, 2u, 7u, 100u}) {
      std::vector<std::atomic<int>> hits(n);
      for (auto& h : hits) h = 0;
      pool.parallelFor(n, [&](std::size_t i) { ++hits[i]; });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(hits[i].load(), 1) << threads << " threads, item " << i << " of " << n;
    }
  }
}

TEST(ThreadPool, ManyJobsInARowOnTheSameWorkers) {
  ThreadPool pool(3);
  long sum = 0;
  for (int job = 0; job < 2000; ++job) {
    std::vector<long> out(5, 0);
    pool.parallelFor(out.size(), [&](std::size_t i) { out[i] = static_cast<long>(i) + job; });
    for (long v : out) sum += v;
  }
  // sum over jobs of (0+1+2+3+4 + 5 job) = 2000 * 10 + 5 * (1999 * 2000 / 2)
  EXPECT_EQ(sum, 2000L * 10 + 5L * 1999 * 2000 / 2);
}

TEST(ThreadPool, RethrowsAnItemsExceptionAfterTheOthersRan) {
  ThreadPool pool(2);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.parallelFor(10,
                                [&](std::size_t i) {
                                  ++ran;
                                  if (i == 3) throw std::runtime_error("item 3");
                                }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 10);
  // The pool still works afterwards.
  std::atomic<int> again{0};
  pool.parallelFor(4, [&](std::size_t) { ++again; });
  EXPECT_EQ(again.load(), 4);
}

TEST(ThreadPool, RefusesZeroThreads) { EXPECT_THROW(ThreadPool(0), std::invalid_argument); }
