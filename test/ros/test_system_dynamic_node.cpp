// rostest: a system of lines without a moored vessel in ~mode dynamic (SystemDynamicNode) on
// test/data/small_system.yaml (a three-leg buoy in regular waves; nothing driven from outside, so
// the node steps on ROS time). The test drives /clock (use_sim_time) in irregular increments and
// checks that the states published at the grid stamps t0 + k dt are
//   * bit-identical to core::SystemDynamics advanced here to k dt on one thread (the node runs
//     ~threads 2),
//   * equal, printed to 12 significant digits, to `cable_sim dynamic` on the file (its
//     system_timeseries.csv: the buoy's position and every leg's top tension),
// that nothing is published between grid points (live: test_system_dynamic_node.test; and from a
// bag played with `rosbag play --clock`, test_system_dynamic_node.replay.test, where the run
// starts at the first /clock the node receives), that ~solve_static (SystemStatics) returns
// core::solveSystemStatic's solution bit for bit, and that /diagnostics has the run's status
// ("system lockstep") with its real-time factor and one status per line.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PointStamped.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosgraph_msgs/Clock.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SystemStatics.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"

namespace core = mooring_dynamics::core;
namespace fs = std::filesystem;

namespace {

const std::string kProblem = std::string(MD_SOURCE_DIR) + "/test/data/small_system.yaml";
const ros::Time kStart(500.0);  // the first /clock: the run's t0
constexpr double kDt = 0.1;     // [s] the file's dt (no output_interval): the grid
constexpr int kSteps = 30;      // 3 s
std::string g_node = "/system_dyn";
std::string g_mode = "live";  // live: the test publishes /clock; replay: rosbag play --clock
const std::vector<std::string> kLines = {"leg_e", "leg_nw", "leg_sw"};

/// One row: t, buoy x, y, z, the three top tensions (as cable_sim's system_timeseries.csv).
using Row = std::vector<double>;

std::string csv12(double v) {
  char buf[40];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

ros::Time gridStamp(int k) { return kStart + ros::Duration(static_cast<double>(k) * kDt); }

struct Listener {
  std::map<uint64_t, geometry_msgs::PointStamped> buoy;
  std::map<uint64_t, double> top[3];
  std::map<std::string, std::string> run_values;
  std::vector<std::string> statuses;
  std::vector<ros::Subscriber> subs;
  Listener() {
    ros::NodeHandle nh;
    subs.push_back(nh.subscribe<geometry_msgs::PointStamped>(
        g_node + "/points/buoy/position", 1000,
        [this](const geometry_msgs::PointStamped::ConstPtr& m) { buoy[m->header.stamp.toNSec()] = *m; }));
    for (int i = 0; i < 3; ++i)
      subs.push_back(nh.subscribe<mooring_dynamics::CableState>(
          g_node + "/lines/" + kLines[i] + "/cable_state", 1000, [this, i](const mooring_dynamics::CableState::ConstPtr& m) {
            if (!m->tension.empty()) top[i][m->header.stamp.toNSec()] = m->tension.back();
          }));
    subs.push_back(nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 10, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          for (const auto& st : m->status) {
            statuses.push_back(st.name);
            if (st.name == "mooring_dynamics: " + g_node + " system lockstep")
              for (const auto& kv : st.values) run_values[kv.key] = kv.value;
          }
        }));
  }
  bool has(const ros::Time& t) const {
    const uint64_t n = t.toNSec();
    return buoy.count(n) && top[0].count(n) && top[1].count(n) && top[2].count(n);
  }
  void spinUntil(const std::function<bool()>& done, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end && !done()) {
      ros::spinOnce();
      ros::WallDuration(0.005).sleep();
    }
  }
};

Listener* g_listener = nullptr;

/// core::SystemDynamics on the file, advanced to k dt in turn (as the node and cable_sim do).
std::vector<Row> coreSeries() {
  core::SystemProblem s = core::loadSystemFromFile(kProblem);
  core::DynamicOptions o = s.dynamics;
  o.threads = 1;
  core::SystemDynamics sim(s, o, 1);
  std::vector<Row> out;
  auto row = [&] {
    const auto p = sim.points()[0];
    Row r{sim.time(), p.x, p.y, p.z};
    for (std::size_t i = 0; i < 3; ++i) r.push_back(sim.line(i).topTension());
    out.push_back(r);
  };
  row();
  for (long k = 1; k <= kSteps; ++k) {
    std::string why;
    EXPECT_TRUE(sim.advanceTo(static_cast<double>(k) * kDt, &why)) << why;
    row();
  }
  return out;
}

