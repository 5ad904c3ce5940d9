// ros_latency: latency and throughput of the lockstep cable node (run by bench/ros_latency).
//
// Publishes a heaving fairlead (PoseStamped about the problem's static top, (x, y, z) for model: 3d
// and (x, z) for model: 2d; stamps on a simulated
// clock) to <~node>/top_pose and times, on the wall clock, each publish -> the CableState with the
// same stamp (received by a separate spinner thread).
//  1. latency: ~latency_samples samples at ~latency_rate Hz (stamps 1/rate apart): median, p99, max;
//  2. throughput: rates from ~rates (Hz, increasing), ~phase_seconds each; a rate is sustained when
//     every sample is answered and the last answer comes within ~max_backlog s of the last publish
//     (the node keeps up instead of queueing). Prints the highest sustained rate.
// Parameters: ~node (/mooring_dynamics_node), ~problem_file (required: where the static top is),
// ~heave [m] (0.5), ~period [s] (8).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace {

struct Prober {
  std::string node;
  double x0 = 0, y0 = 0, z0 = 0, heave = 0.5, period = 8.0;
  double sim_t = 0.0;                   // simulated time of the next sample [s]
  const ros::Time epoch{1000.0};
  ros::Publisher pub;
  ros::Subscriber sub;
  std::mutex m;
  std::map<uint64_t, ros::WallTime> sent, received;
  std::size_t nodes = 0;

  void onState(const mooring_dynamics::CableState::ConstPtr& s) {
    const ros::WallTime now = ros::WallTime::now();
    std::lock_guard<std::mutex> l(m);
    nodes = s->positions.size();
    received.emplace(s->header.stamp.toNSec(), now);  // first answer only (republished states are ignored)
  }
  /// Publish the next sample, `dt` simulated seconds after the previous one; returns its stamp.
  uint64_t publish(double dt) {
    sim_t += dt;
    geometry_msgs::PoseStamped p;
    p.header.stamp = epoch + ros::Duration(sim_t);
    p.header.frame_id = "world";
    p.pose.position.x = x0;
    p.pose.position.y = y0;
    p.pose.position.z = z0 + heave * std::sin(2.0 * M_PI * sim_t / period) *
                                 mooring_dynamics::ros_bridge::rampFactor(sim_t, period);
    p.pose.orientation.w = 1.0;
    {
      std::lock_guard<std::mutex> l(m);
      sent[p.header.stamp.toNSec()] = ros::WallTime::now();
    }
    pub.publish(p);
    return p.header.stamp.toNSec();
  }
  bool waitAnswer(uint64_t stamp, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end) {
      {
        std::lock_guard<std::mutex> l(m);
        if (received.count(stamp)) return true;
      }
      ros::WallDuration(0.0002).sleep();
    }
    return false;
  }
  double latencyMs(uint64_t stamp) {
    std::lock_guard<std::mutex> l(m);
    auto r = received.find(stamp);
    return r == received.end() ? NAN : (r->second - sent[stamp]).toSec() * 1000.0;
  }
};

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double k = p * (v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(k));
  return i + 1 < v.size() ? v[i] + (k - i) * (v[i + 1] - v[i]) : v.back();
}

