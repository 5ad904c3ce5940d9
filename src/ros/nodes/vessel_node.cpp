#include "mooring_dynamics/ros/nodes/vessel_node.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/names.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/numerics/thread_pool.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/nodes/params.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

constexpr double kWarnPeriod = 5.0;  // [s] throttle of repeated warnings

/// A line name as one level of a topic name: characters other than letters, digits and '_' become '_'.
std::string topicName(const std::string& name) {
  std::string out = name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "l_" + out;
  return out;
}

}  // namespace

bool paramsNameVesselFile(const ros::NodeHandle& pnh) {
  std::string file;
  if (!pnh.getParam("problem_file", file) || file.empty() || !core::isSystemFile(file)) return false;
  const core::SystemProblem s = core::loadSystemFromFile(file);
  return s.vessel.present && s.hasVesselPoints();
}

double VesselNode::wallNow() const { return (ros::WallTime::now() - wall0_).toSec(); }

VesselNode::~VesselNode() { worker_.reset(); }

void VesselNode::drainSolver() {
  if (worker_) worker_->drain();
}

VesselNode::VesselNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh), wall0_(ros::WallTime::now()) {
  if (!pnh_.getParam("problem_file", file_) || file_.empty())
    throw std::runtime_error("parameter " + pnh_.resolveName("problem_file") + ": a system file with a `vessel:` section is needed");
  system_ = core::loadSystemFromFile(file_);  // throws core::ProblemError naming the key
  if (!system_.vessel.present || !system_.hasVesselPoints())
    throw std::runtime_error("parameter " + pnh_.resolveName("problem_file") + " = \"" + file_ +
                             "\": no line ends on the vessel (give `vessel.lines`, or points of type vessel)");

  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  pnh_.param<std::string>("vessel_frame", vessel_frame_, system_.vessel.frame);
  if (vessel_frame_.empty()) vessel_frame_ = system_.vessel.frame;
  if (vessel_frame_ == frame_id_)
    throw std::runtime_error("parameter " + pnh_.resolveName("vessel_frame") + " = \"" + vessel_frame_ +
                             "\": must differ from ~frame_id (the body frame moves with the vessel)");

  pnh_.param<std::string>("motion_source", motion_source_, "pose");
  if (motion_source_ != "pose" && motion_source_ != "odometry" && motion_source_ != "tf" && motion_source_ != "gnss")
    throw std::runtime_error("parameter " + pnh_.resolveName("motion_source") + " = \"" + motion_source_ +
                             "\": must be \"pose\" (~vessel_pose, geometry_msgs/PoseStamped), \"odometry\" "
                             "(~vessel_odom, nav_msgs/Odometry), \"tf\" (~frame_id <- ~vessel_frame) or \"gnss\" "
                             "(~fix sensor_msgs/NavSatFix and ~heading)");
  pnh_.param("use_twist", use_twist_, true);
  const double poll_rate = doubleParam(pnh_, "tf_poll_rate", 20.0, [](double v) { return v > 0.0; }, "must be > 0 [Hz]");
  tf_timeout_ = doubleParam(pnh_, "tf_timeout", 0.1, [](double v) { return v >= 0.0; }, "must be >= 0 [s]");
  const int threads = intParam(pnh_, "threads", core::ThreadPool::hardwareThreads(), 1, "must be >= 1");

  core::DynamicOptions dyn = system_.dynamics;
  dyn.dt = doubleParam(pnh_, "dt", dyn.dt, [](double v) { return v > 0.0; }, "must be > 0 [s]");
  dyn.threads = 1;  // each line on one thread; `threads` lines side by side (as cable_sim dynamic)
  core::VesselLockstepOptions lo;
  lo.threads = threads;
  lo.start_tolerance = doubleParam(pnh_, "start_tolerance", lo.start_tolerance, [](double v) { return v >= 0.0; },
                                   "must be >= 0 [m]");
  lo.start_angle_tolerance = doubleParam(pnh_, "start_angle_tolerance", lo.start_angle_tolerance,
                                         [](double v) { return v >= 0.0; }, "must be >= 0 [rad]");
  lo.loop_back = doubleParam(pnh_, "loop_back", lo.loop_back, [](double v) { return v > 0.0; }, "must be > 0 [s]");
  lo.max_gap = doubleParam(pnh_, "max_gap", lo.max_gap, [](double) { return true; }, "");
  lo.max_speed = doubleParam(pnh_, "max_speed", lo.max_speed, [](double) { return true; }, "");
  lo.jumps_to_reinit = intParam(pnh_, "jumps_to_reinit", lo.jumps_to_reinit, 1, "must be >= 1");
  lo.failures_to_reinit = intParam(pnh_, "failures_to_reinit", lo.failures_to_reinit, 1, "must be >= 1");
  pnh_.param<bool>("restart_failed_lines", lo.restart_failed_lines, lo.restart_failed_lines);
  lo.solve_interval = doubleParam(pnh_, "solve_interval", 0.0, [](double v) { return v >= 0.0; },
                                  "must be >= 0 [s] (0: every pose solved in lockstep)");
  decimated_ = lo.solve_interval > 0.0;
  const double max_solver_lag =
      decimated_ ? doubleParam(pnh_, "max_solver_lag", 1.0, [&lo](double v) { return v > lo.solve_interval; },
                               "must be > ~solve_interval [s]")
                 : 0.0;
  max_solver_lag_ = max_solver_lag;
  loop_back_ = lo.loop_back;

  VesselMonitorOptions mo;
  mo.motion_timeout = doubleParam(pnh_, "motion_timeout", mo.motion_timeout, [](double v) { return v > 0.0; },
                                  "must be > 0 [s]");
  mo.min_real_time_factor = doubleParam(pnh_, "min_real_time_factor", mo.min_real_time_factor,
                                        [](double v) { return v >= 0.0; }, "must be >= 0");
  mo.max_utilization = doubleParam(pnh_, "max_utilization", mo.max_utilization, [](double v) { return v > 0.0; },
                                   "must be > 0 (tension over minimum breaking load)");
  const double diag_period = doubleParam(pnh_, "diagnostics_period", 1.0, [](double v) { return v > 0.0; },
                                         "must be > 0 [s]");
  const double marker_scale = doubleParam(pnh_, "marker_scale", 1.0, [](double v) { return v > 0.0; }, "must be > 0");
  pnh_.param("publish_fairlead_frames", publish_fairlead_frames_, false);
  pnh_.param("publish_vessel_frame", publish_vessel_frame_, false);
  if (publish_vessel_frame_ && motion_source_ == "tf")
    throw std::runtime_error("parameter " + pnh_.resolveName("publish_vessel_frame") +
                             " = true: must be false when ~motion_source is \"tf\" (the vessel frame is the input)");
  std::string default_prefix = ros::this_node::getName();
  if (!default_prefix.empty() && default_prefix[0] == '/') default_prefix.erase(0, 1);
  pnh_.param<std::string>("frame_prefix", frame_prefix_, default_prefix + "/");

  const ros::WallTime w0 = ros::WallTime::now();
  try {
    lockstep_ = std::make_unique<core::VesselLockstep>(system_, dyn, lo);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file_ + ": " + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error("dynamic mode: cannot start from the statics at the file's vessel pose: " +
                             std::string(e.what()));
  }
  const double ms = (ros::WallTime::now() - w0).toSec() * 1000.0;
  // TEST HOOK (failure injection, tests only; docs/ros_interface.md): ~test_fail_line names a line
  // whose step ending at solver time ~test_fail_time [s] counts as failed.
  std::string fail_line;
  pnh_.param<std::string>("test_fail_line", fail_line, "");
  if (!fail_line.empty()) {
    std::size_t idx = system_.lines.size();
    for (std::size_t i = 0; i < system_.lines.size(); ++i)
      if (system_.lines[i].name == fail_line) idx = i;
    if (idx == system_.lines.size())
      throw std::runtime_error("parameter " + pnh_.resolveName("test_fail_line") + " = \"" + fail_line +
                               "\": no line of that name");
    const double at = doubleParam(pnh_, "test_fail_time", 1.0, [](double v) { return v > 0.0; }, "must be > 0 [s]");
    lockstep_->setFailureInjection([idx, at](std::size_t line, double t1) {
      return line == idx && std::abs(t1 - at) < 1e-9;
    });
    ROS_WARN("mooring_dynamics: TEST HOOK: line %s fails at solver time %g s (~test_fail_line)", fail_line.c_str(), at);
  }

  std::vector<std::string> names;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    const std::string& n = system_.lines[i].name;
    names.push_back(n);
    topic_names_.push_back(topicName(n));
    if (topic_names_.back() != n)
      ROS_WARN("mooring_dynamics: line \"%s\" is published as lines/%s (topic names take letters, digits and _)",
               n.c_str(), topic_names_.back().c_str());
    marker_options_.push_back(
        markerOptionsFor(system_.lineProblem(i, std::vector<double>(3 * system_.points.size(), 0.0)), marker_scale));
  }
  monitor_ = std::make_unique<VesselMonitor>(names, mo, wallNow());

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
  if (publish_fairlead_frames_ || publish_vessel_frame_) tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  wrench_pub_ = pnh_.advertise<geometry_msgs::WrenchStamped>("wrench", 100, /*latch=*/true);
  wrench_world_pub_ = pnh_.advertise<geometry_msgs::WrenchStamped>("wrench_world", 100, /*latch=*/true);
  const core::VesselWrench w0wrench = lockstep_->wrench();
  answer_wrench_ = w0wrench;
  snapshotForDiagnostics();
  fairlead_pubs_.resize(system_.lines.size());
  for (std::size_t i = 0; i < system_.lines.size(); ++i)
    state_pubs_.push_back(pnh_.advertise<CableState>("lines/" + topic_names_[i] + "/cable_state", 100, true));
  for (const core::FairleadForce& f : w0wrench.fairleads)
    if (f.line < fairlead_pubs_.size() && !fairlead_pubs_[f.line])
      fairlead_pubs_[f.line] =
          pnh_.advertise<geometry_msgs::WrenchStamped>("lines/" + topic_names_[f.line] + "/fairlead_wrench", 100, true);
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  reset_srv_ = pnh_.advertiseService("reset", &VesselNode::onReset, this);
  solve_srv_ = pnh_.advertiseService("solve_static", &VesselNode::onSolveStatic, this);
  release_srv_ = pnh_.advertiseService("release", &VesselNode::onRelease, this);
  winch_srv_ = pnh_.advertiseService("winch", &VesselNode::onWinch, this);
  std::string input;
  if (motion_source_ == "pose") {
    // TCP_NODELAY: a pose is sent at once, not held back to share a packet (Nagle), which at
    // hundreds of poses a second adds milliseconds to some of them.
    motion_sub_ = pnh_.subscribe("vessel_pose", 100, &VesselNode::onPose, this, ros::TransportHints().tcpNoDelay());
    input = motion_sub_.getTopic();
  } else if (motion_source_ == "odometry") {
    motion_sub_ = pnh_.subscribe("vessel_odom", 100, &VesselNode::onOdometry, this, ros::TransportHints().tcpNoDelay());
    input = motion_sub_.getTopic() + (use_twist_ ? " (pose and twist: Hermite path through both)"
                                                  : " (pose only, ~use_twist false: velocities from the pose sequence)");
  } else if (motion_source_ == "gnss") {
    // The fixes drive the vessel (docs/problem_format.md, dynamics.gnss): the first accepted fix
    // puts the vessel at its file pose (datum first_fix), the heading turns it, the antenna's
    // lever arm is taken off; the same core::GnssTrack as cable_sim dynamic on a track CSV.
    core::GnssOptions go = system_.dynamics.gnss;
    go.enabled = true;
    gnss_ = std::make_unique<GnssInput>(
        pnh_, go, system_.vessel.pose, Eigen::Vector2d::Zero(),
        [this](const ros::Time& stamp, const core::RigidPose& p) {
          onWorldPose(stamp, p, "fix");
          std::lock_guard<std::mutex> l(monitor_mutex_);
          monitor_->onMotionReceived(wallNow());
        },
        [this](const std::string& message) {
          {
            std::lock_guard<std::mutex> l(monitor_mutex_);
            monitor_->onMotionReceived(wallNow());
          }
          reject(message, vessel_keys::kGnssRejected);
        });
    input = gnss_->topics();
  } else {
    tf_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / poll_rate), &VesselNode::pollTf, this);
    input = "tf " + frame_id_ + " <- " + vessel_frame_ + " polled at " + formatNumber(poll_rate) + " Hz";
  }
  diag_timer_ = nh_.createWallTimer(ros::WallDuration(diag_period), &VesselNode::onDiagnosticsTimer, this);
  if (publish_fairlead_frames_) publishAnchorFrames();
  if (decimated_) {
    monitor_->onSolverLag(0.0);
    worker_ = std::make_unique<SampleWorker>(
        [this](const SampleWorker::Sample& q) {
          std::lock_guard<std::mutex> l(solver_mutex_);
          solveSample(q.stamp, q.pose, q.field, q.has_twist ? &q.twist : nullptr);
        },
        [this](const SampleWorker::Sample& q, double lag, long skipped) { onSolverBehind(q, lag, skipped); },
        max_solver_lag, 0.5 * lo.solve_interval);
    input += "; decimated: a solve every " + formatNumber(lo.solve_interval) +
             " s on a solver thread, every pose answered at once from the last solve (~solve_interval)";
  }

  ROS_INFO("mooring_dynamics: moored vessel, dynamic (lockstep) mode: \"%s\" from %s: %zu lines, %zu points; statics "
           "at the file's pose in %.0f ms; dt %g s; %d thread(s); vessel motion from %s; world frame %s, body frame %s",
           system_.name.c_str(), file_.c_str(), system_.lines.size(), system_.points.size(), ms, dyn.dt, threads,
           input.c_str(), frame_id_.c_str(), vessel_frame_.c_str());
}

