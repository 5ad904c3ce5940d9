// rostest of the dynamic (lockstep) node's inputs and outputs besides the motion itself
// (test/ros/test_lockstep_io.test): unknown and other input frames, a silent source
// (diagnostics WARN, last state republished), ~reset and ~solve_static (with and without
// reinitialise), /diagnostics content, markers only when subscribed and in ~frame_id, tf frames
// of instruments on the line (tf lookup), the tf motion source.
//
// Problem test/data/small_catenary.yaml: 150 m of chain, anchor (0, -100) m, static top (100, 0) m,
// 76 nodes, dt 0.1 s. Each test uses its own stamps (later tests start > max_gap = 5 s after the
// previous ones, so the node re-initialises instead of integrating across the pause).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/ros/publish/markers.hpp"

using mooring_dynamics::CableState;
using mooring_dynamics::SolveStatic;

namespace {

constexpr double kTopX = 100.0, kTopZ = 0.0;
// Statics re-solved at the same top by two paths (service, driver) agree to the solver's
// tolerance; 1e-6 relative leaves a wide margin and still catches a wrong top or a dynamic state.
constexpr double kSameStatics = 1e-6;
// Positions that the solver sets exactly (a static top held at a point) [m].
constexpr double kExactPosition = 1e-6;
// Quiet time after which "no answer" is accepted: the node answers a pose in milliseconds.
constexpr double kNoAnswerWait = 0.5;  // [s]

struct Outputs {
  std::map<uint64_t, CableState> states;
  int state_count = 0;
  CableState last;
  std::map<std::string, std::vector<diagnostic_msgs::DiagnosticStatus>> diag;  // every status, per name
  ros::Subscriber s_state, s_diag;

  explicit Outputs(const std::string& node) {
    ros::NodeHandle nh;
    s_state = nh.subscribe<CableState>(node + "/cable_state", 100, [this](const CableState::ConstPtr& m) {
      states[m->header.stamp.toNSec()] = *m;
      last = *m;
      ++state_count;
    });
    s_diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          for (const auto& s : m->status) diag[s.name].push_back(s);
        });
  }
  bool waitFor(const ros::Time& stamp, double timeout = 5.0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end) {
      ros::spinOnce();
      if (states.count(stamp.toNSec())) return true;
      ros::WallDuration(0.002).sleep();
    }
    return false;
  }
  int countDuring(double seconds) {
    const int before = state_count;
    spinFor(seconds);
    return state_count - before;
  }
  static void spinFor(double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < end) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
  }
  /// A diagnostics status of `node` received since this object was made whose message contains
  /// `text`, within `timeout` (each status covers one diagnostics period, so they are all kept).
  /// `out` is that status, or the latest one when none matched.
  bool waitDiag(const std::string& node, const std::string& text, diagnostic_msgs::DiagnosticStatus& out,
                double timeout = 5.0) {
    const std::string name = "mooring_dynamics: " + node + " lockstep";
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    std::size_t seen = 0;
    while (ros::ok() && ros::WallTime::now() < end) {
      ros::spinOnce();
      auto& v = diag[name];
      for (; seen < v.size(); ++seen) {
        out = v[seen];
        if (out.message.find(text) != std::string::npos) {
          v.erase(v.begin(), v.begin() + static_cast<long>(seen) + 1);  // later waits look further
          return true;
        }
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }
};

geometry_msgs::PoseStamped pose(const ros::Time& stamp, double x, double z, const std::string& frame = "world") {
  geometry_msgs::PoseStamped p;
  p.header.stamp = stamp;
  p.header.frame_id = frame;
  p.pose.position.x = x;
  p.pose.position.z = z;
  p.pose.orientation.w = 1.0;
  return p;
}

bool connect(const ros::Publisher& pub, const Outputs& o) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (ros::ok() && ros::WallTime::now() < end) {
    if (pub.getNumSubscribers() > 0 && o.s_state.getNumPublishers() > 0) return true;
    ros::WallDuration(0.05).sleep();
    ros::spinOnce();
  }
  return false;
}

