// Determinism of the lockstep mode: one ship track (stamped fairlead positions) gives the same
// top-tension series
//   * live: published as PoseStamped with wall-clock node time (test_determinism.test),
//   * replayed from a bag with `rosbag play --clock` and use_sim_time (test_determinism.replay.test),
//   * offline: core::DynamicSolver2D or DynamicSolver3D (the problem's model) on the same problem
//     and the same top motion (linear between the samples, the top followed by position),
//     without ROS,
// to kDeterminism relative. dt 0.1 s, track at 10 Hz. Problem (~problem_file) by default
// test/data/small_catenary.yaml (model: 2d); test_determinism.3d.test and .3d_replay.test run
// config/chain_mooring_3d.yaml (model: 3d) with a sway along y (~sway).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rosbag/bag.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"
#include "mooring_dynamics/ros/nodes/lockstep.hpp"

using mooring_dynamics::CableState;
namespace core = mooring_dynamics::core;

namespace {

// The same arithmetic on the same numbers: any difference is a bug (message conversion, stamp
// handling, dropped or reordered samples). 1e-9 leaves room for nothing but rounding.
constexpr double kDeterminism = 1e-9;
constexpr double kDt = 0.1;          // [s] base step = sample spacing
constexpr int kSamples = 61;         // 6 s at 10 Hz
const ros::Time kStart(2000.0);      // first stamp (sim time in the bag)

std::string g_mode = "live", g_node = "/live";
std::string g_problem_file = std::string(MD_SOURCE_DIR) + "/test/data/small_catenary.yaml";
double g_sway = 0.0;  // [m] amplitude along y (model: 3d only)

struct Sample {
  ros::Time stamp;
  double x, y, z;
};

core::Problem problem() { return core::loadProblemFromFile(g_problem_file); }

/// Ship track: starts at the problem's static top (x0, y0, z0); surge 0.3 m (period 5 s), heave
/// 0.1 m (period 3 s) and sway g_sway (period 4 s), all starting from 0 so the track starts at
/// the rest position.
std::vector<Sample> track() {
  const double kPi = 3.141592653589793;
  const core::StaticResult st = core::solveStaticModel(problem());
  EXPECT_TRUE(st.summary.converged) << st.summary.message;
  const core::NodeState& top = st.nodes.back();
  std::vector<Sample> v;
  for (int k = 0; k < kSamples; ++k) {
    const double t = kDt * k;
    v.push_back({kStart + ros::Duration(t), top.x - 0.3 * std::sin(2 * kPi * t / 5.0),
                 top.y + g_sway * std::sin(2 * kPi * t / 4.0), top.z + 0.1 * std::sin(2 * kPi * t / 3.0)});
  }
  return v;
}

/// The core alone on the same track, as the lockstep node sets it up: statics of the problem,
/// then per sample the top moves linearly from the previous sample (position followed with
/// velocity and feedback), advanced to the sample's time after the first. `Solver` is
/// core::DynamicSolver2D or DynamicSolver3D.
template <class Solver>
std::vector<double> offlineTopTension(const core::Problem& problem, const std::vector<Sample>& tr) {
  core::Problem p = problem;
  p.dynamics.dt = kDt;
  p.dynamics.output_interval = 0.0;
  p.dynamics.top_motion = core::TopMotion();
  p.dynamics.top_motion.prescribe_position = true;
  p.dynamics.duration = kDt;
  Solver s(p);
  std::vector<double> out{s.snapshot().nodes.back().tension};
  const core::NodeState& top = s.initialStatic().nodes.back();
  double tp = 0.0, xp = top.x, yp = top.y, zp = top.z;
  for (std::size_t k = 1; k < tr.size(); ++k) {
    const double t = (tr[k].stamp - tr[0].stamp).toSec();
    const double x = tr[k].x, y = tr[k].y, z = tr[k].z;
    if constexpr (std::is_same_v<Solver, core::DynamicSolver3D>)
      s.setTopInput([=](double tau) {
        return mooring_dynamics::ros_bridge::linearTopState(tau, tp, xp, yp, zp, t, x, y, z);
      });
    else
      s.setTopInput([=](double tau) {
        return mooring_dynamics::ros_bridge::linearTopInput(tau, tp, xp, zp, t, x, z);
      });
    const core::StepReport r = s.advanceTo(t);
    EXPECT_TRUE(r.ok) << r.message;
    out.push_back(s.snapshot().nodes.back().tension);
    tp = t;
    xp = x;
    yp = y;
    zp = z;
  }
  return out;
}

std::vector<double> offlineTopTension(const std::vector<Sample>& tr) {
  const core::Problem p = problem();
  return p.formulation == core::Formulation::ThreeD ? offlineTopTension<core::DynamicSolver3D>(p, tr)
                                                    : offlineTopTension<core::DynamicSolver2D>(p, tr);
}

/// The same track as a problem-file position_table through core::runDynamic (cable_sim dynamic).
std::vector<double> positionTableTopTension(const std::vector<Sample>& tr) {
  core::Problem p = problem();
  p.dynamics.dt = kDt;
  p.dynamics.output_interval = 0.0;
  p.dynamics.duration = (tr.back().stamp - tr.front().stamp).toSec();
  p.dynamics.top_motion = core::TopMotion();
  p.dynamics.top_motion.type = core::TopMotion::Type::PositionTable;
  p.dynamics.top_motion.prescribe_position = true;
  for (const Sample& s : tr) {
    p.dynamics.top_motion.table.push_back({(s.stamp - tr[0].stamp).toSec(), s.x, s.y, s.z});
  }
  return p.formulation == core::Formulation::ThreeD ? core::runDynamic3D(p).top_tension : core::runDynamic(p).top_tension;
}

geometry_msgs::PoseStamped toPose(const Sample& s) {
  geometry_msgs::PoseStamped m;
  m.header.stamp = s.stamp;
  m.header.frame_id = "world";
  m.pose.position.x = s.x;
  m.pose.position.y = s.y;
  m.pose.position.z = s.z;
  m.pose.orientation.w = 1.0;
  return m;
}

}  // namespace