void VesselNode::onPose(const geometry_msgs::PoseStamped::ConstPtr& msg) {
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose, "pose");
}

void VesselNode::onOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  // REP 105: the pose is child_frame_id's in header.frame_id, the twist in child_frame_id's axes:
  // the vessel's body frame. VesselLockstep rotates it into the world with the sample's
  // orientation (v = R v_body, omega = R omega_body), as cable_sim dynamic does with a motion
  // table's velocity columns, so that both give the same bits. (A pose in another frame than
  // ~frame_id is transformed; the body-frame twist needs no transform as long as that frame does
  // not move against ~frame_id.) With ~use_twist false: the pose only, velocities from the poses.
  if (!use_twist_) {
    onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.pose, "pose.pose");
    return;
  }
  core::BodyTwist tw;
  const auto& l = msg->twist.twist.linear;
  const auto& a = msg->twist.twist.angular;
  tw.linear = Eigen::Vector3d(l.x, l.y, l.z);
  tw.angular = Eigen::Vector3d(a.x, a.y, a.z);
  onMotion(msg->header.stamp, msg->header.frame_id, msg->pose.pose, "pose.pose", &tw);
}

void VesselNode::pollTf(const ros::WallTimerEvent&) {
  geometry_msgs::TransformStamped tr;
  try {
    tr = tf_buffer_->lookupTransform(frame_id_, vessel_frame_, ros::Time(0));
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: no transform %s <- %s (~vessel_frame): %s; state kept",
                      frame_id_.c_str(), vessel_frame_.c_str(), e.what());
    return;  // silence, reported by the diagnostics as such
  }
  if (tr.header.stamp == last_tf_stamp_) return;  // nothing new since the last poll
  last_tf_stamp_ = tr.header.stamp;
  geometry_msgs::Pose p;
  p.position.x = tr.transform.translation.x;
  p.position.y = tr.transform.translation.y;
  p.position.z = tr.transform.translation.z;
  p.orientation = tr.transform.rotation;
  onMotion(tr.header.stamp, frame_id_, p, "transform");
}

