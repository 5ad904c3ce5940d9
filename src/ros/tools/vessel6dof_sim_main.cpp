// vessel6dof_sim: the two-way coupling example of a moored vessel (vessel_6dof.launch). A 6-DOF
// rigid body (RigidBodyVessel, rigid_body_vessel.hpp: mass and added mass, hydrostatic heave, roll
// and pitch restoring, linear damping, sinusoidal wave forces) publishes its pose on `vessel_pose`
// (geometry_msgs/PoseStamped in ~frame_id: the body origin and orientation; remap to the vessel
// node's ~vessel_pose) and applies the lines' wrench it reads from `vessel_wrench`
// (geometry_msgs/WrenchStamped in the body frame about the body origin: the node's ~wrench).
//
// Lockstep: step k's pose goes out with stamp t_k; step k + 1 is taken with the wrench answering
// t_k (held over the step: explicit coupling). With ~wait_for_wrench (default) the vessel waits
// for that answer, so the coupled run does not depend on timing; one step per ~dt / ~speed of
// wall time. It starts at the file's vessel.pose, in equilibrium with the lines' static wrench.
//
// Parameters (private): ~problem_file (a vessel file), ~frame_id (world), ~dt [s] (0.1),
// ~speed (1 = real time), ~wait_for_wrench (true), ~mass [kg], ~inertia [Ixx, Iyy, Izz] [kg m^2],
// ~added_mass, ~damping, ~wave_amplitude (6 values each, body axes), ~waterplane_area [m^2],
// ~gm_transverse, ~gm_longitudinal [m], ~wave_period, ~ramp [s].
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"
#include "mooring_dynamics/ros/tools/rigid_body_vessel.hpp"

namespace md = mooring_dynamics::ros_bridge;
namespace core = mooring_dynamics::core;
using Vec6 = Eigen::Matrix<double, 6, 1>;

namespace {

/// A 6-vector parameter; throws naming it when it has another length.
void param6(ros::NodeHandle& pnh, const std::string& name, Vec6& v) {
  std::vector<double> x;
  if (!pnh.getParam(name, x)) return;
  if (x.size() != 6) throw std::runtime_error("~" + name + ": needs 6 values (surge, sway, heave, roll, pitch, yaw), has " + std::to_string(x.size()));
  for (int i = 0; i < 6; ++i) v[i] = x[static_cast<std::size_t>(i)];
}

class Vessel6DofNode {
 public:
  explicit Vessel6DofNode(ros::NodeHandle& pnh) {
    std::string file;
    pnh.param<std::string>("problem_file", file, "");
    if (file.empty()) throw std::runtime_error("~problem_file: required (a vessel file: the vessel starts at vessel.pose)");
    const core::SystemProblem s = core::loadSystemFromFile(file);
    if (!s.vessel.present) throw std::runtime_error("~problem_file = " + file + ": has no vessel: section");
    const core::VesselStaticResult st = core::solveVesselStatic(s, s.vessel.pose);
    if (!st.system.summary.converged) throw std::runtime_error("the vessel's statics did not converge: " + st.system.summary.message);
    pnh.param<std::string>("frame_id", frame_id_, "world");
    body_frame_ = s.vessel.frame;
    pnh.param("dt", dt_, dt_);
    double speed = 1.0;
    pnh.param("speed", speed, speed);
    pnh.param("wait_for_wrench", wait_, wait_);
    md::RigidBodyVesselOptions o;
    pnh.param("mass", o.mass, o.mass);
    std::vector<double> inertia;
    if (pnh.getParam("inertia", inertia)) {
      if (inertia.size() != 3) throw std::runtime_error("~inertia: needs 3 values [Ixx, Iyy, Izz]");
      o.inertia = Eigen::Vector3d(inertia[0], inertia[1], inertia[2]);
    }
    param6(pnh, "added_mass", o.added_mass);
    param6(pnh, "damping", o.damping);
    param6(pnh, "wave_amplitude", o.wave_amplitude);
    pnh.param("waterplane_area", o.waterplane_area, o.waterplane_area);
    pnh.param("gm_transverse", o.gm_transverse, o.gm_transverse);
    pnh.param("gm_longitudinal", o.gm_longitudinal, o.gm_longitudinal);
    pnh.param("wave_period", o.wave_period, o.wave_period);
    pnh.param("ramp", o.ramp, o.ramp);
    o.water_density = s.environment.water_density;
    o.gravity = s.environment.gravity;
    if (!(std::isfinite(dt_) && dt_ > 0.0)) throw std::runtime_error("~dt = " + std::to_string(dt_) + ": must be > 0 [s]");
    if (!(std::isfinite(speed) && speed > 0.0)) throw std::runtime_error("~speed = " + std::to_string(speed) + ": must be > 0");
    const std::string e = o.validate();
    if (!e.empty()) throw std::runtime_error("~" + e);
    wrench_ = st.wrench.body6();
    model_ = std::make_unique<md::RigidBodyVessel>(o, s.vessel.pose.position, s.vessel.pose.orientation, wrench_);
    pub_ = pnh.advertise<geometry_msgs::PoseStamped>("vessel_pose", 10);
    sub_ = pnh.subscribe("vessel_wrench", 10, &Vessel6DofNode::onWrench, this);
    timer_ = pnh.createWallTimer(ros::WallDuration(dt_ / speed), &Vessel6DofNode::tick, this);
    ROS_INFO("vessel6dof_sim: %g t, heave period %.2f s, roll period %.2f s; %zu lines pull (%.0f, %.0f, %.0f) N at the "
             "start; dt %g s, %s", o.mass / 1000.0, model_->heavePeriod(), model_->rollPeriod(), s.lines.size(),
             wrench_[0], wrench_[1], wrench_[2], dt_, wait_ ? "waiting for each wrench (lockstep)" : "latest wrench");
  }

