// Shared by the moored-vessel node's rostests (test_vessel_node.cpp, test_vessel_node_storm.cpp):
// the test's parameters (~mode, ~node, ~source, ~twist, ~fail_line), the 40-pose track on
// test/data/small_vessel.yaml and core::VesselLockstep's wrench series on it, the node's outputs by
// stamp (Listener) and the tests' main.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace vessel_node_test {

namespace core = mooring_dynamics::core;

constexpr int kSamples = 40;      // 4 s at 10 Hz
constexpr double kDt = 0.1;       // [s] sample spacing = the file's dt
inline const ros::Time kStart(3000.0);  // first stamp (sim time in the bag)
constexpr double kPi = 3.14159265358979323846;

inline std::string g_mode = "live", g_node = "/vessel";
inline std::string g_source = "pose";  // live: pose (PoseStamped), odometry (Odometry) or tf (world -> base_link)
inline bool g_twist = false;
inline std::string g_fail_line;  // the node's ~test_fail_line (failure injection at solver time 1 s), or empty
constexpr double kFailTime = 1.0;  // [s] the node's ~test_fail_time in test_vessel_node.fail.test           // odometry: the node uses the twist (~use_twist true); core and CLI get it too
inline const std::string kProblem = std::string(MD_SOURCE_DIR) + "/test/data/small_vessel.yaml";

struct Sample {
  ros::Time stamp;
  geometry_msgs::Pose pose;
  core::BodyTwist twist;  ///< the track's exact twist, body frame (REP 105, as in nav_msgs/Odometry)
};

/// Surge 0.5 m (period 4 s) and yaw 2 deg (period 5 s), from the file's pose (0, 0, 0, yaw 0).
inline std::vector<Sample> track() {
  std::vector<Sample> v;
  for (int k = 0; k < kSamples; ++k) {
    const double t = kDt * k;
    const double yaw = 2.0 * kPi / 180.0 * std::sin(2 * kPi * t / 5.0);
    Sample s;
    s.stamp = kStart + ros::Duration(t);
    s.pose.position.x = 0.5 * std::sin(2 * kPi * t / 4.0);
    s.pose.orientation.z = std::sin(0.5 * yaw);
    s.pose.orientation.w = std::cos(0.5 * yaw);
    // The derivatives: surge velocity (world x) turned into the body by -yaw; yaw rate about z.
    const double xdot = 0.5 * (2 * kPi / 4.0) * std::cos(2 * kPi * t / 4.0);
    const double yawdot = 2.0 * kPi / 180.0 * (2 * kPi / 5.0) * std::cos(2 * kPi * t / 5.0);
    s.twist.linear = Eigen::Vector3d(std::cos(yaw) * xdot, -std::sin(yaw) * xdot, 0.0);
    s.twist.angular = Eigen::Vector3d(0.0, 0.0, yawdot);
    v.push_back(s);
  }
  return v;
}

inline geometry_msgs::PoseStamped toMsg(const Sample& s) {
  geometry_msgs::PoseStamped m;
  m.header.stamp = s.stamp;
  m.header.frame_id = "world";
  m.pose = s.pose;
  return m;
}

/// The 12 numbers of a wrench row: body force, body moment, world force, world moment.
using Row = std::vector<double>;
inline Row rowOf(const geometry_msgs::WrenchStamped& b, const geometry_msgs::WrenchStamped& w) {
  return {b.wrench.force.x,  b.wrench.force.y,  b.wrench.force.z,  b.wrench.torque.x, b.wrench.torque.y, b.wrench.torque.z,
          w.wrench.force.x,  w.wrench.force.y,  w.wrench.force.z,  w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z};
}

