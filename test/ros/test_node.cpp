// rostest for mooring_dynamics_node in static mode (test/ros/test_node.test).
//
// The node loads test/data/small_catenary.yaml: 150 m of chain, anchor at (0, -100) m, top held at
// (100, 0) m, 75 intervals -> 76 nodes; the line can reach 180 m from the anchor (max_strain 0.2).
// Checks: the latched CableState and MarkerArray of the problem's own static case; ~solve_static
// with good position / force / default requests; bad requests (NaN, y != 0, unreachable top, bad
// mode) answered with success = false and a message naming the problem, after which the node
// still keeps its last good state and answers good requests; the same problem loaded as a
// parameter map; bad parameters rejected in-process (StaticNode throws, so main() exits 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <ros/ros.h>
#include <ros/topic.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"
#include "mooring_dynamics/ros/nodes/static_node.hpp"

using mooring_dynamics::CableState;
using mooring_dynamics::SolveStatic;
namespace rb = mooring_dynamics::ros_bridge;

namespace {

constexpr std::size_t kNodes = 76;
constexpr double kAnchorX = 0.0, kAnchorZ = -100.0;
constexpr double kTopX = 100.0, kTopZ = 0.0;
const ros::Duration kTimeout(10.0);

std::string g_node = "/mooring_dynamics_node";
std::string g_map_node = "/mooring_dynamics_node_map";

ros::ServiceClient client() {
  ros::NodeHandle nh;
  const std::string name = g_node + "/solve_static";
  EXPECT_TRUE(ros::service::waitForService(name, ros::Duration(10.0))) << name << " did not appear";
  return nh.serviceClient<SolveStatic>(name);
}

SolveStatic::Response call(SolveStatic::Request req) {
  SolveStatic srv;
  srv.request = req;
  ros::ServiceClient c = client();
  EXPECT_TRUE(c.call(srv)) << "service call failed (node died?)";
  return srv.response;
}

SolveStatic::Request positionRequest(double x, double z, double y = 0.0) {
  SolveStatic::Request r;
  r.mode = SolveStatic::Request::TOP_POSITION;
  r.top_position.x = x;
  r.top_position.y = y;
  r.top_position.z = z;
  return r;
}

CableState::ConstPtr latestState(const std::string& node) {
  ros::NodeHandle nh;
  return ros::topic::waitForMessage<CableState>(node + "/cable_state", nh, kTimeout);
}

void expectGoodResponse(const SolveStatic::Response& r, double x, double z) {
  EXPECT_TRUE(r.success) << r.message;
  ASSERT_EQ(r.positions.size(), kNodes);
  ASSERT_EQ(r.tension.size(), kNodes);
  EXPECT_GT(r.iterations, 0);
  for (double t : r.tension) EXPECT_GT(t, 0.0);
  EXPECT_NEAR(r.positions.front().x, kAnchorX, 1e-6);
  EXPECT_NEAR(r.positions.front().z, kAnchorZ, 1e-6);
  EXPECT_NEAR(r.positions.back().x, x, 1e-6);
  EXPECT_NEAR(r.positions.back().z, z, 1e-6);
  for (const auto& p : r.positions) EXPECT_EQ(p.y, 0.0);
  // The top force is the internal force at the top: its magnitude is the top tension (shear ~ 0).
  EXPECT_NEAR(std::hypot(r.top_force.x, r.top_force.z), r.tension.back(), 1e-3 * r.tension.back());
  // Static balance of the whole line (no current): horizontal forces at the ends agree, and the
  // vertical forces differ by the wet weight 150 m x 31.85 N/m. The box scheme balances forces in
  // the local frame, so the global balance holds to O((ds/R)^2) ~ 1e-4 here (ds = 2 m, radius of
  // curvature R ~ 30 m): checked to 1e-3, enough to catch a sign or frame error.
  EXPECT_NEAR(r.top_force.x, r.anchor_force.x, 1e-3 * r.tension.back());
  EXPECT_NEAR(r.top_force.z - r.anchor_force.z, 150.0 * 31.85, 1e-3 * 150.0 * 31.85);
}

}  // namespace

// --- Latched outputs of the problem's own static case ------------------------------------------

