#include "mooring_dynamics/ros/nodes/lockstep_node.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/nodes/params.hpp"
#include "mooring_dynamics/ros/nodes/static_node.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

constexpr double kWarnPeriod = 5.0;  // [s] throttle of repeated warnings

}  // namespace

double LockstepNode::wallNow() const { return (ros::WallTime::now() - wall0_).toSec(); }

LockstepNode::LockstepNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh), wall0_(ros::WallTime::now()) {
  problem_ = loadProblemFromParams(pnh_, source_);
  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  pnh_.param<std::string>("vessel_frame", vessel_frame_, frame_id_);
  if (vessel_frame_.empty()) vessel_frame_ = frame_id_;
  const double marker_scale =
      doubleParam(pnh_, "marker_scale", 1.0, [](double v) { return v > 0.0; }, "must be > 0");
  marker_options_ = markerOptionsFor(problem_, marker_scale);
  if (pnh_.hasParam("tension_range")) {
    std::vector<double> r;
    if (!pnh_.getParam("tension_range", r) || r.size() != 2 || !std::isfinite(r[0]) || !std::isfinite(r[1]) ||
        !(r[1] > r[0]))
      throw std::runtime_error("parameter " + pnh_.resolveName("tension_range") +
                               ": must be a list [min, max] of two finite tensions in N with max > min");
    marker_options_.tension_min = r[0];
    marker_options_.tension_max = r[1];
  }

  pnh_.param<std::string>("motion_source", motion_source_, "pose");
  if (motion_source_ != "pose" && motion_source_ != "odometry" && motion_source_ != "tf" && motion_source_ != "gnss")
    throw std::runtime_error("parameter " + pnh_.resolveName("motion_source") + " = \"" + motion_source_ +
                             "\": must be \"pose\" (~top_pose, geometry_msgs/PoseStamped), \"odometry\" "
                             "(~top_odom, nav_msgs/Odometry), \"tf\" (~tf_source_frame) or \"gnss\" (~fix, "
                             "sensor_msgs/NavSatFix, and ~heading)");
  pnh_.param<std::string>("tf_source_frame", tf_source_frame_, "");
  if (motion_source_ == "tf" && tf_source_frame_.empty())
    throw std::runtime_error("parameter " + pnh_.resolveName("tf_source_frame") +
                             ": must name the fairlead's tf frame when ~motion_source is \"tf\"");
  const double poll_rate =
      doubleParam(pnh_, "tf_poll_rate", 20.0, [](double v) { return v > 0.0; }, "must be > 0 [Hz]");
  tf_timeout_ = doubleParam(pnh_, "tf_timeout", 0.1, [](double v) { return v >= 0.0; }, "must be >= 0 [s]");

  const double dt = doubleParam(pnh_, "dt", problem_.dynamics.dt, [](double v) { return v > 0.0; }, "must be > 0");
  LockstepOptions lo;
  lo.start_tolerance = doubleParam(pnh_, "start_tolerance", lo.start_tolerance, [](double v) { return v >= 0.0; },
                                   "must be >= 0 [m]");
  lo.loop_back = doubleParam(pnh_, "loop_back", lo.loop_back, [](double v) { return v >= 0.0; }, "must be >= 0 [s]");
  lo.max_gap = doubleParam(pnh_, "max_gap", lo.max_gap, [](double) { return true; }, "");
  lo.max_speed = doubleParam(pnh_, "max_speed", lo.max_speed, [](double) { return true; }, "");
  MonitorOptions mo;
  mo.motion_timeout = doubleParam(pnh_, "motion_timeout", mo.motion_timeout, [](double v) { return v > 0.0; },
                                  "must be > 0 [s]");
  mo.min_real_time_factor = doubleParam(pnh_, "min_real_time_factor", mo.min_real_time_factor,
                                        [](double v) { return v >= 0.0; }, "must be >= 0");
  mo.max_utilization = doubleParam(pnh_, "max_utilization", mo.max_utilization, [](double v) { return v > 0.0; },
                                   "must be > 0 (tension over minimum breaking load)");
  for (const core::Segment& g : problem_.segments) mo.segment_mbl.push_back(problem_.materials[g.material].mbl);
  const double diag_period = doubleParam(pnh_, "diagnostics_period", 1.0, [](double v) { return v > 0.0; },
                                         "must be > 0 [s]");
  pnh_.param("republish_when_silent", republish_when_silent_, true);
  mo.line_name = problem_.name;

  pnh_.param("publish_body_frames", publish_body_frames_, false);
  std::string default_prefix = ros::this_node::getName();
  if (!default_prefix.empty() && default_prefix[0] == '/') default_prefix.erase(0, 1);
  pnh_.param<std::string>("body_frame_prefix", body_frame_prefix_, default_prefix + "/");
  if (publish_body_frames_) {
    frame_marks_ = marker_options_.bodies;
    std::vector<double> instrument_s;
    if (pnh_.hasParam("instrument_s") && !pnh_.getParam("instrument_s", instrument_s))
      throw std::runtime_error("parameter " + pnh_.resolveName("instrument_s") + ": must be a list of arclengths [m]");
    const double length = problem_.totalLength();
    for (double s : instrument_s) {
      if (!(std::isfinite(s) && s >= 0.0 && s <= length))
        throw std::runtime_error("parameter " + pnh_.resolveName("instrument_s") + ": entry " + formatNumber(s) +
                                 ": must be an arclength from the anchor in [0, " + formatNumber(length) + "] m");
      BodyMark m;
      char buf[32];
      std::snprintf(buf, sizeof buf, "s%g", s);
      m.name = buf;
      m.s = s;
      frame_marks_.push_back(m);
    }
  }

  const ros::WallTime w0 = ros::WallTime::now();
  try {
    driver_ = std::make_unique<LockstepDriver>(problem_, dt, lo);
  } catch (const std::exception& e) {
    throw std::runtime_error("dynamic mode: cannot start from the problem's statics (" + describeTop(problem_.top, problem_.formulation) +
                             "): " + e.what());
  }
  const double ms = (ros::WallTime::now() - w0).toSec() * 1000.0;
  monitor_ = std::make_unique<LockstepMonitor>(mo, wallNow());

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
  if (publish_body_frames_) tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  state_pub_ = pnh_.advertise<CableState>("cable_state", 100, /*latch=*/true);
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  wrench_pub_ = pnh_.advertise<geometry_msgs::WrenchStamped>("top_wrench", 100, /*latch=*/true);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  reset_srv_ = pnh_.advertiseService("reset", &LockstepNode::onReset, this);
  solve_srv_ = pnh_.advertiseService("solve_static", &LockstepNode::onSolveStatic, this);
  release_srv_ = pnh_.advertiseService("release", &LockstepNode::onRelease, this);
  winch_srv_ = pnh_.advertiseService("winch", &LockstepNode::onWinch, this);
  std::string input;
  if (motion_source_ == "pose") {
    motion_sub_ = pnh_.subscribe("top_pose", 100, &LockstepNode::onPose, this);
    input = motion_sub_.getTopic();
  } else if (motion_source_ == "odometry") {
    motion_sub_ = pnh_.subscribe("top_odom", 100, &LockstepNode::onOdometry, this);
    input = motion_sub_.getTopic();
  } else if (motion_source_ == "gnss") {
    // The fixes drive the top (docs/problem_format.md, dynamics.gnss): the track starts at the
    // static top, whose position the first accepted fix puts it at (datum first_fix); a tow's
    // smoother starts on top.tow_velocity, as cable_sim dynamic's does.
    if (!driver_->threeD())
      throw std::runtime_error("parameter " + pnh_.resolveName("motion_source") +
                               " = \"gnss\": a ship track moves the top in the horizontal plane; the problem needs "
                               "model: 3d");
    core::GnssOptions go = problem_.dynamics.gnss;
    go.enabled = true;
    core::RigidPose start;
    start.position = Eigen::Vector3d(driver_->staticTopX(), driver_->staticTopY(), driver_->staticTopZ());
    gnss_ = std::make_unique<GnssInput>(
        pnh_, go, start, Eigen::Vector2d(problem_.top.tow_vx, problem_.top.tow_vy),
        [this](const ros::Time& stamp, const core::RigidPose& p) {
          onMotion(stamp, frame_id_, p.position.x(), p.position.y(), p.position.z(), "fix");
        },
        [this](const std::string& message) { reject(message, lockstep_keys::kGnssRejected); });
    input = gnss_->topics();
  } else {
    tf_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / poll_rate), &LockstepNode::pollTf, this);
    input = "tf " + frame_id_ + " <- " + tf_source_frame_ + " polled at " + formatNumber(poll_rate) + " Hz";
  }
  diag_timer_ = nh_.createWallTimer(ros::WallDuration(diag_period), &LockstepNode::onDiagnosticsTimer, this);

  ROS_INFO("mooring_dynamics: dynamic (lockstep) mode, %s model: loaded \"%s\" from %s: %zu segment(s), %.2f m "
           "of line; statics in %.0f ms, static top at (%g, %g, %g) m; dt %g s; top motion from %s; frame %s, wrench "
           "in %s",
           driver_->threeD() ? "3-D" : "2-D (x-z plane)", problem_.name.c_str(), source_.c_str(),
           problem_.segments.size(), problem_.totalLength(), ms, driver_->staticTopX(), driver_->staticTopY(),
           driver_->staticTopZ(), dt, input.c_str(), frame_id_.c_str(), vessel_frame_.c_str());
}

