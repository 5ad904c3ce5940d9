#include "mooring_dynamics/ros/nodes/system_dynamic_node.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/numerics/thread_pool.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/nodes/params.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

constexpr double kWarnPeriod = 5.0;  // [s] throttle of repeated warnings
// A grid point is reached when ROS time is within this fraction of dt_out of it (the stamps are
// whole nanoseconds, the grid k * dt_out is not): the same slack as cable_sim's sample count.
constexpr double kGridSlack = 1e-9;

std::string topicName(const std::string& name) {
  std::string out = name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "l_" + out;
  return out;
}

}  // namespace

double SystemDynamicNode::wallNow() const { return (ros::WallTime::now() - wall0_).toSec(); }

SystemDynamicNode::SystemDynamicNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh), wall0_(ros::WallTime::now()) {
  if (!pnh_.getParam("problem_file", file_) || file_.empty())
    throw std::runtime_error("parameter " + pnh_.resolveName("problem_file") + ": a system file is needed");
  system_ = core::loadSystemFromFile(file_);  // throws core::ProblemError naming the key
  pnh_.param<std::string>("frame_id", frame_id_, "world");
  if (frame_id_.empty()) throw std::runtime_error("parameter " + pnh_.resolveName("frame_id") + ": must not be empty");
  threads_ = intParam(pnh_, "threads", core::ThreadPool::hardwareThreads(), 1, "must be >= 1");
  dyn_ = system_.dynamics;
  dyn_.dt = doubleParam(pnh_, "dt", dyn_.dt, [](double v) { return v > 0.0; }, "must be > 0 [s]");
  dyn_.threads = 1;  // each line on one thread; `threads` lines side by side (as cable_sim dynamic)
  dout_ = dyn_.output_interval > 0.0 ? dyn_.output_interval : dyn_.dt;
  loop_back_ = doubleParam(pnh_, "loop_back", 1.0, [](double v) { return v > 0.0; }, "must be > 0 [s]");
  max_gap_ = doubleParam(pnh_, "max_gap", 5.0, [](double) { return true; }, "");
  VesselMonitorOptions mo;
  mo.motion_timeout = doubleParam(pnh_, "clock_timeout", mo.motion_timeout, [](double v) { return v > 0.0; },
                                  "must be > 0 [s]");
  mo.min_real_time_factor = doubleParam(pnh_, "min_real_time_factor", mo.min_real_time_factor,
                                        [](double v) { return v >= 0.0; }, "must be >= 0");
  mo.max_utilization = doubleParam(pnh_, "max_utilization", mo.max_utilization, [](double v) { return v > 0.0; },
                                   "must be > 0 (tension over minimum breaking load)");
  const double diag_period = doubleParam(pnh_, "diagnostics_period", 1.0, [](double v) { return v > 0.0; },
                                         "must be > 0 [s]");
  const double marker_scale = doubleParam(pnh_, "marker_scale", 1.0, [](double v) { return v > 0.0; }, "must be > 0");
  {
    core::SystemProblem check = system_;
    check.dynamics = dyn_;
    const std::string bad = check.validate();
    if (!bad.empty()) throw std::invalid_argument(file_ + ": " + bad + " (with ~dt = " + formatNumber(dyn_.dt) + " s)");
  }

  const ros::WallTime w0 = ros::WallTime::now();
  try {
    sim_ = std::make_unique<core::SystemDynamics>(system_, dyn_, threads_);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file_ + ": " + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error("dynamic mode: cannot start from the system's statics: " + std::string(e.what()));
  }
  const double ms = (ros::WallTime::now() - w0).toSec() * 1000.0;

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
    state_pubs_.push_back(pnh_.advertise<CableState>("lines/" + topic_names_.back() + "/cable_state", 100, true));
  }
  for (const core::SystemPoint& p : system_.points) {
    const std::string t = topicName(p.name);
    wrench_pubs_.push_back(pnh_.advertise<geometry_msgs::WrenchStamped>("points/" + t + "/wrench", 100, true));
    position_pubs_.push_back(p.free() ? pnh_.advertise<geometry_msgs::PointStamped>("points/" + t + "/position", 100, true)
                                      : ros::Publisher());
  }
  monitor_ = std::make_unique<VesselMonitor>(names, mo, wallNow());
  marker_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  reset_srv_ = pnh_.advertiseService("reset", &SystemDynamicNode::onReset, this);
  solve_srv_ = pnh_.advertiseService("solve_static", &SystemDynamicNode::onSolveStatic, this);
  std::string clock;
  if (ros::Time::isSimTime()) {
    // Only the latest clock matters: every grid point up to it is computed in turn.
    clock_sub_ = nh_.subscribe("/clock", 1, &SystemDynamicNode::onClock, this);
    clock = "/clock (use_sim_time)";
  } else {
    tick_timer_ = nh_.createWallTimer(ros::WallDuration(dout_), &SystemDynamicNode::onWallTick, this);
    clock = "the wall clock (a tick every " + formatNumber(dout_) + " s)";
  }
  diag_timer_ = nh_.createWallTimer(ros::WallDuration(diag_period), &SystemDynamicNode::onDiagnosticsTimer, this);
  std::size_t free_points = 0;
  for (const auto& p : system_.points) free_points += p.free() ? 1 : 0;
  ROS_INFO("mooring_dynamics: system of lines, dynamic mode: \"%s\" from %s: %zu lines, %zu points (%zu free), %zu "
           "independent group(s); statics in %.0f ms; dt %g s, states every %g s of ROS time from %s; %d thread(s); "
           "frame %s",
           system_.name.c_str(), file_.c_str(), system_.lines.size(), system_.points.size(), free_points,
           sim_->lineGroups().size(), ms, dyn_.dt, dout_, clock.c_str(), threads_, frame_id_.c_str());
}