TEST(Node, LatchedCableStateOfTheProblem) {
  // Whatever ran before (requests republish the state), the problem's own top boundary is asked
  // for first: the latched state is then the problem's own, as at the node's start.
  SolveStatic::Request own;
  own.mode = SolveStatic::Request::PROBLEM_DEFAULT;
  ASSERT_TRUE(call(own).success);
  CableState::ConstPtr s = latestState(g_node);
  ASSERT_TRUE(s) << "no CableState on " << g_node << "/cable_state within 10 s";
  EXPECT_EQ(s->header.frame_id, "world");
  EXPECT_EQ(s->line_name, "small catenary (ROS test)");
  ASSERT_EQ(s->positions.size(), kNodes);
  EXPECT_EQ(s->s.size(), kNodes);
  EXPECT_EQ(s->tension.size(), kNodes);
  EXPECT_EQ(s->shear.size(), kNodes);
  EXPECT_EQ(s->strain.size(), kNodes);
  EXPECT_EQ(s->angle.size(), kNodes);
  EXPECT_TRUE(s->converged);
  EXPECT_FALSE(s->slack);
  EXPECT_DOUBLE_EQ(s->s.front(), 0.0);
  EXPECT_NEAR(s->s.back(), 150.0, 1e-9);
  EXPECT_NEAR(s->positions.front().x, kAnchorX, 1e-6);
  EXPECT_NEAR(s->positions.front().z, kAnchorZ, 1e-6);
  EXPECT_NEAR(s->positions.back().x, kTopX, 1e-6);
  EXPECT_NEAR(s->positions.back().z, kTopZ, 1e-6);
  for (const auto& p : s->positions) EXPECT_EQ(p.y, 0.0);
  EXPECT_DOUBLE_EQ(s->min_tension, *std::min_element(s->tension.begin(), s->tension.end()));
  EXPECT_GT(s->min_tension, 0.0);
  EXPECT_EQ(s->top_force.y, 0.0);
  EXPECT_NEAR(std::hypot(s->top_force.x, s->top_force.z), s->tension.back(), 1e-3 * s->tension.back());
}

TEST(Node, LatchedMarkers) {
  ros::NodeHandle nh;
  auto m = ros::topic::waitForMessage<visualization_msgs::MarkerArray>(g_node + "/markers", nh, kTimeout);
  ASSERT_TRUE(m) << "no MarkerArray on " << g_node << "/markers within 10 s";
  bool line = false, anchor = false, top = false, label = false, seabed = false;
  for (const auto& k : m->markers) {
    EXPECT_EQ(k.header.frame_id, "world") << k.ns;
    if (k.ns == "cable") {
      line = true;
      EXPECT_EQ(k.type, visualization_msgs::Marker::LINE_STRIP);
      EXPECT_EQ(k.points.size(), kNodes);
      EXPECT_EQ(k.colors.size(), kNodes);
      EXPECT_GT(k.scale.x, 0.0);
      // Blue at the lowest tension (near the anchor), red at the highest (the top).
      EXPECT_GT(k.colors.back().r, 0.99);
      EXPECT_LT(k.colors.back().b, 0.01);
    } else if (k.ns == "anchor") {
      anchor = true;
      EXPECT_NEAR(k.pose.position.z, kAnchorZ, 1e-6);
    } else if (k.ns == "top") {
      top = true;
      EXPECT_NEAR(k.pose.position.x, kTopX, 1e-6);
    } else if (k.ns == "label") {
      label = true;
      EXPECT_EQ(k.type, visualization_msgs::Marker::TEXT_VIEW_FACING);
      EXPECT_NE(k.text.find("kN"), std::string::npos) << k.text;
    } else if (k.ns == "seabed") {
      seabed = true;
      EXPECT_EQ(k.type, visualization_msgs::Marker::CUBE);
      EXPECT_NEAR(k.pose.position.z + 0.5 * k.scale.z, -120.0, 1e-6);  // top face at the seabed
    }
  }
  EXPECT_TRUE(line && anchor && top && label && seabed);
}

// Each node puts the line's anchor on /tf_static in its own ~frame_id (world, ocean), at the
// problem's anchor position (test/data/small_catenary.yaml): rviz then finds its fixed frame.
TEST(Node, AnchorFramesOnTfStatic) {
  ros::NodeHandle nh;
  std::map<std::string, geometry_msgs::TransformStamped> frames;
  auto sub = nh.subscribe<tf2_msgs::TFMessage>("/tf_static", 10, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
    for (const auto& t : m->transforms) frames[t.child_frame_id] = t;
  });
  const std::map<std::string, std::string> expected = {{g_node.substr(1) + "/anchor", "world"},
                                                       {g_map_node.substr(1) + "/anchor", "ocean"}};
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(kTimeout.toSec());
  auto all = [&] {
    for (const auto& kv : expected)
      if (!frames.count(kv.first)) return false;
    return true;
  };
  while (!all() && ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  for (const auto& kv : expected) {
    ASSERT_EQ(frames.count(kv.first), 1u) << kv.first;
    const auto& t = frames[kv.first];
    EXPECT_EQ(t.header.frame_id, kv.second);
    EXPECT_DOUBLE_EQ(t.transform.translation.x, kAnchorX);
    EXPECT_DOUBLE_EQ(t.transform.translation.y, 0.0);
    EXPECT_DOUBLE_EQ(t.transform.translation.z, kAnchorZ);
  }
}

