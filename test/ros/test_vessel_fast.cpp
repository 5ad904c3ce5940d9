// rostest: a 1 kHz vessel simulator against the moored-vessel node in decimated mode
// (~solve_interval 0.1 s; docs/ros_interface.md, "A fast vessel simulator"). The driver publishes
// a PoseStamped every millisecond of wall time with simulated stamps 1 ms apart (an Hs 2 m sea,
// core::generateStormMotion), /clock at 100 Hz, and times each pose -> its ~wrench (same stamp).
//   * every pose is answered exactly once (stamps matched), none lost;
//   * pose-to-wrench latency p99 under ~p99_ms in this run: 5 ms for the 3-line vessel, 10 ms for
//     the 8-line spread mooring. The targets are 2 and 5 ms; on the shared 2-core host one
//     run's p99 scatters between 1.5 and 3 ms for the 3 lines, and 1.4-1.6 ms of it is the
//     transport's and this harness's alone (measured with no solving at all), so a single run
//     cannot hold 2 ms without failing on a busy spell. The bounds here tell the decimated mode
//     from lockstep (a lockstep solve takes 12 and 60 ms); the targets are checked on the median
//     of several runs (docs/performance.md, "A vessel simulator at 1 kHz");
//   * every answer is a state the solver reached: its body wrench equals, bit for bit, the wrench
//     of core::VesselLockstep fed the same poses with the same solve_interval after one of its
//     solves at a stamp no later than the pose's (an answer never comes from the future), and
//     the diagnostics count the poses answered and held.
// test_vessel_fast.test: test/data/small_vessel.yaml; test_vessel_fast.spread.test: config/spread_mooring.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/storm_motion.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace core = mooring_dynamics::core;
namespace rb = mooring_dynamics::ros_bridge;

namespace {

constexpr double kRate = 1000.0;         // [Hz] the simulator's pose rate
// /clock every 10th pose (100 Hz), as a simulator may throttle it: every process under
// use_sim_time takes each /clock message on a thread of its own, and at 1 kHz those wake-ups
// alone move this host's p99 from 1.4-1.6 to 2.0-2.2 ms with no solving at all (measured).
constexpr std::size_t kClockEvery = 10;
constexpr double kSolveInterval = 0.1;   // [s] the node's ~solve_interval (the files' dt)
constexpr double kSettle = 2.0;          // [s, wall] for the last answers and a diagnostics period
const ros::Time kEpoch(5000.0);          // first stamp (simulated)

std::string g_node = "/vessel_fast", g_problem;
double g_duration = 15.0;  // [s] of poses
double g_p99_ms = 2.0;     // [ms] the latency target

/// The simulator's poses: the storm generator at 1 kHz (Hs 2 m, Tp 8 s, 5 s ramp from the file's
/// pose at the origin, 1 m mean offset with 1 m of slow drift).
std::vector<geometry_msgs::PoseStamped> poses() {
  core::StormMotionOptions o = core::mooringStorm(2.0, 8.0, 30.0, 1, g_duration);
  o.dt = 1.0 / kRate;
  o.ramp = 5.0;
  o.mean_offset = 1.0;
  o.drift_amplitude = 1.0;
  std::vector<geometry_msgs::PoseStamped> out;
  for (const core::PoseSample& p : core::generateStormMotion(o)) {
    geometry_msgs::PoseStamped m;
    m.header.stamp = kEpoch + ros::Duration(p.t);
    m.header.frame_id = "world";
    m.pose.position.x = p.pose.position.x();
    m.pose.position.y = p.pose.position.y();
    m.pose.position.z = p.pose.position.z();
    m.pose.orientation.x = p.pose.orientation.x();
    m.pose.orientation.y = p.pose.orientation.y();
    m.pose.orientation.z = p.pose.orientation.z();
    m.pose.orientation.w = p.pose.orientation.w();
    out.push_back(m);
  }
  return out;
}

struct Answers {
  std::mutex m;
  std::map<uint64_t, ros::WallTime> received;  // stamp -> wall time of the first answer
  std::map<uint64_t, geometry_msgs::Wrench> wrench;
  long duplicates = 0;
  std::map<std::string, std::string> diag;  // the node's overall status values (latest)
};

/// Body force of every state core::VesselLockstep reaches on these poses (the start and each
/// solve), with the stamp of the pose it was solved at.
std::vector<std::pair<uint64_t, geometry_msgs::Vector3>> coreStates(const std::vector<geometry_msgs::PoseStamped>& in) {
  const core::SystemProblem s = core::loadSystemFromFile(g_problem);
  core::DynamicOptions dyn = s.dynamics;
  dyn.threads = 1;
  core::VesselLockstepOptions lo;
  lo.solve_interval = kSolveInterval;
  core::VesselLockstep run(s, dyn, lo);
  std::vector<std::pair<uint64_t, geometry_msgs::Vector3>> out;
  out.emplace_back(0, rb::toBodyWrench(run.wrench(), "base_link", kEpoch).wrench.force);  // the file's statics
  for (const auto& p : in) {
    const auto r = run.onSample((p.header.stamp - in.front().header.stamp).toSec(), rb::toRigidPose(p.pose));
    if (r.publish) out.emplace_back(p.header.stamp.toNSec(), rb::toBodyWrench(run.wrench(), "base_link", kEpoch).wrench.force);
  }
  return out;
}

}  // namespace

