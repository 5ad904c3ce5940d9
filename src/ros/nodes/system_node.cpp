#include "mooring_dynamics/ros/nodes/system_node.hpp"

#include <algorithm>
#include <stdexcept>

#include <geometry_msgs/WrenchStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

bool paramsNameSystemFile(const ros::NodeHandle& pnh) {
  std::string file;
  return pnh.getParam("problem_file", file) && !file.empty() && core::isSystemFile(file);
}

SystemStaticNode::SystemStaticNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {
  std::string file;
  if (!pnh_.getParam("problem_file", file) || file.empty())
    throw std::runtime_error("parameter " + pnh_.resolveName("problem_file") + ": a system file is needed");
  system_ = core::loadSystemFromFile(file);  // throws core::ProblemError naming the key
  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  pnh_.param("marker_scale", marker_scale_, 1.0);
  if (!(marker_scale_ > 0.0))
    throw std::runtime_error("parameter " + pnh_.resolveName("marker_scale") + " = " + formatNumber(marker_scale_) +
                             ": must be > 0");
  for (const auto& l : system_.lines)
    line_pubs_.push_back(pnh_.advertise<CableState>("lines/" + l.name + "/cable_state", 1, /*latch=*/true));
  for (const auto& p : system_.points)
    point_pubs_.push_back(pnh_.advertise<geometry_msgs::WrenchStamped>("points/" + p.name + "/wrench", 1, true));
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  solve_srv_ = pnh_.advertiseService("solve_static", &SystemStaticNode::onSolveStatic, this);
  ROS_INFO("mooring_dynamics: system '%s' from %s: %zu lines, %zu points", system_.name.c_str(), file.c_str(),
           system_.lines.size(), system_.points.size());
}

bool SystemStaticNode::start() {
  core::SystemStaticResult r;
  try {
    r = core::solveSystemStatic(system_);
  } catch (const std::exception& e) {
    ROS_ERROR("mooring_dynamics: system statics: %s", e.what());
    return false;
  }
  if (!r.summary.converged) {
    ROS_ERROR("mooring_dynamics: system statics did not converge: %s (nothing published)", r.summary.message.c_str());
    return false;
  }
  const ros::Time stamp = ros::Time::now();
  // One tension colour scale for all lines (drawn once, with the first line).
  double tmin = 1e300, tmax = -1e300;
  for (const auto& l : r.lines)
    for (const auto& n : l.nodes) {
      tmin = std::min(tmin, n.tension);
      tmax = std::max(tmax, n.tension);
    }
  visualization_msgs::MarkerArray all;
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    const std::string& name = system_.lines[i].name;
    const CableState state = toCableState(r.lines[i], name, frame_id_, stamp);
    line_pubs_[i].publish(state);
    // The line's own markers, in a namespace of its own so that the ids of the lines do not clash.
    core::Problem p = system_.lineProblem(i, std::vector<double>(3 * system_.points.size(), 0.0));
    MarkerOptions mo = markerOptionsFor(p, marker_scale_);
    mo.tension_min = tmin;
    mo.tension_max = tmax;
    mo.label_name = name;  // legs that meet at one point stack their labels there
    mo.label_row = static_cast<int>(i);
    visualization_msgs::MarkerArray m = makeMarkers(state, system_.environment, mo);
    for (auto& mk : m.markers) {
      if (i > 0 && mk.ns == "scale") continue;
      mk.ns = name + "/" + mk.ns;
      all.markers.push_back(mk);
    }
  }
  marker_pub_.publish(all);
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    geometry_msgs::WrenchStamped w;
    w.header.stamp = stamp;
    w.header.frame_id = frame_id_;
    w.wrench.force.x = r.points[k].fx;
    w.wrench.force.y = r.points[k].fy;
    w.wrench.force.z = r.points[k].fz;
    point_pubs_[k].publish(w);
  }
  ROS_INFO("mooring_dynamics: system statics: %s", r.summary.message.c_str());
  return true;
}

bool SystemStaticNode::onSolveStatic(SystemStatics::Request& req, SystemStatics::Response& res) {
  try {
    toSystemStaticsResponse(system_, core::solveSystemStatic(system_), res);
  } catch (const std::exception& e) {
    res = SystemStatics::Response();
    res.success = false;
    res.message = std::string("system statics: ") + e.what();
  }
  if (req.reinitialise) res.message += " (reinitialise ignored: static mode)";
  ROS_INFO("mooring_dynamics: ~solve_static: %s", res.message.c_str());
  return true;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