void VesselNode::reject(const std::string& message, const char* key) {
  ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: vessel pose dropped: %s; state kept", message.c_str());
  std::lock_guard<std::mutex> l(monitor_mutex_);
  monitor_->onInputRejected(wallNow(), message, key);
}

void VesselNode::onMotion(const ros::Time& stamp, const std::string& frame, const geometry_msgs::Pose& pose_in,
                          const std::string& field, const core::BodyTwist* twist) {
  // Counted after it is handled: the answer (decimated mode) waits for no lock the solver
  // thread may hold.
  onMotionIn(stamp, frame, pose_in, field, twist);
  std::lock_guard<std::mutex> l(monitor_mutex_);
  monitor_->onMotionReceived(wallNow());
}

void VesselNode::onMotionIn(const ros::Time& stamp, const std::string& frame, const geometry_msgs::Pose& pose_in,
                            const std::string& field, const core::BodyTwist* twist) {
  if (stamp.isZero()) {
    reject("header.stamp = 0: lockstep mode needs stamped poses", vessel_keys::kZeroStamp);
    return;
  }
  geometry_msgs::Pose pose = pose_in;
  if (!frame.empty() && frame != frame_id_) {
    geometry_msgs::PoseStamped in, out;
    in.header.stamp = stamp;
    in.header.frame_id = frame;
    in.pose = pose_in;
    try {
      tf_buffer_->transform(in, out, frame_id_, ros::Duration(tf_timeout_));
    } catch (const tf2::TransformException& e) {
      reject("header.frame_id = \"" + frame + "\": no transform to \"" + frame_id_ + "\" (~frame_id) at stamp " +
                 formatNumber(stamp.toSec()) + ": " + e.what(),
             vessel_keys::kUnknownFrame);
      return;
    }
    pose = out.pose;
  }
  onWorldPose(stamp, toRigidPose(pose), field, twist);
}