TEST(VesselNodeAt1kHz, EveryPoseAnsweredPromptlyWithASolvedState) {
  ros::NodeHandle nh;
  Answers a;
  ros::Subscriber ws = nh.subscribe<geometry_msgs::WrenchStamped>(
      g_node + "/wrench", 100000, [&a](const geometry_msgs::WrenchStamped::ConstPtr& w) {
        const ros::WallTime now = ros::WallTime::now();
        std::lock_guard<std::mutex> l(a.m);
        const uint64_t k = w->header.stamp.toNSec();
        if (a.received.count(k)) {
          ++a.duplicates;
          return;
        }
        a.received.emplace(k, now);
        a.wrench.emplace(k, w->wrench);
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::Subscriber ds = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&a](const diagnostic_msgs::DiagnosticArray::ConstPtr& d) {
        std::lock_guard<std::mutex> l(a.m);
        for (const auto& st : d->status)
          if (st.name.find(g_node.substr(1) + " vessel lockstep") != std::string::npos)
            for (const auto& kv : st.values) a.diag[kv.key] = kv.value;
      });
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/vessel_pose", 100000);
  ros::Publisher clock = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  for (int i = 0; i < 200 && (pub.getNumSubscribers() == 0 || ws.getNumPublishers() == 0); ++i)
    ros::WallDuration(0.05).sleep();
  ASSERT_GT(pub.getNumSubscribers(), 0u) << g_node << " does not listen";

  const std::vector<geometry_msgs::PoseStamped> in = poses();
  std::vector<ros::WallTime> sent(in.size());
  ros::WallRate rate(kRate);
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (k % kClockEvery == 0) {
      rosgraph_msgs::Clock c;
      c.clock = in[k].header.stamp;
      clock.publish(c);
    }
    sent[k] = ros::WallTime::now();
    pub.publish(in[k]);
    rate.sleep();
  }
  const double wall_span = (ros::WallTime::now() - sent.front()).toSec();
  ros::WallDuration(kSettle).sleep();

  std::lock_guard<std::mutex> l(a.m);
  // Every pose answered once.
  EXPECT_EQ(a.received.size(), in.size());
  EXPECT_EQ(a.duplicates, 0);
  std::vector<double> latency_ms;
  for (std::size_t k = 0; k < in.size(); ++k) {
    const auto it = a.received.find(in[k].header.stamp.toNSec());
    if (it == a.received.end()) continue;
    latency_ms.push_back(1e3 * (it->second - sent[k]).toSec());
  }
  ASSERT_FALSE(latency_ms.empty());
  std::sort(latency_ms.begin(), latency_ms.end());
  const double p50 = latency_ms[latency_ms.size() / 2], p99 = latency_ms[latency_ms.size() * 99 / 100];
  std::printf("1 kHz on %s: %zu poses in %.2f s wall, %zu answered; latency p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
              g_problem.c_str(), in.size(), wall_span, a.received.size(), p50, p99, latency_ms.back());
  std::fflush(stdout);
  EXPECT_LT(p99, g_p99_ms);

  // Every answer is a solved state, from a solve at or before its pose's stamp.
  const auto states = coreStates(in);
  std::size_t bad = 0, lag_sum = 0, lagged = 0;
  for (const auto& [stamp, w] : a.wrench) {
    std::size_t j = states.size();  // the latest matching state not after the pose
    for (std::size_t i = 0; i < states.size() && states[i].first <= stamp; ++i)
      if (states[i].second.x == w.force.x && states[i].second.y == w.force.y && states[i].second.z == w.force.z) j = i;
    if (j == states.size()) {
      ++bad;
      continue;
    }
    // Solves behind the pose's own: 0 when the answer is the last solve at or before the stamp.
    std::size_t last = 0;
    while (last + 1 < states.size() && states[last + 1].first <= stamp) ++last;
    lag_sum += last - j;
    lagged += last > j;
  }
  EXPECT_EQ(bad, 0u) << "answers that are no solved state at or before their stamp";
  EXPECT_GT(states.size(), static_cast<std::size_t>(g_duration / kSolveInterval) - 2);
  // The diagnostics count them: every pose answered, all but the solved ones held.
  EXPECT_EQ(a.diag["poses answered (window / total)"].substr(a.diag["poses answered (window / total)"].find("/ ") + 2),
            std::to_string(in.size()));
  const std::string held = a.diag["poses held, not solved (window / total)"];
  ASSERT_NE(held.find("/ "), std::string::npos) << held;
  EXPECT_EQ(std::stol(held.substr(held.find("/ ") + 2)), static_cast<long>(in.size() - (states.size() - 1)));
  std::printf("1 kHz: %zu solves; %zu answers one or more solves behind their stamp's (mean %.2f solves)\n",
              states.size() - 1, lagged,
              a.wrench.empty() ? 0.0 : static_cast<double>(lag_sum) / static_cast<double>(a.wrench.size()));
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_vessel_fast");
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("node", g_node, g_node);
  pnh.param<std::string>("problem_file", g_problem, std::string(MD_SOURCE_DIR) + "/test/data/small_vessel.yaml");
  pnh.param("duration", g_duration, g_duration);
  pnh.param("p99_ms", g_p99_ms, g_p99_ms);
  return RUN_ALL_TESTS();
}
