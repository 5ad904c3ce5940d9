// Fixed points on tf: a line's anchor, a system's anchors and fixed points, as frames on
// /tf_static (latched, once at start), oriented as the world frame.
//
// rviz needs its fixed frame (~frame_id, "world" by default) on tf; a node that publishes no
// transform leaves rviz at "Global Status: Warn (Fixed Frame [world] does not exist)". The anchors
// are the natural frames to put there: they do not move, and a user can attach sensors or
// visuals to them. Parameter ~publish_anchor_frames (default true), names `<~frame_prefix>anchor`
// (one line) or `<~frame_prefix><point>` (a system's anchor and fixed points); the prefix
// defaults to the node's name + "/". The moored vessel's node puts its anchors on tf itself
// (~publish_fairlead_frames).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// The anchor of one line (none when its lower end is free: a towed or drifting line).
std::vector<geometry_msgs::TransformStamped> anchorFrames(const core::Problem& problem, const std::string& world_frame,
                                                          const std::string& prefix, const ros::Time& stamp);
/// The anchor and fixed points of a system.
std::vector<geometry_msgs::TransformStamped> anchorFrames(const core::SystemProblem& system,
                                                          const std::string& world_frame, const std::string& prefix,
                                                          const ros::Time& stamp);

/// Reads ~publish_anchor_frames, ~frame_id and ~frame_prefix and, when enabled, sends `frames`
/// (made by `make(world_frame, prefix)`) on /tf_static. Keep the returned broadcaster alive
/// (a latched publisher).
template <class Make>
std::unique_ptr<tf2_ros::StaticTransformBroadcaster> publishAnchorFrames(const ros::NodeHandle& pnh, const Make& make) {
  bool enabled = true;
  pnh.param("publish_anchor_frames", enabled, true);
  if (!enabled) return nullptr;
  std::string world, prefix = ros::this_node::getName();
  if (!prefix.empty() && prefix[0] == '/') prefix.erase(0, 1);
  pnh.param<std::string>("frame_id", world, "world");
  pnh.param<std::string>("frame_prefix", prefix, prefix + "/");
  const std::vector<geometry_msgs::TransformStamped> frames = make(world, prefix);
  if (frames.empty()) return nullptr;
  auto broadcaster = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  broadcaster->sendTransform(frames);
  return broadcaster;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
