// GNSS motion source of the lockstep nodes (~motion_source gnss): sensor_msgs/NavSatFix on ~fix
// and a heading on ~heading (~heading_type imu: sensor_msgs/Imu, its orientation's yaw;
// quaternion: geometry_msgs/QuaternionStamped), both in ENU (REP 103/105), through
// core::GnssTrack with the problem's dynamics.gnss options (defaults when the section is absent).
// Every accepted fix becomes a pose at the fix's stamp, handed to the node's callback; rejected
// fixes and headings are counted for the diagnostics. The same samples in the same order give the
// same poses as `cable_sim dynamic` on a track CSV.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <geometry_msgs/QuaternionStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>

#include "mooring_dynamics/core/model/gnss.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// A fix message as the core sees it: stamp, position, status, the larger of the east and north
/// variances (NaN when the covariance is unknown).
core::GnssFix toGnssFix(const sensor_msgs::NavSatFix& msg);
/// REP 103 yaw [rad] of an orientation (NaN when the quaternion is not finite or not of unit norm
/// within core::kUnitQuaternionTolerance).
double yawOf(const geometry_msgs::Quaternion& q);

class GnssInput {
 public:
  using PoseCallback = std::function<void(const ros::Time& stamp, const core::RigidPose& pose)>;
  using RejectCallback = std::function<void(const std::string& message)>;
  /// Reads ~heading_type (imu or quaternion; default quaternion) and subscribes ~fix, ~heading.
  /// `on_reject` hears every rejected fix or heading (the node counts and logs it).
  GnssInput(ros::NodeHandle& pnh, const core::GnssOptions& options, const core::RigidPose& start,
            const Eigen::Vector2d& start_velocity, PoseCallback on_pose, RejectCallback on_reject);

  void onFix(const sensor_msgs::NavSatFix& msg);
  void onHeading(const ros::Time& stamp, const geometry_msgs::Quaternion& q);

  /// For the diagnostics: fixes and headings by verdict, heading gaps, the last rejection.
  std::vector<std::pair<std::string, std::string>> values() const;
  long rejected() const;
  const std::string& lastRejection() const { return last_rejection_; }
  std::string topics() const;

 private:
  void note(const core::GnssTrack::Result& r);

  core::GnssTrack track_;
  PoseCallback on_pose_;
  RejectCallback on_reject_;
  ros::Subscriber fix_sub_, heading_sub_;
  std::string last_rejection_;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
