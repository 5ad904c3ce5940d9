// sea_state_vessel: plays a vessel file's storm in ROS without a simulator (issue "Design storms";
// launch/vessel_storm.launch). The vessel's motion is the one `cable_sim dynamic` computes from the
// file (VesselMotionSource: wave-frequency motion by the hull's RAOs in vessel.sea_state, slow
// surge, sway and yaw under the lines' wrench and the wave drift with vessel.low_frequency). It
// publishes the pose and body twist on `vessel_odom` (nav_msgs/Odometry: header.frame_id ~frame_id,
// child_frame_id the vessel's body frame, twist in body axes, REP 105; remap to the mooring node's
// ~vessel_odom) and reads the lines' wrench on `vessel_wrench` (geometry_msgs/WrenchStamped in the
// body frame about the body origin: the node's ~wrench), which moves the slow drift.
//
// Lockstep: sample k goes out with stamp start + k dt; sample k + 1 is computed once the wrench
// answering stamp k is in (with ~wait_for_wrench, the default), so the run does not depend on
// timing and its samples are those of `cable_sim dynamic` on the same file. One sample per
// ~dt / ~speed of wall time at most. Stops publishing after dynamics.duration (or ~duration).
//
// Parameters (private): ~problem_file (a vessel file with vessel.sea_state and/or
// vessel.low_frequency), ~frame_id (world), ~speed (1 = real time), ~wait_for_wrench (true),
// ~duration [s] (the file's dynamics.duration; 0 = no end), ~subscribers (1: the first sample
// goes out once this many subscribers listen to vessel_odom). The step is the file's dynamics.dt.
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_motion_source.hpp"

namespace core = mooring_dynamics::core;

namespace {

class SeaStateVesselNode {
 public:
  explicit SeaStateVesselNode(ros::NodeHandle& pnh) {
    std::string file;
    pnh.param<std::string>("problem_file", file, "");
    if (file.empty()) throw std::runtime_error("~problem_file: required (a vessel file with vessel.sea_state or vessel.low_frequency)");
    system_ = core::loadSystemFromFile(file);
    if (!system_.vessel.sea_state && !system_.vessel.low_frequency)
      throw std::runtime_error("~problem_file = " + file + ": its vessel has neither sea_state nor low_frequency: nothing to play");
    source_ = std::make_unique<core::VesselMotionSource>(system_);
    pnh.param<std::string>("frame_id", frame_id_, "world");
    body_frame_ = system_.vessel.frame;
    dt_ = system_.dynamics.dt;
    double speed = 1.0;
    pnh.param("speed", speed, speed);
    pnh.param("wait_for_wrench", wait_, wait_);
    duration_ = system_.dynamics.duration;
    pnh.param("duration", duration_, duration_);
    pnh.param("subscribers", subscribers_, subscribers_);
    if (subscribers_ < 1) throw std::runtime_error("~subscribers = " + std::to_string(subscribers_) + ": must be >= 1");
    if (!(std::isfinite(speed) && speed > 0.0)) throw std::runtime_error("~speed = " + std::to_string(speed) + ": must be > 0");
    if (!(std::isfinite(duration_) && duration_ >= 0.0))
      throw std::runtime_error("~duration = " + std::to_string(duration_) + ": must be >= 0 [s] (0: no end)");
    pub_ = pnh.advertise<nav_msgs::Odometry>("vessel_odom", 10);
    sub_ = pnh.subscribe("vessel_wrench", 10, &SeaStateVesselNode::onWrench, this);
    timer_ = pnh.createWallTimer(ros::WallDuration(dt_ / speed), &SeaStateVesselNode::tick, this);
    const core::WaveSpec& w = system_.environment.waves;
    ROS_INFO("sea_state_vessel: \"%s\": Hs %g m, Tp %g s toward %.0f deg, seed %u%s%s; dt %g s, %s", system_.name.c_str(),
             w.hs, w.tp, w.direction * 180.0 / 3.14159265358979323846, w.seed,
             system_.vessel.low_frequency ? ", slow drift" : "", system_.vessel.wave_drift ? " with wave drift" : "", dt_,
             wait_ ? "waiting for each wrench (lockstep)" : "latest wrench");
  }

