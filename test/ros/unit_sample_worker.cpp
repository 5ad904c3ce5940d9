// The decimated vessel node's solver thread (SampleWorker, no ROS master): samples handed on in
// order, a solver that falls more than max_lag behind gets the newest sample only (the others
// counted as skipped), nothing lost, and drain/stop return.
#include "mooring_dynamics/ros/nodes/sample_worker.hpp"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

using mooring_dynamics::ros_bridge::SampleWorker;

namespace {
SampleWorker::Sample at(double t) {
  SampleWorker::Sample s;
  s.stamp = ros::Time(100.0 + t);
  return s;
}
}  // namespace

// A source at 1 kHz (of stamps and of wall time) and a solve of 20 ms: after the first solve the
// waiting samples span ~20 ms (< max_lag 50 ms: all solved, one by one, ~400 ms), then they span
// far more than max_lag: the newest goes to `behind`, the rest are skipped. Every sample is
// solved, skipped or handed to `behind`, exactly once, in stamp order.
TEST(SampleWorker, ASolverBehindGetsTheNewestSampleAndTheOthersAreCounted) {
  constexpr int kSamples = 300;
  constexpr double kMaxLag = 0.05;  // [s]
  std::mutex m;
  std::vector<double> handed;
  long skipped = 0, behind = 0;
  {
    SampleWorker w(
        [&](const SampleWorker::Sample& s) {
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
          std::lock_guard<std::mutex> l(m);
          handed.push_back(s.stamp.toSec());
        },
        [&](const SampleWorker::Sample& s, double lag, long n) {
          EXPECT_GT(lag, kMaxLag);
          std::lock_guard<std::mutex> l(m);
          handed.push_back(s.stamp.toSec());
          skipped += n;
          ++behind;
        },
        kMaxLag);
    for (int k = 0; k < kSamples; ++k) {
      w.push(at(1e-3 * k));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    w.drain();
    EXPECT_EQ(w.pending(), 0u);
  }
  std::lock_guard<std::mutex> l(m);
  EXPECT_GE(behind, 1);
  EXPECT_EQ(static_cast<long>(handed.size()) + skipped, kSamples);
  for (std::size_t i = 1; i < handed.size(); ++i) EXPECT_LT(handed[i - 1], handed[i]) << i;
  EXPECT_DOUBLE_EQ(handed.back(), 100.0 + 1e-3 * (kSamples - 1));  // the newest is never skipped
}

// Samples slower than the solver: each handed on by itself, none skipped; stopping with samples
// still waiting returns (they are discarded) and does not hang.
TEST(SampleWorker, AQuickSolverTakesEverySampleAndStopsCleanly) {
  std::atomic<long> solved{0}, behind{0};
  {
    SampleWorker w([&](const SampleWorker::Sample&) { ++solved; },
                   [&](const SampleWorker::Sample&, double, long) { ++behind; }, 0.05);
    for (int k = 0; k < 50; ++k) w.push(at(1e-3 * k));
    w.drain();
    EXPECT_EQ(solved.load(), 50);
    SampleWorker slow([](const SampleWorker::Sample&) { std::this_thread::sleep_for(std::chrono::milliseconds(50)); },
                      [](const SampleWorker::Sample&, double, long) {}, 10.0);
    for (int k = 0; k < 20; ++k) slow.push(at(1e-3 * k));
  }  // slow's destructor: the solve in hand finishes, the rest are dropped
  EXPECT_EQ(behind.load(), 0);
}
