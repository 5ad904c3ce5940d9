#include "mooring_dynamics/ros/nodes/sample_worker.hpp"

#include <utility>
#include <vector>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace mooring_dynamics {
namespace ros_bridge {

SampleWorker::SampleWorker(Solve solve, Thinned thinned, double max_lag)
    : solve_(std::move(solve)), thinned_(std::move(thinned)), max_lag_(max_lag) {
  thread_ = std::thread([this] { run(); });
}

SampleWorker::~SampleWorker() {
  {
    std::lock_guard<std::mutex> l(m_);
    stop_ = true;
  }
  cv_.notify_all();
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
  for (;;) {
    {
      std::unique_lock<std::mutex> l(m_);
      busy_ = false;
      idle_cv_.notify_all();
      cv_.wait(l, [this] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      batch.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.end()));
      queue_.clear();
      busy_ = true;
    }
    const double lag = (batch.back().stamp - batch.front().stamp).toSec();
    if (batch.size() > 1 && lag > max_lag_) {
      thinned_(static_cast<long>(batch.size() - 1), lag);
      batch.erase(batch.begin(), batch.end() - 1);
    }
    for (const Sample& s : batch) {
      {
        std::lock_guard<std::mutex> l(m_);
        if (stop_) return;
      }
      solve_(s);
    }
  }
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
