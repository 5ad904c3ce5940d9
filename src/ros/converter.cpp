#include "mooring_dynamics/ros/converter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mooring_dynamics {
namespace ros_bridge {

std::string formatNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

CableState toCableState(const std::vector<core::NodeState>& nodes, const EndForces& forces, bool converged,
                        const std::string& line_name, const std::string& frame_id, const ros::Time& stamp) {
  CableState msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  msg.line_name = line_name;
  const std::size_t n = nodes.size();
  msg.s.reserve(n);
  msg.positions.reserve(n);
  msg.tension.reserve(n);
  msg.shear.reserve(n);
  msg.strain.reserve(n);
  msg.angle.reserve(n);
  double tmin = std::numeric_limits<double>::infinity();
  for (const core::NodeState& ns : nodes) {
    msg.s.push_back(ns.s);
    geometry_msgs::Point p;
    p.x = ns.x;
    p.y = ns.y;  // 0 from the 2-D solver
    p.z = ns.z;
    msg.positions.push_back(p);
    msg.tension.push_back(ns.tension);
    msg.shear.push_back(ns.shear);
    msg.strain.push_back(ns.strain);
    msg.angle.push_back(ns.angle);
    tmin = std::min(tmin, ns.tension);
  }
  msg.top_force.x = forces.top_x;
  msg.top_force.y = forces.top_y;
  msg.top_force.z = forces.top_z;
  msg.anchor_force.x = forces.anchor_x;
  msg.anchor_force.y = forces.anchor_y;
  msg.anchor_force.z = forces.anchor_z;
  msg.min_tension = n ? tmin : 0.0;
  msg.slack = n > 0 && tmin <= 0.0;
  msg.converged = converged;
  return msg;
}

CableState toCableState(const core::StaticResult& result, const std::string& line_name,
                        const std::string& frame_id, const ros::Time& stamp) {
  EndForces f;
  f.top_x = result.top_force_x;
  f.top_y = result.top_force_y;
  f.top_z = result.top_force_z;
  f.anchor_x = result.anchor_force_x;
  f.anchor_y = result.anchor_force_y;
  f.anchor_z = result.anchor_force_z;
  return toCableState(result.nodes, f, result.summary.converged, line_name, frame_id, stamp);
}

void toResponse(const core::StaticResult& result, SolveStatic::Response& res) {
  res.success = result.summary.converged;
  res.message = result.summary.message;
  res.iterations = result.summary.iterations;
  res.top_force.x = result.top_force_x;
  res.top_force.y = result.top_force_y;
  res.top_force.z = result.top_force_z;
  res.anchor_force.x = result.anchor_force_x;
  res.anchor_force.y = result.anchor_force_y;
  res.anchor_force.z = result.anchor_force_z;
  res.positions.clear();
  res.tension.clear();
  res.positions.reserve(result.nodes.size());
  res.tension.reserve(result.nodes.size());
  for (const core::NodeState& ns : result.nodes) {
    geometry_msgs::Point p;
    p.x = ns.x;
    p.y = ns.y;  // 0 from the 2-D solver
    p.z = ns.z;
    res.positions.push_back(p);
    res.tension.push_back(ns.tension);
  }
}

void toFailureResponse(const std::string& message, SolveStatic::Response& res) {
  res = SolveStatic::Response();
  res.success = false;
  res.message = message;
}

namespace {

/// Empty when the 3 components are usable as a top position / force for the model, else the error.
std::string checkVector(const std::string& field, double x, double y, double z, const char* what,
                        core::Formulation model) {
  const double c[3] = {x, y, z};
  const char* axis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(c[i])) return field + "." + axis[i] + " = " + formatNumber(c[i]) + ": must be finite";
  if (model == core::Formulation::TwoD && y != 0.0)
    return field + ".y = " + formatNumber(y) + ": must be 0; the problem is model: 2d, whose static solver works in " +
           "the vertical x-z plane of the frame (x east, z up) through the anchor, so the " + what +
           " must lie in that plane (model: 3d takes any y)";
  return "";
}

}  // namespace

std::string describeTop(const core::TopBoundary& top, core::Formulation model) {
  const bool d3 = model == core::Formulation::ThreeD;
  auto vec = [d3](double x, double y, double z) {
    return d3 ? "(x, y, z) = (" + formatNumber(x) + ", " + formatNumber(y) + ", " + formatNumber(z) + ")"
              : "(x, z) = (" + formatNumber(x) + ", " + formatNumber(z) + ")";
  };
  switch (top.type) {
    case core::TopBoundary::Type::Position:
      return "top position " + vec(top.x, top.y, top.z) + " m";
    case core::TopBoundary::Type::Force:
      return "top force " + vec(top.fx, top.fy, top.fz) + " N";
    case core::TopBoundary::Type::Buoy:
      return "surface buoy at the top (diameter " + formatNumber(top.buoy.diameter) + " m)";
    case core::TopBoundary::Type::Body:
      return "subsurface buoy at the top (body index " + std::to_string(top.body) + ")";
  }
  return "unknown top boundary";
}

TopBoundaryRequest topBoundaryFromRequest(const SolveStatic::Request& req, const core::TopBoundary& problem_top,
                                          core::Formulation model) {
  TopBoundaryRequest out;
  const bool d3 = model == core::Formulation::ThreeD;
  switch (req.mode) {
    case SolveStatic::Request::TOP_POSITION: {
      const auto& p = req.top_position;
      out.error = checkVector("top_position", p.x, p.y, p.z, "top position", model);
      if (!out.error.empty()) return out;
      out.top = problem_top;  // keeps e.g. buoy data; only type and position matter here
      out.top.type = core::TopBoundary::Type::Position;
      out.top.x = p.x;
      out.top.y = d3 ? p.y : 0.0;
      out.top.z = p.z;
      break;
    }
    case SolveStatic::Request::TOP_FORCE: {
      const auto& f = req.top_force;
      out.error = checkVector("top_force", f.x, f.y, f.z, "top force", model);
      if (!out.error.empty()) return out;
      out.top = problem_top;
      out.top.type = core::TopBoundary::Type::Force;
      out.top.fx = f.x;
      out.top.fy = d3 ? f.y : 0.0;
      out.top.fz = f.z;
      break;
    }
    case SolveStatic::Request::PROBLEM_DEFAULT:
      out.top = problem_top;
      break;
    default:
      out.error = "mode = " + std::to_string(static_cast<int>(req.mode)) +
                  ": must be 0 (TOP_POSITION), 1 (TOP_FORCE) or 2 (PROBLEM_DEFAULT)";
      return out;
  }
  out.ok = true;
  out.summary = describeTop(out.top, model);
  return out;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