void VesselNode::onWorldPose(const ros::Time& stamp, const core::RigidPose& rp, const std::string& field,
                             const core::BodyTwist* twist) {
  if (decimated_) {
    answerAndQueue(stamp, rp, field, twist);
    return;
  }
  std::lock_guard<std::mutex> l(solver_mutex_);
  solveSample(stamp, rp, field, twist);
}

void VesselNode::answerAndQueue(const ros::Time& stamp, const core::RigidPose& rp, const std::string& field,
                                const core::BodyTwist* twist) {
  // Answered unless malformed or out of order (the solver thread's lockstep counts those as dropped).
  const bool valid = rp.validate(field).empty() && (!twist || twist->validate("twist").empty());
  bool answered = false;
  {
    std::lock_guard<std::mutex> l(answer_mutex_);
    const bool in_order = !answered_any_ || stamp > last_answered_ || (last_answered_ - stamp).toSec() > loop_back_;
    if (valid && in_order) {
      wrench_pub_.publish(toBodyWrench(answer_wrench_, vessel_frame_, stamp));
      wrench_world_pub_.publish(toWorldWrench(answer_wrench_, frame_id_, stamp));
      answered_any_ = true;
      last_answered_ = stamp;
      answered = true;
    }
  }
  if (answered) {
    std::lock_guard<std::mutex> l(monitor_mutex_);
    monitor_->onAnswered();
  }
  SampleWorker::Sample q;
  q.stamp = stamp;
  q.pose = rp;
  q.field = field;
  q.has_twist = twist != nullptr;
  if (twist) q.twist = *twist;
  worker_->push(std::move(q));
}

