// rostest for mooring_dynamics_node in dynamic (lockstep) mode on the 3-D model
// (test/ros/test_lockstep3d.test).
//
// Problem config/chain_mooring_3d.yaml (model: 3d): the A.3 chain mooring in a 60 deg cross
// current, 170 nodes, buoy top (replaced by the motion samples), dt 0.1 s. Its static top is
// taken from the core's static solve of the same file. Nodes:
//   /sway3d   pose source: a 1 m sway along y (period 4 s) at 10 Hz; the published top follows y,
//             the line between the anchor and the top moves in y, the wrench carries a y component
//             that changes with the sway; ~solve_static takes a top position with y and re-
//             initialises there.
//   /odom3d   odometry source, ~vessel_frame `vessel90` (world turned 90 deg about z): a first
//             sample 0.5 m off in y re-solves statics there; the wrench's world y shows up as its
//             vessel x.
//   /tf3d     tf source (world <- fairlead3d, broadcast by the test): y reaches the state.
//   /planar2d model: 2d (test/data/small_catenary.yaml): a pose with y = 0.5 m is dropped and
//             named in /diagnostics, a pose in the plane is answered.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "lockstep_listener.hpp"
#include "mooring_dynamics/ReleaseLine.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/Winch.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"

using lockstep_test::Listener;
using lockstep_test::waitForConnection;
using mooring_dynamics::CableState;
using mooring_dynamics::SolveStatic;
namespace core = mooring_dynamics::core;

namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kSway = 1.0;     // [m] amplitude along y
constexpr double kPeriod = 4.0;   // [s]
constexpr double kRate = 10.0;    // [Hz]
// The top follows the track through velocity with position feedback (docs/method.md), lagging by
// a fraction of the motion per sample; a top that ignored y would be off by the full amplitude.
constexpr double kFollowFraction = 0.25;
// A static solve puts the top where it is held to the solver's tolerance: 1e-6 m is far above it.
constexpr double kHeldAt = 1e-6;
// The sway must change the line's pull along y by more than this [N]: the quasi-static change of
// a 1 m sway on this ~1.4 kN line is tens of N, the solver's noise far below 1 N.
constexpr double kSwayForce = 1.0;
const ros::Time kT0(3000.0);

struct Top {
  double x, y, z;
};

/// Static top of the shipped 3-D mooring, as the node solves it on start.
Top staticTop() {
  const core::Problem p = core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/chain_mooring_3d.yaml");
  const core::StaticResult r = core::solveStaticModel(p);
  EXPECT_TRUE(r.summary.converged) << r.summary.message;
  return {r.nodes.back().x, r.nodes.back().y, r.nodes.back().z};
}

geometry_msgs::PoseStamped pose(const ros::Time& stamp, double x, double y, double z) {
  geometry_msgs::PoseStamped p;
  p.header.stamp = stamp;
  p.header.frame_id = "world";
  p.pose.position.x = x;
  p.pose.position.y = y;
  p.pose.position.z = z;
  p.pose.orientation.w = 1.0;
  return p;
}

}  // namespace