void LockstepNode::checkOrientation(const geometry_msgs::Quaternion& q, const std::string& field) {
  // The orientation is not used (the top is a moment-free point): a bad one does not drop the
  // sample, it is counted; a non-finite one (a broken source) also warns. A zero or otherwise
  // non-unit quaternion is common in hand-written poses and only counted.
  const double c[4] = {q.x, q.y, q.z, q.w};
  for (double v : c)
    if (!std::isfinite(v)) {
      monitor_->onInputNote(wallNow(), field + " = (" + formatNumber(q.x) + ", " + formatNumber(q.y) + ", " +
                                           formatNumber(q.z) + ", " + formatNumber(q.w) + "): not finite (unused)",
                            lockstep_keys::kOrientationNonFinite, true);
      return;
    }
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (std::abs(n - 1.0) > core::kUnitQuaternionTolerance)
    monitor_->onInputNote(wallNow(), field + ": norm " + formatNumber(n) + " (unused)", lockstep_keys::kOrientationNonUnit,
                          false);
}

void LockstepNode::onPose(const geometry_msgs::PoseStamped::ConstPtr& msg) {
  checkOrientation(msg->pose.orientation, "pose.orientation");
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.position.x, msg->pose.position.y,
           msg->pose.position.z, "pose.position");
}

void LockstepNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  checkOrientation(msg->pose.pose.orientation, "pose.pose.orientation");
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.pose.position.x, msg->pose.pose.position.y,
           msg->pose.pose.position.z, "pose.pose.position");
}

void LockstepNode::pollTf(const ros::WallTimerEvent&) {
  geometry_msgs::TransformStamped tr;
  try {
    tr = tf_buffer_->lookupTransform(frame_id_, tf_source_frame_, ros::Time(0));
  } catch (const tf2::TransformException& e) {
    // Nothing new to use: counts as silence (diagnostics), and the failure is logged (throttled).
    const std::string msg = "no transform " + frame_id_ + " <- " + tf_source_frame_ + " (~tf_source_frame): " +
                            e.what();
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion: %s; state kept", msg.c_str());
    monitor_->onInputRejected(wallNow(), msg, lockstep_keys::kNoTransform);
    return;
  }
  if (tr.header.stamp == last_tf_stamp_) return;  // no new transform since the last poll
  last_tf_stamp_ = tr.header.stamp;
  onMotion(tr.header.stamp, frame_id_, tr.transform.translation.x, tr.transform.translation.y,
           tr.transform.translation.z, "transform.translation");
}

void LockstepNode::reject(const std::string& message, const char* key) {
  ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion dropped: %s; state kept", message.c_str());
  monitor_->onInputRejected(wallNow(), message, key);
}