std::vector<std::vector<std::string>> cliSeries() {
  const fs::path dir = fs::temp_directory_path() / ("md_system_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string cmd = std::string(CABLE_SIM_EXE) + " dynamic " + kProblem + " --duration " +
                          std::to_string(kSteps * kDt) + " --threads 1 --out " + dir.string() + " --no-progress >" +
                          (fs::temp_directory_path() / ("md_system_cli_" + std::to_string(::getpid()) + ".log")).string() +
                          " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::vector<std::vector<std::string>> rows;
  std::ifstream f(dir / "system_timeseries.csv");
  std::string line;
  std::getline(f, line);
  EXPECT_EQ(line, "t,buoy_x,buoy_y,buoy_z,leg_e_top_tension,leg_nw_top_tension,leg_sw_top_tension");
  while (std::getline(f, line)) {
    std::vector<std::string> cols;
    std::stringstream ls(line);
    std::string c;
    while (std::getline(ls, c, ',')) cols.push_back(c);
    rows.push_back(cols);
  }
  fs::remove_all(dir);
  return rows;
}

void publishClock(ros::Publisher& pub, const ros::Time& t) {
  rosgraph_msgs::Clock c;
  c.clock = t;
  pub.publish(c);
}

/// Live: the test is the clock. The start (t0 = kStart) is sent until the static state comes back,
/// then irregular increments (a simulator's), never on the grid except by chance; the node
/// computes every grid point passed, in turn. Returns the number of grid steps to check.
int driveLiveClock(Listener& l) {
  ros::NodeHandle nh;
  ros::Publisher clock = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  for (int i = 0; i < 200 && !l.has(kStart); ++i) {
    publishClock(clock, kStart);
    l.spinUntil([&] { return l.has(kStart); }, 0.1);
  }
  EXPECT_TRUE(l.has(kStart)) << "no static start state from " << g_node;
  const double offsets[] = {0.05, 0.23, 0.2999, 0.31, 0.71, 1.0, 1.55, 1.9, 2.04, 2.5, 2.77, 3.0};
  for (double dt : offsets) {
    publishClock(clock, kStart + ros::Duration(dt));
    ros::WallDuration(0.05).sleep();
    ros::spinOnce();
  }
  const ros::Time last = gridStamp(kSteps);
  for (int i = 0; i < 300 && !l.has(last); ++i) {
    publishClock(clock, kStart + ros::Duration(3.0));
    l.spinUntil([&] { return l.has(last); }, 0.1);
  }
  return kSteps;
}

/// Replay: `rosbag play --clock` on a bag whose messages span [kStart, kStart + 3 s]. The run
/// starts at the first /clock the node receives (the first ones may go out before the connection
/// is up): its static state carries that stamp, returned in `epoch`. Returns the grid steps
/// published after it.
int driveReplayClock(Listener& l, ros::Time& epoch) {
  EXPECT_TRUE(ros::service::waitForService(g_node + "/solve_static", ros::Duration(20.0)));
  const std::string bag_file = (fs::temp_directory_path() / ("md_system_" + std::to_string(::getpid()) + ".bag")).string();
  {
    rosbag::Bag bag(bag_file, rosbag::bagmode::Write);
    for (int i = 0; i <= 60; ++i) {
      rosgraph_msgs::Clock c;
      c.clock = kStart + ros::Duration(0.05 * i);
      bag.write("/md_ticks", c.clock, c);
    }
  }
  const std::string cmd = "rosbag play --clock -q -r 2 " + bag_file + " >/dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::remove(bag_file.c_str());
  l.spinUntil([&] { return !l.buoy.empty(); }, 10.0);
  if (l.buoy.empty()) return 0;
  epoch.fromNSec(l.buoy.begin()->first);
  // rosbag's last /clock may fall just short of the last message's time: the grid points up to
  // the clock's end, i.e. as many states as arrive (until none has come for a second).
  std::size_t n = 0;
  for (int i = 0; i < 30 && (n == 0 || l.buoy.size() != n); ++i) {
    n = l.buoy.size();
    l.spinUntil([&] { return l.buoy.size() != n; }, 1.0);
  }
  return static_cast<int>(l.buoy.size()) - 1;
}

}  // namespace