TEST(Determinism, NodeMatchesCoreOffline) {
  const std::vector<Sample> tr = track();
  ros::NodeHandle nh;
  std::map<uint64_t, double> got;
  ros::Subscriber sub = nh.subscribe<CableState>(g_node + "/cable_state", 1000, [&](const CableState::ConstPtr& m) {
    got[m->header.stamp.toNSec()] = m->tension.back();
  });
  const ros::WallTime connect_end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (sub.getNumPublishers() == 0 && ros::WallTime::now() < connect_end) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_GT(sub.getNumPublishers(), 0) << "no connection to " << g_node;

  auto waitAll = [&](double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end && got.size() < tr.size()) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
  };

  if (g_mode == "live") {
    ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/top_pose", 100);
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
    while (pub.getNumSubscribers() == 0 && ros::WallTime::now() < end) ros::WallDuration(0.05).sleep();
    ASSERT_GT(pub.getNumSubscribers(), 0);
    for (const Sample& s : tr) {
      pub.publish(toPose(s));
      ros::WallDuration(0.02).sleep();  // about 50 Hz: faster than real time, slower than the solver
      ros::spinOnce();
    }
  } else {
    // Write the bag, then play it with --clock (the node runs on sim time).
    char path[] = "/tmp/md_determinism_XXXXXX";
    const int fd = mkstemp(path);
    ASSERT_GE(fd, 0);
    close(fd);
    const std::string bag_file = std::string(path) + ".bag";
    std::remove(path);
    {
      rosbag::Bag bag(bag_file, rosbag::bagmode::Write);
      for (const Sample& s : tr) bag.write(g_node + "/top_pose", s.stamp, toPose(s));
    }
    const std::string cmd = "rosbag play --clock -q --wait-for-subscribers -r 5 " + bag_file + " >/dev/null 2>&1";
    const int rc = std::system(cmd.c_str());
    ASSERT_EQ(rc, 0) << cmd;
    std::remove(bag_file.c_str());
  }
  waitAll(30.0);
  ASSERT_EQ(got.size(), tr.size()) << "the node did not answer every sample (" << g_mode << ")";

  const std::vector<double> ref = offlineTopTension(tr);
  ASSERT_EQ(ref.size(), tr.size());
  double worst = 0.0;
  std::size_t k = 0;
  for (const Sample& s : tr) {
    const double node = got[s.stamp.toNSec()];
    const double rel = std::abs(node - ref[k]) / std::abs(ref[k]);
    worst = std::max(worst, rel);
    EXPECT_LE(rel, kDeterminism) << "sample " << k << ": node " << node << " N, core " << ref[k] << " N";
    ++k;
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));

  // The same track as a problem-file position_table through core::runDynamic (cable_sim
  // dynamic): followed row by row on the same segments, it gives the node's series.
  const std::vector<double> tab = positionTableTopTension(tr);
  ASSERT_EQ(tab.size(), ref.size());
  double worst_tab = 0.0;
  for (std::size_t i = 0; i < std::min(tab.size(), ref.size()); ++i) {
    worst_tab = std::max(worst_tab, std::abs(tab[i] - ref[i]) / std::abs(ref[i]));
    EXPECT_LE(std::abs(tab[i] - ref[i]) / std::abs(ref[i]), kDeterminism) << "position_table, sample " << i;
  }
  RecordProperty("position_table_worst_relative_difference", std::to_string(worst_tab));
  std::printf("worst relative difference node vs core: %.3g; position_table run vs core: %.3g\n", worst, worst_tab);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_determinism");
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("mode", g_mode, g_mode);
  pnh.param<std::string>("node", g_node, g_node);
  pnh.param<std::string>("problem_file", g_problem_file, g_problem_file);
  pnh.param("sway", g_sway, g_sway);
  return RUN_ALL_TESTS();
}
