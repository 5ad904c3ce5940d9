// ROS node state for a system of lines (core/model/system.hpp: multi-leg and branched moorings),
// static mode: the system's equilibrium on start, published per line and per point.
//
// Parameters (private): ~problem_file (a system file: `points` and `lines`), ~frame_id
// (default "world"), ~marker_scale (default 1.0).
// Publications (latched), all in ~frame_id:
//   ~lines/<line>/cable_state  mooring_dynamics/CableState of each line (line_name = <line>)
//   ~markers                   visualization_msgs/MarkerArray of every line (namespaces <line>/...),
//                              coloured on one tension scale (drawn with the first line)
//   ~points/<point>/wrench     geometry_msgs/WrenchStamped: the lines' pull on each point [N]
//                              (on an anchor or fixed point what it must resist; on a free point
//                              what its buoyancy, drag and wind balance)
// Service: ~solve_static (mooring_dynamics/SystemStatics): the system's statics again (reinitialise
// is ignored in static mode).
// Full description: docs/ros_interface.md ("Systems of lines").
#pragma once

#include <string>
#include <vector>

#include <ros/ros.h>

#include "mooring_dynamics/SystemStatics.h"

#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class SystemStaticNode {
 public:
  /// Loads the system from ~problem_file and advertises the topics. Throws core::ProblemError
  /// (bad file) or std::runtime_error (bad parameters).
  SystemStaticNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  /// Solves and publishes; false (logged) when the system does not converge.
  bool start();
  const core::SystemProblem& system() const { return system_; }
  bool onSolveStatic(SystemStatics::Request& req, SystemStatics::Response& res);

 private:
  ros::NodeHandle nh_, pnh_;
  core::SystemProblem system_;
  std::string frame_id_ = "world";
  double marker_scale_ = 1.0;
  std::vector<ros::Publisher> line_pubs_, point_pubs_;
  ros::Publisher marker_pub_;
  ros::ServiceServer solve_srv_;
};

/// True when ~problem_file names a system file (points and lines).
bool paramsNameSystemFile(const ros::NodeHandle& pnh);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
