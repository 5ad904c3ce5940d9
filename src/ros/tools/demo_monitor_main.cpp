// demo_monitor: prints one live line for scripts/demo: time since the first state, top tension,
// minimum tension, real-time factor and diagnostics level of a lockstep cable node.
//   ~node      cable node name (default /mooring_dynamics_node)
//   ~state_topic  CableState topic to follow (default <node>/cable_state; a vessel: one of its
//              lines, <node>/lines/<line>/cable_state)
//   ~duration  [s, wall] exit (status 0) after this long; 0 = until shutdown (default 0)
//   ~interval  [s, wall] refresh period (default 0.5)
// On a terminal the line is rewritten in place; otherwise one line per refresh. At exit: a summary
// line (states, top tension range, last real-time factor); exit status 2 when no state arrived.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace {

class Monitor {
 public:
  explicit Monitor(ros::NodeHandle& pnh) {
    pnh.param<std::string>("node", node_, "/mooring_dynamics_node");
    pnh.param("duration", duration_, 0.0);
    pnh.param("interval", interval_, 0.5);
    ros::NodeHandle nh;
    pnh.param<std::string>("state_topic", topic_, node_ + "/cable_state");
    s1_ = nh.subscribe(topic_, 100, &Monitor::onState, this);
    s2_ = nh.subscribe("/diagnostics", 10, &Monitor::onDiag, this);
    tty_ = isatty(fileno(stdout));
    start_ = ros::WallTime::now();
    timer_ = nh.createWallTimer(ros::WallDuration(interval_), &Monitor::tick, this);
  }
  int finish() {
    if (tty_) std::printf("\n");
    if (states_ == 0) {
      std::printf("demo_monitor: no state from %s\n", topic_.c_str());
      return 2;
    }
    std::printf("demo_monitor: %ld states over %.1f s simulated; top tension %.3f .. %.3f kN; real-time factor %s\n",
                states_, t_, tmin_ / 1000.0, tmax_ / 1000.0, rtf_.c_str());
    return 0;
  }

 private:
  void onState(const mooring_dynamics::CableState::ConstPtr& m) {
    if (m->tension.empty()) return;
    if (states_ == 0) first_ = m->header.stamp;
    ++states_;
    t_ = (m->header.stamp - first_).toSec();
    top_ = m->tension.back();
    min_ = m->min_tension;
    tmin_ = std::min(tmin_, top_);
    tmax_ = std::max(tmax_, top_);
  }
  void onDiag(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    for (const auto& s : m->status) {
      // The run's status: "<node> lockstep", "<node> vessel lockstep" or "<node> system lockstep"
      // (not the per-line statuses of the vessel and system nodes).
      if (!mooring_dynamics::ros_bridge::isRunStatusName(s.name, node_)) continue;
      static const char* levels[] = {"OK", "WARN", "ERROR", "STALE"};
      level_ = s.level >= 0 && s.level <= 3 ? levels[s.level] : "?";
      message_ = s.message;
      for (const auto& kv : s.values)
        if (kv.key == "real-time factor (window)" && kv.value != "-") rtf_ = kv.value;
    }
  }
  void tick(const ros::WallTimerEvent&) {
    char line[256];
    if (states_ == 0)
      std::snprintf(line, sizeof line, "waiting for %s/cable_state ...", node_.c_str());
    else
      std::snprintf(line, sizeof line, "t = %7.1f s | top tension %8.3f kN | min tension %8.3f kN | RTF %6s | %s",
                    t_, top_ / 1000.0, min_ / 1000.0, rtf_.c_str(), level_.c_str());
    if (tty_)
      std::printf("\r%-110.110s", line);
    else
      std::printf("%s\n", line);
    std::fflush(stdout);
    if (duration_ > 0.0 && (ros::WallTime::now() - start_).toSec() >= duration_) ros::shutdown();
  }

  std::string node_, topic_;
  double duration_ = 0.0, interval_ = 0.5;
  ros::Subscriber s1_, s2_;
  ros::WallTimer timer_;
  bool tty_ = false;
  ros::WallTime start_;
  ros::Time first_;
  long states_ = 0;
  double t_ = 0.0, top_ = 0.0, min_ = 0.0;
  double tmin_ = std::numeric_limits<double>::infinity(), tmax_ = -std::numeric_limits<double>::infinity();
  std::string rtf_ = "-", level_ = "-", message_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_monitor", ros::init_options::AnonymousName);
  ros::NodeHandle pnh("~");
  Monitor m(pnh);
  ros::spin();
  return m.finish();
}
