// ROS node state for a moored vessel in lockstep (~mode dynamic with a system file that has a
// `vessel:` section; issue 19, DESIGN.md section 6). The vessel's pose samples go through
// core::VesselLockstep, the same class `cable_sim dynamic` feeds a motion table through, so the
// node (live or replaying a bag) and the CLI give the same wrench series bit for bit. This class
// only wires topics, tf, services, diagnostics and logs; messages come from converter.hpp.
//
// Parameters (private namespace; full table with units and defaults: docs/ros_interface.md,
// "Moored vessel"):
//   ~problem_file     a system file with a `vessel:` section
//   ~frame_id         world frame of the poses and world-frame outputs (default "world")
//   ~vessel_frame     body frame (default: vessel.frame of the file)
//   ~motion_source    "pose" (~vessel_pose, PoseStamped), "odometry" (~vessel_odom, Odometry: its
//                     pose, and its twist unless ~use_twist is false), "tf" (poll ~frame_id <-
//                     ~vessel_frame at ~tf_poll_rate) or "gnss" (~fix NavSatFix and ~heading,
//                     through the file's dynamics.gnss options, as cable_sim dynamic on a track)
//   ~use_twist        odometry: take the velocities at the samples from the twist (default true)
//   ~threads          threads that advance the lines (default: hardware threads; same bits for any)
//   ~dt, ~start_tolerance, ~start_angle_tolerance, ~loop_back, ~max_gap, ~max_speed, ~jumps_to_reinit
//   ~tf_timeout, ~tf_poll_rate, ~motion_timeout, ~diagnostics_period, ~min_real_time_factor
//   ~marker_scale, ~publish_fairlead_frames, ~frame_prefix, ~publish_vessel_frame
//   ~solve_interval   [s] 0 (default): every pose solved in the callback, in lockstep, bit for bit
//                     as cable_sim; > 0 (a fast simulator): decimated mode, each pose answered at
//                     once on ~wrench and ~wrench_world (its stamp) with the last solve's wrench,
//                     a pose solved on a solver thread when solve_interval has passed since the
//                     last solved one (core::VesselLockstepOptions::solve_interval)
//   ~max_solver_lag   [s] decimated mode: a solver further behind restarts the lines from statics
//                     at the newest pose (it could not catch up by solving)
// Publications: ~wrench, ~wrench_world, ~lines/<line>/cable_state, ~lines/<line>/fairlead_wrench,
// ~markers (when subscribed), /diagnostics, /tf (optional fairlead and vessel frames), /tf_static
// (anchors, with the fairlead frames). Services: ~reset (std_srvs/Trigger), ~release (ReleaseLine), ~solve_static
// (mooring_dynamics/VesselStatics).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "mooring_dynamics/ReleaseLine.h"
#include "mooring_dynamics/Winch.h"
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "mooring_dynamics/VesselStatics.h"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/nodes/gnss_input.hpp"
#include "mooring_dynamics/ros/nodes/sample_worker.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

class VesselNode {
 public:
  /// Reads parameters, loads the system, solves its statics at the file's pose (the start of the
  /// run), advertises and subscribes. Throws core::ProblemError (bad file), std::runtime_error
  /// (bad parameter: named with its value and the constraint; statics fail) or
  /// std::invalid_argument (invalid system).
  VesselNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  ~VesselNode();

  /// One pose sample (public for tests): `frame` its frame (empty: ~frame_id), `field` the message
  /// field of the pose for messages.
  /// `twist`: the body-frame twist of the sample (odometry with ~use_twist), or null.
  void onMotion(const ros::Time& stamp, const std::string& frame, const geometry_msgs::Pose& pose,
                const std::string& field, const core::BodyTwist* twist = nullptr);
  /// One pose sample already in ~frame_id (world, REP 103): the lockstep step and its outputs.
  void onWorldPose(const ros::Time& stamp, const core::RigidPose& pose, const std::string& field,
                   const core::BodyTwist* twist = nullptr);

  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSolveStatic(VesselStatics::Request& req, VesselStatics::Response& res);
  /// ~winch: command the winch at a line's fairlead (Winch).
  bool onWinch(Winch::Request& req, Winch::Response& res);
  /// ~release: let go an end of a line (ReleaseLine).
  bool onRelease(ReleaseLine::Request& req, ReleaseLine::Response& res);

  /// Decimated mode (~solve_interval > 0): blocks until every pose received so far is solved or
  /// held (tests). No-op otherwise.
  void drainSolver();

  const core::VesselLockstep& lockstep() const { return *lockstep_; }
  const VesselMonitor& monitor() const { return *monitor_; }

