// rostest for mooring_dynamics_node in dynamic (lockstep) mode (test/ros/test_lockstep.test).
//
// Problem test/data/small_catenary.yaml: 150 m of chain, anchor at (0, -100) m, static top at
// (100, 0) m, 76 nodes; no dynamics section, dt = 0.1 s from ~dt (or the default).
// The test publishes stamped top positions (wall clock, explicit stamps) and waits after each one
// for the node's answer, so the run is deterministic. Checks: one CableState and one WrenchStamped
// per accepted pose, with the pose's stamp; the top follows the poses; the wrench is minus the
// top force (the line pulls the vessel down); a NaN pose and a stamp going back (< 1 s) or equal
// are dropped and the node keeps answering; a stamp going back by more than 1 s re-initialises
// from statics; a first pose 1 m from the static top re-solves statics there; the wrench is
// rotated into ~vessel_frame by tf; odometry input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "lockstep_listener.hpp"

using lockstep_test::Listener;
using lockstep_test::waitForConnection;
using mooring_dynamics::CableState;

namespace {

constexpr double kTopX = 100.0, kTopZ = 0.0;
constexpr std::size_t kNodes = 76;
const ros::Time kT0(1000.0);  // explicit stamps, far from 0

std::string g_node = "/lockstep";
std::string g_vessel_node = "/lockstep_vessel";

geometry_msgs::PoseStamped pose(const ros::Time& stamp, double x, double z, double y = 0.0) {
  geometry_msgs::PoseStamped p;
  p.header.stamp = stamp;
  p.header.frame_id = "world";
  p.pose.position.x = x;
  p.pose.position.y = y;
  p.pose.position.z = z;
  p.pose.orientation.w = 1.0;
  return p;
}

void expectConsistent(const CableState& s, const geometry_msgs::WrenchStamped& w, const std::string& frame) {
  EXPECT_EQ(s.header.frame_id, "world");
  EXPECT_EQ(w.header.frame_id, frame);
  EXPECT_EQ(s.header.stamp, w.header.stamp);
  ASSERT_EQ(s.positions.size(), kNodes);
  EXPECT_EQ(s.tension.size(), kNodes);
  EXPECT_TRUE(s.converged);
  for (double t : s.tension) EXPECT_TRUE(std::isfinite(t));
  EXPECT_NEAR(s.positions.front().x, 0.0, 1e-6);
  EXPECT_NEAR(s.positions.front().z, -100.0, 1e-6);
  // The line pulls the vessel down and toward the anchor (x < 0 in world).
  if (frame == "world") {
    EXPECT_DOUBLE_EQ(w.wrench.force.x, -s.top_force.x);
    EXPECT_DOUBLE_EQ(w.wrench.force.z, -s.top_force.z);
    EXPECT_LT(w.wrench.force.x, 0.0);
  }
  EXPECT_LT(w.wrench.force.z, 0.0);
  EXPECT_EQ(w.wrench.torque.x, 0.0);
  EXPECT_EQ(w.wrench.torque.y, 0.0);
  EXPECT_EQ(w.wrench.torque.z, 0.0);
}

}  // namespace

