// mooring_dynamics_node: cable solver behind ROS topics and a service.
//   ~mode static  (default): static solves (StaticNode, ~solve_static)
//   ~mode dynamic: lockstep time-domain run driven by a stamped top motion (LockstepNode)
// Exit status 1 when the problem cannot be loaded (bad file, bad YAML, missing parameter) or a
// parameter is invalid: the error is logged with ROS_FATAL and names the key, its value and the
// constraint.
#include <cstdio>

#include <ros/ros.h>

#include "mooring_dynamics/ros/nodes/run_node.hpp"

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // log lines appear promptly when stdout is a pipe or file
  ros::init(argc, argv, "mooring_dynamics_node");
  ros::NodeHandle nh, pnh("~");
  return mooring_dynamics::ros_bridge::runNode(nh, pnh);
}