void SystemDynamicNode::onClock(const rosgraph_msgs::Clock::ConstPtr& msg) { onTime(msg->clock); }

void SystemDynamicNode::onWallTick(const ros::WallTimerEvent&) { onTime(ros::Time::now()); }

bool SystemDynamicNode::start(const ros::Time& stamp, core::VesselLockstep::Outcome outcome, const std::string& why) {
  const ros::WallTime w0 = ros::WallTime::now();
  if (!pristine_) {
    try {
      sim_ = std::make_unique<core::SystemDynamics>(system_, dyn_, threads_);
    } catch (const std::exception& e) {
      core::VesselLockstep::Result r;
      r.message = "cannot restart from statics: " + std::string(e.what());
      handle(r, stamp, (ros::WallTime::now() - w0).toSec(), 0.0);
      return false;
    }
  }
  pristine_ = false;
  started_ = true;
  epoch_ = stamp;
  last_time_ = stamp;
  k_ = 0;
  core::VesselLockstep::Result r;
  r.outcome = outcome;
  r.publish = true;
  r.message = why;
  handle(r, stamp, (ros::WallTime::now() - w0).toSec(), 0.0);
  return true;
}

void SystemDynamicNode::onTime(const ros::Time& now) {
  using O = core::VesselLockstep::Outcome;
  monitor_->onMotionReceived(wallNow());
  if (now.isZero()) return;  // use_sim_time before the first /clock: no time yet
  if (!started_) {
    start(now, O::Started, "");
    return;
  }
  if (now < last_time_) {
    const double back = (last_time_ - now).toSec();
    if (back > loop_back_)
      start(now, O::Reinitialised, "ROS time went back by " + formatNumber(back) + " s (bag loop?)");
    return;  // a small step back (clock jitter): nothing to do until time passes the next grid point
  }
  if (max_gap_ > 0.0 && (now - last_time_).toSec() > max_gap_) {
    start(now, O::Reinitialised,
          "ROS time jumped ahead by " + formatNumber((now - last_time_).toSec()) + " s (more than ~max_gap = " +
              formatNumber(max_gap_) + " s)");
    return;
  }
  last_time_ = now;
  const long k_max = static_cast<long>(std::floor((now - epoch_).toSec() / dout_ + kGridSlack));
  while (k_ < k_max && ros::ok()) {
    const long k = k_ + 1;
    const double target = static_cast<double>(k) * dout_;  // as cable_sim dynamic: advanceTo(k * dt_out)
    const ros::Time stamp = epoch_ + ros::Duration(target);
    const double before = sim_->time();
    const ros::WallTime w0 = ros::WallTime::now();
    std::string why;
    const bool ok = sim_->advanceTo(target, &why);
    const double spent = (ros::WallTime::now() - w0).toSec();
    if (!ok) {
      // A group failed and even its statics failed: every line restarts from statics here.
      (void)spent;
      start(stamp, O::RecoveredFailure, "restarted from statics after a failure: " + why);
      return;
    }
    k_ = k;
    core::VesselLockstep::Result r;
    r.outcome = O::Advanced;
    r.publish = true;
    for (const core::LineGroupRestart& g : sim_->lastRestarts()) {
      std::string names;
      for (std::size_t i : g.lines) {
        names += (names.empty() ? "" : ", ") + system_.lines[i].name;
        r.failed_lines.push_back(i);
      }
      r.outcome = O::LinesRestarted;
      r.message += (r.message.empty() ? "" : "; ") + g.reason + " (t = " + formatNumber(g.time) +
                   " s); restarted from statics: " + names + "; the other lines go on";
    }
    handle(r, stamp, spent, sim_->time() - before);
  }
}

