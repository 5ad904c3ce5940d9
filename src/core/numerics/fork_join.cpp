#include "mooring_dynamics/core/numerics/fork_join.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define MD_CPU_RELAX() _mm_pause()
#else
#define MD_CPU_RELAX() std::this_thread::yield()
#endif

namespace mooring_dynamics {
namespace core {

namespace {
/// Polls `ready` for up to ForkJoin::kSpinSeconds; true when it turned true.
template <class Ready>
bool spinUntil(const Ready& ready) {
  using Clock = std::chrono::steady_clock;
  constexpr int kPollsBeforeClock = 256;  // most waits end within these (a few microseconds)
  for (int i = 0; i < kPollsBeforeClock; ++i) {
    if (ready()) return true;
    MD_CPU_RELAX();
  }
  const auto deadline = Clock::now() + std::chrono::duration<double>(ForkJoin::kSpinSeconds);
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
      MD_CPU_RELAX();
    }
    if (Clock::now() > deadline) return ready();
  }
}
}  // namespace

ForkJoin::ForkJoin() : worker_([this] { loop(); }) {}

ForkJoin::~ForkJoin() {
  stop_.store(true, std::memory_order_seq_cst);
  { std::lock_guard<std::mutex> lock(mutex_); }
  wake_.notify_one();
  worker_.join();
}

void ForkJoin::post(void (*fn)(void*), void* arg) {
  fn_ = fn;
  arg_ = arg;
  error_ = nullptr;
  // Sequentially consistent with the worker's sleeping_ store and posted_ check (loop): either
  // this sees it sleeping, or it sees the job before it sleeps. The mutex then orders the
  // notification after its wait began.
  posted_.fetch_add(1, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst)) {
    { std::lock_guard<std::mutex> lock(mutex_); }
    wake_.notify_one();
  }
}

std::exception_ptr ForkJoin::wait() {
  const unsigned job = posted_.load(std::memory_order_relaxed);
  auto finished = [&] { return done_.load(std::memory_order_acquire) == job; };
  if (!spinUntil(finished))
    while (!finished()) std::this_thread::yield();  // the worker is running a long job
  return error_;
}

void ForkJoin::loop() {
  unsigned seen = 0;
  for (;;) {
    auto posted = [&] { return posted_.load(std::memory_order_seq_cst) != seen || stop_.load(std::memory_order_seq_cst); };
    if (!spinUntil(posted)) {
      std::unique_lock<std::mutex> lock(mutex_);
      sleeping_.store(true, std::memory_order_seq_cst);
      wake_.wait(lock, posted);
      sleeping_.store(false, std::memory_order_relaxed);
    }
    if (stop_.load(std::memory_order_acquire)) return;
    seen = posted_.load(std::memory_order_acquire);
    try {
      fn_(arg_);
    } catch (...) {
      error_ = std::current_exception();
    }
    done_.store(seen, std::memory_order_release);
  }
}

bool TwoEndedClaims::claim(bool below, int& j0, int& j1) {
  std::uint64_t now = ends_.load(std::memory_order_relaxed);
  for (;;) {
    const int lo = static_cast<int>(static_cast<std::uint32_t>(now >> 32));
    const int hi = static_cast<int>(static_cast<std::uint32_t>(now));
    if (lo >= hi) return false;
    const int piece = std::min(hi - lo, std::max(kMinPiece, (hi - lo) / 4));
    j0 = below ? lo : hi - piece;
    j1 = below ? lo + piece : hi;
    const std::uint64_t next = below ? pack(j1, hi) : pack(lo, j0);
    if (ends_.compare_exchange_weak(now, next, std::memory_order_relaxed)) return true;
  }
}

int balancedSplit(const std::vector<double>& cost, double first_extra) {
  const int n = static_cast<int>(cost.size());
  if (n < 2) return 0;
  double total = 0.0;
  for (double c : cost) total += c;
  int best = 1;
  double best_gap = std::numeric_limits<double>::infinity(), below = 0.0;
  for (int s = 1; s < n; ++s) {
    below += cost[static_cast<std::size_t>(s - 1)];
    const double gap = std::abs(first_extra + below - (total - below));
    if (gap < best_gap) {
      best_gap = gap;
      best = s;
    }
  }
  return best;
}

}  // namespace core
}  // namespace mooring_dynamics