double VesselNode::sampleTime(const ros::Time& stamp, const core::RigidPose& rp, const std::string& field) {
  // The epoch is the first stamp of a usable pose; VesselLockstep checks (and counts) every sample.
  if (!have_epoch_ && rp.validate(field).empty()) {
    have_epoch_ = true;
    epoch_ = stamp;
  }
  return have_epoch_ ? (stamp - epoch_).toSec() : 0.0;
}

void VesselNode::onSolverBehind(const SampleWorker::Sample& q, double lag, long skipped) {
  std::lock_guard<std::mutex> l(solver_mutex_);
  const double t = sampleTime(q.stamp, q.pose, q.field);
  const ros::WallTime w0 = ros::WallTime::now();
  const core::VesselLockstep::Result r = lockstep_->restartAt(
      t, q.pose,
      "the solver fell " + formatNumber(lag) + " s behind the poses (~max_solver_lag " + formatNumber(max_solver_lag_) +
          " s): " + std::to_string(skipped) + " pose(s) skipped, the lines restarted from statics at the newest");
  {
    std::lock_guard<std::mutex> m(monitor_mutex_);
    monitor_->onThinned(skipped);
  }
  handle(r, q.stamp, (ros::WallTime::now() - w0).toSec(), 0.0);
}

void VesselNode::solveSample(const ros::Time& stamp, const core::RigidPose& rp, const std::string& field,
                             const core::BodyTwist* twist) {
  const double t = sampleTime(stamp, rp, field);
  const double before = lockstep_->solverTime();
  const ros::WallTime w0 = ros::WallTime::now();
  core::VesselLockstep::Result r = lockstep_->onSample(t, rp, twist);
  const double spent = (ros::WallTime::now() - w0).toSec();
  if (r.outcome == core::VesselLockstep::Outcome::Dropped && r.message.rfind("pose", 0) == 0)
    r.message = field + r.message.substr(4);  // name the message field
  else if (r.outcome == core::VesselLockstep::Outcome::Dropped && r.message.rfind("twist", 0) == 0)
    r.message = "twist.twist" + r.message.substr(5);  // nav_msgs/Odometry's field
  const bool advanced = r.outcome == core::VesselLockstep::Outcome::Advanced ||
                        r.outcome == core::VesselLockstep::Outcome::LinesRestarted;
  handle(r, stamp, spent, advanced ? lockstep_->solverTime() - before : 0.0);
}

