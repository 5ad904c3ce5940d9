// vessel_sim: two-way coupling example (vessel.launch). A vessel in surge and heave
// (VesselModel, companions.hpp: mass-spring-dampers driven by a wave force and by the cable's
// force) publishes its fairlead position as geometry_msgs/PoseStamped on `fairlead_pose` (remap to
// the cable node's ~top_pose) and reads the cable's force on it from `cable_wrench`
// (geometry_msgs/WrenchStamped in ~frame_id: the cable node's ~top_wrench).
//
// Lockstep coupling: the vessel's own clock runs in steps of ~dt from the start stamp; the pose of
// step k is published with stamp t_k, and step k + 1 is taken with the wrench answering t_k (the
// force is held over the step: explicit coupling). With ~wait_for_wrench (default) the vessel
// waits for that answer, so the coupled run does not depend on timing; wall-clock pacing: one step
// per ~dt / ~speed. Surge and heave only: with a model: 3d problem the fairlead's y stays at the
// static top's and the wrench's y is not used.
//
// Parameters (private): ~problem_file (start at the problem's static top, in equilibrium with the
// static cable force), ~frame_id (world), ~dt [s] (0.1), ~speed [-] (1 = real time),
// ~wait_for_wrench (true), and the VesselOptions fields ~mass [kg], ~heave_stiffness,
// ~surge_stiffness [N/m], ~heave_damping, ~surge_damping [N s/m], ~wave_heave_force,
// ~wave_surge_force [N], ~wave_period [s], ~ramp [s].
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace md = mooring_dynamics::ros_bridge;

namespace {

class VesselSimNode {
 public:
  explicit VesselSimNode(ros::NodeHandle& pnh) {
    std::string problem_file;
    pnh.param<std::string>("problem_file", problem_file, "");
    if (problem_file.empty()) throw std::runtime_error("~problem_file: required (the vessel starts at its static top)");
    top_ = md::staticTop(mooring_dynamics::core::loadProblemFromFile(problem_file));
    pnh.param<std::string>("frame_id", frame_id_, "world");
    pnh.param("dt", dt_, dt_);
    double speed = 1.0;
    pnh.param("speed", speed, speed);
    pnh.param("wait_for_wrench", wait_, wait_);
    md::VesselOptions o;
    pnh.param("mass", o.mass, o.mass);
    pnh.param("heave_stiffness", o.heave_stiffness, o.heave_stiffness);
    pnh.param("surge_stiffness", o.surge_stiffness, o.surge_stiffness);
    pnh.param("heave_damping", o.heave_damping, o.heave_damping);
    pnh.param("surge_damping", o.surge_damping, o.surge_damping);
    pnh.param("wave_heave_force", o.wave_heave_force, o.wave_heave_force);
    pnh.param("wave_surge_force", o.wave_surge_force, o.wave_surge_force);
    pnh.param("wave_period", o.wave_period, o.wave_period);
    pnh.param("ramp", o.ramp, o.ramp);
    if (!(std::isfinite(dt_) && dt_ > 0.0)) throw std::runtime_error("~dt must be > 0 [s]");
    if (!(std::isfinite(speed) && speed > 0.0)) throw std::runtime_error("~speed must be > 0");
    const std::string e = o.validate();
    if (!e.empty()) throw std::runtime_error("~" + e);
    model_ = std::make_unique<md::VesselModel>(o, top_.x, top_.z, top_.fx, top_.fz);
    fx_ = top_.fx;
    fz_ = top_.fz;
    pub_ = pnh.advertise<geometry_msgs::PoseStamped>("fairlead_pose", 10);
    sub_ = pnh.subscribe("cable_wrench", 10, &VesselSimNode::onWrench, this);
    timer_ = pnh.createWallTimer(ros::WallDuration(dt_ / speed), &VesselSimNode::tick, this);
    ROS_INFO("vessel_sim: mass %g kg, heave period %.2f s, starting at (%g, %g) m with the static cable force "
             "(%g, %g) N; dt %g s, %s", o.mass, 2 * M_PI * std::sqrt(o.mass / o.heave_stiffness), top_.x, top_.z,
             top_.fx, top_.fz, dt_, wait_ ? "waiting for each wrench (lockstep)" : "latest wrench (free running)");
  }

 private:
  void onWrench(const geometry_msgs::WrenchStamped::ConstPtr& w) {
    if (!std::isfinite(w->wrench.force.x) || !std::isfinite(w->wrench.force.z)) {
      ROS_WARN_THROTTLE(5.0, "vessel_sim: non-finite cable force ignored");
      return;
    }
    if (!w->header.frame_id.empty() && w->header.frame_id != frame_id_)
      ROS_WARN_ONCE("vessel_sim: cable wrench in frame \"%s\", expected \"%s\": used as is",
                    w->header.frame_id.c_str(), frame_id_.c_str());
    fx_ = w->wrench.force.x;
    fz_ = w->wrench.force.z;
    if (w->header.stamp == stamp_) answered_ = true;
  }

  void publish() {
    geometry_msgs::PoseStamped p;
    p.header.stamp = stamp_;
    p.header.frame_id = frame_id_;
    p.pose.position.x = model_->x();
    p.pose.position.y = top_.y;  // surge and heave only: held at the static top's y (model: 3d)
    p.pose.position.z = model_->z();
    p.pose.orientation.w = 1.0;
    pub_.publish(p);
    answered_ = false;
    sent_ = ros::WallTime::now();
  }

  void tick(const ros::WallTimerEvent&) {
    if (!started_) {
      const ros::Time now = ros::Time::now();
      if (now.isZero() || pub_.getNumSubscribers() == 0) return;
      started_ = true;
      start_ = now;
      stamp_ = now;
      publish();  // step 0: the static top
      return;
    }
    if (wait_ && !answered_) {
      if ((ros::WallTime::now() - sent_).toSec() > 2.0) {
        ROS_WARN_THROTTLE(5.0, "vessel_sim: no cable wrench for stamp %.3f after 2 s: sending the pose again",
                          stamp_.toSec());
        publish();
      }
      return;
    }
    model_->step(dt_, fx_, fz_);
    stamp_ = start_ + ros::Duration(model_->t());
    publish();
  }

  md::StaticTop top_;
  std::string frame_id_;
  double dt_ = 0.1;
  bool wait_ = true;
  std::unique_ptr<md::VesselModel> model_;
  double fx_ = 0.0, fz_ = 0.0;
  ros::Publisher pub_;
  ros::Subscriber sub_;
  ros::WallTimer timer_;
  bool started_ = false, answered_ = false;
  ros::Time start_, stamp_;
  ros::WallTime sent_;
};

int run() {
  ros::NodeHandle pnh("~");
  std::unique_ptr<VesselSimNode> node;
  try {
    node = std::make_unique<VesselSimNode>(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("vessel_sim: %s", e.what());
    return 1;
  }
  ros::spin();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "vessel_sim");
  return run();
}