void LockstepNode::onMotion(const ros::Time& stamp, const std::string& frame, double x, double y, double z,
                            const std::string& field) {
  monitor_->onMotionReceived(wallNow());
  const double c[3] = {x, y, z};
  const char* axis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c[i])) {
      char st[32];
      std::snprintf(st, sizeof st, "%.6f", stamp.toSec());
      reject(field + "." + axis[i] + " = " + formatNumber(c[i]) + " (stamp " + st + "): must be finite",
             lockstep_keys::kNonFinite);
      return;
    }
  }
  if (stamp.isZero()) {
    reject("header.stamp = 0: lockstep mode needs stamped motion", lockstep_keys::kZeroStamp);
    return;
  }
  if (!frame.empty() && frame != frame_id_) {
    // Transform the fairlead position into ~frame_id at the sample's stamp.
    geometry_msgs::PointStamped in, out;
    in.header.stamp = stamp;
    in.header.frame_id = frame;
    in.point.x = x;
    in.point.y = y;
    in.point.z = z;
    try {
      tf_buffer_->transform(in, out, frame_id_, ros::Duration(tf_timeout_));
    } catch (const tf2::TransformException& e) {
      reject("header.frame_id = \"" + frame + "\": no transform to \"" + frame_id_ + "\" (~frame_id) at stamp " +
                 formatNumber(stamp.toSec()) + ": " + e.what(),
             lockstep_keys::kUnknownFrame);
      return;
    }
    x = out.point.x;
    y = out.point.y;
    z = out.point.z;
  }
  // model: 2d: a fairlead off the plane y = 0 is dropped (lockstep.hpp); named here with its field.
  const std::string planar = driver_->planarError(y);
  if (!planar.empty()) {
    reject(field + "." + planar + " (in " + frame_id_ + ")", lockstep_keys::kOffPlane);
    return;
  }
  if (!have_epoch_) {
    have_epoch_ = true;
    epoch_ = stamp;
  }
  const double t = (stamp - epoch_).toSec();
  const ros::WallTime w0 = ros::WallTime::now();
  const LockstepDriver::Result r = driver_->onSample(t, x, y, z);
  handle(r, stamp, (ros::WallTime::now() - w0).toSec());
}

void LockstepNode::handle(const LockstepDriver::Result& r, const ros::Time& stamp, double wall_spent) {
  const double ms = wall_spent * 1000.0;
  monitor_->onResult(r, wallNow(), wall_spent, r.publish ? &driver_->state() : nullptr, driver_->solverTime());
  switch (r.outcome) {
    case LockstepDriver::Outcome::Dropped:
      if (r.start_failed)
        ROS_ERROR_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion at stamp %.6f: %s", stamp.toSec(),
                           r.message.c_str());
      else
        ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: top motion at stamp %.6f dropped: %s; state kept",
                          stamp.toSec(), r.message.c_str());
      return;
    case LockstepDriver::Outcome::Started:
      ROS_INFO("mooring_dynamics: lockstep run starts at stamp %.6f (%.0f ms): %s", stamp.toSec(), ms,
               r.message.c_str());
      break;
    case LockstepDriver::Outcome::Reinitialised:
      ROS_WARN("mooring_dynamics: stamp %.6f: %s", stamp.toSec(), r.message.c_str());
      break;
    case LockstepDriver::Outcome::Failed:
    case LockstepDriver::Outcome::RecoveredFailure:
      ROS_ERROR("mooring_dynamics: line %s, stamp %.6f: %s", problem_.name.c_str(), stamp.toSec(), r.message.c_str());
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
  last_state_ = toCableState(s, problem_.name, frame_id_, stamp);
  for (const core::LineEventRecord& e : driver_->events()) last_state_.events.push_back(core::lineEventText(e));
  last_state_.winch_rate = driver_->winchRate();
  state_pub_.publish(last_state_);

  // Force of the line on the vessel at the fairlead: minus the force the vessel applies to the line.
  geometry_msgs::Vector3Stamped f;
  f.header.stamp = stamp;
  f.header.frame_id = frame_id_;
  f.vector.x = -s.top_force_x;
  f.vector.y = -s.top_force_y;  // 0 from the 2-D solver
  f.vector.z = -s.top_force_z;
  if (vessel_frame_ != frame_id_) {
    try {
      const geometry_msgs::TransformStamped tr =
          tf_buffer_->lookupTransform(vessel_frame_, frame_id_, stamp, ros::Duration(tf_timeout_));
      geometry_msgs::Vector3Stamped g;
      tf2::doTransform(f, g, tr);  // rotation only (a free vector)
      f = g;
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: no transform %s <- %s at %.6f (%s): ~top_wrench published "
                        "in %s", vessel_frame_.c_str(), frame_id_.c_str(), stamp.toSec(), e.what(), frame_id_.c_str());
    }
  }
  last_wrench_.header = f.header;
  last_wrench_.wrench.force = f.vector;
  last_wrench_.wrench.torque = geometry_msgs::Vector3();
  wrench_pub_.publish(last_wrench_);
  have_output_ = true;
  last_stamp_ = stamp;
  publishMarkersAndFrames();
}

