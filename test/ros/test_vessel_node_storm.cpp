// rostest: the moored-vessel lockstep node riding out a storm from a bag (VesselNode, ~mode dynamic
// on config/spread_mooring.yaml, test_vessel_node_storm.test): every sample answered with the wrench
// of core::VesselLockstep on the same poses, bit for bit, and each line's fallback steps in
// /diagnostics as that run counts them. The small vessel's track, services and bad samples:
// test_vessel_node.cpp; the listener and the main: vessel_node_test_util.hpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <rosbag/bag.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/storm_motion.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "vessel_node_test_util.hpp"

namespace core = mooring_dynamics::core;
namespace fs = std::filesystem;
using namespace vessel_node_test;

// test_vessel_node_storm.test: the shipped spread mooring (config/spread_mooring.yaml: 8 chain
// lines, `type: chain`, fallback after one cut) in 40 s of an Hs 6 m storm (generateStormMotion:
// JONSWAP, Tp 10 s, waves toward 30 deg, 4 m offset down-wave, 3 m drift; the first 20 s ramped
// in), played from a bag at its own rate under use_sim_time. Every sample is answered, with the
// wrench of a core VesselLockstep run on the same poses bit for bit, and /diagnostics reports each
// line's fallback steps as that run counts them (some lines fold in this sea).
TEST(VesselNode, RidesOutAnHs6StormFromABagWithFallbackCountsInDiagnostics) {
  if (g_mode != "storm") GTEST_SKIP() << "test_vessel_node_storm.test only";
  const std::string problem = std::string(MD_SOURCE_DIR) + "/config/spread_mooring.yaml";
  const std::vector<core::PoseSample> motion = core::generateStormMotion(core::mooringStorm(6.0, 10.0, 30.0, 1, 40.0));
  std::vector<Sample> tr;
  for (const core::PoseSample& m : motion) {
    Sample x;
    x.stamp = kStart + ros::Duration(m.t);
    x.pose.position.x = m.pose.position.x();
    x.pose.position.y = m.pose.position.y();
    x.pose.position.z = m.pose.position.z();
    x.pose.orientation.x = m.pose.orientation.x();
    x.pose.orientation.y = m.pose.orientation.y();
    x.pose.orientation.z = m.pose.orientation.z();
    x.pose.orientation.w = m.pose.orientation.w();
    tr.push_back(x);
  }
  // The core's run on the same poses (the node's time: stamp - first stamp; no twist).
  core::SystemProblem s = core::loadSystemFromFile(problem);
  core::VesselLockstepOptions lo;
  lo.threads = 2;
  core::VesselLockstep run(s, s.dynamics, lo);
  std::vector<Row> ref;
  for (const Sample& x : tr) {
    const core::VesselLockstep::Result r =
        run.onSample((x.stamp - tr[0].stamp).toSec(), mooring_dynamics::ros_bridge::toRigidPose(x.pose), nullptr);
    ASSERT_TRUE(r.outcome == core::VesselLockstep::Outcome::Started || r.outcome == core::VesselLockstep::Outcome::Advanced)
        << "core, t = " << (x.stamp - tr[0].stamp).toSec() << ": " << r.message;
    const core::VesselWrench w = run.wrench();
    Row row;
    for (const Eigen::Vector3d* v : {&w.force_body, &w.moment_body, &w.force_world, &w.moment_world})
      for (int i = 0; i < 3; ++i) row.push_back((*v)[i]);
    ref.push_back(row);
  }
  std::map<std::string, long> expected;
  long total = 0;
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    expected[s.lines[i].name] = run.dynamics().lineFallbackSteps(i);
    total += expected[s.lines[i].name];
  }
  ASSERT_GT(total, 0) << "this sea folds some lines";

  Listener& l = *g_listener;
  ros::NodeHandle nh;
  std::map<std::string, std::string> line_fallback;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          for (const auto& kv : st.values)
            if (st.name.find(" line ") != std::string::npos && kv.key == "fallback steps (total)")
              line_fallback[st.name.substr(st.name.find(" line ") + 6)] = kv.value;
      });
  ASSERT_TRUE(connect(nullptr)) << "no connection to " << g_node;
  const std::string bag_file = (fs::temp_directory_path() / ("md_storm_" + std::to_string(::getpid()) + ".bag")).string();
  {
    rosbag::Bag bag(bag_file, rosbag::bagmode::Write);
    for (const Sample& x : tr) bag.write(g_node + "/vessel_pose", x.stamp, toMsg(x));
  }
  const std::string cmd = "rosbag play --clock -q --wait-for-subscribers " + bag_file + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::remove(bag_file.c_str());
  l.spinUntil([&] { return l.has(tr.back().stamp); }, 120.0);
  for (std::size_t k = 0; k < tr.size(); ++k) {
    ASSERT_TRUE(l.has(tr[k].stamp)) << "no wrench for sample " << k;
    const Row node = rowOf(l.body[tr[k].stamp.toNSec()], l.world[tr[k].stamp.toNSec()]);
    for (std::size_t c = 0; c < 12; ++c) EXPECT_EQ(node[c], ref[k][c]) << "sample " << k << " column " << c;
  }
  // /diagnostics after the last sample: each line's total as the core counted it.
  l.spinUntil([&] {
    if (line_fallback.size() < expected.size()) return false;
    for (const auto& [name, n] : expected)
      if (line_fallback[name] != std::to_string(n)) return false;
    return true;
  }, 10.0);
  for (const auto& [name, n] : expected) EXPECT_EQ(line_fallback[name], std::to_string(n)) << name;
  std::printf("Hs 6 storm from a bag: %zu samples answered, %ld fallback steps in all\n", tr.size(), total);
}

int main(int argc, char** argv) { return testMain(argc, argv, "test_vessel_node_storm"); }
