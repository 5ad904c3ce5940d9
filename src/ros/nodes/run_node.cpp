// src/ros/nodes: the product's node kinds and what they need around them. runNode (this file)
// reads ~mode and the problem file and builds one of: StaticNode (static_node.cpp), LockstepNode
// (lockstep_node.cpp, a single line following a motion source; the lockstep rules in
// lockstep.cpp), VesselNode (vessel_node.cpp, a moored vessel on many lines), SystemStaticNode
// (system_node.cpp) and SystemDynamicNode (system_dynamic_node.cpp, stepping on ROS time). Beside
// them: their parameters (params.cpp), GNSS input (gnss_input.cpp) and their diagnostics
// (lockstep_monitor.cpp, vessel_monitor.cpp; ROS-free). Messages and markers are made in
// src/ros/publish; simulators and drivers live in src/ros/tools.
#include "mooring_dynamics/ros/nodes/run_node.hpp"

#include <exception>
#include <memory>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/publish/anchor_frames.hpp"
#include "mooring_dynamics/ros/nodes/lockstep_node.hpp"
#include "mooring_dynamics/ros/nodes/static_node.hpp"
#include "mooring_dynamics/ros/nodes/system_dynamic_node.hpp"
#include "mooring_dynamics/ros/nodes/system_node.hpp"
#include "mooring_dynamics/ros/nodes/vessel_node.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

int runNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  std::string mode;
  pnh.param<std::string>("mode", mode, "static");
  std::unique_ptr<StaticNode> static_node;
  std::unique_ptr<LockstepNode> lockstep_node;
  std::unique_ptr<SystemStaticNode> system_node;
  std::unique_ptr<VesselNode> vessel_node;
  std::unique_ptr<SystemDynamicNode> system_dynamic_node;
  try {
    if (paramsNameSystemFile(pnh)) {  // several lines joined at points (a moored vessel among them)
      if (mode == "dynamic" && paramsNameVesselFile(pnh)) {
        vessel_node = std::make_unique<VesselNode>(nh, pnh);  // driven by the vessel's poses
      } else if (mode == "dynamic") {
        system_dynamic_node = std::make_unique<SystemDynamicNode>(nh, pnh);  // free points, on ROS time
      } else if (mode != "static") {
        ROS_FATAL("mooring_dynamics: parameter %s = \"%s\": must be \"static\" or \"dynamic\"",
                  pnh.resolveName("mode").c_str(), mode.c_str());
        ros::shutdown();
        return 1;
      } else {
        system_node = std::make_unique<SystemStaticNode>(nh, pnh);
      }
    } else if (mode == "static") {
      static_node = std::make_unique<StaticNode>(nh, pnh);
    } else if (mode == "dynamic") {
      lockstep_node = std::make_unique<LockstepNode>(nh, pnh);
    } else {
      ROS_FATAL("mooring_dynamics: parameter %s = \"%s\": must be \"static\" or \"dynamic\"",
                pnh.resolveName("mode").c_str(), mode.c_str());
      ros::shutdown();
      return 1;
    }
  } catch (const core::ProblemError& e) {
    ROS_FATAL("mooring_dynamics: cannot load the problem: %s", e.what());
    ros::shutdown();
    return 1;
  } catch (const std::exception& e) {
    ROS_FATAL("mooring_dynamics: %s", e.what());
    ros::shutdown();
    return 1;
  }
  // The anchors on /tf_static: fixed frames for users, and ~frame_id on tf for rviz.
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> anchors;
  const ros::Time now = ros::Time::now();
  auto lineAnchors = [&](const core::Problem& p) {
    return [&](const std::string& world, const std::string& prefix) { return anchorFrames(p, world, prefix, now); };
  };
  if (static_node) anchors = publishAnchorFrames(pnh, lineAnchors(static_node->problem()));
  if (lockstep_node) anchors = publishAnchorFrames(pnh, lineAnchors(lockstep_node->problem()));
  if (system_node)
    anchors = publishAnchorFrames(pnh, [&](const std::string& world, const std::string& prefix) {
      return anchorFrames(system_node->system(), world, prefix, now);
    });
  if (system_dynamic_node)
    anchors = publishAnchorFrames(pnh, [&](const std::string& world, const std::string& prefix) {
      return anchorFrames(system_dynamic_node->system(), world, prefix, now);
    });
  if (static_node) static_node->start();
  if (system_node) system_node->start();
  ros::spin();
  return 0;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