void LockstepNode::publishMarkersAndFrames() {
  if (marker_pub_.getNumSubscribers() > 0)
    marker_pub_.publish(makeMarkers(last_state_, problem_.environment, marker_options_));
  if (!tf_broadcaster_ || frame_marks_.empty()) return;
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const BodyMark& b : frame_marks_) {
    geometry_msgs::TransformStamped t;
    t.header = last_state_.header;
    t.child_frame_id = body_frame_prefix_ + b.name;
    const geometry_msgs::Point p = pointAtArclength(last_state_, b.s);
    t.transform.translation.x = p.x;
    t.transform.translation.y = p.y;
    t.transform.translation.z = p.z;
    // x axis along the cable tangent toward the top: (sin a cos b, sin a sin b, cos a), a =
    // inclination from +z, b = azimuth of its horizontal part (0 in 2-D, where a is signed toward
    // +x), of the nearest node: a rotation about z by b after one about y by a - pi/2.
    const std::vector<core::NodeState>& nodes = driver_->state().nodes;  // the state last published
    double a = 0.0, az = 0.0, best = 1e300;
    for (const core::NodeState& ns : nodes)
      if (std::abs(ns.s - b.s) < best) {
        best = std::abs(ns.s - b.s);
        a = ns.angle;
        az = ns.azimuth;
      }
    const double th = a - 0.5 * M_PI;
    const double cy = std::cos(0.5 * th), sy = std::sin(0.5 * th), cz = std::cos(0.5 * az), sz = std::sin(0.5 * az);
    // q = qz(b) qy(th)
    t.transform.rotation.w = cz * cy;
    t.transform.rotation.x = -sz * sy;
    t.transform.rotation.y = cz * sy;
    t.transform.rotation.z = sz * cy;
    frames.push_back(t);
  }
  tf_broadcaster_->sendTransform(frames);
}

void LockstepNode::onDiagnosticsTimer(const ros::WallTimerEvent&) {
  const double now = wallNow();
  if (monitor_->silent(now) && monitor_->everReceived()) {
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: no top motion for %.1f s; %s", monitor_->secondsSinceMotion(now),
                      have_output_ && republish_when_silent_ ? "republishing the last good state"
                                                             : "last good state kept (latched)");
    if (have_output_ && republish_when_silent_) {
      state_pub_.publish(last_state_);
      wrench_pub_.publish(last_wrench_);
      publishMarkersAndFrames();
    }
  }
  const LockstepMonitor::Summary s = monitor_->summarise(now);
  diagnostic_msgs::DiagnosticArray arr;
  arr.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus st;
  st.level = static_cast<int8_t>(s.level);
  st.name = "mooring_dynamics: " + ros::this_node::getName() + " lockstep";
  st.hardware_id = problem_.name;
  st.message = s.message;
  std::vector<std::pair<std::string, std::string>> values(s.values.begin(), s.values.end());
  // Line events (an end let go, the line parted): counted, the last one shown, and a warning.
  const std::vector<core::LineEventRecord> events = driver_->events();
  values.emplace_back("line events", std::to_string(events.size()));
  values.emplace_back("line length", formatNumber(driver_->lineLength()) + " m");
  values.emplace_back("winch rate", formatNumber(driver_->winchRate()) + " m/s");
  if (!events.empty()) {
    values.emplace_back("last line event", core::lineEventText(events.back()));
    if (st.level < diagnostic_msgs::DiagnosticStatus::WARN) {
      st.level = diagnostic_msgs::DiagnosticStatus::WARN;
      st.message = "line event: " + core::lineEventText(events.back());
    }
  }
  if (gnss_)
    for (const auto& kv : gnss_->values()) values.push_back(kv);
  for (const auto& kv : values) {
    diagnostic_msgs::KeyValue k;
    k.key = kv.first;
    k.value = kv.second;
    st.values.push_back(k);
  }
  arr.status.push_back(st);
  diag_pub_.publish(arr);
}

