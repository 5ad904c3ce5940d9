#include "mooring_dynamics/ros/nodes/sample_worker.hpp"

#include <utility>
#include <vector>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace mooring_dynamics {
namespace ros_bridge {

SampleWorker::SampleWorker(Solve solve, Behind behind, double max_lag)
    : solve_(std::move(solve)), behind_(std::move(behind)), max_lag_(max_lag) {
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
  {
    std::lock_guard<std::mutex> l(m_);
    queue_.push_back(std::move(s));
  }
  cv_.notify_one();
}

std::size_t SampleWorker::pending() const {
  std::lock_guard<std::mutex> l(m_);
  return queue_.size();
}

void SampleWorker::drain() {
  std::unique_lock<std::mutex> l(m_);
  idle_cv_.wait(l, [this] { return stop_ || (queue_.empty() && !busy_); });
}

void SampleWorker::run() {
  // Below the receiving thread in the scheduler (Linux: a thread's own nice value), so that on a
  // busy host a pose is answered before the solve in progress goes on. Failing to: no harm.
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
      cv_.wait(l, [this] { return stop_ || !queue_.empty(); });
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
