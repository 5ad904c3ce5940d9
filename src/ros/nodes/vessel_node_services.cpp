// The vessel node's services (~release, ~winch, ~reset, ~solve_static): the requests checked and
// answered; the run's state is touched under solver_mutex_ (decimated mode: after the solve in
// progress). The node itself: vessel_node.cpp.
#include <cmath>
#include <limits>

#include "mooring_dynamics/core/solvers/vessel_statics.hpp"
#include "mooring_dynamics/ros/nodes/params.hpp"
#include "mooring_dynamics/ros/nodes/vessel_node.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

bool VesselNode::onRelease(ReleaseLine::Request& req, ReleaseLine::Response& res) {
  core::LineEvent::End end = core::LineEvent::End::Top;
  if (req.end == "anchor") {
    end = core::LineEvent::End::Anchor;
  } else if (req.end != "top") {
    res.success = false;
    res.message = "end = \"" + req.end + "\": must be top or anchor";
    return true;
  }
  std::lock_guard<std::mutex> l(solver_mutex_);
  const std::string err = lockstep_->releaseLine(req.line, end, "released by ~release");
  snapshotForDiagnostics();
  res.success = err.empty();
  res.message = err.empty() ? "line " + req.line + ": " + req.end + " let go at solver time " +
                                  std::to_string(lockstep_->solverTime()) + " s; it pulls nothing from the next sample on"
                            : err;
  if (res.success) ROS_WARN("mooring_dynamics: %s", res.message.c_str());
  return true;
}

bool VesselNode::onWinch(Winch::Request& req, Winch::Response& res) {
  if (!(req.target_length >= 0.0)) {  // NaN too
    res.success = false;
    res.message = "target_length = " + formatNumber(req.target_length) + ": must be > 0 [m], or 0 for none";
    return true;
  }
  std::lock_guard<std::mutex> l(solver_mutex_);
  std::string note;
  const double target = req.target_length > 0.0 ? req.target_length : std::numeric_limits<double>::quiet_NaN();
  const std::string err = lockstep_->winchLine(req.line, req.rate, target, note);
  snapshotForDiagnostics();
  res.success = err.empty();
  res.message = err.empty() ? "line " + req.line + ": winch " + note : err;
  const std::vector<double> lengths = lockstep_->lineLengths();
  for (std::size_t i = 0; i < system_.lines.size() && i < lengths.size(); ++i)
    if (system_.lines[i].name == req.line) res.line_length = lengths[i];
  ROS_INFO("mooring_dynamics: ~winch: %s", res.message.c_str());
  return true;
}

bool VesselNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  std::lock_guard<std::mutex> l(solver_mutex_);
  const ros::WallTime w0 = ros::WallTime::now();
  const core::VesselLockstep::Result r = lockstep_->reset();
  if (!r.publish) {
    // Before the first sample there is nothing to reset: not an error.
    res.success = !lockstep_->started();
    res.message = lockstep_->started() ? "reset failed: " + r.message : "nothing to reset: no pose received yet";
    ROS_INFO("mooring_dynamics: ~reset: %s", res.message.c_str());
    return true;
  }
  handle(r, last_stamp_, (ros::WallTime::now() - w0).toSec(), 0.0);
  res.success = true;
  res.message = "every line restarted from statics at the last accepted pose (stamp " +
                formatNumber(last_stamp_.toSec()) + ")";
  ROS_INFO("mooring_dynamics: ~reset: %s", res.message.c_str());
  return true;
}

bool VesselNode::onSolveStatic(VesselStatics::Request& req, VesselStatics::Response& res) {
  const VesselStaticsRequest q = vesselStaticsFromRequest(req, system_.vessel.pose);
  if (!q.ok) {
    res = VesselStatics::Response();
    res.success = false;
    res.message = "invalid request: " + q.error;
    ROS_WARN("mooring_dynamics: ~solve_static rejected: %s", res.message.c_str());
    std::lock_guard<std::mutex> l(monitor_mutex_);
    monitor_->onRequestRejected(wallNow(), "~solve_static: " + res.message);
    return true;
  }
  const ros::WallTime t0 = ros::WallTime::now();
  try {
    core::StiffnessResult k;
    core::VesselStaticResult at;
    if (q.want_stiffness) {
      k = core::mooringStiffness(system_, q.pose);
      at = k.at;
    } else {
      at = core::solveVesselStatic(system_, q.pose);
    }
    std::vector<core::OffsetPoint> curve;
    if (q.has_offset) curve = core::offsetCurve(system_, q.pose, q.dof, q.offsets);
    toVesselStaticsResponse(system_, at, q.want_stiffness ? &k : nullptr, q.has_offset ? &curve : nullptr, q, res);
  } catch (const std::exception& e) {
    res = VesselStatics::Response();
    res.success = false;
    res.message = q.summary + ": " + e.what();
    std::lock_guard<std::mutex> l(monitor_mutex_);
    monitor_->onRequestRejected(wallNow(), "~solve_static: " + res.message);
  }
  const double ms = (ros::WallTime::now() - t0).toSec() * 1000.0;
  ROS_INFO("mooring_dynamics: ~solve_static, %.0f ms (dynamic run untouched): %s", ms, res.message.c_str());
  return true;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