void VesselNode::handle(const core::VesselLockstep::Result& r, const ros::Time& stamp, double wall_spent,
                        double advanced) {
  using O = core::VesselLockstep::Outcome;
  std::vector<double> top;
  std::vector<core::TensionPeak> peaks;
  if (r.publish)
    for (std::size_t i = 0; i < system_.lines.size(); ++i) {
      const core::StaticResult line = lockstep_->dynamics().line(i);
      top.push_back(line.topTension());
      peaks.push_back(core::tensionPeak(system_.materials, system_.lines[i].segments, line.nodes));
    }
  std::vector<long> fallback(system_.lines.size(), 0);
  for (std::size_t i = 0; i < fallback.size(); ++i) fallback[i] = lockstep_->dynamics().lineFallbackSteps(i);
  std::string last_event;
  if (r.outcome != core::VesselLockstep::Outcome::Held) snapshotForDiagnostics();
  {
    std::lock_guard<std::mutex> l(monitor_mutex_);
    monitor_->onResult(r, wallNow(), wall_spent, advanced, r.publish ? &top : nullptr, lockstep_->solverTime(),
                       r.publish ? &peaks : nullptr);
    monitor_->onFallbackSteps(fallback);
    last_event = monitor_->lastEvent();
    if (r.outcome != core::VesselLockstep::Outcome::Dropped) {
      have_processed_ = true;
      last_processed_ = stamp;
    }
  }
  const double ms = wall_spent * 1000.0;
  switch (r.outcome) {
    case O::Dropped:
      ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: vessel pose at stamp %.6f dropped: %s; state kept",
                        stamp.toSec(), r.message.c_str());
      return;
    case O::Started:
      ROS_INFO("mooring_dynamics: vessel lockstep run starts at stamp %.6f (%.0f ms)%s%s", stamp.toSec(), ms,
               r.message.empty() ? "" : ": ", r.message.c_str());
      break;
    case O::Reinitialised:
      ROS_WARN("mooring_dynamics: stamp %.6f: restarted from statics: %s", stamp.toSec(), r.message.c_str());
      break;
    case O::Failed:  // the last good state is published again, converged false (not this stamp's)
    case O::RecoveredFailure:
    case O::LinesRestarted:
      ROS_ERROR("mooring_dynamics: stamp %.6f: %s", stamp.toSec(), last_event.c_str());
      break;
    case O::Held:
      return;  // answered from the last solve (decimated mode)
    case O::Advanced:
      ROS_DEBUG("mooring_dynamics: stamp %.6f: solver t = %.3f s, %.1f ms", stamp.toSec(), lockstep_->solverTime(), ms);
      break;
  }
  failed_sample_ = r.outcome == O::Failed;
  if (r.publish) publish(stamp);
}