TEST(Lockstep3D, SwayFollowedInYAndWrenchHasY) {
  const Top top = staticTop();
  ros::NodeHandle nh;
  Listener l("/sway3d");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/sway3d/top_pose", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to /sway3d";

  const int n = static_cast<int>(kPeriod * kRate);  // one period
  double max_dev = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double t = k / kRate;
    const ros::Time stamp = kT0 + ros::Duration(t);
    const double y = top.y + kSway * std::sin(2.0 * kPi * t / kPeriod);
    pub.publish(pose(stamp, top.x, y, top.z));
    ASSERT_TRUE(l.waitFor(stamp, 10.0)) << "no answer to the pose at k = " << k;
    const CableState& s = l.states[stamp.toNSec()];
    const geometry_msgs::WrenchStamped& w = l.wrenches[stamp.toNSec()];
    SCOPED_TRACE("k = " + std::to_string(k));
    ASSERT_TRUE(s.converged);
    EXPECT_EQ(w.header.frame_id, "world");
    EXPECT_DOUBLE_EQ(w.wrench.force.x, -s.top_force.x);
    EXPECT_DOUBLE_EQ(w.wrench.force.y, -s.top_force.y);
    EXPECT_DOUBLE_EQ(w.wrench.force.z, -s.top_force.z);
    EXPECT_NE(w.wrench.force.y, 0.0) << "no y component in the wrench (the line lies in a cross current)";
    max_dev = std::max(max_dev, std::abs(s.positions.back().y - y));
  }
  EXPECT_EQ(l.state_count, n + 1);
  RecordProperty("max_top_y_deviation_m", std::to_string(max_dev));
  EXPECT_LT(max_dev, kFollowFraction * kSway) << "the top does not follow the commanded sway";

  // Crest (t = T/4) and trough (t = 3T/4): the top is on either side of its static y, the upper
  // part of the line (the node at 95 % of the node count, ~4 m below the top) moved the same way
  // (farther down the chain's inertia and drag put its sway out of phase: 3/4 of the way up it
  // is already reversed), and the line pulls the vessel toward -y harder at the crest.
  const CableState& crest = l.states[(kT0 + ros::Duration(0.25 * kPeriod)).toNSec()];
  const CableState& trough = l.states[(kT0 + ros::Duration(0.75 * kPeriod)).toNSec()];
  EXPECT_GT(crest.positions.back().y, top.y + (1.0 - kFollowFraction) * kSway);
  EXPECT_LT(trough.positions.back().y, top.y - (1.0 - kFollowFraction) * kSway);
  const std::size_t upper = crest.positions.size() * 95 / 100;
  EXPECT_GT(crest.positions[upper].y, trough.positions[upper].y + kSway);
  const double wy_crest = l.wrenches[(kT0 + ros::Duration(0.25 * kPeriod)).toNSec()].wrench.force.y;
  const double wy_trough = l.wrenches[(kT0 + ros::Duration(0.75 * kPeriod)).toNSec()].wrench.force.y;
  RecordProperty("wrench_y_crest_N", std::to_string(wy_crest));
  RecordProperty("wrench_y_trough_N", std::to_string(wy_trough));
  EXPECT_LT(wy_crest, wy_trough - kSwayForce) << "the wrench's y does not respond to the sway";

  // ~solve_static with y != 0 (model: 3d) and reinitialise: the run restarts with the top there.
  ros::ServiceClient cl = nh.serviceClient<SolveStatic>("/sway3d/solve_static");
  ASSERT_TRUE(cl.waitForExistence(ros::Duration(5.0)));
  SolveStatic srv;
  srv.request.mode = SolveStatic::Request::TOP_POSITION;
  srv.request.top_position.x = top.x;
  srv.request.top_position.y = top.y + 2.0;
  srv.request.top_position.z = top.z;
  srv.request.reinitialise = true;
  const ros::Time last = kT0 + ros::Duration(n / kRate);
  l.forget(last);
  ASSERT_TRUE(cl.call(srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(srv.response.reinitialised) << srv.response.message;
  ASSERT_FALSE(srv.response.positions.empty());
  EXPECT_NEAR(srv.response.positions.back().y, top.y + 2.0, kHeldAt);
  EXPECT_NE(srv.response.top_force.y, 0.0);
  EXPECT_NE(srv.response.message.find("(x, y, z)"), std::string::npos) << srv.response.message;
  ASSERT_TRUE(l.waitFor(last)) << "no state published after the re-initialisation";
  EXPECT_NEAR(l.states[last.toNSec()].positions.back().y, top.y + 2.0, kHeldAt);
}

TEST(Lockstep3D, OdometryYAndVesselFrame) {
  const Top top = staticTop();
  ros::NodeHandle nh;
  Listener l("/odom3d");
  ros::Publisher pub = nh.advertise<nav_msgs::Odometry>("/odom3d/top_odom", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to /odom3d";
  for (int k = 0; k <= 3; ++k) {
    nav_msgs::Odometry o;
    o.header.stamp = kT0 + ros::Duration(0.1 * k);
    o.header.frame_id = "world";
    o.pose.pose.position.x = top.x;
    o.pose.pose.position.y = top.y + 0.5 + 0.05 * k;
    o.pose.pose.position.z = top.z;
    o.pose.pose.orientation.w = 1.0;
    pub.publish(o);
    ASSERT_TRUE(l.waitFor(o.header.stamp, 10.0)) << "no answer to odometry k = " << k;
    const CableState& s = l.states[o.header.stamp.toNSec()];
    const geometry_msgs::WrenchStamped& w = l.wrenches[o.header.stamp.toNSec()];
    SCOPED_TRACE("k = " + std::to_string(k));
    // k = 0: 0.5 m from the static top: statics re-solved with the top there, y included.
    if (k == 0) {
      EXPECT_NEAR(s.positions.back().y, top.y + 0.5, kHeldAt);
    }
    // vessel90 = world turned 90 deg about z: vessel x = world y, vessel y = -world x.
    EXPECT_EQ(w.header.frame_id, "vessel90");
    EXPECT_NEAR(w.wrench.force.x, -s.top_force.y, 1e-9 * std::abs(s.top_force.y) + 1e-9);
    EXPECT_NEAR(w.wrench.force.y, s.top_force.x, 1e-9 * std::abs(s.top_force.x) + 1e-9);
    EXPECT_NEAR(w.wrench.force.z, -s.top_force.z, 1e-9 * std::abs(s.top_force.z));
  }
}

TEST(Lockstep3D, TfSourceCarriesY) {
  const Top top = staticTop();
  ros::NodeHandle nh;
  Listener l("/tf3d");
  tf2_ros::TransformBroadcaster br;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (ros::ok() && ros::WallTime::now() < end && l.s1.getNumPublishers() == 0) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_GT(l.s1.getNumPublishers(), 0) << "no connection to /tf3d";
  geometry_msgs::TransformStamped tr;
  tr.header.frame_id = "world";
  tr.child_frame_id = "fairlead3d";
  tr.transform.translation.x = top.x;
  tr.transform.translation.y = top.y - 0.3;
  tr.transform.translation.z = top.z;
  tr.transform.rotation.w = 1.0;
  // Broadcast until the node has used a transform (it polls at ~tf_poll_rate).
  bool answered = false;
  const ros::WallTime end2 = ros::WallTime::now() + ros::WallDuration(15.0);
  for (int k = 0; ros::ok() && ros::WallTime::now() < end2 && !answered; ++k) {
    tr.header.stamp = kT0 + ros::Duration(0.1 * k);
    br.sendTransform(tr);
    for (int i = 0; i < 10 && !answered; ++i) {
      ros::WallDuration(0.01).sleep();
      ros::spinOnce();
      answered = !l.states.empty();
    }
  }
  ASSERT_TRUE(answered) << "the tf source produced no state";
  const CableState& s = l.states.begin()->second;
  EXPECT_NEAR(s.positions.back().y, top.y - 0.3, kHeldAt);
  EXPECT_NEAR(s.positions.back().x, top.x, kHeldAt);
}

// ~release (line events): after the sway test, /sway3d's anchor is let go; from the next sample
// on the line pulls its anchor with nothing and the event is on the state. Bad requests (an end
// other than top or anchor, another line's name, the same end again, a 2-D line) are refused with
// the field named.
TEST(Lockstep3D, ReleaseServiceLetsTheAnchorGo) {
  const Top top = staticTop();
  ros::NodeHandle nh;
  Listener l("/sway3d");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/sway3d/top_pose", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to /sway3d";
  const ros::Time t1 = kT0 + ros::Duration(10.0), t2 = t1 + ros::Duration(0.1);
  pub.publish(pose(t1, top.x, top.y, top.z));
  ASSERT_TRUE(l.waitFor(t1, 10.0));
  const geometry_msgs::Vector3 held = l.states[t1.toNSec()].anchor_force;
  const double held_norm = std::sqrt(held.x * held.x + held.y * held.y + held.z * held.z);
  ASSERT_GT(held_norm, 100.0);
  EXPECT_TRUE(l.states[t1.toNSec()].events.empty());

  ros::ServiceClient cl = nh.serviceClient<mooring_dynamics::ReleaseLine>("/sway3d/release");
  ASSERT_TRUE(cl.waitForExistence(ros::Duration(5.0)));
  mooring_dynamics::ReleaseLine bad;
  bad.request.end = "bottom";
  ASSERT_TRUE(cl.call(bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("end = \"bottom\": must be top or anchor"), std::string::npos) << bad.response.message;
  bad.request.end = "anchor";
  bad.request.line = "other";
  ASSERT_TRUE(cl.call(bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("line = other"), std::string::npos) << bad.response.message;

  mooring_dynamics::ReleaseLine rel;
  rel.request.end = "anchor";
  ASSERT_TRUE(cl.call(rel));
  ASSERT_TRUE(rel.response.success) << rel.response.message;
  ASSERT_TRUE(cl.call(rel));
  EXPECT_FALSE(rel.response.success);
  EXPECT_NE(rel.response.message.find("free already"), std::string::npos) << rel.response.message;

  pub.publish(pose(t2, top.x, top.y, top.z));
  ASSERT_TRUE(l.waitFor(t2, 10.0));
  const CableState& s = l.states[t2.toNSec()];
  EXPECT_TRUE(s.converged);
  const geometry_msgs::Vector3& f = s.anchor_force;
  EXPECT_LT(std::sqrt(f.x * f.x + f.y * f.y + f.z * f.z), 1e-3 * held_norm) << "the let-go anchor still pulled";
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_NE(s.events[0].find("released anchor"), std::string::npos) << s.events[0];

  ros::ServiceClient cl2 = nh.serviceClient<mooring_dynamics::ReleaseLine>("/planar2d/release");
  ASSERT_TRUE(cl2.waitForExistence(ros::Duration(5.0)));
  mooring_dynamics::ReleaseLine r2;
  r2.request.end = "top";
  ASSERT_TRUE(cl2.call(r2));
  EXPECT_FALSE(r2.response.success);
  EXPECT_NE(r2.response.message.find("need model: 3d"), std::string::npos) << r2.response.message;
}

// ~winch: /odom3d's fairlead winch pays out 2 m at 1 m/s; the states carry the line's length (the
// last node's s) and the rate, the target is reached and held. A target below the top segment's
// shortest is refused with the limits named, and a 2-D line's node refuses the winch.
TEST(Lockstep3D, WinchServicePaysOutToTheTarget) {
  const Top top = staticTop();
  ros::NodeHandle nh;
  Listener l("/odom3d");
  ros::Publisher pub = nh.advertise<nav_msgs::Odometry>("/odom3d/top_odom", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to /odom3d";
  auto sample = [&](const ros::Time& t) {
    nav_msgs::Odometry o;
    o.header.stamp = t;
    o.header.frame_id = "world";
    o.pose.pose.position.x = top.x;
    o.pose.pose.position.y = top.y + 0.65;  // where OdometryYAndVesselFrame left it
    o.pose.pose.position.z = top.z;
    o.pose.pose.orientation.w = 1.0;
    pub.publish(o);
    return l.waitFor(t, 10.0);
  };
  const ros::Time t0 = kT0 + ros::Duration(20.0);
  ASSERT_TRUE(sample(t0));
  const double L0 = l.states[t0.toNSec()].line_length;
  EXPECT_NEAR(L0, l.states[t0.toNSec()].s.back(), 1e-12);

  ros::ServiceClient cl = nh.serviceClient<mooring_dynamics::Winch>("/odom3d/winch");
  ASSERT_TRUE(cl.waitForExistence(ros::Duration(5.0)));
  mooring_dynamics::Winch bad;
  bad.request.rate = -1.0;
  bad.request.target_length = 0.5;
  ASSERT_TRUE(cl.call(bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("target length = 0.5 m: outside"), std::string::npos) << bad.response.message;
  EXPECT_NEAR(bad.response.line_length, L0, 1e-12);
  bad.request.target_length = -5.0;  // not "none": refused with the field named
  ASSERT_TRUE(cl.call(bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("target_length = -5: must be > 0"), std::string::npos) << bad.response.message;

  mooring_dynamics::Winch w;
  w.request.rate = 1.0;
  w.request.target_length = L0 + 2.0;
  ASSERT_TRUE(cl.call(w));
  ASSERT_TRUE(w.response.success) << w.response.message;
  for (int k = 1; k <= 30; ++k) ASSERT_TRUE(sample(t0 + ros::Duration(0.1 * k))) << "k = " << k;
  const CableState& mid = l.states[(t0 + ros::Duration(1.0)).toNSec()];
  EXPECT_NEAR(mid.line_length, L0 + 1.0, 1e-6);
  EXPECT_NEAR(mid.winch_rate, 1.0, 1e-9);
  const CableState& end = l.states[(t0 + ros::Duration(3.0)).toNSec()];
  EXPECT_TRUE(end.converged);
  EXPECT_NEAR(end.line_length, L0 + 2.0, 1e-6);
  EXPECT_EQ(end.winch_rate, 0.0);
  EXPECT_NEAR(end.positions.back().x, top.x, 0.05);  // the fairlead still holds the top

  ros::ServiceClient cl2 = nh.serviceClient<mooring_dynamics::Winch>("/planar2d/winch");
  ASSERT_TRUE(cl2.waitForExistence(ros::Duration(5.0)));
  mooring_dynamics::Winch w2;
  w2.request.rate = 0.5;
  ASSERT_TRUE(cl2.call(w2));
  EXPECT_FALSE(w2.response.success);
  EXPECT_NE(w2.response.message.find("needs model: 3d"), std::string::npos) << w2.response.message;
}

TEST(Lockstep2D, OutOfPlanePoseDroppedAndNamed) {
  ros::NodeHandle nh;
  Listener l("/planar2d");
  std::string last_error;
  ros::Subscriber ds = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          if (st.name.find("planar2d") != std::string::npos)
            for (const auto& kv : st.values)
              if (kv.key == "last error") last_error = kv.value;
      });
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/planar2d/top_pose", 100);
  ASSERT_TRUE(waitForConnection(pub, l)) << "no connection to /planar2d";
  pub.publish(pose(kT0, 100.0, 0.5, 0.0));
  EXPECT_EQ(l.countDuring(0.5), 0) << "a pose off the plane of a 2-D problem was answered";
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (ros::ok() && ros::WallTime::now() < end && last_error.empty()) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  EXPECT_NE(last_error.find("pose.position.y = 0.5 m: the problem is model: 2d"), std::string::npos) << last_error;
  const ros::Time t1 = kT0 + ros::Duration(0.1);
  pub.publish(pose(t1, 100.0, 0.0, 0.0));
  ASSERT_TRUE(l.waitFor(t1)) << "no answer to a pose in the plane after the dropped one";
  EXPECT_EQ(l.states[t1.toNSec()].positions.back().y, 0.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_lockstep3d");
  return RUN_ALL_TESTS();
}
