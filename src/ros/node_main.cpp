// mooring_dynamics_node: static cable solver behind ROS topics and a service.
// Exit status 1 when the problem cannot be loaded (bad file, bad YAML, missing parameter):
// the error is logged with ROS_FATAL and names the key, its value and the constraint.
#include <cstdio>
#include <exception>
#include <memory>

#include <ros/ros.h>

#include "mooring_dynamics/core/problem_io.hpp"
#include "mooring_dynamics/ros/static_node.hpp"

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // log lines appear promptly when stdout is a pipe or file
  ros::init(argc, argv, "mooring_dynamics_node");
  ros::NodeHandle nh, pnh("~");
  std::unique_ptr<mooring_dynamics::ros_bridge::StaticNode> node;
  try {
    node = std::make_unique<mooring_dynamics::ros_bridge::StaticNode>(nh, pnh);
  } catch (const mooring_dynamics::core::ProblemError& e) {
    ROS_FATAL("mooring_dynamics: cannot load the problem: %s", e.what());
    ros::shutdown();
    return 1;
  } catch (const std::exception& e) {
    ROS_FATAL("mooring_dynamics: %s", e.what());
    ros::shutdown();
    return 1;
  }
  node->start();
  ros::spin();
  return 0;
}
