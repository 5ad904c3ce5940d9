// wave_buoy: synthetic wave-driven buoy for demo.launch. Publishes the fairlead position of a
// heaving and surging buoy (WaveBuoyMotion, companions.hpp) as geometry_msgs/PoseStamped on
// `top_pose` (remap it to the cable node's ~top_pose), stamped with ros::Time::now().
//
// Parameters (private): ~problem_file (the motion is about that problem's static top, y included
// for model: 3d; or ~x0, ~y0, ~z0 [m]; the motion itself stays in x and z), ~frame_id (world), ~rate [Hz] (10), ~heave [m] (1.0), ~surge [m] (0.5), ~period [s] (8),
// ~ramp [s] (10). It starts publishing once the topic has a subscriber, so the first sample (at
// the static top, at rest) is not lost.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace md = mooring_dynamics::ros_bridge;

namespace {

class WaveBuoyNode {
 public:
  explicit WaveBuoyNode(ros::NodeHandle& pnh) {
    std::string problem_file;
    pnh.param<std::string>("problem_file", problem_file, "");
    if (!problem_file.empty()) {
      const md::StaticTop top = md::staticTop(mooring_dynamics::core::loadProblemFromFile(problem_file));
      x0_ = top.x;
      y0_ = top.y;
      z0_ = top.z;
    }
    pnh.param("x0", x0_, x0_);
    pnh.param("y0", y0_, y0_);
    pnh.param("z0", z0_, z0_);
    pnh.param<std::string>("frame_id", frame_id_, "world");
    double rate = 10.0;
    pnh.param("rate", rate, rate);
    pnh.param("heave", o_.heave, o_.heave);
    pnh.param("surge", o_.surge, o_.surge);
    pnh.param("period", o_.period, o_.period);
    pnh.param("ramp", o_.ramp, o_.ramp);
    if (!(std::isfinite(rate) && rate > 0.0)) throw std::runtime_error("~rate must be > 0 [Hz]");
    if (!(std::isfinite(o_.period) && o_.period > 0.0)) throw std::runtime_error("~period must be > 0 [s]");
    pub_ = pnh.advertise<geometry_msgs::PoseStamped>("top_pose", 10);
    timer_ = pnh.createWallTimer(ros::WallDuration(1.0 / rate), &WaveBuoyNode::tick, this);
    ROS_INFO("wave_buoy: heave %g m, surge %g m, period %g s about (%g, %g, %g) m in %s at %g Hz on %s", o_.heave,
             o_.surge, o_.period, x0_, y0_, z0_, frame_id_.c_str(), rate, pub_.getTopic().c_str());
  }

 private:
  void tick(const ros::WallTimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // use_sim_time before /clock
    if (!started_) {
      if (pub_.getNumSubscribers() == 0) return;
      started_ = true;
      start_ = now;
    }
    if (now <= last_) return;
    last_ = now;
    geometry_msgs::PoseStamped p;
    p.header.stamp = now;
    p.header.frame_id = frame_id_;
    md::waveBuoyPosition(o_, x0_, z0_, (now - start_).toSec(), p.pose.position.x, p.pose.position.z);
    p.pose.position.y = y0_;
    p.pose.orientation.w = 1.0;
    pub_.publish(p);
  }

  md::WaveBuoyOptions o_;
  double x0_ = 0.0, y0_ = 0.0, z0_ = 0.0;
  std::string frame_id_;
  ros::Publisher pub_;
  ros::WallTimer timer_;
  bool started_ = false;
  ros::Time start_, last_;
};

int run() {
  ros::NodeHandle pnh("~");
  std::unique_ptr<WaveBuoyNode> node;
  try {
    node = std::make_unique<WaveBuoyNode>(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("wave_buoy: %s", e.what());
    return 1;
  }
  ros::spin();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "wave_buoy");
  return run();
}