void SystemDynamicNode::handle(const core::VesselLockstep::Result& r, const ros::Time& stamp, double wall_spent,
                               double advanced) {
  using O = core::VesselLockstep::Outcome;
  std::vector<double> top;
  std::vector<core::TensionPeak> peaks;
  if (r.publish)
    for (std::size_t i = 0; i < system_.lines.size(); ++i) {
      const core::StaticResult line = sim_->line(i);
      top.push_back(line.topTension());
      peaks.push_back(core::tensionPeak(system_.materials, system_.lines[i].segments, line.nodes));
    }
  monitor_->onResult(r, wallNow(), wall_spent, advanced, r.publish ? &top : nullptr, sim_->time(),
                     r.publish ? &peaks : nullptr);
  switch (r.outcome) {
    case O::Dropped:
      ROS_ERROR_THROTTLE(kWarnPeriod, "mooring_dynamics: stamp %.6f: %s; last state kept", stamp.toSec(),
                         r.message.c_str());
      return;
    case O::Started:
      ROS_INFO("mooring_dynamics: system run starts at ROS time %.6f", stamp.toSec());
      break;
    case O::Reinitialised:
      ROS_WARN("mooring_dynamics: ROS time %.6f: restarted from statics: %s", stamp.toSec(), r.message.c_str());
      break;
    case O::Failed:  // not produced here: a failed group restarts (above)
    case O::RecoveredFailure:
    case O::LinesRestarted:
      ROS_ERROR("mooring_dynamics: ROS time %.6f: %s", stamp.toSec(), monitor_->lastEvent().c_str());
      break;
    case O::Held:  // not produced here: no vessel lockstep
    case O::Advanced:
      break;
  }
  if (r.publish) publish(stamp);
}