 private:
  void onWrench(const geometry_msgs::WrenchStamped::ConstPtr& w) {
    Vec6 v;
    v << w->wrench.force.x, w->wrench.force.y, w->wrench.force.z, w->wrench.torque.x, w->wrench.torque.y, w->wrench.torque.z;
    if (!v.allFinite()) {
      ROS_WARN_THROTTLE(5.0, "vessel6dof_sim: non-finite wrench ignored");
      return;
    }
    if (!w->header.frame_id.empty() && w->header.frame_id != body_frame_)
      ROS_WARN_ONCE("vessel6dof_sim: wrench in frame \"%s\", expected the body frame \"%s\": used as is",
                    w->header.frame_id.c_str(), body_frame_.c_str());
    wrench_ = v;
    if (w->header.stamp == stamp_) answered_ = true;
  }

  void publish() {
    geometry_msgs::PoseStamped p;
    p.header.stamp = stamp_;
    p.header.frame_id = frame_id_;
    p.pose.position.x = model_->position().x();
    p.pose.position.y = model_->position().y();
    p.pose.position.z = model_->position().z();
    p.pose.orientation.x = model_->orientation().x();
    p.pose.orientation.y = model_->orientation().y();
    p.pose.orientation.z = model_->orientation().z();
    p.pose.orientation.w = model_->orientation().w();
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
      publish();  // step 0: the file's pose
      return;
    }
    if (wait_ && !answered_) {
      if ((ros::WallTime::now() - sent_).toSec() > 2.0) {
        ROS_WARN_THROTTLE(5.0, "vessel6dof_sim: no wrench for stamp %.3f after 2 s: sending the pose again", stamp_.toSec());
        publish();
      }
      return;
    }
    model_->step(dt_, wrench_);
    stamp_ = start_ + ros::Duration(model_->t());
    publish();
  }

  std::string frame_id_, body_frame_;
  double dt_ = 0.1;
  bool wait_ = true;
  std::unique_ptr<md::RigidBodyVessel> model_;
  Vec6 wrench_ = Vec6::Zero();
  ros::Publisher pub_;
  ros::Subscriber sub_;
  ros::WallTimer timer_;
  bool started_ = false, answered_ = false;
  ros::Time start_, stamp_;
  ros::WallTime sent_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "vessel6dof_sim");
  ros::NodeHandle pnh("~");
  std::unique_ptr<Vessel6DofNode> node;
  try {
    node = std::make_unique<Vessel6DofNode>(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("vessel6dof_sim: %s", e.what());
    return 1;
  }
  ros::spin();
  return 0;
}
