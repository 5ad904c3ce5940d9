// A storm played in ROS without a simulator (test/ros/test_sea_state_vessel.test): sea_state_vessel
// publishes the hull's motion from config/spread_mooring_storm.yaml (RAOs, slow drift, wave drift)
// and the lockstep node answers each sample with the lines' wrench. Checks, against the core run
// in this process on the same file (VesselMotionSource driving VesselLockstep, as cable_sim
// dynamic does), independent of ROS timing:
//  * lockstep: all 41 samples of the 4 s are played (the player waits for the wrench of each
//    before the next), and every wrench seen answers a sample's stamp;
//  * the poses and the wrenches are the core's, sample by sample.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/core/solvers/vessel_motion_source.hpp"

namespace core = mooring_dynamics::core;

namespace {
/// Samples in the 4 s played at dt 0.1 s: 0 .. 40.
constexpr std::size_t kSamples = 41;
/// [m] The node's poses against the core's: the wrench goes to the message in body axes and back
/// to the world (two rotations, ~1e-16 relative) before it moves the slow drift, and the stamps
/// carry the times in nanoseconds; over 4 s of slow motion that is far below a micrometre.
constexpr double kPoseTol = 1e-6;
/// Relative: the node's wrench against the core's at those poses.
constexpr double kWrenchRelTol = 1e-6;
/// The first wrenches may go out before this test's subscription is connected.
constexpr std::size_t kMissedWrenches = 10;
}  // namespace

TEST(SeaStateVessel, PlaysTheFilesStormInLockstep) {
  ros::NodeHandle nh;
  std::map<uint64_t, nav_msgs::Odometry> odom;
  std::map<uint64_t, geometry_msgs::WrenchStamped> wrenches;
  ros::Subscriber a = nh.subscribe<nav_msgs::Odometry>("/sea_state_vessel/vessel_odom", 1000,
                                                       [&](const nav_msgs::Odometry::ConstPtr& m) {
                                                         odom[m->header.stamp.toNSec()] = *m;
                                                       });
  ros::Subscriber b = nh.subscribe<geometry_msgs::WrenchStamped>(
      "/mooring_dynamics_node/wrench", 1000,
      [&](const geometry_msgs::WrenchStamped::ConstPtr& m) { wrenches[m->header.stamp.toNSec()] = *m; });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(90.0);
  while (ros::ok() && ros::WallTime::now() < end && (odom.size() < kSamples || !wrenches.count(odom.rbegin()->first))) {
    ros::spinOnce();
    ros::WallDuration(0.005).sleep();
  }
  // The player starts once this test listens to the poses; the node's first wrenches may go out
  // before this test's subscription to them is connected: those are not seen here.
  ASSERT_EQ(odom.size(), kSamples) << "the 4 s storm was not played";
  ASSERT_GE(wrenches.size(), kSamples - kMissedWrenches) << "too few wrenches seen";

  // The same run in this process.
  const core::SystemProblem s = core::loadSystemFromFile(std::string(MD_SOURCE_DIR) + "/config/spread_mooring_storm.yaml");
  core::VesselMotionSource src(s);
  core::VesselLockstep lock(s, s.dynamics);
  for (const auto& kv : wrenches) ASSERT_TRUE(odom.count(kv.first)) << "a wrench answers no sample's stamp";
  auto o = odom.begin();
  std::size_t compared = 0;
  for (std::size_t k = 0; k < kSamples; ++k, ++o) {
    const core::PoseSample p = src.sample(static_cast<double>(k) * s.dynamics.dt);
    const auto r = lock.onSample(p.t, p.pose, &p.twist);
    ASSERT_TRUE(r.outcome == core::VesselLockstep::Outcome::Started || r.outcome == core::VesselLockstep::Outcome::Advanced)
        << r.message;
    const core::VesselWrench cw = lock.wrench();
    src.advance(s.dynamics.dt, cw);
    const auto& pp = o->second.pose.pose.position;
    EXPECT_NEAR(pp.x, p.pose.position.x(), kPoseTol) << "sample " << k;
    EXPECT_NEAR(pp.y, p.pose.position.y(), kPoseTol) << "sample " << k;
    EXPECT_NEAR(pp.z, p.pose.position.z(), kPoseTol) << "sample " << k;
    const auto w = wrenches.find(o->first);
    if (w == wrenches.end()) continue;
    const Eigen::Vector3d f(w->second.wrench.force.x, w->second.wrench.force.y, w->second.wrench.force.z);
    EXPECT_LE((f - cw.force_body).norm(), kWrenchRelTol * cw.force_body.norm()) << "sample " << k;
    ++compared;
  }
  EXPECT_GE(compared, kSamples - kMissedWrenches);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_sea_state_vessel");
  return RUN_ALL_TESTS();
}
