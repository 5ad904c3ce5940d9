// Two-way fork-join on one persistent worker thread: the dynamic solvers split the assembly and
// the elimination of a Newton iteration into two halves (dynamics.threads = 2). The halves do
// the same operations whether they run one after the other or at the same time, so results do
// not depend on the number of threads.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace mooring_dynamics {
namespace core {

class ForkJoin {
 public:
  ForkJoin();  ///< starts the worker thread
  ~ForkJoin();  ///< stops and joins it
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  /// Runs a() on the calling thread and b() on the worker; returns when both are done. An
  /// exception thrown by either is rethrown here after both have finished (a's first). Not
  /// reentrant: one caller at a time, and not from inside a() or b().
  template <class A, class B>
  void run(A&& a, B&& b) {
    post(&invoke<std::remove_reference_t<B>>, &b);
    std::exception_ptr error;
    try {
      a();
    } catch (...) {
      error = std::current_exception();
    }
    const std::exception_ptr worker_error = wait();
    if (error) std::rethrow_exception(error);
    if (worker_error) std::rethrow_exception(worker_error);
  }

  /// How long the worker keeps polling for the next job before it sleeps on a condition
  /// variable [s]: the gaps between the parallel parts of a Newton iteration are microseconds,
  /// and waking a sleeping thread costs tens of them; between time steps of a node that waits
  /// for its next input the worker does not hold a core.
  static constexpr double kSpinSeconds = 200e-6;

 private:
  template <class F>
  static void invoke(void* f) {
    (*static_cast<F*>(f))();
  }
  void post(void (*fn)(void*), void* arg);
  std::exception_ptr wait();
  void loop();

  // The flags each thread polls on cache lines of their own (128 bytes: the adjacent-line
  // prefetcher pairs lines), so that no other write to memory nearby invalidates them.
  static constexpr std::size_t kLine = 128;
  alignas(kLine) std::atomic<unsigned> posted_{0};  ///< jobs posted (the worker runs job posted_ when > done_)
  std::atomic<bool> stop_{false};
  std::atomic<bool> sleeping_{false};
  void (*fn_)(void*) = nullptr;
  void* arg_ = nullptr;
  alignas(kLine) std::atomic<unsigned> done_{0};    ///< jobs finished
  std::exception_ptr error_;
  alignas(kLine) char end_[1] = {};
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread worker_;
};

/// a() and b(): on `fork` at the same time when given (a on this thread), else one after the
/// other.
template <class A, class B>
void runBoth(ForkJoin* fork, A&& a, B&& b) {
  if (fork) {
    fork->run(a, b);
  } else {
    a();
    b();
  }
}

/// f(0, m) and f(m, end) by runBoth, or f(0, end) alone when m = 0: the two halves of a line's
/// nodes or intervals, split where the Newton matrix's two-ended elimination meets
/// (BandedMatrix::meetingNode), so that each thread works on the rows it eliminates.
template <class F>
void inHalves(ForkJoin* fork, int m, int end, const F& f) {
  if (m == 0) {
    f(0, end);
    return;
  }
  runBoth(fork, [&] { f(0, m); }, [&] { f(m, end); });
}

/// Where to split n work items of costs cost[0 .. n) for inHalves(split, n, f): the split in
/// [1, n) whose halves' costs, first_extra + sum cost[0 .. split) (the first thread's other
/// work, which may be negative: the second's) and sum cost[split .. n), differ least (the first
/// of equals); 0 (no split) for fewer than two items. Costs are in any one unit, >= 0.
int balancedSplit(const std::vector<double>& cost, double first_extra = 0.0);

}  // namespace core
}  // namespace mooring_dynamics