std::string value(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key) {
  for (const auto& kv : s.values)
    if (kv.key == key) return kv.value;
  return "<missing " + key + ">";
}

SolveStatic::Response solve(SolveStatic::Request req) {
  ros::NodeHandle nh;
  ros::ServiceClient c = nh.serviceClient<SolveStatic>("/io/solve_static");
  EXPECT_TRUE(c.waitForExistence(ros::Duration(10.0)));
  SolveStatic srv;
  srv.request = req;
  EXPECT_TRUE(c.call(srv));
  return srv.response;
}

/// Base stamp of each test: far apart (> max_gap) so each test starts a fresh run.
ros::Time base(int test) { return ros::Time(1000.0 + 100.0 * test); }

}  // namespace

// Order matters (one node, shared state): gtest runs tests in definition order.

TEST(LockstepIo, FramesUnknownAndTransformed) {
  ros::NodeHandle nh;
  Outputs o("/io");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/io/top_pose", 100);
  ASSERT_TRUE(connect(pub, o));
  const ros::Time t0 = base(0);
  pub.publish(pose(t0, kTopX, kTopZ));
  ASSERT_TRUE(o.waitFor(t0));
  // Unknown frame: dropped (no answer), reported on /diagnostics with the frame's name.
  pub.publish(pose(t0 + ros::Duration(0.1), kTopX, kTopZ, "nowhere"));
  EXPECT_EQ(o.countDuring(kNoAnswerWait), 0) << "a pose in an unknown frame was answered";
  diagnostic_msgs::DiagnosticStatus d;
  EXPECT_TRUE(o.waitDiag("/io", "nowhere", d)) << "last diagnostics: " << d.message;
  EXPECT_EQ(d.level, diagnostic_msgs::DiagnosticStatus::WARN);
  // A pose in frame `offset` (world shifted by +10 m in x) is transformed: 90 m there = 100 m in world.
  const ros::Time t1 = t0 + ros::Duration(0.2);
  pub.publish(pose(t1, kTopX - 10.0, kTopZ, "offset"));
  ASSERT_TRUE(o.waitFor(t1)) << "no answer to a pose in a known frame";
  EXPECT_EQ(o.states[t1.toNSec()].header.frame_id, "world");
  EXPECT_NEAR(o.states[t1.toNSec()].positions.back().x, kTopX, 0.05);
}

TEST(LockstepIo, MarkersOnlyWhenSubscribedAndBodyFrames) {
  ros::NodeHandle nh;
  Outputs o("/io");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/io/top_pose", 100);
  ASSERT_TRUE(connect(pub, o));
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const ros::Time t0 = base(1);
  pub.publish(pose(t0, kTopX, kTopZ));
  ASSERT_TRUE(o.waitFor(t0));
  // Nobody subscribed to the markers so far: nothing was published (so nothing is latched).
  int markers = 0;
  visualization_msgs::MarkerArray last_markers;
  ros::Subscriber ms = nh.subscribe<visualization_msgs::MarkerArray>(
      "/io/markers", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        ++markers;
        last_markers = *m;
      });
  Outputs::spinFor(kNoAnswerWait);
  EXPECT_EQ(markers, 0) << "markers were published without a subscriber";
  const ros::Time t1 = t0 + ros::Duration(0.1);
  pub.publish(pose(t1, kTopX, kTopZ + 0.02));
  ASSERT_TRUE(o.waitFor(t1));
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (markers == 0 && ros::WallTime::now() < end) Outputs::spinFor(0.01);
  ASSERT_GT(markers, 0) << "no markers after subscribing";
  bool cable = false, scale = false, label = false;
  for (const auto& m : last_markers.markers) {
    EXPECT_EQ(m.header.frame_id, "world") << m.ns;
    EXPECT_EQ(m.header.stamp, t1) << m.ns;
    cable |= m.ns == "cable";
    scale |= m.ns == "scale";
    label |= m.ns == "label";
  }
  EXPECT_TRUE(cable && scale && label);

  // Instrument frames at s = 50 m and 100 m: tf world <- line/s50 at the state's stamp is the
  // line's position there.
  const CableState& s = o.states[t1.toNSec()];
  for (double at : {50.0, 100.0}) {
    const std::string child = at == 50.0 ? "line/s50" : "line/s100";
    geometry_msgs::TransformStamped tr;
    std::string err;
    ASSERT_TRUE(buffer.canTransform("world", child, t1, ros::Duration(5.0), &err)) << child << ": " << err;
    tr = buffer.lookupTransform("world", child, t1);
    const geometry_msgs::Point p = mooring_dynamics::ros_bridge::pointAtArclength(s, at);
    EXPECT_NEAR(tr.transform.translation.x, p.x, kExactPosition) << child;
    EXPECT_NEAR(tr.transform.translation.z, p.z, kExactPosition) << child;
    // The frame's x axis is the cable tangent: it points up and away from the anchor.
    const auto& q = tr.transform.rotation;
    const double xz = 2.0 * (q.x * q.z - q.w * q.y);  // z component of the rotated x axis
    EXPECT_GT(xz, 0.0) << child;
  }
}