TEST(Node, SameProblemAsParameterMap) {
  CableState::ConstPtr s = latestState(g_map_node);
  ASSERT_TRUE(s) << "no CableState on " << g_map_node << "/cable_state within 10 s";
  EXPECT_EQ(s->header.frame_id, "ocean");
  ASSERT_EQ(s->positions.size(), kNodes);
  EXPECT_NEAR(s->positions.back().x, kTopX, 1e-6);
  // Same problem, same answer as the problem's default top boundary on the main node.
  SolveStatic::Request req;
  req.mode = SolveStatic::Request::PROBLEM_DEFAULT;
  const SolveStatic::Response r = call(req);
  expectGoodResponse(r, kTopX, kTopZ);
  ASSERT_EQ(r.tension.size(), kNodes);
  EXPECT_NEAR(s->tension.back(), r.tension.back(), 1e-9 * r.tension.back());
}

// --- Service ------------------------------------------------------------------------------------

TEST(Node, GoodPositionRequestIsSolvedAndRepublished) {
  const SolveStatic::Response r = call(positionRequest(90.0, 0.0));
  expectGoodResponse(r, 90.0, 0.0);
  CableState::ConstPtr s = latestState(g_node);
  ASSERT_TRUE(s);
  ASSERT_EQ(s->positions.size(), kNodes);
  EXPECT_NEAR(s->positions.back().x, 90.0, 1e-6);
  EXPECT_NEAR(s->tension.back(), r.tension.back(), 1e-9 * r.tension.back());
}

TEST(Node, ForceRequestReproducesPosition) {
  // The top force found for a top position, applied as a force, puts the top back there.
  const SolveStatic::Response rp = call(positionRequest(110.0, -5.0));
  expectGoodResponse(rp, 110.0, -5.0);
  SolveStatic::Request req;
  req.mode = SolveStatic::Request::TOP_FORCE;
  req.top_force = rp.top_force;
  const SolveStatic::Response rf = call(req);
  EXPECT_TRUE(rf.success) << rf.message;
  ASSERT_EQ(rf.positions.size(), kNodes);
  EXPECT_NEAR(rf.positions.back().x, 110.0, 1e-3);
  EXPECT_NEAR(rf.positions.back().z, -5.0, 1e-3);
  EXPECT_NEAR(rf.top_force.x, rp.top_force.x, 1e-6 * rf.tension.back());
}

TEST(Node, NanRequestIsRejected) {
  const SolveStatic::Response r = call(positionRequest(std::numeric_limits<double>::quiet_NaN(), 0.0));
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("top_position.x = nan"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("finite"), std::string::npos) << r.message;
  EXPECT_TRUE(r.positions.empty());

  SolveStatic::Request f;
  f.mode = SolveStatic::Request::TOP_FORCE;
  f.top_force.x = 1000.0;
  f.top_force.z = std::numeric_limits<double>::infinity();
  const SolveStatic::Response rf = call(f);
  EXPECT_FALSE(rf.success);
  EXPECT_NE(rf.message.find("top_force.z = inf"), std::string::npos) << rf.message;
}

TEST(Node, OutOfPlaneRequestIsRejected) {
  const SolveStatic::Response r = call(positionRequest(90.0, 0.0, 5.0));
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("top_position.y = 5"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("x-z plane"), std::string::npos) << r.message;
}

TEST(Node, UnreachableTopIsRejected) {
  // 400 m from the anchor; 150 m of chain stretches to 180 m at most.
  const SolveStatic::Response r = call(positionRequest(400.0, 0.0));
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("top.position"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("reach"), std::string::npos) << r.message;
  EXPECT_TRUE(r.positions.empty());
}

TEST(Node, UnknownModeIsRejected) {
  SolveStatic::Request req = positionRequest(90.0, 0.0);
  req.mode = 7;
  const SolveStatic::Response r = call(req);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("mode = 7"), std::string::npos) << r.message;
}

