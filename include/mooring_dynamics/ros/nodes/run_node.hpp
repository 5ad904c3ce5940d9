// Entry point of mooring_dynamics_node (kept out of main() so main stays tiny): reads ~mode,
// builds a StaticNode ("static", default) or a LockstepNode ("dynamic"), spins.
#pragma once

#include <ros/ros.h>

namespace mooring_dynamics {
namespace ros_bridge {

/// Runs the node until shutdown. Returns the process exit status: 0 after a normal shutdown, 1
/// when the problem or a parameter is bad (logged with ROS_FATAL; nothing advertised).
int runNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