TEST(LockstepIo, ResetAndSolveStatic) {
  ros::NodeHandle nh;
  Outputs o("/io");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/io/top_pose", 100);
  ASSERT_TRUE(connect(pub, o));
  const ros::Time t0 = base(2);
  ros::Time last;
  for (int k = 0; k <= 10; ++k) {  // surge 0.5 m toward the anchor in 1 s
    last = t0 + ros::Duration(0.1 * k);
    pub.publish(pose(last, kTopX - 0.05 * k, kTopZ));
    ASSERT_TRUE(o.waitFor(last)) << "k = " << k;
  }
  // Reference: statics with the top at (99.5, 0), without touching the dynamic run.
  SolveStatic::Request q;
  q.mode = SolveStatic::Request::TOP_POSITION;
  q.top_position.x = kTopX - 0.5;
  q.top_position.z = kTopZ;
  const int before = o.state_count;
  const SolveStatic::Response ref = solve(q);
  ASSERT_TRUE(ref.success) << ref.message;
  EXPECT_FALSE(ref.reinitialised);
  EXPECT_EQ(o.countDuring(kNoAnswerWait), 0) << "solve_static without reinitialise published a state";
  EXPECT_EQ(o.state_count, before);

  // ~reset: statics at the current top (99.5, 0), published with the last stamp.
  ros::ServiceClient rc = nh.serviceClient<std_srvs::Trigger>("/io/reset");
  ASSERT_TRUE(rc.waitForExistence(ros::Duration(10.0)));
  std_srvs::Trigger tr;
  o.states.erase(last.toNSec());
  ASSERT_TRUE(rc.call(tr));
  EXPECT_TRUE(tr.response.success) << tr.response.message;
  EXPECT_NE(tr.response.message.find("reset requested"), std::string::npos) << tr.response.message;
  ASSERT_TRUE(o.waitFor(last)) << "no state after ~reset";
  const CableState& r = o.states[last.toNSec()];
  EXPECT_NEAR(r.positions.back().x, kTopX - 0.5, kExactPosition);
  EXPECT_NEAR(r.top_force.x, ref.top_force.x, kSameStatics * std::abs(ref.top_force.x));
  EXPECT_NEAR(r.top_force.z, ref.top_force.z, kSameStatics * std::abs(ref.top_force.z));

  // ~solve_static with reinitialise at (99, 0): the run restarts there.
  q.top_position.x = kTopX - 1.0;
  q.reinitialise = true;
  o.states.erase(last.toNSec());
  const SolveStatic::Response re = solve(q);
  ASSERT_TRUE(re.success) << re.message;
  EXPECT_TRUE(re.reinitialised) << re.message;
  ASSERT_TRUE(o.waitFor(last)) << "no state after ~solve_static with reinitialise";
  EXPECT_NEAR(o.states[last.toNSec()].positions.back().x, kTopX - 1.0, kExactPosition);
  EXPECT_NEAR(o.states[last.toNSec()].top_force.x, re.top_force.x, kSameStatics * std::abs(re.top_force.x));
  // The next pose advances from there.
  const ros::Time next = last + ros::Duration(0.1);
  pub.publish(pose(next, kTopX - 1.0, kTopZ));
  ASSERT_TRUE(o.waitFor(next));

  // A bad request: refused with a message naming the field; the run goes on.
  q.top_position.z = std::nan("");
  const SolveStatic::Response bad = solve(q);
  EXPECT_FALSE(bad.success);
  EXPECT_FALSE(bad.reinitialised);
  EXPECT_NE(bad.message.find("top_position.z = nan"), std::string::npos) << bad.message;
  const ros::Time after = next + ros::Duration(0.1);
  pub.publish(pose(after, kTopX - 1.0, kTopZ));
  ASSERT_TRUE(o.waitFor(after)) << "no answer after a bad service request";
}