int run() {
  ros::NodeHandle pnh("~"), nh;
  Prober pr;
  std::string problem_file;
  pnh.param<std::string>("node", pr.node, "/mooring_dynamics_node");
  pnh.param<std::string>("problem_file", problem_file, "");
  pnh.param("heave", pr.heave, pr.heave);
  pnh.param("period", pr.period, pr.period);
  double latency_rate = 10.0, phase_seconds = 3.0, max_backlog = 0.1;
  int latency_samples = 300;
  std::vector<double> rates{10, 20, 50, 100, 200, 300, 500, 700, 1000, 1500, 2000, 3000, 5000};
  pnh.param("latency_rate", latency_rate, latency_rate);
  pnh.param("latency_samples", latency_samples, latency_samples);
  pnh.param("phase_seconds", phase_seconds, phase_seconds);
  pnh.param("max_backlog", max_backlog, max_backlog);
  pnh.param("rates", rates, rates);
  if (problem_file.empty()) {
    std::fprintf(stderr, "ros_latency: ~problem_file is required\n");
    return 2;
  }
  const auto problem = mooring_dynamics::core::loadProblemFromFile(problem_file);
  const auto top = mooring_dynamics::ros_bridge::staticTop(problem);
  pr.x0 = top.x;
  pr.y0 = top.y;
  pr.z0 = top.z;

  pr.pub = nh.advertise<geometry_msgs::PoseStamped>(pr.node + "/top_pose", 10000);
  pr.sub = nh.subscribe(pr.node + "/cable_state", 10000, &Prober::onState, &pr,
                        ros::TransportHints().tcpNoDelay());
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && (pr.pub.getNumSubscribers() == 0 || pr.sub.getNumPublishers() == 0) &&
         ros::WallTime::now() < end)
    ros::WallDuration(0.05).sleep();
  if (pr.pub.getNumSubscribers() == 0) {
    std::fprintf(stderr, "ros_latency: no connection to %s\n", pr.node.c_str());
    return 2;
  }
  ros::WallDuration(0.3).sleep();

  // First sample: the static top at sim time 0 (starts the run from the problem's statics).
  pr.sim_t = -1.0 / latency_rate;
  if (!pr.waitAnswer(pr.publish(1.0 / latency_rate), 10.0)) {
    std::fprintf(stderr, "ros_latency: the node did not answer the first sample\n");
    return 2;
  }

  std::printf("%zu nodes; samples 1/rate apart in simulated time too (a real-time source at that rate)\n",
              pr.nodes);

  // 1. Latency at latency_rate (one sample every 1/rate wall seconds, stamps 1/rate apart).
  std::vector<double> lat;
  int lost = 0;
  for (int k = 0; k < latency_samples && ros::ok(); ++k) {
    const ros::WallTime t0 = ros::WallTime::now();
    const uint64_t s = pr.publish(1.0 / latency_rate);
    if (pr.waitAnswer(s, 2.0))
      lat.push_back(pr.latencyMs(s));
    else
      ++lost;
    const ros::WallDuration rest = ros::WallDuration(1.0 / latency_rate) - (ros::WallTime::now() - t0);
    if (rest > ros::WallDuration(0)) rest.sleep();
  }
  if (lat.empty()) {
    std::fprintf(stderr, "ros_latency: no answers\n");
    return 2;
  }
  std::printf("latency pose -> cable_state at %g Hz (%zu samples, %d unanswered): median %.2f ms, p99 %.2f ms, "
              "max %.2f ms\n", latency_rate, lat.size(), lost, percentile(lat, 0.5), percentile(lat, 0.99),
              *std::max_element(lat.begin(), lat.end()));

  // 2. Throughput sweep.
  double best = 0.0;
  for (double rate : rates) {
    if (!ros::ok()) break;
    const int n = std::max(20, static_cast<int>(rate * phase_seconds));
    std::vector<uint64_t> stamps;
    const ros::WallTime start = ros::WallTime::now();
    for (int k = 0; k < n; ++k) {
      const ros::WallTime due = start + ros::WallDuration(k / rate);
      const ros::WallDuration wait = due - ros::WallTime::now();
      if (wait > ros::WallDuration(0)) wait.sleep();
      stamps.push_back(pr.publish(1.0 / rate));
    }
    const ros::WallTime last_sent = ros::WallTime::now();
    const bool last = pr.waitAnswer(stamps.back(), 30.0);
    int answered = 0;
    std::vector<double> l;
    for (uint64_t s : stamps) {
      const double ms = pr.latencyMs(s);
      if (std::isfinite(ms)) {
        ++answered;
        l.push_back(ms);
      }
    }
    const double backlog = last ? pr.latencyMs(stamps.back()) / 1000.0 : INFINITY;
    (void)last_sent;
    const bool ok = answered == n && backlog <= max_backlog;
    std::printf("rate %6.0f Hz: %d/%d answered, median latency %8.2f ms, last answer %.3f s after its pose: %s\n",
                rate, answered, n, l.empty() ? NAN : percentile(l, 0.5), backlog, ok ? "sustained" : "falls behind");
    std::fflush(stdout);
    if (!ok) break;
    best = rate;
    ros::WallDuration(0.2).sleep();
  }
  std::printf("highest sustained input rate: %g Hz (of the rates tried; criterion: all answered, the last within "
              "%g s)\n", best, max_backlog);
  spinner.stop();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "ros_latency", ros::init_options::AnonymousName);
  return run();
}