void SystemDynamicNode::publish(const ros::Time& stamp) {
  last_stamp_ = stamp;
  std::vector<CableState> states;
  double tmin = 1e300, tmax = -1e300;
  for (std::size_t i = 0; i < system_.lines.size(); ++i) {
    states.push_back(toCableState(sim_->line(i), system_.lines[i].name, frame_id_, stamp));
    state_pubs_[i].publish(states.back());
    for (double t : states.back().tension) {
      tmin = std::min(tmin, t);
      tmax = std::max(tmax, t);
    }
  }
  const std::vector<core::SystemPointResult> pts = sim_->points();
  for (std::size_t p = 0; p < pts.size(); ++p) {
    geometry_msgs::WrenchStamped w;
    w.header.stamp = stamp;
    w.header.frame_id = frame_id_;
    w.wrench.force.x = pts[p].fx;
    w.wrench.force.y = pts[p].fy;
    w.wrench.force.z = pts[p].fz;
    wrench_pubs_[p].publish(w);
    if (position_pubs_[p]) {
      geometry_msgs::PointStamped x;
      x.header = w.header;
      x.point.x = pts[p].x;
      x.point.y = pts[p].y;
      x.point.z = pts[p].z;
      position_pubs_[p].publish(x);
    }
  }
  if (marker_pub_.getNumSubscribers() == 0) return;
  // Every line on one tension scale, each in a namespace of its own (the colour bar once).
  visualization_msgs::MarkerArray all;
  for (std::size_t i = 0; i < states.size(); ++i) {
    MarkerOptions mo = marker_options_[i];
    mo.tension_min = tmin;
    mo.tension_max = tmax;
    mo.sea_surface = i == 0;
    mo.label_name = system_.lines[i].name;  // legs that meet at one point stack their labels there
    mo.label_row = static_cast<int>(i);
    visualization_msgs::MarkerArray m = makeMarkers(states[i], system_.environment, mo);
    for (auto& mk : m.markers) {
      if (i > 0 && mk.ns == "scale") continue;
      mk.ns = topic_names_[i] + "/" + mk.ns;
      all.markers.push_back(mk);
    }
  }
  marker_pub_.publish(all);
}

void SystemDynamicNode::onDiagnosticsTimer(const ros::WallTimerEvent&) {
  const double now = wallNow();
  if (monitor_->silent(now) && monitor_->everReceived())
    ROS_WARN_THROTTLE(kWarnPeriod, "mooring_dynamics: ROS time has not moved for %.1f s (wall); last state kept",
                      monitor_->secondsSinceMotion(now));
  diag_pub_.publish(toDiagnostics(monitor_->summarise(now), ros::this_node::getName(), "system lockstep", system_.name,
                                  ros::Time::now()));
}

bool SystemDynamicNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (!started_) {
    res.success = true;
    res.message = "nothing to reset: ROS time has not started the run yet";
    return true;
  }
  const ros::Time at = epoch_ + ros::Duration(static_cast<double>(k_) * dout_);
  res.success = start(at, core::VesselLockstep::Outcome::Reinitialised, "reset");
  res.message = res.success ? "every line restarted from statics at ROS time " + formatNumber(at.toSec())
                            : "reset failed: " + monitor_->lastEvent();
  ROS_INFO("mooring_dynamics: ~reset: %s", res.message.c_str());
  return true;
}

bool SystemDynamicNode::onSolveStatic(SystemStatics::Request& req, SystemStatics::Response& res) {
  const ros::WallTime t0 = ros::WallTime::now();
  try {
    toSystemStaticsResponse(system_, core::solveSystemStatic(system_), res);
  } catch (const std::exception& e) {
    res = SystemStatics::Response();
    res.success = false;
    res.message = std::string("system statics: ") + e.what();
  }
  if (res.success && req.reinitialise && started_) {
    const ros::Time at = epoch_ + ros::Duration(static_cast<double>(k_) * dout_);
    res.reinitialised = start(at, core::VesselLockstep::Outcome::Reinitialised, "~solve_static with reinitialise");
  }
  ROS_INFO("mooring_dynamics: ~solve_static, %.0f ms: %s%s", (ros::WallTime::now() - t0).toSec() * 1000.0,
           res.message.c_str(), res.reinitialised ? " (run restarted from it)" : "");
  return true;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