TEST(LockstepIo, SilentSourceAndDiagnostics) {
  ros::NodeHandle nh;
  Outputs o("/io");
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>("/io/top_pose", 100);
  ASSERT_TRUE(connect(pub, o));
  const ros::Time t0 = base(3);
  ros::Time last;
  for (int k = 0; k <= 5; ++k) {
    last = t0 + ros::Duration(0.1 * k);
    pub.publish(pose(last, kTopX, kTopZ));
    ASSERT_TRUE(o.waitFor(last));
  }
  diagnostic_msgs::DiagnosticStatus d;
  ASSERT_TRUE(o.waitDiag("/io", "", d));
  EXPECT_NE(value(d, "real-time factor (total)"), "-");
  EXPECT_NE(value(d, "top tension [N]"), "-");
  EXPECT_EQ(value(d, "slack now"), "false");
  // Silent for longer than ~motion_timeout (3 s): WARN, and the last state is republished
  // (same stamp) at the diagnostics period.
  ASSERT_TRUE(o.waitDiag("/io", "no motion for", d, 8.0)) << d.message;
  EXPECT_EQ(d.level, diagnostic_msgs::DiagnosticStatus::WARN);
  const int before = o.state_count;
  Outputs::spinFor(1.0);
  EXPECT_GE(o.state_count - before, 2) << "the last state is not republished while the source is silent";
  EXPECT_EQ(o.last.header.stamp, last);
  // Motion again: answered, diagnostics back to OK.
  const ros::Time next = last + ros::Duration(0.1);
  pub.publish(pose(next, kTopX, kTopZ));
  ASSERT_TRUE(o.waitFor(next));
  for (int k = 2; k <= 10; ++k) {
    const ros::Time t = last + ros::Duration(0.1 * k);
    pub.publish(pose(t, kTopX, kTopZ));
    ASSERT_TRUE(o.waitFor(t));
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_TRUE(o.waitDiag("/io", "running", d, 2.0)) << d.message;
}

TEST(LockstepIo, TfSource) {
  ros::NodeHandle nh;
  Outputs o("/tfsrc");
  // Before any fairlead transform: the node reports the missing transform.
  diagnostic_msgs::DiagnosticStatus d;
  EXPECT_TRUE(o.waitDiag("/tfsrc", "fairlead", d)) << d.message;
  tf2_ros::TransformBroadcaster br;
  const ros::Time t0 = base(4);
  for (int k = 0; k <= 10; ++k) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = t0 + ros::Duration(0.1 * k);
    t.header.frame_id = "world";
    t.child_frame_id = "fairlead";
    t.transform.translation.x = kTopX;
    t.transform.translation.z = kTopZ + 0.01 * k;
    t.transform.rotation.w = 1.0;
    // Send until the node answers (the first sends may go out before /tf is connected); the node
    // uses each new stamp once, whatever the number of polls (50 Hz) and sends.
    bool answered = false;
    for (int i = 0; i < 100 && !answered; ++i) {
      br.sendTransform(t);
      answered = o.waitFor(t.header.stamp, 0.05);
    }
    ASSERT_TRUE(answered) << "no state for the fairlead transform k = " << k;
    EXPECT_EQ(o.states[t.header.stamp.toNSec()].header.frame_id, "world");
  }
  EXPECT_NEAR(o.last.positions.back().z, kTopZ + 0.1, 0.05) << "the top does not follow the fairlead frame";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_lockstep_io");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
