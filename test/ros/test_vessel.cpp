// Two-way coupling smoke test (test/ros/test_vessel.test): the vessel's poses and the cable's
// wrenches alternate one for one (every pose stamp gets a wrench with that stamp, and the vessel
// advances only after it), the vessel heaves in the waves, and the wrench pulls it down. (Its x
// component is only -60 N in the statics of this mooring in a current and changes sign as the
// vessel surges, so it is not checked.)
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

TEST(Vessel, PosesAndWrenchesInLockstep) {
  ros::NodeHandle nh;
  std::map<uint64_t, geometry_msgs::PoseStamped> poses;
  std::map<uint64_t, geometry_msgs::WrenchStamped> wrenches;
  ros::Subscriber a = nh.subscribe<geometry_msgs::PoseStamped>(
      "/vessel_sim/fairlead_pose", 1000, [&](const geometry_msgs::PoseStamped::ConstPtr& m) {
        poses[m->header.stamp.toNSec()] = *m;
      });
  ros::Subscriber b = nh.subscribe<geometry_msgs::WrenchStamped>(
      "/mooring_dynamics_node/top_wrench", 1000, [&](const geometry_msgs::WrenchStamped::ConstPtr& m) {
        wrenches[m->header.stamp.toNSec()] = *m;
      });
  constexpr std::size_t kSteps = 60;  // 6 s of vessel time (about 1.2 s of wall time at speed 5)
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(40.0);
  while (ros::ok() && ros::WallTime::now() < end && poses.size() < kSteps) {
    ros::spinOnce();
    ros::WallDuration(0.005).sleep();
  }
  ASSERT_GE(poses.size(), kSteps) << "the vessel did not run";
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();
  // Every pose but the newest has been answered with a wrench of the same stamp.
  std::size_t answered = 0;
  double zmin = 1e9, zmax = -1e9;
  for (const auto& kv : poses) {
    zmin = std::min(zmin, kv.second.pose.position.z);
    zmax = std::max(zmax, kv.second.pose.position.z);
    auto w = wrenches.find(kv.first);
    if (w == wrenches.end()) continue;
    ++answered;
    EXPECT_LT(w->second.wrench.force.z, 0.0) << "the line must pull the vessel down";
  }
  EXPECT_GE(answered + 1, poses.size()) << "poses without a wrench: the coupling is not in lockstep";
  // The 25 kN wave force on a 31.6 kN/m waterplane stiffness heaves the vessel by decimetres.
  EXPECT_GT(zmax - zmin, 0.1) << "the vessel does not move";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_vessel");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
