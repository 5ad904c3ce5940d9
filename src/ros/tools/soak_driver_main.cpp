// soak_driver: drives the lockstep node through a long storm on simulated time, as fast as the node
// answers (scripts/soak, docs/reliability.md). For every sample it publishes /clock (= the sample's
// stamp; the node runs with /use_sim_time) and the motion, then waits for the node's answer with
// that stamp before the next: so every input is either answered or counted as unanswered after
// ~answer_timeout of wall time. Every ~rss_every simulated seconds it reads the node's resident
// size (/proc/<~node_pid>/status, VmRSS).
//
//   ~kind "line": a single line (LockstepNode): the top follows the sea surface vertically and is
//        held horizontally, the paper's S-tether case (section 7.2): z = z_static + eta(x, y, t),
//        eta from the problem's own `environment.waves` (the same sea the line's drag sees), or
//        from ~hs/~tp when the problem has none. Publishes <node>/top_pose; answer <node>/cable_state.
//   ~kind "vessel": a moored vessel (VesselNode): the body origin heaves with the surface
//        (heave = eta), surges with the surface particles (xi = sum -a coth(kh) sin(-omega t +
//        phase) cos(direction)) about a mean offset ~mean_surge, and pitches kPitchRao times the
//        wave slope; JONSWAP ~hs, ~tp, ~gamma, ~seed, ~components travelling along +x, ramped in
//        over ~ramp. Publishes <node>/vessel_pose; answer <node>/wrench and every
//        <node>/lines/<line>/cable_state with the stamp.
//
// Parameters (private): ~kind, ~problem_file, ~node (the node's name, e.g. /cable), ~duration
// [s, simulated], ~interval [s] between samples, ~node_pid, ~rss_every [s] (60), ~out (directory
// for tension.csv and rss.csv), ~answer_timeout [s, wall] (60), ~hs [m], ~tp [s], ~gamma,
// ~seed, ~components, ~ramp [s], ~mean_surge [m], ~start_stamp [s] (1000).
//
// tension.csv: t (simulated seconds since the first sample), then the top tension of every line
// [N] as answered; rss.csv: t, wall [s], rss_kb, sent, answered. Exit status 0 when every sample
// was answered, 1 otherwise (or on a setup error).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/waves.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace core = mooring_dynamics::core;
namespace md = mooring_dynamics::ros_bridge;