TEST(SystemDynamicNode, StatesOnTheGridMatchCoreAndCli) {
  Listener& l = *g_listener;
  ros::Time epoch = kStart;
  const int steps = g_mode == "replay" ? driveReplayClock(l, epoch) : driveLiveClock(l);
  ASSERT_GE(steps, 20) << "fewer than 20 grid points (the node missed more than a second of the clock)";
  auto grid = [&](int k) { return epoch + ros::Duration(static_cast<double>(k) * kDt); };
  ASSERT_TRUE(l.has(grid(steps))) << "no state at the last grid stamp; " << l.buoy.size() << " states from "
                                   << (epoch - kStart).toSec() << " s to "
                                   << (l.buoy.empty() ? 0.0 : ros::Time().fromNSec(l.buoy.rbegin()->first).toSec() - kStart.toSec())
                                   << " s after t0";

  const std::vector<Row> ref = coreSeries();
  const std::vector<std::vector<std::string>> cli = cliSeries();
  ASSERT_EQ(ref.size(), static_cast<std::size_t>(kSteps + 1));
  ASSERT_EQ(cli.size(), ref.size()) << "rows of cable_sim's system_timeseries.csv";
  EXPECT_EQ(l.buoy.size(), static_cast<std::size_t>(steps + 1)) << "one state per grid point, none in between";
  double moved = 0.0;
  for (int k = 0; k <= steps; ++k) {
    const uint64_t n = grid(k).toNSec();
    ASSERT_TRUE(l.has(grid(k))) << "no state for grid point " << k;
    const geometry_msgs::PointStamped& p = l.buoy[n];
    EXPECT_EQ(p.header.frame_id, "world");
    const Row node{p.point.x, p.point.y, p.point.z, l.top[0][n], l.top[1][n], l.top[2][n]};
    for (std::size_t c = 0; c < node.size(); ++c) {
      EXPECT_EQ(node[c], ref[k][c + 1]) << "grid point " << k << " column " << c;  // bits
      ASSERT_GT(cli[k].size(), c + 1);
      EXPECT_EQ(csv12(node[c]), cli[k][c + 1]) << "grid point " << k << " column " << c << " (cable_sim)";
    }
    moved = std::max(moved, std::abs(node[0] - ref[0][1]) + std::abs(node[2] - ref[0][3]));
  }
  // The waves move the legs and the buoy: the comparison is not between resting states. [m]
  EXPECT_GT(moved, 1e-4);
  std::printf("system node (%s): %d grid points, buoy moved up to %.3g m (|dx| + |dz|)\n", g_mode.c_str(), steps, moved);
}

TEST(SystemDynamicNode, SolveStaticIsTheCoreStatics) {
  const std::string srv = g_node + "/solve_static";
  ASSERT_TRUE(ros::service::waitForService(srv, ros::Duration(20.0)));
  mooring_dynamics::SystemStatics call;
  ASSERT_TRUE(ros::service::call(srv, call));
  ASSERT_TRUE(call.response.success) << call.response.message;
  EXPECT_FALSE(call.response.reinitialised);
  const core::SystemProblem s = core::loadSystemFromFile(kProblem);
  const core::SystemStaticResult r = core::solveSystemStatic(s);
  ASSERT_EQ(call.response.point_names.size(), r.points.size());
  EXPECT_EQ(call.response.point_names[0], "buoy");
  EXPECT_EQ(call.response.point_positions[0].x, r.points[0].x);
  EXPECT_EQ(call.response.point_positions[0].z, r.points[0].z);
  EXPECT_EQ(call.response.point_pull[1].x, r.points[1].fx);
  ASSERT_EQ(call.response.line_names.size(), 3u);
  EXPECT_EQ(call.response.line_names[2], "leg_sw");
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(call.response.top_tension[i], r.lines[i].topTension());
}

TEST(SystemDynamicNode, DiagnosticsHaveTheRunAndEveryLine) {
  Listener& l = *g_listener;
  l.spinUntil([&] { return l.run_values.count("real-time factor (total)") && l.run_values["real-time factor (total)"] != "-"; },
              10.0);
  ASSERT_TRUE(l.run_values.count("real-time factor (total)")) << "no \"system lockstep\" status";
  EXPECT_NE(l.run_values["real-time factor (total)"], "-");
  for (const auto& name : kLines) {
    bool found = false;
    for (const auto& st : l.statuses) found = found || st == "mooring_dynamics: " + g_node + " line " + name;
    EXPECT_TRUE(found) << name;
  }
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_system_dynamic_node");
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("node", g_node, g_node);
  pnh.param<std::string>("mode", g_mode, g_mode);
  Listener l;
  g_listener = &l;
  return RUN_ALL_TESTS();
}
