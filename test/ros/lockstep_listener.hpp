// Shared by the lockstep rostests (test_lockstep.cpp, test_lockstep3d.cpp): collects one node's
// CableState and WrenchStamped outputs keyed by stamp.
#pragma once

#include <map>
#include <string>

#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"

namespace lockstep_test {

using mooring_dynamics::CableState;

/// Collects the outputs of one node, keyed by stamp (nanoseconds).
struct Listener {
  std::map<uint64_t, CableState> states;
  std::map<uint64_t, geometry_msgs::WrenchStamped> wrenches;
  int state_count = 0, wrench_count = 0;
  ros::Subscriber s1, s2;

  explicit Listener(const std::string& node) {
    ros::NodeHandle nh;
    s1 = nh.subscribe<CableState>(node + "/cable_state", 100, [this](const CableState::ConstPtr& m) {
      states[m->header.stamp.toNSec()] = *m;
      ++state_count;
    });
    s2 = nh.subscribe<geometry_msgs::WrenchStamped>(node + "/top_wrench", 100,
                                                    [this](const geometry_msgs::WrenchStamped::ConstPtr& m) {
                                                      wrenches[m->header.stamp.toNSec()] = *m;
                                                      ++wrench_count;
                                                    });
  }
  /// Spin until both a state and a wrench with `stamp` arrived, or `timeout` passes.
  bool waitFor(const ros::Time& stamp, double timeout = 5.0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end) {
      ros::spinOnce();
      if (states.count(stamp.toNSec()) && wrenches.count(stamp.toNSec())) return true;
      ros::WallDuration(0.002).sleep();
    }
    return false;
  }
  /// Forget what arrived with `stamp` (before publishing a pose with a stamp used before).
  void forget(const ros::Time& stamp) {
    states.erase(stamp.toNSec());
    wrenches.erase(stamp.toNSec());
  }
  /// Spin for `seconds`, returning how many states arrived meanwhile.
  int countDuring(double seconds) {
    const int before = state_count;
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < end) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
    return state_count - before;
  }
};

inline bool waitForConnection(const ros::Publisher& pub, const Listener& l) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (ros::ok() && ros::WallTime::now() < end) {
    if (pub.getNumSubscribers() > 0 && l.s1.getNumPublishers() > 0 && l.s2.getNumPublishers() > 0) return true;
    ros::WallDuration(0.05).sleep();
    ros::spinOnce();
  }
  return false;
}

}  // namespace lockstep_test
