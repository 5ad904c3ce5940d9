// ROS node state for a system of lines without a moored vessel in dynamic mode (~mode dynamic with
// a system file: multi-leg and branched moorings with free buoys and junction bodies; issue 19).
//
// Nothing of such a system is driven from outside: its anchors and fixed points stay, its free
// points move by their own force balance (core::SystemDynamics), exactly what `cable_sim dynamic`
// runs on the file. So the node follows **ROS time**: the first time it sees is the start (the
// system's statics, published with that stamp), and whenever ROS time passes t0 + k * dt_out
// (dt_out = dynamics.output_interval, else ~dt) the system is advanced to k * dt_out, each grid
// point in turn, as `cable_sim dynamic` does, and published with the stamp t0 + k * dt_out. Under
// use_sim_time the node reads /clock itself (a simulator's clock, or `rosbag play --clock`); else
// a wall timer ticks every dt_out. The states depend only on the grid, not on when the clock
// messages come, so live, replayed and CLI runs give the same bits.
//
// Parameters (private; docs/ros_interface.md, "Systems of lines", dynamic mode):
//   ~problem_file, ~frame_id, ~marker_scale, ~dt, ~threads, ~loop_back, ~max_gap,
//   ~clock_timeout, ~diagnostics_period, ~min_real_time_factor
// Publications: ~lines/<line>/cable_state, ~points/<point>/wrench, ~points/<point>/position (free
// points), ~markers (when subscribed), /diagnostics; the anchors and fixed points on /tf_static
// (runNode, ~publish_anchor_frames). Services: ~reset (std_srvs/Trigger),
// ~solve_static (mooring_dynamics/SystemStatics).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Trigger.h>

#include "mooring_dynamics/SystemStatics.h"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class SystemDynamicNode {
 public:
  /// Reads parameters, loads the system, solves its statics (the start of the run), advertises
  /// and starts following ROS time. Throws core::ProblemError (bad file), std::runtime_error (bad
  /// parameter, named with its value and the constraint; statics fail) or std::invalid_argument.
  SystemDynamicNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// ROS time is now `now` (public for tests): advance through every grid point up to it.
  void onTime(const ros::Time& now);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSolveStatic(SystemStatics::Request& req, SystemStatics::Response& res);
  const core::SystemProblem& system() const { return system_; }

 private:
  void onClock(const rosgraph_msgs::Clock::ConstPtr& msg);
  void onWallTick(const ros::WallTimerEvent&);
  void onDiagnosticsTimer(const ros::WallTimerEvent&);
  /// (Re)start from statics at ROS time `stamp` (publishes the static state with that stamp).
  bool start(const ros::Time& stamp, core::VesselLockstep::Outcome outcome, const std::string& why);
  void handle(const core::VesselLockstep::Result& r, const ros::Time& stamp, double wall_spent, double advanced);
  void publish(const ros::Time& stamp);
  double wallNow() const;

  ros::NodeHandle nh_, pnh_;
  core::SystemProblem system_;
  core::DynamicOptions dyn_;
  int threads_ = 1;
  std::string file_, frame_id_ = "world";
  double dout_ = 0.1, loop_back_ = 1.0, max_gap_ = 5.0;
  std::vector<std::string> topic_names_;
  std::vector<MarkerOptions> marker_options_;
  std::unique_ptr<core::SystemDynamics> sim_;
  bool pristine_ = true;  ///< sim_ is the file's static start, not advanced
  std::unique_ptr<VesselMonitor> monitor_;
  ros::Publisher marker_pub_, diag_pub_;
  std::vector<ros::Publisher> state_pubs_, wrench_pubs_, position_pubs_;
  ros::Subscriber clock_sub_;
  ros::ServiceServer reset_srv_, solve_srv_;
  ros::WallTimer tick_timer_, diag_timer_;
  ros::WallTime wall0_;
  bool started_ = false;
  ros::Time epoch_;       ///< ROS time of the run's start (solver time 0)
  ros::Time last_time_;   ///< the latest ROS time seen
  long k_ = 0;            ///< grid points reached: solver time k_ * dout_
  ros::Time last_stamp_;  ///< stamp of the last published state
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
