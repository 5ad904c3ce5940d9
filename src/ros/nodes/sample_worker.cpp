#include "mooring_dynamics/ros/nodes/sample_worker.hpp"

#include <utility>
#include <vector>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace mooring_dynamics {
namespace ros_bridge {

SampleWorker::SampleWorker(Solve solve, Behind behind, double max_lag, double wake_interval)
    : solve_(std::move(solve)), behind_(std::move(behind)), max_lag_(max_lag), wake_interval_(wake_interval) {
  thread_ = std::thread([this] { run(); });
}

SampleWorker::~SampleWorker() {
  {
    std::lock_guard<std::mutex> l(m_);
    stop_ = true;
  }
  cv_.notify_all();
  idle_cv_.notify_all();
  thread_.join();
}

void SampleWorker::push(Sample s) {
  bool wake;
  {
    std::lock_guard<std::mutex> l(m_);
    wake = !woken_any_ || s.stamp < last_wake_ || (s.stamp - last_wake_).toSec() >= wake_interval_;
    if (wake) {
      woken_any_ = true;
      woke_ = true;
      last_wake_ = s.stamp;
    }
    queue_.push_back(std::move(s));
  }
  if (wake) cv_.notify_one();
}

std::size_t SampleWorker::pending() const {
  std::lock_guard<std::mutex> l(m_);
  return queue_.size();
}

void SampleWorker::drain() {
  std::unique_lock<std::mutex> l(m_);
  flush_ = true;
  cv_.notify_one();
  idle_cv_.wait(l, [this] { return stop_ || (queue_.empty() && !busy_); });
  flush_ = false;
}

void SampleWorker::run() {
  // Below the receiving thread in the scheduler, so that a pose is answered before the solve in
  // progress goes on: Linux's SCHED_IDLE (any ordinary thread that wakes preempts it; it runs on
  // what is left of the cores), else a nice value of kNice. Failing to: no harm.
#ifdef SCHED_IDLE
  sched_param none{};
  none.sched_priority = 0;
  if (pthread_setschedparam(pthread_self(), SCHED_IDLE, &none) != 0)
#endif
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kNice);
  std::vector<Sample> batch;
  auto idle = [this] {  // (under m_)
    busy_ = false;
    idle_cv_.notify_all();
  };
  for (;;) {
    {
      std::unique_lock<std::mutex> l(m_);
      idle();
      // Woken by a sample that asks for it (push), by drain or stop: then everything waiting.
      cv_.wait(l, [this] { return stop_ || (!queue_.empty() && (woke_ || flush_)); });
      woke_ = false;
      if (stop_) return;
      batch.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.end()));
      queue_.clear();
      busy_ = true;
    }
    const double lag = handed_any_ ? (batch.back().stamp - last_handed_).toSec() : 0.0;
    handed_any_ = true;
    last_handed_ = batch.back().stamp;
    if (lag > max_lag_) {
      behind_(batch.back(), lag, static_cast<long>(batch.size() - 1));
      continue;
    }
    for (const Sample& s : batch) {
      {
        std::lock_guard<std::mutex> l(m_);
        if (stop_) {
          idle();
          return;
        }
      }
      solve_(s);
    }
  }
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