TEST(Lockstep, HeaveBadInputAndBagLoop) {
  ros::NodeHandle nh;
  Listener l(g_node);
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/top_pose", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to " << g_node;

  // 2 s of a 0.1 m heave (period 2 s) at 10 Hz, starting at the static top. (A 0.5 m heave
  // snaps this light 200 m line slack on the downstroke: compression, the wrench then pushes up.)
  const double kPi = 3.141592653589793;
  constexpr double kHeave = 0.1;  // [m]
  double t_first = 0.0, t_top_max = 0.0, max_dev = 0.0;
  for (int k = 0; k <= 20; ++k) {
    const ros::Time stamp = kT0 + ros::Duration(0.1 * k);
    const double z = kTopZ + kHeave * std::sin(kPi * 0.1 * k);
    const ros::WallTime w0 = ros::WallTime::now();
    pub.publish(pose(stamp, kTopX, z));
    ASSERT_TRUE(l.waitFor(stamp)) << "no answer to the pose at k = " << k;
    const double wall = (ros::WallTime::now() - w0).toSec();
    if (k == 0) t_first = wall;
    t_top_max = std::max(t_top_max, wall);
    const CableState& s = l.states[stamp.toNSec()];
    SCOPED_TRACE("k = " + std::to_string(k));
    expectConsistent(s, l.wrenches[stamp.toNSec()], "world");
    // The top follows the pose through the core's velocity condition with position feedback
    // (docs/method.md): it lags by a fraction of the heave.
    max_dev = std::max(max_dev, std::hypot(s.positions.back().x - kTopX, s.positions.back().z - z));
  }
  EXPECT_EQ(l.state_count, 21);
  EXPECT_EQ(l.wrench_count, 21);
  RecordProperty("max_top_deviation_m", std::to_string(max_dev));
  EXPECT_LT(max_dev, 0.5 * kHeave) << "the top does not follow the commanded heave";
  RecordProperty("first_answer_s", std::to_string(t_first));
  RecordProperty("slowest_answer_s", std::to_string(t_top_max));
  // Heave changes the top tension: not the same force at the crest (k = 5) and trough (k = 15).
  const double fz_up = l.states[(kT0 + ros::Duration(0.5)).toNSec()].top_force.z;
  const double fz_down = l.states[(kT0 + ros::Duration(1.5)).toNSec()].top_force.z;
  EXPECT_GT(std::abs(fz_up - fz_down), 1.0) << "top force does not respond to heave";
  const geometry_msgs::Vector3 static_force = l.states[kT0.toNSec()].top_force;

  // NaN pose: dropped, no output; the next good pose is answered.
  const ros::Time t_nan = kT0 + ros::Duration(2.05);
  pub.publish(pose(t_nan, kTopX, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(l.countDuring(0.5), 0) << "a NaN pose was answered";
  const ros::Time t_good = kT0 + ros::Duration(2.1);
  pub.publish(pose(t_good, kTopX, 0.0));
  ASSERT_TRUE(l.waitFor(t_good)) << "no answer after a NaN pose";

  // Stamp going back by less than 1 s, and an equal stamp: dropped.
  pub.publish(pose(kT0 + ros::Duration(1.6), kTopX, 0.0));
  pub.publish(pose(t_good, kTopX, 0.1));
  EXPECT_EQ(l.countDuring(0.5), 0) << "a pose with an old or repeated stamp was answered";
  const ros::Time t_next = kT0 + ros::Duration(2.2);
  pub.publish(pose(t_next, kTopX, 0.0));
  ASSERT_TRUE(l.waitFor(t_next)) << "no answer after an old stamp";

  // Stamp going back by 2.2 s (bag loop): re-initialised from statics at that stamp.
  const int before = l.state_count;
  l.forget(kT0);
  pub.publish(pose(kT0, kTopX, kTopZ));
  ASSERT_TRUE(l.waitFor(kT0)) << "no answer after a bag loop";
  EXPECT_EQ(l.state_count, before + 1);
  const CableState& s0 = l.states[kT0.toNSec()];
  expectConsistent(s0, l.wrenches[kT0.toNSec()], "world");
  EXPECT_NEAR(s0.top_force.x, static_force.x, 1e-6 * std::abs(static_force.x));
  EXPECT_NEAR(s0.top_force.z, static_force.z, 1e-6 * std::abs(static_force.z));
  const ros::Time t1 = kT0 + ros::Duration(0.1);
  l.forget(t1);
  pub.publish(pose(t1, kTopX, 0.05));
  ASSERT_TRUE(l.waitFor(t1)) << "no answer after the re-initialisation";
}

TEST(Lockstep, OdometryFarStartAndVesselFrame) {
  ros::NodeHandle nh;
  Listener l(g_vessel_node);
  ros::Publisher pub = nh.advertise<nav_msgs::Odometry>(g_vessel_node + "/top_odom", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to " << g_vessel_node;
  // First sample 1 m from the static top (> 0.5 m): statics are re-solved with the top there.
  for (int k = 0; k <= 3; ++k) {
    nav_msgs::Odometry o;
    o.header.stamp = kT0 + ros::Duration(0.1 * k);
    o.header.frame_id = "world";
    o.pose.pose.position.x = kTopX - 1.0 - 0.1 * k;
    o.pose.pose.position.z = kTopZ;
    o.pose.pose.orientation.w = 1.0;
    pub.publish(o);
    ASSERT_TRUE(l.waitFor(o.header.stamp)) << "no answer to odometry k = " << k;
    const CableState& s = l.states[o.header.stamp.toNSec()];
    const geometry_msgs::WrenchStamped& w = l.wrenches[o.header.stamp.toNSec()];
    SCOPED_TRACE("k = " + std::to_string(k));
    expectConsistent(s, w, "vessel");
    // k = 0: statics re-solved with the top exactly there (later samples: see the heave test).
    if (k == 0) {
      EXPECT_NEAR(s.positions.back().x, o.pose.pose.position.x, 1e-6);
      EXPECT_NEAR(s.positions.back().z, kTopZ, 1e-6);
    }
    // vessel = world turned by 180 degrees about z: x and y flip, z stays.
    EXPECT_NEAR(w.wrench.force.x, s.top_force.x, 1e-9 * std::abs(s.top_force.x));
    EXPECT_NEAR(w.wrench.force.z, -s.top_force.z, 1e-9 * std::abs(s.top_force.z));
  }
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_lockstep");
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("node", g_node, g_node);
  pnh.param<std::string>("vessel_node", g_vessel_node, g_vessel_node);
  return RUN_ALL_TESTS();
}
