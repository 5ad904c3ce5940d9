// src/ros/publish: core structs to ROS messages and what the nodes publish besides. converter.cpp
// (this file) is the one place core results become CableState, WrenchStamped and service
// responses, and messages become core inputs; markers.cpp builds the rviz markers;
// anchor_frames.cpp the static tf frames of anchors and fairleads.
#include "mooring_dynamics/ros/publish/converter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

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
  if (!nodes.empty()) msg.line_length = nodes.back().s;
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

// ---------------------------------------------------------------------------------------------
// Moored vessel

namespace {

geometry_msgs::Vector3 vec3(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::WrenchStamped wrenchStamped(const Eigen::Vector3d& f, const Eigen::Vector3d& m, const std::string& frame,
                                           const ros::Time& stamp) {
  geometry_msgs::WrenchStamped w;
  w.header.stamp = stamp;
  w.header.frame_id = frame;
  w.wrench.force = vec3(f);
  w.wrench.torque = vec3(m);
  return w;
}

geometry_msgs::Wrench wrench(const Eigen::Vector3d& f, const Eigen::Vector3d& m) {
  geometry_msgs::Wrench w;
  w.force = vec3(f);
  w.torque = vec3(m);
  return w;
}

}  // namespace

core::RigidPose toRigidPose(const geometry_msgs::Pose& pose) {
  core::RigidPose p;
  p.position = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  p.orientation = Eigen::Quaterniond(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  return p;
}

geometry_msgs::Pose toPoseMsg(const core::RigidPose& pose) {
  geometry_msgs::Pose m;
  m.position.x = pose.position.x();
  m.position.y = pose.position.y();
  m.position.z = pose.position.z();
  m.orientation.x = pose.orientation.x();
  m.orientation.y = pose.orientation.y();
  m.orientation.z = pose.orientation.z();
  m.orientation.w = pose.orientation.w();
  return m;
}

geometry_msgs::WrenchStamped toBodyWrench(const core::VesselWrench& w, const std::string& body_frame,
                                          const ros::Time& stamp) {
  return wrenchStamped(w.force_body, w.moment_body, body_frame, stamp);
}

geometry_msgs::WrenchStamped toWorldWrench(const core::VesselWrench& w, const std::string& world_frame,
                                           const ros::Time& stamp) {
  return wrenchStamped(w.force_world, w.moment_world, world_frame, stamp);
}

geometry_msgs::WrenchStamped toFairleadWrench(const core::FairleadForce& f, const core::RigidPose& vessel,
                                              const std::string& world_frame, const ros::Time& stamp) {
  const Eigen::Vector3d arm = f.position - vessel.position;
  return wrenchStamped(f.force, arm.cross(f.force), world_frame, stamp);
}

geometry_msgs::TransformStamped fairleadTransform(const core::FairleadForce& f, const core::RigidPose& vessel,
                                                  const std::string& world_frame, const std::string& child,
                                                  const ros::Time& stamp) {
  core::RigidPose at = vessel;
  at.position = f.position;
  return vesselTransform(at, world_frame, child, stamp);
}

geometry_msgs::TransformStamped vesselTransform(const core::RigidPose& pose, const std::string& world_frame,
                                                const std::string& body_frame, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = world_frame;
  t.child_frame_id = body_frame;
  const geometry_msgs::Pose p = toPoseMsg(pose);
  t.transform.translation.x = p.position.x;
  t.transform.translation.y = p.position.y;
  t.transform.translation.z = p.position.z;
  t.transform.rotation = p.orientation;
  return t;
}

VesselStaticsRequest vesselStaticsFromRequest(const VesselStatics::Request& req, const core::RigidPose& file_pose) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  VesselStaticsRequest out;
  if (req.use_file_pose) {
    out.pose = file_pose;
  } else {
    out.pose = toRigidPose(req.pose);
    const std::string bad = out.pose.validate("pose");
    if (!bad.empty()) {
      out.error = bad;
      return out;
    }
    out.pose.orientation.normalize();
  }
  out.want_stiffness = req.want_stiffness;
  if (!req.offset_dof.empty()) {
    if (!core::parseVesselDof(req.offset_dof, out.dof)) {
      out.error = "offset_dof = \"" + req.offset_dof + "\": must be empty (no offset curve) or one of surge, sway, "
                  "heave, roll, pitch, yaw";
      return out;
    }
    out.has_offset = true;
    out.angular = static_cast<int>(out.dof) >= 3;
    const double range = req.offset_range;
    if (!(std::isfinite(range) && range > 0.0)) {
      out.error = "offset_range = " + formatNumber(range) + ": must be > 0 and finite (" +
                  (out.angular ? "deg" : "m") + ")";
      return out;
    }
    if (out.angular && range >= 90.0) {
      out.error = "offset_range = " + formatNumber(range) + " deg: must be < 90 for " + req.offset_dof;
      return out;
    }
    if (req.offset_steps < 2 || req.offset_steps > kMaxOffsetSteps) {
      out.error = "offset_steps = " + std::to_string(req.offset_steps) + ": must be in [2, " +
                  std::to_string(kMaxOffsetSteps) + "] when offset_dof is given";
      return out;
    }
    const std::size_t n = req.offset_steps;
    for (std::size_t k = 0; k < n; ++k) {
      const double a = -range + 2.0 * range * static_cast<double>(k) / static_cast<double>(n - 1);
      out.offsets.push_back(out.angular ? a * kDeg : a);
    }
  }
  const Eigen::Quaterniond& q = out.pose.orientation;
  const double yaw = std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()), 1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
  std::ostringstream os;
  os << (req.use_file_pose ? "file pose" : "pose") << " (x, y, z) = (" << formatNumber(out.pose.position.x()) << ", "
     << formatNumber(out.pose.position.y()) << ", " << formatNumber(out.pose.position.z()) << ") m, yaw "
     << formatNumber(yaw / kDeg) << " deg";
  out.summary = os.str();
  out.ok = true;
  return out;
}

