#include "mooring_dynamics/ros/lockstep_node.hpp"

#include <cmath>
#include <stdexcept>

#include <geometry_msgs/Vector3Stamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/ros/converter.hpp"
#include "mooring_dynamics/ros/static_node.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

constexpr double kWarnPeriod = 5.0;  // [s] throttle of repeated warnings
constexpr double kMaxOutOfPlane = 1e-3;  // [m] |y| above this is warned about (once)

}  // namespace

LockstepNode::LockstepNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {
  problem_ = loadProblemFromParams(pnh_, source_);
  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  pnh_.param<std::string>("vessel_frame", vessel_frame_, frame_id_);
  if (vessel_frame_.empty()) vessel_frame_ = frame_id_;
  pnh_.param("marker_scale", marker_options_.scale, 1.0);
  if (!(std::isfinite(marker_options_.scale) && marker_options_.scale > 0.0))
    throw std::runtime_error("parameter " + pnh_.resolveName("marker_scale") + " = " +
                             formatNumber(marker_options_.scale) + ": must be > 0");
  pnh_.param<std::string>("motion_source", motion_source_, "pose");
  if (motion_source_ != "pose" && motion_source_ != "odometry")
    throw std::runtime_error("parameter " + pnh_.resolveName("motion_source") + " = \"" + motion_source_ +
                             "\": must be \"pose\" (~top_pose, geometry_msgs/PoseStamped) or \"odometry\" "
                             "(~top_odom, nav_msgs/Odometry)");
  double dt = problem_.dynamics.dt;
  if (pnh_.hasParam("dt")) pnh_.getParam("dt", dt);
  if (!(std::isfinite(dt) && dt > 0.0))
    throw std::runtime_error("parameter " + pnh_.resolveName("dt") + " = " + formatNumber(dt) + ": must be > 0");
  LockstepOptions lo;
  pnh_.param("start_tolerance", lo.start_tolerance, lo.start_tolerance);
  if (!(std::isfinite(lo.start_tolerance) && lo.start_tolerance >= 0.0))
    throw std::runtime_error("parameter " + pnh_.resolveName("start_tolerance") + " = " +
                             formatNumber(lo.start_tolerance) + ": must be >= 0");

  const ros::WallTime w0 = ros::WallTime::now();
  try {
    driver_ = std::make_unique<LockstepDriver>(problem_, dt, lo);
  } catch (const std::exception& e) {
    throw std::runtime_error("dynamic mode: cannot start from the problem's statics (" + describeTop(problem_.top) +
                             "): " + e.what());
  }
  const double ms = (ros::WallTime::now() - w0).toSec() * 1000.0;

  if (vessel_frame_ != frame_id_) {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
  }
  state_pub_ = pnh_.advertise<CableState>("cable_state", 100, /*latch=*/true);
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  wrench_pub_ = pnh_.advertise<geometry_msgs::WrenchStamped>("top_wrench", 100, /*latch=*/true);
  if (motion_source_ == "pose")
    motion_sub_ = pnh_.subscribe("top_pose", 100, &LockstepNode::onPose, this);
  else
    motion_sub_ = pnh_.subscribe("top_odom", 100, &LockstepNode::onOdometry, this);

  ROS_INFO("mooring_dynamics: dynamic (lockstep) mode: loaded \"%s\" from %s: %zu segment(s), %.2f m of line; "
           "statics in %.0f ms, static top at (%g, %g) m; dt %g s; top motion from %s; frame %s, wrench in %s",
           problem_.name.c_str(), source_.c_str(), problem_.segments.size(), problem_.totalLength(), ms,
           driver_->staticTopX(), driver_->staticTopZ(), dt, motion_sub_.getTopic().c_str(), frame_id_.c_str(),
           vessel_frame_.c_str());
}

void LockstepNode::onPose(const geometry_msgs::PoseStamped::ConstPtr& msg) {
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.position.x, msg->pose.position.y,
           msg->pose.position.z, "pose.position");
}

void LockstepNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.pose.position.x, msg->pose.pose.position.y,
           msg->pose.pose.position.z, "pose.pose.position");
}