namespace {

/// Pitch of the vessel per unit wave slope at its origin: a 90 m hull in waves of ~190 m length
/// pitches well below the slope of the surface (RAO ~ 0.3 at Tp 11 s); enough to move the
/// fairleads +-1 to 2 m in a storm, which is what the lines feel.
constexpr double kPitchRao = 0.3;

long readRssKb(int pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

class SoakDriver {
 public:
  explicit SoakDriver(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    pnh.param<std::string>("kind", kind_, "line");
    if (kind_ != "line" && kind_ != "vessel") throw std::runtime_error("~kind = \"" + kind_ + "\": must be line or vessel");
    std::string file;
    pnh.param<std::string>("problem_file", file, "");
    if (file.empty()) throw std::runtime_error("~problem_file: required");
    pnh.param<std::string>("node", node_, "/cable");
    pnh.param("duration", duration_, 3600.0);
    pnh.param("interval", interval_, 0.5);
    pnh.param("node_pid", pid_, 0);
    pnh.param("rss_every", rss_every_, 60.0);
    pnh.param("answer_timeout", answer_timeout_, 60.0);
    pnh.param<std::string>("out", out_, ".");
    double start = 1000.0;
    pnh.param("start_stamp", start, start);
    stamp0_ = ros::Time(start);
    if (!(duration_ > 0.0 && interval_ > 0.0 && rss_every_ > 0.0 && answer_timeout_ > 0.0))
      throw std::runtime_error("~duration, ~interval, ~rss_every and ~answer_timeout must be > 0");

    core::WaveSpec spec;
    spec.type = core::WaveSpec::Type::Jonswap;
    spec.hs = 6.0;
    spec.tp = 11.0;
    spec.components = 200;
    spec.seed = 7;
    double ramp = 60.0;
    double depth = 100.0, gravity = 9.81;
    if (kind_ == "line") {
      const core::Problem p = core::loadProblemFromFile(file);
      const md::StaticTop top = md::staticTop(p);
      x0_ = top.x;
      y0_ = top.y;
      z0_ = top.z;
      depth = p.environment.depth;
      gravity = p.environment.gravity;
      if (p.environment.waves.type != core::WaveSpec::Type::None) {
        spec = p.environment.waves;  // the line's own sea, with its own ramp
        ramp = 0.0;
      }
      lines_ = {p.name};
    } else {
      const core::SystemProblem s = core::loadSystemFromFile(file);
      if (!s.vessel.present) throw std::runtime_error("~problem_file = " + file + ": no vessel: section");
      x0_ = s.vessel.pose.position.x();
      y0_ = s.vessel.pose.position.y();
      z0_ = s.vessel.pose.position.z();
      depth = s.environment.depth;
      gravity = s.environment.gravity;
      for (const auto& l : s.lines) lines_.push_back(l.name);
    }
    pnh.param("hs", spec.hs, spec.hs);
    pnh.param("tp", spec.tp, spec.tp);
    pnh.param("gamma", spec.gamma, spec.gamma);
    int seed = static_cast<int>(spec.seed), comps = spec.components;
    pnh.param("seed", seed, seed);
    pnh.param("components", comps, comps);
    spec.seed = static_cast<std::uint32_t>(seed);
    spec.components = comps;
    pnh.param("ramp", ramp, ramp);
    pnh.param("mean_surge", mean_surge_, kind_ == "vessel" ? 5.0 : 0.0);
    ramp_ = ramp;
    if (spec.type == core::WaveSpec::Type::None) spec.type = core::WaveSpec::Type::Jonswap;
    const std::string bad = spec.validate();
    if (!bad.empty()) throw std::runtime_error(bad);
    spec_ = spec;
    waves_ = core::WaveField(spec, depth, gravity);
    depth_ = depth;

    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    if (kind_ == "line") {
      pose_pub_ = nh.advertise<geometry_msgs::PoseStamped>(node_ + "/top_pose", 10);
      subs_.push_back(nh.subscribe<mooring_dynamics::CableState>(
          node_ + "/cable_state", 100, [this](const mooring_dynamics::CableState::ConstPtr& m) { onState(0, *m); }));
    } else {
      pose_pub_ = nh.advertise<geometry_msgs::PoseStamped>(node_ + "/vessel_pose", 10);
      for (std::size_t i = 0; i < lines_.size(); ++i)
        subs_.push_back(nh.subscribe<mooring_dynamics::CableState>(
            node_ + "/lines/" + lines_[i] + "/cable_state", 100,
            [this, i](const mooring_dynamics::CableState::ConstPtr& m) { onState(i, *m); }));
      subs_.push_back(nh.subscribe<geometry_msgs::WrenchStamped>(
          node_ + "/wrench", 100, [this](const geometry_msgs::WrenchStamped::ConstPtr& m) {
            if (m->header.stamp == waiting_) wrench_seen_ = true;
          }));
    }
    tension_.assign(lines_.size(), 0.0);
    seen_.assign(lines_.size(), false);
  }

  int run() {
    // Wait until the node listens and we listen to it (wall clock: /clock is ours to publish).
    const ros::WallTime w_setup = ros::WallTime::now();
    while (ros::ok() && (pose_pub_.getNumSubscribers() == 0 || !allConnected())) {
      if ((ros::WallTime::now() - w_setup).toSec() > 120.0) {
        ROS_FATAL("soak_driver: the node %s did not connect within 120 s", node_.c_str());
        return 1;
      }
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
    }
    std::ofstream tens(out_ + "/tension.csv"), rss(out_ + "/rss.csv");
    tens << "t";
    for (const auto& l : lines_) tens << "," << l;
    tens << "\n";
    rss << "t,wall,rss_kb,sent,answered\n";
    const long n = static_cast<long>(std::floor(duration_ / interval_ + 1e-9));
    const ros::WallTime w0 = ros::WallTime::now();
    double next_rss = 0.0;
    long sent = 0, answered = 0;
    for (long k = 0; k <= n && ros::ok(); ++k) {
      const double t = static_cast<double>(k) * interval_;
      const ros::Time stamp = stamp0_ + ros::Duration(t);
      rosgraph_msgs::Clock c;
      c.clock = stamp;
      clock_pub_.publish(c);
      geometry_msgs::PoseStamped p;
      p.header.stamp = stamp;
      p.header.frame_id = "world";
      motion(t, p.pose);
      waiting_ = stamp;
      std::fill(seen_.begin(), seen_.end(), false);
      wrench_seen_ = kind_ == "line";
      pose_pub_.publish(p);
      ++sent;
      const ros::WallTime wa = ros::WallTime::now();
      while (ros::ok() && !answeredNow() && (ros::WallTime::now() - wa).toSec() < answer_timeout_)
        ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
      if (answeredNow()) {
        ++answered;
        tens << t;
        for (double v : tension_) tens << "," << v;
        tens << "\n";
      } else {
        ROS_ERROR("soak_driver: no answer to the sample at t = %.3f s within %.0f s", t, answer_timeout_);
      }
      if (t + 1e-9 >= next_rss || k == n) {
        rss << t << "," << (ros::WallTime::now() - w0).toSec() << "," << (pid_ > 0 ? readRssKb(pid_) : -1) << ","
            << sent << "," << answered << "\n";
        rss.flush();
        next_rss += rss_every_;
      }
    }
    const double wall = (ros::WallTime::now() - w0).toSec();
    std::printf("soak_driver: %s: %.0f s simulated in %.1f s wall (RTF %.1f), %ld samples sent, %ld answered\n",
                kind_.c_str(), static_cast<double>(n) * interval_, wall, static_cast<double>(n) * interval_ / wall,
                sent, answered);
    return answered == sent ? 0 : 1;
  }

 private:
  bool allConnected() const {
    for (const auto& s : subs_)
      if (s.getNumPublishers() == 0) return false;
    return true;
  }
  bool answeredNow() const {
    if (!wrench_seen_) return false;
    for (bool b : seen_)
      if (!b) return false;
    return true;
  }
  void onState(std::size_t i, const mooring_dynamics::CableState& m) {
    if (m.header.stamp != waiting_ || m.tension.empty()) return;
    seen_[i] = true;
    tension_[i] = m.tension.back();
  }

  void motion(double t, geometry_msgs::Pose& pose) const {
    pose.orientation.w = 1.0;
    pose.position.x = x0_;
    pose.position.y = y0_;
    if (kind_ == "line") {
      pose.position.z = z0_ + waves_.elevation(x0_, y0_, t);  // the problem's own ramp
      return;
    }
    // The vessel at its origin (x0, y0): heave, surge and slope of the surface, ramped in.
    const double r = md::rampFactor(t, ramp_);
    double eta = 0.0, xi = 0.0, slope = 0.0;
    for (const core::WaveComponent& c : waves_.components()) {
      const double th = c.k * (x0_ * std::cos(c.direction) + y0_ * std::sin(c.direction)) - c.omega * t + c.phase;
      eta += c.amplitude * std::cos(th);
      xi += -c.amplitude / std::tanh(c.k * depth_) * std::sin(th) * std::cos(c.direction);
      slope += -c.amplitude * c.k * std::sin(th) * std::cos(c.direction);
    }
    pose.position.x = x0_ + r * (mean_surge_ + xi);
    pose.position.z = z0_ + r * eta;
    const double pitch = -kPitchRao * r * slope;  // bow up (negative pitch about +y) on a rising slope
    pose.orientation.y = std::sin(0.5 * pitch);
    pose.orientation.w = std::cos(0.5 * pitch);
  }

  std::string kind_, node_, out_;
  double duration_ = 3600.0, interval_ = 0.5, rss_every_ = 60.0, answer_timeout_ = 60.0;
  int pid_ = 0;
  ros::Time stamp0_;
  double x0_ = 0.0, y0_ = 0.0, z0_ = 0.0, depth_ = 100.0, ramp_ = 60.0, mean_surge_ = 0.0;
  core::WaveSpec spec_;
  core::WaveField waves_;
  std::vector<std::string> lines_;
  ros::Publisher clock_pub_, pose_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Time waiting_;
  std::vector<bool> seen_;
  std::vector<double> tension_;
  bool wrench_seen_ = false;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "soak_driver");
  ros::NodeHandle nh, pnh("~");
  try {
    SoakDriver d(nh, pnh);
    return d.run();
  } catch (const std::exception& e) {
    ROS_FATAL("soak_driver: %s", e.what());
    return 1;
  }
}
