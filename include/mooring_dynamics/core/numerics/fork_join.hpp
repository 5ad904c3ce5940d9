// Two-way fork-join on one persistent worker thread: the dynamic solvers split the assembly and
// the elimination of a Newton iteration into two halves (dynamics.threads = 2). The halves do
// the same operations whether they run one after the other or at the same time, so results do
// not depend on the number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
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

/// Items [lo, hi) handed out from both ends, each claim taking a piece of what is left (a
/// quarter, at least kMinPiece items): one thread claims from below, the other from above, and
/// they meet where their speeds put them. Lock-free (one atomic word holds both ends).
class TwoEndedClaims {
 public:
  static constexpr int kMinPiece = 2;
  TwoEndedClaims(int lo, int hi) : ends_(pack(lo, hi)) {}
  /// The next piece [j0, j1) from the lower end; false when nothing is left.
  bool fromBelow(int& j0, int& j1) { return claim(true, j0, j1); }
  /// The next piece [j0, j1) from the upper end; false when nothing is left.
  bool fromAbove(int& j0, int& j1) { return claim(false, j0, j1); }

 private:
  static std::uint64_t pack(int lo, int hi) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(lo)) << 32) | static_cast<std::uint32_t>(hi);
  }
  bool claim(bool below, int& j0, int& j1);
  alignas(128) std::atomic<std::uint64_t> ends_;  ///< lo in the high half, hi in the low half (a line of its own)
};

/// f(j0, j1, continued) over pieces that together cover [0, n) once, shared between this
/// thread and the fork's worker as they go: this thread takes [0, guess - margin) and then
/// pieces from below, the worker [guess + margin, n) and then pieces from above (margin a third
/// of the smaller side), so that a thread the host slows down does fewer items. `continued` is
/// true when the piece begins where the same thread's previous one ended (it then comes from
/// below). For work whose result does not depend on which thread does an item nor on how the
/// items are grouped. Without a fork or with guess outside (0, n): f(0, n, false) here.
template <class F>
void sharedHalves(ForkJoin* fork, int guess, int n, const F& f) {
  if (!fork || guess <= 0 || guess >= n) {
    f(0, n, false);
    return;
  }
  const int margin = std::min(guess, n - guess) / 3;
  const int bulk_lo = guess - margin, bulk_hi = guess + margin;
  TwoEndedClaims middle(bulk_lo, bulk_hi);
  fork->run(
      [&] {
        if (bulk_lo > 0) f(0, bulk_lo, false);
        int j0, j1;
        bool continued = bulk_lo > 0;
        while (middle.fromBelow(j0, j1)) {
          f(j0, j1, continued);
          continued = true;
        }
      },
      [&] {
        if (bulk_hi < n) f(bulk_hi, n, false);
        int j0, j1;
        while (middle.fromAbove(j0, j1)) f(j0, j1, false);
      });
}

/// Where to split n work items of costs cost[0 .. n) for inHalves(split, n, f): the split in
/// [1, n) whose halves' costs, first_extra + sum cost[0 .. split) (the first thread's other
/// work, which may be negative: the second's) and sum cost[split .. n), differ least (the first
/// of equals); 0 (no split) for fewer than two items. Costs are in any one unit, >= 0.
int balancedSplit(const std::vector<double>& cost, double first_extra = 0.0);

}  // namespace core
}  // namespace mooring_dynamics
