// rostest: the node on a system file (config/three_leg_buoy.yaml) publishes one latched
// CableState per line, every line's markers in namespaces of their own, and a wrench per point;
// the lines meet at the buoy, and the three legs' pulls on the buoy sum to the buoy's wrench.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SystemStatics.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"

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
  // The legs' labels name their line and stack above the buoy they share instead of overlapping:
  // three distinct heights (the rows are 1.4 text heights apart; 0.5 of one is clearly apart).
  std::set<double> label_heights;
  for (const auto& mk : m.markers)
    if (mk.ns.size() > 6 && mk.ns.compare(mk.ns.size() - 6, 6, "/label") == 0) {
      EXPECT_EQ(mk.text.rfind(mk.ns.substr(0, mk.ns.find('/')) + ": T top = ", 0), 0u) << mk.text;
      for (double h : label_heights) EXPECT_GT(std::abs(mk.pose.position.z - h), 0.5 * mk.scale.z) << mk.text;
      label_heights.insert(mk.pose.position.z);
    }
  EXPECT_EQ(label_heights.size(), 3u);
}

// The anchors are on /tf_static at the file's positions (config/three_leg_buoy.yaml), axes as the
// world's: fixed frames for users, and ~frame_id on tf for rviz (its Global Status stays Ok).
TEST(SystemNode, AnchorsOnTfStatic) {
  const std::string node = nodeName();
  tf2_msgs::TFMessage tf;
  ASSERT_TRUE(waitFor("/tf_static", tf));
  std::map<std::string, geometry_msgs::TransformStamped> frames;
  for (const auto& t : tf.transforms) frames[t.child_frame_id] = t;
  const std::string prefix = node.substr(1) + "/";
  const std::map<std::string, std::array<double, 3>> expected = {
      {"anchor_e", {250, 0, -100}}, {"anchor_nw", {-125, 216.506, -100}}, {"anchor_sw", {-125, -216.506, -100}}};
  EXPECT_EQ(frames.size(), expected.size());
  for (const auto& kv : expected) {
    ASSERT_EQ(frames.count(prefix + kv.first), 1u) << prefix + kv.first;
    const auto& t = frames[prefix + kv.first];
    EXPECT_EQ(t.header.frame_id, "world");
    EXPECT_DOUBLE_EQ(t.transform.translation.x, kv.second[0]);
    EXPECT_DOUBLE_EQ(t.transform.translation.y, kv.second[1]);
    EXPECT_DOUBLE_EQ(t.transform.translation.z, kv.second[2]);
    EXPECT_DOUBLE_EQ(t.transform.rotation.w, 1.0);
  }
}

// ~solve_static (SystemStatics) in static mode: the core's system statics, bit for bit, every
// point and line in the file's order; the buoy's pull is what its buoyancy, current and wind balance.
TEST(SystemNode, SolveStaticIsTheCoreStatics) {
  const std::string srv = nodeName() + "/solve_static";
  ASSERT_TRUE(ros::service::waitForService(srv, ros::Duration(kWaitSeconds)));
  mooring_dynamics::SystemStatics call;
  ASSERT_TRUE(ros::service::call(srv, call));
  ASSERT_TRUE(call.response.success) << call.response.message;
  const mooring_dynamics::core::SystemProblem s =
      mooring_dynamics::core::loadSystemFromFile(std::string(MD_SOURCE_DIR) + "/config/three_leg_buoy.yaml");
  const mooring_dynamics::core::SystemStaticResult r = mooring_dynamics::core::solveSystemStatic(s);
  ASSERT_EQ(call.response.point_names.size(), r.points.size());
  for (std::size_t p = 0; p < r.points.size(); ++p) {
    EXPECT_EQ(call.response.point_names[p], r.points[p].name);
    EXPECT_EQ(call.response.point_positions[p].x, r.points[p].x);
    EXPECT_EQ(call.response.point_positions[p].y, r.points[p].y);
    EXPECT_EQ(call.response.point_positions[p].z, r.points[p].z);
    EXPECT_EQ(call.response.point_pull[p].z, r.points[p].fz);
  }
  ASSERT_EQ(call.response.top_tension.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(call.response.top_tension[i], r.lines[i].topTension());
  EXPECT_LE(call.response.min_tension[0], call.response.top_tension[0]);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_system_node");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
