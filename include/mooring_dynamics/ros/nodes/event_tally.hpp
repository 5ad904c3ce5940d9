// Counts of named events (a sample dropped for one reason, a restart for another, a rejected
// service request) per diagnostics window and in total, for the lockstep and vessel monitors.
// ROS-free. Every key given at construction is always reported (also at 0), so that a tool or
// a test can read it before the first event; a key not listed is appended when first counted.
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace mooring_dynamics {
namespace ros_bridge {

class EventTally {
 public:
  EventTally() = default;
  explicit EventTally(std::vector<std::string> keys)
      : keys_(std::move(keys)), window_(keys_.size(), 0), total_(keys_.size(), 0) {}

  void count(const std::string& key, long n = 1) {
    const std::size_t i = index(key);
    window_[i] += n;
  }
  /// Events in the current window / since the start (the window included).
  long window(const std::string& key) const {
    const auto it = std::find(keys_.begin(), keys_.end(), key);
    return it == keys_.end() ? 0 : window_[static_cast<std::size_t>(it - keys_.begin())];
  }
  long total(const std::string& key) const {
    const auto it = std::find(keys_.begin(), keys_.end(), key);
    if (it == keys_.end()) return 0;
    const std::size_t i = static_cast<std::size_t>(it - keys_.begin());
    return total_[i] + window_[i];
  }
  /// Appends "<key> (window / total)" = "w / t" for every key, then starts a new window.
  void closeWindow(std::vector<std::pair<std::string, std::string>>& values) {
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      total_[i] += window_[i];
      values.emplace_back(keys_[i] + " (window / total)", std::to_string(window_[i]) + " / " + std::to_string(total_[i]));
      window_[i] = 0;
    }
  }

 private:
  std::size_t index(const std::string& key) {
    const auto it = std::find(keys_.begin(), keys_.end(), key);
    if (it != keys_.end()) return static_cast<std::size_t>(it - keys_.begin());
    keys_.push_back(key);
    window_.push_back(0);
    total_.push_back(0);
    return keys_.size() - 1;
  }
  std::vector<std::string> keys_;
  std::vector<long> window_, total_;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
