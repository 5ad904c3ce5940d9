// The solver thread of the vessel node's decimated mode (~solve_interval > 0; docs/ros_interface.md,
// "A fast vessel simulator"). The receiving thread answers each pose at once from the last solve
// and pushes it here; this thread hands the samples to `solve` in arrival order, so that the
// lockstep's checks and counts see every one. When the newest waiting sample is more than
// `max_lag` seconds (of stamps) after the last one handed on, the solver has fallen behind and
// cannot catch up by solving (the lines must still be stepped through all of that time): the
// newest goes to `behind` (the node restarts the lines from statics there), the others are
// skipped, and both are counted by the caller (never lost silently).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <ros/time.h>

#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class SampleWorker {
 public:
  struct Sample {
    ros::Time stamp;
    core::RigidPose pose;  ///< world frame (~frame_id)
    std::string field;     ///< message field of the pose, for messages
    bool has_twist = false;
    core::BodyTwist twist;
  };
  using Solve = std::function<void(const Sample&)>;
  /// The newest sample, the lag [s] of stamps behind it, and the samples skipped before it.
  using Behind = std::function<void(const Sample& newest, double lag, long skipped)>;

  /// Starts the thread. `max_lag` [s] > 0. `wake_interval` [s] >= 0: a pushed sample wakes the
  /// thread only when its stamp is at least this after the last one that did (or goes back):
  /// samples in between wait in the queue and are handed on with the next (a 1 kHz source held
  /// between solves 0.1 s apart wakes it 20 times a second, not 1000: fewer thread switches
  /// beside the receiving thread). 0: every sample wakes it.
  SampleWorker(Solve solve, Behind behind, double max_lag, double wake_interval = 0.0);
  /// Stops the thread after the sample in hand (waiting samples are discarded) and joins it.
  ~SampleWorker();
  SampleWorker(const SampleWorker&) = delete;
  SampleWorker& operator=(const SampleWorker&) = delete;

  /// Nice value of the solver thread (Linux; the receiving thread keeps the process's).
  static constexpr int kNice = 10;

  void push(Sample s);
  /// Samples waiting (not yet handed to `solve`).
  std::size_t pending() const;
  /// Blocks until every sample pushed so far has been handed on and solved, or the worker stops
  /// (tests; returns only when the source pauses).
  void drain();

 private:
  void run();

  Solve solve_;
  Behind behind_;
  double max_lag_, wake_interval_;
  bool woken_any_ = false;
  ros::Time last_wake_;  ///< stamp of the last sample that woke the thread (under m_)
  bool flush_ = false;   ///< drain(): hand on what waits without a wake (under m_)
  bool woke_ = false;    ///< a sample asked for a wake since the last batch (under m_)
  mutable std::mutex m_;
  std::condition_variable cv_, idle_cv_;
  std::deque<Sample> queue_;
  bool busy_ = false, stop_ = false;
  bool handed_any_ = false;  ///< (worker thread only)
  ros::Time last_handed_;    ///< stamp of the last sample handed on (worker thread only)
  std::thread thread_;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