bool LockstepNode::onRelease(ReleaseLine::Request& req, ReleaseLine::Response& res) {
  res.success = false;
  core::LineEvent::End end = core::LineEvent::End::Top;
  if (!req.line.empty() && req.line != problem_.name) {
    res.message = "line = " + req.line + ": this node runs one line, " + problem_.name + " (or leave line empty)";
    return true;
  }
  if (req.end == "anchor")
    end = core::LineEvent::End::Anchor;
  else if (req.end != "top") {
    res.message = "end = \"" + req.end + "\": must be top or anchor";
    return true;
  }
  const std::string err = driver_->release(end, "released by ~release");
  res.success = err.empty();
  res.message = err.empty() ? req.end + " let go at solver time " + std::to_string(driver_->solverTime()) +
                                  " s; it carries no force from the next sample on"
                            : err;
  if (res.success) ROS_WARN("mooring_dynamics: ~release: %s", res.message.c_str());
  return true;
}

bool LockstepNode::onWinch(Winch::Request& req, Winch::Response& res) {
  res.success = false;
  res.line_length = driver_->lineLength();
  if (!req.line.empty() && req.line != problem_.name) {
    res.message = "line = " + req.line + ": this node runs one line, " + problem_.name + " (or leave line empty)";
    return true;
  }
  if (!(req.target_length >= 0.0)) {  // NaN too
    res.message = "target_length = " + formatNumber(req.target_length) + ": must be > 0 [m], or 0 for none";
    return true;
  }
  std::string note;
  const double target = req.target_length > 0.0 ? req.target_length : std::numeric_limits<double>::quiet_NaN();
  const std::string err = driver_->winch(req.rate, target, note);
  res.success = err.empty();
  res.message = err.empty() ? "winch " + note : err;
  ROS_INFO("mooring_dynamics: ~winch: %s", res.message.c_str());
  return true;
}

bool LockstepNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  const ros::WallTime w0 = ros::WallTime::now();
  const LockstepDriver::Result r = driver_->reset();
  res.success = r.publish;
  res.message = r.message;
  if (!r.publish) {
    // Before the first sample there is nothing to reset: not an error.
    if (!driver_->started()) res.success = true;
    ROS_INFO("mooring_dynamics: ~reset: %s", r.message.c_str());
    return true;
  }
  handle(r, last_stamp_, (ros::WallTime::now() - w0).toSec());
  ROS_INFO("mooring_dynamics: ~reset: %s", r.message.c_str());
  return true;
}

bool LockstepNode::onSolveStatic(SolveStatic::Request& req, SolveStatic::Response& res) {
  const TopBoundaryRequest top = topBoundaryFromRequest(req, problem_.top, problem_.formulation);
  if (!top.ok) {
    toFailureResponse("invalid request: " + top.error, res);
    ROS_WARN("mooring_dynamics: ~solve_static rejected: %s", res.message.c_str());
    monitor_->onRequestRejected(wallNow(), "~solve_static: " + res.message);
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
    ROS_WARN("mooring_dynamics: ~solve_static failed after %.0f ms (dynamic state unchanged): %s", ms,
             res.message.c_str());
    monitor_->onRequestRejected(wallNow(), "~solve_static: " + res.message);
    return true;
  }
  toResponse(o.result, res);
  res.message = top.summary + ": " + o.message;
  res.reinitialised = false;
  if (req.reinitialise) {
    const core::NodeState& tn = o.result.nodes.back();
    const ros::WallTime w0 = ros::WallTime::now();
    const LockstepDriver::Result r = driver_->reinitialiseAt(tn.x, tn.y, tn.z, "~solve_static with reinitialise");
    if (r.publish) {
      res.reinitialised = true;
      res.message += "; dynamic run re-initialised from this solution at stamp " + formatNumber(last_stamp_.toSec());
      handle(r, last_stamp_, (ros::WallTime::now() - w0).toSec());
    } else {
      res.message += "; not re-initialised: " + r.message;
    }
  }
  ROS_INFO("mooring_dynamics: ~solve_static, %.0f ms: %s", ms, res.message.c_str());
  return true;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
