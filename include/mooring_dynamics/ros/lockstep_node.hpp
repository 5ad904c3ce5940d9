// ROS node state for the lockstep dynamic mode (~mode: dynamic): the top end follows a stamped
// motion source and the solver advances to every stamp (LockstepDriver, lockstep.hpp, holds the
// policy; this class only wires topics, tf and logs).
//
// Parameters (private namespace), besides ~problem_file / ~problem_yaml / ~frame_id / ~marker_scale:
//   ~motion_source  string  "pose" (subscribe ~top_pose, geometry_msgs/PoseStamped, default) or
//                           "odometry" (subscribe ~top_odom, nav_msgs/Odometry)
//   ~dt             double  base time step [s]; default: the problem's dynamics.dt (0.1 without a
//                           dynamics section)
//   ~vessel_frame   string  frame of ~top_wrench, default ~frame_id (rotated with tf2 otherwise)
//   ~start_tolerance double first sample farther than this from the static top [m] re-solves
//                           statics there, default 0.5
// Publications: ~cable_state (CableState, stamp = motion stamp), ~top_wrench
//   (geometry_msgs/WrenchStamped: force of the line on the vessel at the fairlead), ~markers (only
//   when subscribed). Full description: docs/ros_interface.md.
#pragma once

#include <memory>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/ros/lockstep.hpp"
#include "mooring_dynamics/ros/markers.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class LockstepNode {
 public:
  /// Reads parameters, loads the problem, solves its statics (the start of the dynamic run),
  /// advertises and subscribes. Throws core::ProblemError (bad problem), std::runtime_error (bad
  /// parameters, or the problem's statics fail) or std::invalid_argument (invalid problem).
  LockstepNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Handles one top position sample (public for tests). `field` names the message field of the
  /// position for warnings ("pose.position", "pose.pose.position").
  void onMotion(const ros::Time& stamp, const std::string& frame, double x, double y, double z,
                const std::string& field);

  const LockstepDriver& driver() const { return *driver_; }

 private:
  void onPose(const geometry_msgs::PoseStamped::ConstPtr& msg);
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void publish(const ros::Time& stamp);

  ros::NodeHandle nh_, pnh_;
  core::Problem problem_;
  std::string source_;
  std::string frame_id_ = "world", vessel_frame_;
  std::string motion_source_ = "pose";
  MarkerOptions marker_options_;
  std::unique_ptr<LockstepDriver> driver_;
  ros::Publisher state_pub_, marker_pub_, wrench_pub_;
  ros::Subscriber motion_sub_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  bool have_epoch_ = false;
  ros::Time epoch_;               ///< first stamp received: driver times are seconds after it
  bool warned_y_ = false, warned_frame_ = false;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
