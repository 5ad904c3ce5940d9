// ROS node state for the lockstep dynamic mode (~mode: dynamic): the top end follows a stamped
// motion source and the solver advances to every stamp. LockstepDriver (lockstep.hpp) holds the
// policy and LockstepMonitor (lockstep_monitor.hpp) the health summary; this class only wires
// topics, tf, services, diagnostics and logs.
//
// Parameters (private namespace), besides ~problem_file / ~problem_yaml / ~frame_id / ~marker_scale
// (full table with units and defaults: docs/ros_interface.md):
//   ~motion_source     "pose" (~top_pose, PoseStamped), "odometry" (~top_odom, Odometry) or "tf"
//                      (poll the transform ~frame_id <- ~tf_source_frame at ~tf_poll_rate)
//   ~dt, ~start_tolerance, ~loop_back, ~max_gap, ~max_speed      lockstep policy (LockstepOptions)
//   ~vessel_frame      frame of ~top_wrench (rotated with tf2), default ~frame_id
//   ~tf_timeout        [s] wait for a transform of an input in another frame
//   ~motion_timeout, ~diagnostics_period, ~min_real_time_factor, ~republish_when_silent
//   ~tension_range     [min, max] N colour range of the markers (default: each state's own)
//   ~publish_body_frames, ~instrument_s, ~body_frame_prefix      tf frames on the line
// Publications: ~cable_state, ~top_wrench, ~markers (only when subscribed), /diagnostics, /tf
// (body frames, optional). Services: ~reset (std_srvs/Trigger), ~solve_static (SolveStatic),
// ~release (ReleaseLine, model: 3d).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "mooring_dynamics/ReleaseLine.h"
#include "mooring_dynamics/Winch.h"
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/ros/nodes/gnss_input.hpp"
#include "mooring_dynamics/ros/nodes/lockstep.hpp"
#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class LockstepNode {
 public:
  /// Reads parameters, loads the problem, solves its statics (the start of the dynamic run),
  /// advertises and subscribes. Throws core::ProblemError (bad problem), std::runtime_error (bad
  /// parameters, or the problem's statics fail) or std::invalid_argument (invalid problem).
  LockstepNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Handles one top position sample (public for tests). `frame` is the sample's frame (empty:
  /// ~frame_id); `field` names the message field of the position for warnings.
  void onMotion(const ros::Time& stamp, const std::string& frame, double x, double y, double z,
                const std::string& field);

  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSolveStatic(SolveStatic::Request& req, SolveStatic::Response& res);
  /// ~release: let go an end of the line (ReleaseLine; `line` empty or the problem's name).
  bool onRelease(ReleaseLine::Request& req, ReleaseLine::Response& res);
  /// ~winch: command the winch at the top (Winch; model: 3d).
  bool onWinch(Winch::Request& req, Winch::Response& res);

  const LockstepDriver& driver() const { return *driver_; }
  const core::Problem& problem() const { return problem_; }

 private:
  void onPose(const geometry_msgs::PoseStamped::ConstPtr& msg);
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void pollTf(const ros::WallTimerEvent&);
  void onDiagnosticsTimer(const ros::WallTimerEvent&);
  void reject(const std::string& message, const char* key);
  void checkOrientation(const geometry_msgs::Quaternion& q, const std::string& field);
  void handle(const LockstepDriver::Result& r, const ros::Time& stamp, double wall_spent);
  void publish(const ros::Time& stamp);
  void publishMarkersAndFrames();
  double wallNow() const;

  ros::NodeHandle nh_, pnh_;
  core::Problem problem_;
  std::string source_;
  std::string frame_id_ = "world", vessel_frame_;
  std::string motion_source_ = "pose", tf_source_frame_;
  double tf_timeout_ = 0.1;
  bool republish_when_silent_ = true;
  bool publish_body_frames_ = false;
  std::string body_frame_prefix_;
  std::vector<BodyMark> frame_marks_;  ///< bodies and instruments published as tf frames
  MarkerOptions marker_options_;
  std::unique_ptr<LockstepDriver> driver_;
  std::unique_ptr<LockstepMonitor> monitor_;
  std::unique_ptr<GnssInput> gnss_;  ///< ~motion_source gnss
  ros::Publisher state_pub_, marker_pub_, wrench_pub_, diag_pub_;
  ros::Subscriber motion_sub_;
  ros::ServiceServer reset_srv_, solve_srv_, release_srv_, winch_srv_;
  ros::WallTimer tf_timer_, diag_timer_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  ros::WallTime wall0_;
  bool have_epoch_ = false;
  ros::Time epoch_;               ///< first stamp received: driver times are seconds after it
  ros::Time last_tf_stamp_;       ///< tf source: stamp of the last transform used
  bool have_output_ = false;
  ros::Time last_stamp_;          ///< stamp of the last published state
  CableState last_state_;
  geometry_msgs::WrenchStamped last_wrench_;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
