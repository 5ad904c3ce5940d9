#include "mooring_dynamics/ros/nodes/static_node.hpp"

#include <cmath>
#include <stdexcept>

#include <visualization_msgs/MarkerArray.h>
#include <yaml-cpp/yaml.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

/// A parameter map (as loaded by <rosparam>) -> YAML node, so the core parser sees the same
/// document as from a file. Key order follows the parameter server (alphabetical).
YAML::Node toYaml(XmlRpc::XmlRpcValue& v, const std::string& path) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(static_cast<bool>(v));
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeDouble: return YAML::Node(static_cast<double>(v));
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(static_cast<std::string>(v));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node n(YAML::NodeType::Sequence);
      for (int i = 0; i < v.size(); ++i) n.push_back(toYaml(v[i], path + "[" + std::to_string(i) + "]"));
      return n;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node n(YAML::NodeType::Map);
      for (auto& kv : v) n[kv.first] = toYaml(kv.second, path + "/" + kv.first);
      return n;
    }
    default:
      throw std::runtime_error("parameter " + path + ": unsupported value type (dates and binary data are not "
                               "part of the problem format)");
  }
}

std::string nonEmptyString(const ros::NodeHandle& pnh, const std::string& name) {
  if (!pnh.hasParam(name)) return "";
  XmlRpc::XmlRpcValue v;
  pnh.getParam(name, v);
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString)
    throw std::runtime_error("parameter " + pnh.resolveName(name) + ": must be a string");
  return static_cast<std::string>(v);
}

}  // namespace

core::Problem loadProblemFromParams(const ros::NodeHandle& pnh, std::string& source) {
  const std::string file = nonEmptyString(pnh, "problem_file");
  const bool has_yaml = pnh.hasParam("problem_yaml");
  const std::string file_param = pnh.resolveName("problem_file");
  const std::string yaml_param = pnh.resolveName("problem_yaml");
  if (!file.empty() && has_yaml)
    throw std::runtime_error("both " + file_param + " and " + yaml_param + " are set: set exactly one");
  if (!file.empty()) {
    source = "file " + file;
    return core::loadProblemFromFile(file);
  }
  if (!has_yaml)
    throw std::runtime_error("no problem given: set " + file_param + " (path of a YAML problem file) or " +
                             yaml_param + " (the problem as YAML text or as a parameter map)");
  XmlRpc::XmlRpcValue v;
  pnh.getParam("problem_yaml", v);
  source = "parameter " + yaml_param;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) return core::loadProblemFromString(static_cast<std::string>(v));
  if (v.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    YAML::Emitter e;
    e.SetDoublePrecision(17);
    e << toYaml(v, yaml_param);
    try {
      return core::loadProblemFromString(e.c_str());
    } catch (const core::ProblemError& err) {
      throw core::ProblemError(yaml_param + " (parameter map; line numbers refer to its YAML rendering): " +
                               err.what());
    }
  }
  throw std::runtime_error("parameter " + yaml_param + ": must be a string with YAML text or a map");
}

SolveOutcome solveSafely(const core::Problem& problem) {
  SolveOutcome out;
  try {
    out.result = core::solveStaticModel(problem);
    out.solver_ran = true;
  } catch (const std::invalid_argument& e) {
    out.message = std::string("invalid problem: ") + e.what();
    return out;
  } catch (const std::exception& e) {
    out.message = std::string("solver error: ") + e.what();
    return out;
  }
  const core::StaticResult& r = out.result;
  if (!r.summary.converged) {
    out.message = "static solver failed: " + r.summary.message;
    return out;
  }
  if (r.nodes.empty()) {
    out.message = "static solver returned no nodes";
    return out;
  }
  for (const auto& ns : r.nodes) {
    if (!(std::isfinite(ns.x) && std::isfinite(ns.y) && std::isfinite(ns.z) && std::isfinite(ns.tension))) {
      out.message = "static solver returned a non-finite value at s = " + formatNumber(ns.s) + " m";
      return out;
    }
  }
  double tmin = r.nodes.front().tension;
  for (const auto& ns : r.nodes) tmin = std::min(tmin, ns.tension);
  out.ok = true;
  const std::string force = problem.formulation == core::Formulation::ThreeD
                                ? "(x, y, z) = (" + formatNumber(r.top_force_x) + ", " + formatNumber(r.top_force_y) +
                                      ", " + formatNumber(r.top_force_z) + ")"
                                : "(x, z) = (" + formatNumber(r.top_force_x) + ", " + formatNumber(r.top_force_z) + ")";
  out.message = r.summary.message + "; top tension " + formatNumber(r.topTension() / 1000.0) + " kN, top force " +
                force + " N, min tension " + formatNumber(tmin) + " N" + (tmin <= 0.0 ? " (slack)" : "");
  return out;
}

