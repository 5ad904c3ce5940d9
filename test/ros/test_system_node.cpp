// rostest: the node on a system file (config/three_leg_buoy.yaml) publishes one latched
// CableState per line, every line's markers in namespaces of their own, and a wrench per point;
// the lines meet at the buoy, and the three legs' pulls on the buoy sum to the buoy's wrench.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"

namespace {

// Latched topics arrive at once; the solve takes well under a second.
constexpr double kWaitSeconds = 20.0;
// Positions and forces are the core's doubles copied into messages: rounding only.
constexpr double kSameTol = 1e-6;

template <class M>
bool waitFor(const std::string& topic, M& out) {
  ros::NodeHandle nh;
  bool got = false;
  auto sub = nh.subscribe<M>(topic, 1, [&](const typename M::ConstPtr& m) {
    out = *m;
    got = true;
  });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(kWaitSeconds);
  while (!got && ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  return got;
}

std::string nodeName() {
  ros::NodeHandle p("~");
  std::string n;
  p.param<std::string>("node", n, "/system_node");
  return n;
}

}  // namespace

TEST(SystemNode, PublishesEveryLineAndPoint) {
  const std::string node = nodeName();
  std::map<std::string, mooring_dynamics::CableState> lines;
  for (const char* l : {"leg_e", "leg_nw", "leg_sw"}) {
    mooring_dynamics::CableState s;
    ASSERT_TRUE(waitFor(node + "/lines/" + l + "/cable_state", s)) << l;
    EXPECT_EQ(s.line_name, l);
    EXPECT_EQ(s.header.frame_id, "world");
    EXPECT_TRUE(s.converged);
    EXPECT_EQ(s.positions.size(), 151u);
    EXPECT_GT(s.min_tension, 0.0);
    lines[l] = s;
  }
  // The three legs end at the buoy.
  const auto& top = lines["leg_e"].positions.back();
  for (const auto& kv : lines) {
    EXPECT_NEAR(kv.second.positions.back().x, top.x, kSameTol) << kv.first;
    EXPECT_NEAR(kv.second.positions.back().y, top.y, kSameTol) << kv.first;
    EXPECT_NEAR(kv.second.positions.back().z, top.z, kSameTol) << kv.first;
  }
  // The buoy's wrench is the sum of the legs' pulls (-top_force of each).
  geometry_msgs::WrenchStamped w;
  ASSERT_TRUE(waitFor(node + "/points/buoy/wrench", w));
  double fx = 0, fy = 0, fz = 0;
  for (const auto& kv : lines) {
    fx -= kv.second.top_force.x;
    fy -= kv.second.top_force.y;
    fz -= kv.second.top_force.z;
  }
  EXPECT_NEAR(w.wrench.force.x, fx, 1e-6 * std::abs(fz));
  EXPECT_NEAR(w.wrench.force.y, fy, 1e-6 * std::abs(fz));
  EXPECT_NEAR(w.wrench.force.z, fz, 1e-6 * std::abs(fz));
  EXPECT_LT(w.wrench.force.z, 0.0);  // the legs pull the buoy down
  geometry_msgs::WrenchStamped a;
  ASSERT_TRUE(waitFor(node + "/points/anchor_e/wrench", a));
  EXPECT_NEAR(a.wrench.force.x, lines["leg_e"].anchor_force.x, kSameTol * 1e3);
  // Markers: every line in a namespace of its own.
  visualization_msgs::MarkerArray m;
  ASSERT_TRUE(waitFor(node + "/markers", m));
  std::set<std::string> prefixes;
  for (const auto& mk : m.markers) prefixes.insert(mk.ns.substr(0, mk.ns.find('/')));
  EXPECT_EQ(prefixes, (std::set<std::string>{"leg_e", "leg_nw", "leg_sw"}));
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_system_node");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