void LockstepNode::onMotion(const ros::Time& stamp, const std::string& frame, double x, double y, double z,
                            const std::string& field) {
  const double c[3] = {x, y, z};
  const char* axis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c[i])) {
      ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion dropped: %s.%s = %s (stamp %.6f): must be finite; "
                        "state kept", field.c_str(), axis[i], formatNumber(c[i]).c_str(), stamp.toSec());
      return;
    }
  }
  if (stamp.isZero()) {
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion dropped: header.stamp = 0; lockstep mode needs "
                      "stamped motion");
    return;
  }
  if (!warned_y_ && std::abs(y) > kMaxOutOfPlane) {
    warned_y_ = true;
    ROS_WARN("mooring_dynamics: %s.y = %s m: the dynamic solver is 2-D (x-z plane of %s); y is ignored (warned "
             "once)", field.c_str(), formatNumber(y).c_str(), frame_id_.c_str());
  }
  if (!warned_frame_ && !frame.empty() && frame != frame_id_) {
    warned_frame_ = true;
    ROS_WARN("mooring_dynamics: top motion in frame \"%s\", expected \"%s\" (~frame_id): used as if it were in %s, "
             "not transformed (warned once)", frame.c_str(), frame_id_.c_str(), frame_id_.c_str());
  }
  if (!have_epoch_) {
    have_epoch_ = true;
    epoch_ = stamp;
  }
  const double t = (stamp - epoch_).toSec();
  const ros::WallTime w0 = ros::WallTime::now();
  const LockstepDriver::Result r = driver_->onSample(t, x, z);
  const double ms = (ros::WallTime::now() - w0).toSec() * 1000.0;
  switch (r.outcome) {
    case LockstepDriver::Outcome::Dropped:
      ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion at stamp %.6f dropped: %s", stamp.toSec(),
                        r.message.c_str());
      return;
    case LockstepDriver::Outcome::Started:
      ROS_INFO("mooring_dynamics: lockstep run starts at stamp %.6f (%.0f ms): %s", stamp.toSec(), ms,
               r.message.c_str());
      break;
    case LockstepDriver::Outcome::Reinitialised:
      ROS_WARN("mooring_dynamics: stamp %.6f: %s", stamp.toSec(), r.message.c_str());
      break;
    case LockstepDriver::Outcome::RecoveredFailure:
      ROS_ERROR("mooring_dynamics: stamp %.6f: %s", stamp.toSec(), r.message.c_str());
      break;
    case LockstepDriver::Outcome::Advanced:
      ROS_DEBUG("mooring_dynamics: stamp %.6f: solver t = %.3f s, %d steps, %d cuts, %d Newton iterations, %.1f ms",
                stamp.toSec(), driver_->solverTime(), r.report.steps, r.report.cuts, r.report.newton_iterations, ms);
      break;
  }
  if (r.publish) publish(stamp);
}

void LockstepNode::publish(const ros::Time& stamp) {
  const core::StaticResult& s = driver_->state();
  const CableState state = toCableState(s, problem_.name, frame_id_, stamp);
  state_pub_.publish(state);

  // Force of the line on the vessel at the fairlead: minus the force the vessel applies to the line.
  geometry_msgs::Vector3Stamped f;
  f.header.stamp = stamp;
  f.header.frame_id = frame_id_;
  f.vector.x = -s.top_force_x;
  f.vector.y = 0.0;
  f.vector.z = -s.top_force_z;
  if (tf_buffer_) {
    try {
      const geometry_msgs::TransformStamped tr = tf_buffer_->lookupTransform(vessel_frame_, frame_id_, stamp);
      geometry_msgs::Vector3Stamped g;
      tf2::doTransform(f, g, tr);  // rotation only (a free vector)
      f = g;
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: no transform %s <- %s at %.6f (%s): ~top_wrench published "
                        "in %s", vessel_frame_.c_str(), frame_id_.c_str(), stamp.toSec(), e.what(), frame_id_.c_str());
    }
  }
  geometry_msgs::WrenchStamped w;
  w.header = f.header;
  w.wrench.force = f.vector;
  wrench_pub_.publish(w);

  if (marker_pub_.getNumSubscribers() > 0)
    marker_pub_.publish(makeMarkers(state, problem_.environment, marker_options_));
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