StaticNode::StaticNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {
  problem_ = loadProblemFromParams(pnh_, source_);
  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  pnh_.param("marker_scale", marker_options_.scale, 1.0);
  if (!(std::isfinite(marker_options_.scale) && marker_options_.scale > 0.0))
    throw std::runtime_error("parameter " + pnh_.resolveName("marker_scale") + " = " +
                             formatNumber(marker_options_.scale) + ": must be > 0");
  marker_options_ = markerOptionsFor(problem_, marker_options_.scale);

  state_pub_ = pnh_.advertise<CableState>("cable_state", 1, /*latch=*/true);
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  solve_srv_ = pnh_.advertiseService("solve_static", &StaticNode::onSolveStatic, this);
  ROS_INFO("mooring_dynamics: loaded \"%s\" from %s: %zu segment(s), %.2f m of line, %s; frame %s",
           problem_.name.c_str(), source_.c_str(), problem_.segments.size(), problem_.totalLength(),
           describeTop(problem_.top, problem_.formulation).c_str(), frame_id_.c_str());
}

bool StaticNode::start() {
  const ros::WallTime t0 = ros::WallTime::now();
  SolveOutcome o = solveSafely(problem_);
  const double ms = (ros::WallTime::now() - t0).toSec() * 1000.0;
  if (!o.ok) {
    ROS_ERROR("mooring_dynamics: the problem's own static case (%s) failed after %.0f ms: %s. Nothing is "
              "published until a ~solve_static request succeeds.",
              describeTop(problem_.top, problem_.formulation).c_str(), ms, o.message.c_str());
    return false;
  }
  ROS_INFO("mooring_dynamics: static case (%s), %zu nodes, %.0f ms: %s", describeTop(problem_.top, problem_.formulation).c_str(),
           o.result.nodes.size(), ms, o.message.c_str());
  publish(o.result);
  last_ = std::move(o.result);
  return true;
}

bool StaticNode::onSolveStatic(SolveStatic::Request& req, SolveStatic::Response& res) {
  const TopBoundaryRequest top = topBoundaryFromRequest(req, problem_.top, problem_.formulation);
  if (!top.ok) {
    toFailureResponse("invalid request: " + top.error, res);
    ROS_WARN("mooring_dynamics: ~solve_static rejected: %s", res.message.c_str());
    return true;
  }
  core::Problem p = problem_;
  p.top = top.top;
  const ros::WallTime t0 = ros::WallTime::now();
  SolveOutcome o = solveSafely(p);
  const double ms = (ros::WallTime::now() - t0).toSec() * 1000.0;
  if (!o.ok) {
    toFailureResponse(top.summary + ": " + o.message, res);
    if (o.solver_ran) res.iterations = o.result.summary.iterations;
    ROS_WARN("mooring_dynamics: ~solve_static failed after %.0f ms (last good state kept): %s", ms,
             res.message.c_str());
    return true;
  }
  toResponse(o.result, res);
  res.message = top.summary + ": " + o.message;
  if (req.reinitialise) res.message += " (reinitialise ignored: static mode has no dynamic run)";
  ROS_INFO("mooring_dynamics: ~solve_static, %.0f ms: %s", ms, res.message.c_str());
  publish(o.result);
  last_ = std::move(o.result);
  return true;
}

void StaticNode::publish(const core::StaticResult& result) {
  const CableState state = toCableState(result, problem_.name, frame_id_, ros::Time::now());
  state_pub_.publish(state);
  marker_pub_.publish(makeMarkers(state, problem_.environment, marker_options_));
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