void VesselNode::publish(const ros::Time& stamp) {
  const core::VesselWrench w = lockstep_->wrench();
  if (decimated_) {  // the poses' answers carry it from now on
    std::lock_guard<std::mutex> l(answer_mutex_);
    answer_wrench_ = w;
  } else {
    wrench_pub_.publish(toBodyWrench(w, vessel_frame_, stamp));
    wrench_world_pub_.publish(toWorldWrench(w, frame_id_, stamp));
  }
  const core::RigidPose& pose = lockstep_->dynamics().vesselPose();
  for (const core::FairleadForce& f : w.fairleads)
    if (f.line < fairlead_pubs_.size() && fairlead_pubs_[f.line])
      fairlead_pubs_[f.line].publish(toFairleadWrench(f, pose, frame_id_, stamp));
  const std::vector<core::LineEventRecord> events = lockstep_->dynamics().lineEvents();
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    CableState cs = toCableState(lockstep_->dynamics().line(i), system_.lines[i].name, frame_id_, stamp);
    cs.converged = !failed_sample_;
    cs.winch_rate = lockstep_->dynamics().lineWinchRate(i);
    for (const core::LineEventRecord& e : events)
      if (e.line == system_.lines[i].name) cs.events.push_back(core::lineEventText(e));
    state_pubs_[i].publish(cs);
  }
  have_output_ = true;
  last_stamp_ = stamp;
  publishMarkersAndFrames(stamp);
}

void VesselNode::publishMarkersAndFrames(const ros::Time& stamp) {
  const core::VesselWrench w = lockstep_->wrench();
  const core::RigidPose& pose = lockstep_->dynamics().vesselPose();
  if (tf_broadcaster_) {
    std::vector<geometry_msgs::TransformStamped> frames;
    if (publish_vessel_frame_) frames.push_back(vesselTransform(pose, frame_id_, vessel_frame_, stamp));
    if (publish_fairlead_frames_)
      for (const core::FairleadForce& f : w.fairleads)
        frames.push_back(fairleadTransform(f, pose, frame_id_, frame_prefix_ + system_.points[f.point].name, stamp));
    tf_broadcaster_->sendTransform(frames);
  }
  if (marker_pub_.getNumSubscribers() == 0) return;
  std::vector<CableState> states;
  double tmin = 1e300, tmax = -1e300;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    states.push_back(toCableState(lockstep_->dynamics().line(i), system_.lines[i].name, frame_id_, stamp));
    for (double t : states.back().tension) {
      tmin = std::min(tmin, t);
      tmax = std::max(tmax, t);
    }
  }
  // Every line on one tension scale, each in a namespace of its own (the colour bar once).
  visualization_msgs::MarkerArray all;
  for (std::size_t i = 0; i < states.size(); ++i) {
    MarkerOptions mo = marker_options_[i];
    mo.tension_min = tmin;
    mo.tension_max = tmax;
    mo.sea_surface = i == 0;
    visualization_msgs::MarkerArray m = makeMarkers(states[i], system_.environment, mo);
    for (auto& mk : m.markers) {
      if (i > 0 && mk.ns == "scale") continue;
      mk.ns = topic_names_[i] + "/" + mk.ns;
      all.markers.push_back(mk);
    }
  }
  marker_pub_.publish(all);
}

void VesselNode::publishAnchorFrames() {
  // Anchors and other fixed points do not move: latched on /tf_static once. This also puts
  // ~frame_id on tf before the first pose arrives (rviz's fixed frame).
  std::vector<geometry_msgs::TransformStamped> frames;
  const ros::Time now = ros::Time::now();
  for (const core::SystemPoint& p : system_.points) {
    if (p.type != core::SystemPoint::Type::Anchor && p.type != core::SystemPoint::Type::Fixed) continue;
    core::RigidPose at;
    at.position = Eigen::Vector3d(p.x, p.y, p.z);
    frames.push_back(vesselTransform(at, frame_id_, frame_prefix_ + p.name, now));
  }
  if (frames.empty()) return;
  static_broadcaster_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  static_broadcaster_->sendTransform(frames);
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