 private:
  void onWrench(const geometry_msgs::WrenchStamped::ConstPtr& w) {
    const Eigen::Vector3d f(w->wrench.force.x, w->wrench.force.y, w->wrench.force.z);
    const Eigen::Vector3d m(w->wrench.torque.x, w->wrench.torque.y, w->wrench.torque.z);
    if (!f.allFinite() || !m.allFinite()) {
      ROS_WARN_THROTTLE(5.0, "sea_state_vessel: non-finite wrench ignored");
      return;
    }
    if (!w->header.frame_id.empty() && w->header.frame_id != body_frame_)
      ROS_WARN_ONCE("sea_state_vessel: wrench in frame \"%s\", expected the body frame \"%s\": used as is",
                    w->header.frame_id.c_str(), body_frame_.c_str());
    // Body frame about the body origin -> world, with the orientation of the sample it answers.
    const Eigen::Matrix3d r = sample_.pose.orientation.normalized().toRotationMatrix();
    wrench_.force_body = f;
    wrench_.moment_body = m;
    wrench_.force_world = r * f;
    wrench_.moment_world = r * m;
    if (w->header.stamp == stamp_) answered_ = true;
  }

  void publish() {
    nav_msgs::Odometry o;
    o.header.stamp = stamp_;
    o.header.frame_id = frame_id_;
    o.child_frame_id = body_frame_;
    const core::RigidPose& p = sample_.pose;
    o.pose.pose.position.x = p.position.x();
    o.pose.pose.position.y = p.position.y();
    o.pose.pose.position.z = p.position.z();
    o.pose.pose.orientation.x = p.orientation.x();
    o.pose.pose.orientation.y = p.orientation.y();
    o.pose.pose.orientation.z = p.orientation.z();
    o.pose.pose.orientation.w = p.orientation.w();
    o.twist.twist.linear.x = sample_.twist.linear.x();
    o.twist.twist.linear.y = sample_.twist.linear.y();
    o.twist.twist.linear.z = sample_.twist.linear.z();
    o.twist.twist.angular.x = sample_.twist.angular.x();
    o.twist.twist.angular.y = sample_.twist.angular.y();
    o.twist.twist.angular.z = sample_.twist.angular.z();
    pub_.publish(o);
    answered_ = false;
    sent_ = ros::WallTime::now();
  }

  void tick(const ros::WallTimerEvent&) {
    if (!started_) {
      const ros::Time now = ros::Time::now();
      if (now.isZero() || pub_.getNumSubscribers() < static_cast<std::uint32_t>(subscribers_)) return;
      started_ = true;
      start_ = now;
      stamp_ = now;
      sample_ = source_->sample(0.0);
      publish();  // sample 0
      return;
    }
    if (done_) return;
    if (wait_ && !answered_) {
      if ((ros::WallTime::now() - sent_).toSec() > 2.0) {
        ROS_WARN_THROTTLE(5.0, "sea_state_vessel: no wrench for stamp %.3f after 2 s: sending the sample again", stamp_.toSec());
        publish();
      }
      return;
    }
    source_->advance(dt_, wrench_);  // the lines' wrench of sample k moves the slow drift to k + 1
    ++k_;
    const double t = static_cast<double>(k_) * dt_;
    if (duration_ > 0.0 && t > duration_ + 1e-9) {
      done_ = true;
      ROS_INFO("sea_state_vessel: the storm's %g s are played", duration_);
      return;
    }
    sample_ = source_->sample(t);
    stamp_ = start_ + ros::Duration(t);
    publish();
  }

  core::SystemProblem system_;
  std::unique_ptr<core::VesselMotionSource> source_;
  std::string frame_id_, body_frame_;
  double dt_ = 0.1, duration_ = 0.0;
  bool wait_ = true;
  int subscribers_ = 1;
  core::PoseSample sample_;
  core::VesselWrench wrench_;
  long k_ = 0;
  ros::Publisher pub_;
  ros::Subscriber sub_;
  ros::WallTimer timer_;
  bool started_ = false, answered_ = false, done_ = false;
  ros::Time start_, stamp_;
  ros::WallTime sent_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "sea_state_vessel");
  ros::NodeHandle pnh("~");
  std::unique_ptr<SeaStateVesselNode> node;
  try {
    node = std::make_unique<SeaStateVesselNode>(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("sea_state_vessel: %s", e.what());
    return 1;
  }
  ros::spin();
  return 0;
}
