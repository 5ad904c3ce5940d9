// A small pool of persistent threads for independent work items: the lines of a moored vessel
// or a system between two samples (DESIGN.md section 6). Items are handed out one at a time
// from a shared counter, so a slow core takes fewer; the caller's thread works too. Each item
// must write only its own results: what a run computes then does not depend on the thread
// count, only how fast.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mooring_dynamics {
namespace core {

class ThreadPool {
 public:
  /// `threads` >= 1 threads in all, the caller's included (1: everything runs on the caller).
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// f(i) for every i in [0, n), spread over the threads; returns when all are done. The first
  /// exception an item throws is rethrown here (the other items still run).
  void parallelFor(std::size_t n, const std::function<void(std::size_t)>& f);

  /// std::thread::hardware_concurrency(), at least 1.
  static int hardwareThreads();

 private:
  void workerLoop();
  void runItems();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t items_ = 0;
  std::atomic<std::size_t> next_{0};
  unsigned long generation_ = 0;
  int busy_ = 0;  ///< workers still in the current job
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace core
}  // namespace mooring_dynamics