TEST(Node, StillServesAfterBadRequestsAndKeepsLastGoodState) {
  const SolveStatic::Response good = call(positionRequest(95.0, 0.0));
  expectGoodResponse(good, 95.0, 0.0);
  EXPECT_FALSE(call(positionRequest(std::numeric_limits<double>::quiet_NaN(), 0.0)).success);
  EXPECT_FALSE(call(positionRequest(400.0, 0.0)).success);
  // The published state is still the last good one.
  CableState::ConstPtr s = latestState(g_node);
  ASSERT_TRUE(s);
  ASSERT_EQ(s->positions.size(), kNodes);
  EXPECT_NEAR(s->positions.back().x, 95.0, 1e-6);
  EXPECT_TRUE(s->converged);
  // And the node answers a good request again.
  expectGoodResponse(call(positionRequest(85.0, -2.0)), 85.0, -2.0);
}

// --- In-process: parameters and translation (no other node involved) ----------------------------

TEST(InProcess, BadProblemThrowsProblemError) {
  ros::NodeHandle pnh("~bad_problem");
  pnh.setParam("problem_yaml", std::string("materials: {chain: {EA: -1}}\nline: []\ntop: {position: {x: 1, z: 0}}\n"));
  ros::NodeHandle nh;
  EXPECT_THROW(rb::StaticNode(nh, pnh), mooring_dynamics::core::ProblemError);
  ros::NodeHandle pnh2("~missing_file");
  pnh2.setParam("problem_file", std::string("/nonexistent/problem.yaml"));
  try {
    rb::StaticNode node(nh, pnh2);
    ADD_FAILURE() << "no exception for a missing file";
  } catch (const mooring_dynamics::core::ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/problem.yaml"), std::string::npos) << e.what();
  }
}

TEST(InProcess, MissingOrAmbiguousProblemParametersThrow) {
  ros::NodeHandle nh;
  ros::NodeHandle none("~no_problem");
  EXPECT_THROW(rb::StaticNode(nh, none), std::runtime_error);
  ros::NodeHandle both("~both");
  both.setParam("problem_file", std::string("a.yaml"));
  both.setParam("problem_yaml", std::string("{}"));
  try {
    rb::StaticNode node(nh, both);
    ADD_FAILURE() << "no exception with both parameters set";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exactly one"), std::string::npos) << e.what();
  }
}

TEST(InProcess, ConverterRequestValidation) {
  mooring_dynamics::core::TopBoundary def;
  def.type = mooring_dynamics::core::TopBoundary::Type::Position;
  def.x = 100.0;
  SolveStatic::Request req = positionRequest(50.0, -1.0);
  auto t = rb::topBoundaryFromRequest(req, def);
  ASSERT_TRUE(t.ok) << t.error;
  EXPECT_EQ(t.top.type, mooring_dynamics::core::TopBoundary::Type::Position);
  EXPECT_EQ(t.top.x, 50.0);
  EXPECT_EQ(t.top.z, -1.0);
  req.top_position.z = -std::numeric_limits<double>::infinity();
  t = rb::topBoundaryFromRequest(req, def);
  EXPECT_FALSE(t.ok);
  EXPECT_EQ(t.error, "top_position.z = -inf: must be finite");
  req.mode = SolveStatic::Request::PROBLEM_DEFAULT;
  t = rb::topBoundaryFromRequest(req, def);  // fields are ignored in this mode
  ASSERT_TRUE(t.ok);
  EXPECT_EQ(t.top.x, 100.0);
}

TEST(InProcess, TensionColourScale) {
  const auto lo = rb::tensionColor(1.0, 1.0, 3.0), hi = rb::tensionColor(3.0, 1.0, 3.0);
  EXPECT_FLOAT_EQ(lo.b, 1.0f);
  EXPECT_FLOAT_EQ(lo.r, 0.0f);
  EXPECT_FLOAT_EQ(hi.r, 1.0f);
  EXPECT_FLOAT_EQ(hi.b, 0.0f);
  const auto flat = rb::tensionColor(5.0, 5.0, 5.0);  // no spread: middle of the scale
  EXPECT_FLOAT_EQ(flat.g, 1.0f);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node");
  ros::NodeHandle pnh("~");
  pnh.param("node", g_node, g_node);
  pnh.param("map_node", g_map_node, g_map_node);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int rc = RUN_ALL_TESTS();
  ros::shutdown();
  return rc;
}