 private:
  void onPose(const geometry_msgs::PoseStamped::ConstPtr& msg);
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void pollTf(const ros::WallTimerEvent&);
  void onDiagnosticsTimer(const ros::WallTimerEvent&);
  void reject(const std::string& message, const char* key);
  /// onMotion but the count of poses received.
  void onMotionIn(const ros::Time& stamp, const std::string& frame, const geometry_msgs::Pose& pose,
                  const std::string& field, const core::BodyTwist* twist);
  /// The sample's solver time: seconds after the first usable pose's stamp (set by it).
  double sampleTime(const ros::Time& stamp, const core::RigidPose& pose, const std::string& field);
  /// Decimated mode: the solver fell `lag` seconds behind the newest pose q.
  void onSolverBehind(const SampleWorker::Sample& q, double lag, long skipped);
  /// The lockstep step of one pose and its outputs (on the solver thread in decimated mode).
  void solveSample(const ros::Time& stamp, const core::RigidPose& pose, const std::string& field,
                   const core::BodyTwist* twist);
  /// Decimated mode: answer the pose at once from the last solve, queue it for the solver.
  void answerAndQueue(const ros::Time& stamp, const core::RigidPose& pose, const std::string& field,
                      const core::BodyTwist* twist);
  void handle(const core::VesselLockstep::Result& r, const ros::Time& stamp, double wall_spent, double advanced);
  void publish(const ros::Time& stamp);
  /// Line events, lengths and winch rates for the diagnostics (under both mutexes).
  void snapshotForDiagnostics();
  void publishMarkersAndFrames(const ros::Time& stamp);
  void publishAnchorFrames();
  double wallNow() const;

  ros::NodeHandle nh_, pnh_;
  core::SystemProblem system_;
  std::string file_;
  std::string frame_id_ = "world", vessel_frame_;
  std::string motion_source_ = "pose";
  bool use_twist_ = true;  ///< odometry: the twist gives the velocities at the samples
  double tf_timeout_ = 0.1;
  bool publish_fairlead_frames_ = false, publish_vessel_frame_ = false;
  std::string frame_prefix_;
  std::vector<std::string> topic_names_;       ///< per line: its name as used in topics
  std::vector<MarkerOptions> marker_options_;  ///< per line
  std::unique_ptr<core::VesselLockstep> lockstep_;
  std::unique_ptr<VesselMonitor> monitor_;
  std::unique_ptr<GnssInput> gnss_;  ///< ~motion_source gnss
  ros::Publisher wrench_pub_, wrench_world_pub_, marker_pub_, diag_pub_;
  std::vector<ros::Publisher> state_pubs_;     ///< per line
  std::vector<ros::Publisher> fairlead_pubs_;  ///< per line (empty publisher: the line has no end on the vessel)
  ros::Subscriber motion_sub_;
  ros::ServiceServer reset_srv_, solve_srv_, release_srv_, winch_srv_;
  ros::WallTimer tf_timer_, diag_timer_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_broadcaster_;
  ros::WallTime wall0_;
  bool have_epoch_ = false;
  ros::Time epoch_;          ///< first good stamp: VesselLockstep times are seconds after it
  ros::Time last_tf_stamp_;  ///< tf source: stamp of the last transform used
  bool have_output_ = false;
  ros::Time last_stamp_;     ///< stamp of the last published state
  bool failed_sample_ = false;  ///< the sample being published failed: the last good state, converged false

  // Threads (decimated mode; uncontended otherwise). Lock order: solver_mutex_, then
  // monitor_mutex_, then answer_mutex_.
  std::mutex solver_mutex_;   ///< lockstep_ and the state above (solver thread, services, diagnostics)
  std::mutex monitor_mutex_;  ///< monitor_, the diag_ snapshot and the last processed stamp
  bool have_processed_ = false;
  ros::Time last_processed_;  ///< stamp of the last pose the solver took (not dropped)
  std::vector<core::LineEventRecord> diag_events_;  ///< as of the last solve (snapshotForDiagnostics)
  std::vector<double> diag_lengths_, diag_rates_;   ///< [m], [m/s] per line, as of the last solve
  std::mutex answer_mutex_;   ///< the fields below
  double loop_back_ = 1.0;    ///< [s] as lockstep's: a stamp back by more is a bag loop, answered
  bool decimated_ = false;    ///< ~solve_interval > 0 (set in the constructor, then constant)
  double max_solver_lag_ = 0.0;  ///< [s] ~max_solver_lag (decimated mode)
  core::VesselWrench answer_wrench_;  ///< the last solve's wrench: every pose's answer
  bool answered_any_ = false;
  ros::Time last_answered_;
  std::unique_ptr<SampleWorker> worker_;  ///< decimated mode; last member: stopped first
};

/// True when ~problem_file names a system file with a vessel whose points carry lines.
bool paramsNameVesselFile(const ros::NodeHandle& pnh);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