/// core::VesselLockstep on the same samples, as the node feeds them (time = stamp - first stamp).
inline std::vector<Row> coreSeries(const std::vector<Sample>& tr, bool with_twist = g_twist,
                            bool with_fail = !g_fail_line.empty(), std::vector<std::vector<double>>* tops = nullptr) {
  core::SystemProblem s = core::loadSystemFromFile(kProblem);
  core::DynamicOptions dyn = s.dynamics;
  dyn.threads = 1;
  core::VesselLockstepOptions lo;
  lo.threads = 1;
  core::VesselLockstep run(s, dyn, lo);
  if (with_fail) {  // the same injection as the node's ~test_fail_line
    std::size_t idx = 0;
    for (std::size_t i = 0; i < s.lines.size(); ++i)
      if (s.lines[i].name == g_fail_line) idx = i;
    run.setFailureInjection([idx](std::size_t line, double t1) { return line == idx && std::abs(t1 - kFailTime) < 1e-9; });
  }
  std::vector<Row> out;
  for (const Sample& x : tr) {
    const core::VesselLockstep::Result r = run.onSample((x.stamp - tr[0].stamp).toSec(),
                                                        mooring_dynamics::ros_bridge::toRigidPose(x.pose),
                                                        with_twist ? &x.twist : nullptr);
    EXPECT_TRUE(r.publish) << r.message;
    if (tops) {
      std::vector<double> t;
      for (const core::StaticResult& r : run.lines()) t.push_back(r.topTension());
      tops->push_back(t);
    }
    const core::VesselWrench w = run.wrench();
    Row row;
    for (const Eigen::Vector3d* v : {&w.force_body, &w.moment_body, &w.force_world, &w.moment_world})
      for (int i = 0; i < 3; ++i) row.push_back((*v)[i]);
    out.push_back(row);
  }
  return out;
}

inline const char* const kLineNames[3] = {"bow", "port_quarter", "stbd_quarter"};  // of small_vessel.yaml

/// The node's outputs by stamp.
struct Listener {
  std::map<uint64_t, geometry_msgs::WrenchStamped> body, world;
  std::map<uint64_t, double> top[3];  ///< each line's top tension (CableState), by stamp
  std::vector<std::string> events[3];  ///< each line's events (CableState), of its last state
  std::map<uint64_t, double> length[3];  ///< each line's length (CableState line_length), by stamp
  ros::Subscriber s1, s2;
  std::vector<ros::Subscriber> lines;
  Listener() {
    ros::NodeHandle nh;
    for (int i = 0; i < 3; ++i)
      lines.push_back(nh.subscribe<mooring_dynamics::CableState>(
          g_node + "/lines/" + kLineNames[i] + "/cable_state", 1000, [this, i](const mooring_dynamics::CableState::ConstPtr& m) {
            if (!m->tension.empty()) top[i][m->header.stamp.toNSec()] = m->tension.back();
            events[i] = m->events;
            length[i][m->header.stamp.toNSec()] = m->line_length;
          }));
    s1 = nh.subscribe<geometry_msgs::WrenchStamped>(g_node + "/wrench", 1000, [this](const geometry_msgs::WrenchStamped::ConstPtr& m) {
      body[m->header.stamp.toNSec()] = *m;
    });
    s2 = nh.subscribe<geometry_msgs::WrenchStamped>(g_node + "/wrench_world", 1000,
                                                    [this](const geometry_msgs::WrenchStamped::ConstPtr& m) {
                                                      world[m->header.stamp.toNSec()] = *m;
                                                    });
  }
  bool has(const ros::Time& t) const { return body.count(t.toNSec()) && world.count(t.toNSec()); }
  void spinUntil(const std::function<bool()>& done, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end && !done()) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
  }
};

inline Listener* g_listener = nullptr;

inline bool connect(const ros::Publisher* pub) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < end) {
    if ((!pub || pub->getNumSubscribers() > 0) && g_listener->s1.getNumPublishers() > 0 &&
        g_listener->s2.getNumPublishers() > 0)
      return true;
    ros::WallDuration(0.05).sleep();
    ros::spinOnce();
  }
  return false;
}

/// The tests' main: reads the parameters, then the Listener subscribes (before any test runs).
inline int testMain(int argc, char** argv, const std::string& name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("mode", g_mode, g_mode);
  pnh.param<std::string>("node", g_node, g_node);
  pnh.param<std::string>("source", g_source, g_source);
  pnh.param("twist", g_twist, g_twist);
  pnh.param<std::string>("fail_line", g_fail_line, g_fail_line);
  Listener l;
  g_listener = &l;
  return RUN_ALL_TESTS();
}

}  // namespace vessel_node_test