void toVesselStaticsResponse(const core::SystemProblem& system, const core::VesselStaticResult& at,
                             const core::StiffnessResult* stiffness, const std::vector<core::OffsetPoint>* curve,
                             const VesselStaticsRequest& request, VesselStatics::Response& res) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  res = VesselStatics::Response();
  const core::VesselWrench& w = at.wrench;
  res.wrench_body = wrench(w.force_body, w.moment_body);
  res.wrench_world = wrench(w.force_world, w.moment_world);
  for (std::size_t i = 0; i < system.lines.size(); ++i) {
    res.line_names.push_back(system.lines[i].name);
    res.top_tension.push_back(i < at.system.lines.size() ? at.system.lines[i].topTension() : 0.0);
  }
  std::vector<std::string> failed;
  if (!at.system.summary.converged) failed.push_back("statics at the pose: " + at.system.summary.message);
  if (stiffness) {
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) res.stiffness[static_cast<std::size_t>(6 * i + j)] = stiffness->K(i, j);
    if (!stiffness->converged) failed.push_back("stiffness: " + stiffness->message);
  }
  if (curve) {
    const int c = static_cast<int>(request.dof);
    for (const core::OffsetPoint& p : *curve) {
      res.offsets.push_back(request.angular ? p.offset / kDeg : p.offset);
      res.restoring.push_back(p.wrench[c]);
      res.max_tension.push_back(p.max_tension);
      res.max_tension_line.push_back(p.max_tension_line);
      if (!p.converged)
        failed.push_back("offset " + formatNumber(request.angular ? p.offset / kDeg : p.offset) +
                         (request.angular ? " deg: " : " m: ") + p.message);
    }
  }
  res.success = failed.empty();
  std::ostringstream os;
  os << request.summary << ": ";
  if (res.success) {
    os << "converged; force (body) (" << formatNumber(w.force_body.x()) << ", " << formatNumber(w.force_body.y()) << ", "
       << formatNumber(w.force_body.z()) << ") N, moment (" << formatNumber(w.moment_body.x()) << ", "
       << formatNumber(w.moment_body.y()) << ", " << formatNumber(w.moment_body.z()) << ") N m";
    if (stiffness) os << "; stiffness computed";
    if (curve) os << "; offset curve of " << curve->size() << " points";
  } else {
    os << "NOT converged: ";
    for (std::size_t k = 0; k < failed.size(); ++k) os << (k ? "; " : "") << failed[k];
  }
  res.message = os.str();
}

void toSystemStaticsResponse(const core::SystemProblem& system, const core::SystemStaticResult& r,
                             SystemStatics::Response& res) {
  res = SystemStatics::Response();
  res.success = r.summary.converged;
  res.iterations = static_cast<uint32_t>(std::max(0, r.summary.iterations));
  res.message = (r.summary.converged ? "converged: " : "did not converge: ") + r.summary.message;
  for (const core::SystemPointResult& p : r.points) {
    res.point_names.push_back(p.name);
    geometry_msgs::Point x;
    x.x = p.x;
    x.y = p.y;
    x.z = p.z;
    res.point_positions.push_back(x);
    geometry_msgs::Vector3 f;
    f.x = p.fx;
    f.y = p.fy;
    f.z = p.fz;
    res.point_pull.push_back(f);
  }
  for (std::size_t i = 0; i < r.lines.size(); ++i) {
    res.line_names.push_back(i < system.lines.size() ? system.lines[i].name : "");
    res.top_tension.push_back(r.lines[i].topTension());
    double tmin = r.lines[i].nodes.empty() ? 0.0 : r.lines[i].nodes.front().tension;
    for (const auto& n : r.lines[i].nodes) tmin = std::min(tmin, n.tension);
    res.min_tension.push_back(tmin);
  }
}

diagnostic_msgs::DiagnosticArray toDiagnostics(const std::vector<VesselMonitor::Status>& statuses,
                                               const std::string& node, const std::string& run_name,
                                               const std::string& hardware_id, const ros::Time& stamp) {
  diagnostic_msgs::DiagnosticArray arr;
  arr.header.stamp = stamp;
  for (const VesselMonitor::Status& s : statuses) {
    diagnostic_msgs::DiagnosticStatus st;
    st.level = static_cast<int8_t>(s.level);
    st.name = "mooring_dynamics: " + node + (s.line.empty() ? " " + run_name : " line " + s.line);
    st.hardware_id = hardware_id;
    st.message = s.message;
    for (const auto& kv : s.values) {
      diagnostic_msgs::KeyValue k;
      k.key = kv.first;
      k.value = kv.second;
      st.values.push_back(k);
    }
    arr.status.push_back(st);
  }
  return arr;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
