// rostest: the moored-vessel lockstep node (VesselNode, ~mode dynamic on test/data/small_vessel.yaml,
// three lines). A track of 40 vessel poses (surge and yaw) gives a ~wrench series that is
//   * bit-identical to core::VesselLockstep run here on the same samples (one thread; the node
//     runs ~threads 2: the bits do not depend on the thread count),
//   * equal, printed to 12 significant digits, to `cable_sim dynamic` on a motion table with the
//     same rows (its vessel_timeseries.csv),
// live (test_vessel_node.test) and from a bag replayed with --clock under use_sim_time
// (test_vessel_node.replay.test), and live from nav_msgs/Odometry (test_vessel_node.odom.test, its
// twist set to nonsense and ~use_twist false: unused; test_vessel_node.odom_twist.test, the exact
// twist of the track used: the Hermite path, against a CLI table with the velocity columns) and from tf (test_vessel_node.tf.test, one transform at a time,
// each waiting for its wrench as a simulator in lockstep would). Live PoseStamped only: bad samples (NaN quaternion, non-unit quaternion,
// a stamp going back) are dropped, counted in /diagnostics, and the wrench stays finite. Both:
// ~solve_static (VesselStatics) returns the core's static wrench bit for bit and a stiffness
// matrix positive in surge, sway and yaw.
// The spread mooring in an Hs 6 m storm from a bag: test_vessel_node_storm.cpp. The track, the
// core reference and the listener: vessel_node_test_util.hpp.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <tf2_ros/transform_broadcaster.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/ReleaseLine.h"
#include "mooring_dynamics/Winch.h"
#include "mooring_dynamics/VesselStatics.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"
#include "vessel_node_test_util.hpp"

namespace core = mooring_dynamics::core;
namespace fs = std::filesystem;
using mooring_dynamics::VesselStatics;
using namespace vessel_node_test;

namespace {

/// printf's %.12g as cable_sim's CSV writes it.
std::string csv12(double v) {
  char buf[40];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// `cable_sim dynamic` on a copy of the problem whose vessel.motion_table holds the samples
/// (times as the node computes them, numbers printed exactly); the CSV rows' wrench columns.
std::vector<std::vector<std::string>> cliSeries(const std::vector<Sample>& tr) {
  const fs::path dir = fs::temp_directory_path() / ("md_vessel_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ofstream t(dir / "motion.csv");
    t << (g_twist ? "t,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz\n" : "t,x,y,z,qx,qy,qz,qw\n");
    for (const Sample& s : tr) {
      const auto& p = s.pose;
      t << exact((s.stamp - tr[0].stamp).toSec()) << "," << exact(p.position.x) << "," << exact(p.position.y) << ","
        << exact(p.position.z) << "," << exact(p.orientation.x) << "," << exact(p.orientation.y) << ","
        << exact(p.orientation.z) << "," << exact(p.orientation.w);
      if (g_twist)
        for (const Eigen::Vector3d* v : {&s.twist.linear, &s.twist.angular})
          for (int i = 0; i < 3; ++i) t << "," << exact((*v)[i]);
      t << "\n";
    }
    std::ifstream in(kProblem);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string yaml = ss.str();
    const std::string key = "  frame: base_link\n";
    const std::size_t at = yaml.find(key);
    EXPECT_NE(at, std::string::npos);
    yaml.insert(at + key.size(), "  motion_table: motion.csv\n");
    std::ofstream(dir / "vessel.yaml") << yaml;
  }
  const std::string cmd = std::string(CABLE_SIM_EXE) + " dynamic " + (dir / "vessel.yaml").string() + " --threads 1 --out " +
                          (dir / "out").string() + " --no-progress >" + (dir / "log.txt").string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << cmd;
  std::vector<std::vector<std::string>> rows;
  std::ifstream f(dir / "out" / "vessel_timeseries.csv");
  std::string line;
  std::getline(f, line);  // header
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

}  // namespace

TEST(VesselNode, WrenchSeriesMatchesCoreAndCli) {
  if (g_mode == "storm") GTEST_SKIP() << "not in test_vessel_node_storm.test";
  const std::vector<Sample> tr = track();
  Listener& l = *g_listener;
  ros::NodeHandle nh;
  if (g_mode == "live" && g_source == "tf") {
    // Lockstep by hand, as a simulator would: broadcast the vessel frame, wait for its wrench.
    ASSERT_TRUE(connect(nullptr)) << "no connection to " << g_node;
    tf2_ros::TransformBroadcaster br;
    ros::WallDuration(0.5).sleep();
    for (const Sample& s : tr) {
      geometry_msgs::TransformStamped t;
      t.header.stamp = s.stamp;
      t.header.frame_id = "world";
      t.child_frame_id = "base_link";
      t.transform.translation.x = s.pose.position.x;
      t.transform.translation.y = s.pose.position.y;
      t.transform.translation.z = s.pose.position.z;
      t.transform.rotation = s.pose.orientation;
      // Sent again until answered: the first ones may go out before tf's connection is up.
      for (int k = 0; k < 40 && !l.has(s.stamp); ++k) {
        br.sendTransform(t);
        l.spinUntil([&] { return l.has(s.stamp); }, 0.5);
      }
    }
  } else if (g_mode == "live" && g_source == "odometry") {
    ros::Publisher pub = nh.advertise<nav_msgs::Odometry>(g_node + "/vessel_odom", 100);
    ASSERT_TRUE(connect(&pub)) << "no connection to " << g_node;
    for (const Sample& s : tr) {
      nav_msgs::Odometry m;
      m.header.stamp = s.stamp;
      m.header.frame_id = "world";
      m.child_frame_id = "base_link";
      m.pose.pose = s.pose;
      if (g_twist) {  // the exact twist, body frame: used (~use_twist true, the default)
        m.twist.twist.linear.x = s.twist.linear.x();
        m.twist.twist.linear.y = s.twist.linear.y();
        m.twist.twist.linear.z = s.twist.linear.z();
        m.twist.twist.angular.x = s.twist.angular.x();
        m.twist.twist.angular.y = s.twist.angular.y();
        m.twist.twist.angular.z = s.twist.angular.z();
      } else {
        m.twist.twist.linear.x = 1e3;  // not used (~use_twist false): the velocities come from the poses
      }
      pub.publish(m);
      ros::WallDuration(0.02).sleep();
      ros::spinOnce();
    }
  } else if (g_mode == "live") {
    ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/vessel_pose", 100);
    ASSERT_TRUE(connect(&pub)) << "no connection to " << g_node;
    for (const Sample& s : tr) {
      pub.publish(toMsg(s));
      ros::WallDuration(0.02).sleep();
      ros::spinOnce();
    }
  } else {
    ASSERT_TRUE(connect(nullptr)) << "no connection to " << g_node;
    const std::string bag_file = (fs::temp_directory_path() / ("md_vessel_" + std::to_string(::getpid()) + ".bag")).string();
    {
      rosbag::Bag bag(bag_file, rosbag::bagmode::Write);
      for (const Sample& s : tr) bag.write(g_node + "/vessel_pose", s.stamp, toMsg(s));
    }
    const std::string cmd = "rosbag play --clock -q --wait-for-subscribers -r 5 " + bag_file + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::remove(bag_file.c_str());
  }
  l.spinUntil([&] { return l.has(tr.back().stamp); }, 60.0);

  const std::vector<Row> ref = coreSeries(tr);
  // (cable_sim has no failure injection: with ~test_fail_line the reference is the core alone.)
  const std::vector<std::vector<std::string>> cli = g_fail_line.empty() ? cliSeries(tr) : std::vector<std::vector<std::string>>();
  ASSERT_EQ(ref.size(), tr.size());
  if (g_fail_line.empty()) {
    ASSERT_EQ(cli.size(), tr.size()) << "rows of cable_sim's vessel_timeseries.csv";
  }
  for (std::size_t k = 0; k < tr.size(); ++k) {
    ASSERT_TRUE(l.has(tr[k].stamp)) << "no wrench for sample " << k << " (" << g_mode << ")";
    const geometry_msgs::WrenchStamped& b = l.body[tr[k].stamp.toNSec()];
    EXPECT_EQ(b.header.frame_id, "base_link");
    EXPECT_EQ(l.world[tr[k].stamp.toNSec()].header.frame_id, "world");
    const Row node = rowOf(b, l.world[tr[k].stamp.toNSec()]);
    for (std::size_t c = 0; c < 12; ++c) {
      // Bits: the same doubles through the same code.
      EXPECT_EQ(node[c], ref[k][c]) << "sample " << k << " column " << c;
      if (!g_fail_line.empty()) continue;
      ASSERT_GT(cli[k].size(), c + 1);
      EXPECT_EQ(csv12(node[c]), cli[k][c + 1]) << "sample " << k << " column " << c << " (cable_sim)";
    }
  }
  // The surge and yaw motion does something: the wrench is not the same at every sample.
  EXPECT_NE(ref.front()[0], ref.back()[0]);
  if (g_twist) {
    // The twist is used: the Hermite path's wrench differs from the pose-only path's.
    const std::vector<Row> pose_only = coreSeries(tr, false);
    double diff = 0.0;
    for (std::size_t k = 0; k < tr.size(); ++k) diff = std::max(diff, std::abs(pose_only[k][0] - ref[k][0]));
    EXPECT_GT(diff, 0.0) << "the twist changed nothing";
    std::printf("odometry twist: largest surge-force difference Hermite vs pose-only path %.3g N\n", diff);
  }
}

// ~test_fail_line (test_vessel_node.fail.test): the named line fails at solver time 1 s; the node
// stays up and answers every sample, /diagnostics names the line (ERROR for it, OK for the others),
// and the other lines' top tensions are bit-identical to a clean core run's (no failure).
TEST(VesselNode, AFailedLineRestartsAloneTheOthersGoOn) {
  if (g_fail_line.empty()) GTEST_SKIP() << "test_vessel_node.fail.test only";
  const std::vector<Sample> tr = track();
  Listener& l = *g_listener;
  ros::NodeHandle nh;
  // The totals persist across diagnostics windows: per line "failures (window / total)", and the
  // run's "last event".
  std::map<std::string, std::string> line_failures, run;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          for (const auto& kv : st.values) {
            if (st.name.find(" line ") != std::string::npos && kv.key == "failures (window / total)")
              line_failures[st.name.substr(st.name.find(" line ") + 6)] = kv.value;
            if (st.name.find("vessel lockstep") != std::string::npos) run[kv.key] = kv.value;
          }
      });
  std::map<uint64_t, double>* top = l.top;  // received since the start (the Listener subscribes at once)
  const char* const* names = kLineNames;
  // (The series was sent by WrenchSeriesMatchesCoreAndCli.)
  l.spinUntil([&] { return top[0].size() >= tr.size() && top[1].size() >= tr.size() && top[2].size() >= tr.size(); }, 20.0);
  std::vector<std::vector<double>> clean;
  coreSeries(tr, g_twist, /*with_fail=*/false, &clean);
  bool differs = false;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    const uint64_t n = tr[k].stamp.toNSec();
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(top[i].count(n)) << names[i] << " sample " << k;
      if (names[i] == g_fail_line) {
        differs = differs || top[i][n] != clean[k][static_cast<std::size_t>(i)];
        continue;
      }
      EXPECT_EQ(top[i][n], clean[k][static_cast<std::size_t>(i)]) << names[i] << " sample " << k;
    }
  }
  EXPECT_TRUE(differs) << g_fail_line << " restarted: its tension leaves the clean run's";
  // /diagnostics: one failure, of that line only; the run's last event names it.
  l.spinUntil([&] { return line_failures.size() == 3 && run.count("line failures (window / total)"); }, 10.0);
  for (int i = 0; i < 3; ++i) {
    const std::string n = names[i];
    const std::string v = line_failures[n];
    EXPECT_EQ(v.substr(v.find('/') + 2), n == g_fail_line ? "1" : "0") << n << ": " << v;
  }
  const std::string f = run["line failures (window / total)"];
  EXPECT_EQ(f.substr(f.find('/') + 2), "1") << f;
  EXPECT_NE(run["last event"].find(g_fail_line + " failed and restarted alone"), std::string::npos) << run["last event"];
}

TEST(VesselNode, BadSamplesAreCountedAndTheWrenchStaysFinite) {
  if (g_mode != "live" || g_source != "pose") GTEST_SKIP() << "live PoseStamped only";
  Listener& l = *g_listener;
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/vessel_pose", 100);
  ASSERT_TRUE(connect(&pub));
  std::map<std::string, std::string> overall;
  std::vector<std::string> line_status;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status) {
          if (st.name.find("vessel lockstep") != std::string::npos) {
            overall.clear();
            for (const auto& kv : st.values) overall[kv.key] = kv.value;
          } else if (st.name.find(" line ") != std::string::npos) {
            line_status.push_back(st.name);
          }
        }
      });
  const ros::Time t_last = kStart + ros::Duration(kDt * (kSamples - 1));
  auto pose = [](double qx, double qy, double qz, double qw, const ros::Time& stamp) {
    geometry_msgs::PoseStamped m;
    m.header.stamp = stamp;
    m.header.frame_id = "world";
    m.pose.orientation.x = qx;
    m.pose.orientation.y = qy;
    m.pose.orientation.z = qz;
    m.pose.orientation.w = qw;
    return m;
  };
  const ros::Time bad1 = t_last + ros::Duration(0.1), bad2 = t_last + ros::Duration(0.2);
  const ros::Time back = t_last - ros::Duration(0.45), good = t_last + ros::Duration(0.1);
  pub.publish(pose(0, 0, std::nan(""), 1, bad1));       // NaN quaternion
  pub.publish(pose(0, 0, 0, 1.1, bad2));                 // norm 1.1
  pub.publish(pose(0, 0, 0, 1, back));                   // stamp going back (by less than loop_back)
  ros::WallDuration(0.1).sleep();
  pub.publish(pose(0, 0, 0, 1, good));                   // good again
  l.spinUntil([&] { return l.has(good); }, 20.0);
  ASSERT_TRUE(l.has(good)) << "the node did not answer a good pose after the bad ones";
  EXPECT_FALSE(l.has(bad2));
  EXPECT_FALSE(l.has(back)) << "a stamp going back was answered";
  const geometry_msgs::Wrench& w = l.body[good.toNSec()].wrench;
  for (double v : {w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z}) EXPECT_TRUE(std::isfinite(v));
  // /diagnostics (every ~diagnostics_period, wall clock): 3 samples dropped in all.
  l.spinUntil([&] { return overall.count("samples dropped") && overall["samples dropped"] == "3"; }, 10.0);
  EXPECT_EQ(overall["samples dropped"], "3") << "last event: " << overall["last event"];
  EXPECT_FALSE(line_status.empty());
  bool named = false;
  for (const auto& n : line_status) named = named || n.find("line bow") != std::string::npos;
  EXPECT_TRUE(named) << "one diagnostic status per line, named";
}

TEST(VesselNode, SolveStaticService) {
  if (g_mode == "storm") GTEST_SKIP() << "the small vessel's statics; not in test_vessel_node_storm.test";
  const std::string srv_name = g_node + "/solve_static";
  ASSERT_TRUE(ros::service::waitForService(srv_name, ros::Duration(20.0)));
  VesselStatics srv;
  srv.request.use_file_pose = true;
  srv.request.want_stiffness = true;
  srv.request.offset_dof = "surge";
  srv.request.offset_range = 4.0;
  srv.request.offset_steps = 3;
  ASSERT_TRUE(ros::service::call(srv_name, srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const core::SystemProblem s = core::loadSystemFromFile(kProblem);
  const core::VesselStaticResult ref = core::solveVesselStatic(s, s.vessel.pose);
  const auto& wb = srv.response.wrench_body;
  EXPECT_EQ(wb.force.x, ref.wrench.force_body.x());
  EXPECT_EQ(wb.force.y, ref.wrench.force_body.y());
  EXPECT_EQ(wb.force.z, ref.wrench.force_body.z());
  EXPECT_EQ(wb.torque.x, ref.wrench.moment_body.x());
  EXPECT_EQ(wb.torque.y, ref.wrench.moment_body.y());
  EXPECT_EQ(wb.torque.z, ref.wrench.moment_body.z());
  EXPECT_EQ(srv.response.wrench_world.force.x, ref.wrench.force_world.x());
  ASSERT_EQ(srv.response.line_names.size(), 3u);
  EXPECT_EQ(srv.response.line_names[0], "bow");
  EXPECT_EQ(srv.response.top_tension[0], ref.system.lines[0].topTension());
  EXPECT_GT(srv.response.stiffness[0], 0.0) << "surge";
  EXPECT_GT(srv.response.stiffness[7], 0.0) << "sway";
  EXPECT_GT(srv.response.stiffness[35], 0.0) << "yaw";
  ASSERT_EQ(srv.response.offsets.size(), 3u);
  EXPECT_DOUBLE_EQ(srv.response.offsets[0], -4.0);
  // Pushed forward, the lines pull it back: restoring surge force falls with the offset.
  EXPECT_GT(srv.response.restoring[0], srv.response.restoring[2]);
  EXPECT_EQ(srv.response.max_tension_line.size(), 3u);

  // Bad values: success false, the field named.
  VesselStatics bad;
  bad.request.pose.position.x = std::nan("");
  bad.request.pose.orientation.w = 1.0;
  ASSERT_TRUE(ros::service::call(srv_name, bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("pose.position"), std::string::npos) << bad.response.message;
  VesselStatics bad2;
  bad2.request.use_file_pose = true;
  bad2.request.offset_dof = "sideways";
  ASSERT_TRUE(ros::service::call(srv_name, bad2));
  EXPECT_FALSE(bad2.response.success);
  EXPECT_NE(bad2.response.message.find("offset_dof"), std::string::npos) << bad2.response.message;
}

// ~winch and ~release (issue 21): the port quarter line's winch hauls it in at 0.5 m/s, its
// CableState's line_length following; the bow line let go at its fairlead pulls nothing from the
// next sample on; the event is on its CableState and in /diagnostics; bad requests name the
// field. Runs last (it changes the node's lines for good).
TEST(VesselNode, ReleaseServiceLetsALineGo) {
  if (g_mode != "live" || g_source != "pose") GTEST_SKIP() << "live PoseStamped only";
  Listener& l = *g_listener;
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseStamped>(g_node + "/vessel_pose", 100);
  ASSERT_TRUE(connect(&pub));
  std::map<std::string, std::string> overall;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          if (st.name.find("vessel lockstep") != std::string::npos) {
            overall.clear();
            for (const auto& kv : st.values) overall[kv.key] = kv.value;
          }
      });
  const std::string srv_name = g_node + "/release";
  ASSERT_TRUE(ros::service::waitForService(srv_name, ros::Duration(20.0)));
  mooring_dynamics::ReleaseLine bad;
  bad.request.line = "mast";
  bad.request.end = "top";
  ASSERT_TRUE(ros::service::call(srv_name, bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("line = mast: no line of that name (lines: bow, port_quarter, stbd_quarter)"),
            std::string::npos)
      << bad.response.message;
  bad.request.line = "bow";
  bad.request.end = "middle";
  ASSERT_TRUE(ros::service::call(srv_name, bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("end = \"middle\": must be top or anchor"), std::string::npos) << bad.response.message;

  const std::string winch_srv = g_node + "/winch";
  ASSERT_TRUE(ros::service::waitForService(winch_srv, ros::Duration(20.0)));
  mooring_dynamics::Winch wbad;
  wbad.request.line = "mast";
  wbad.request.rate = 0.5;
  ASSERT_TRUE(ros::service::call(winch_srv, wbad));
  EXPECT_FALSE(wbad.response.success);
  EXPECT_NE(wbad.response.message.find("line = mast: no line of that name"), std::string::npos) << wbad.response.message;
  mooring_dynamics::Winch win;
  win.request.line = "port_quarter";
  win.request.rate = -0.5;
  ASSERT_TRUE(ros::service::call(winch_srv, win));
  ASSERT_TRUE(win.response.success) << win.response.message;
  EXPECT_NE(win.response.message.find("hauling in at 0.5 m/s"), std::string::npos) << win.response.message;
  const double L0 = win.response.line_length;
  ASSERT_GT(L0, 10.0);
  ASSERT_FALSE(l.body.empty());
  const uint64_t commanded = l.body.rbegin()->first;  // the node's last sample before the command

  mooring_dynamics::ReleaseLine rel;
  rel.request.line = "bow";
  rel.request.end = "top";
  ASSERT_TRUE(ros::service::call(srv_name, rel));
  ASSERT_TRUE(rel.response.success) << rel.response.message;
  ASSERT_TRUE(ros::service::call(srv_name, rel));
  EXPECT_FALSE(rel.response.success) << "the same end twice";
  EXPECT_NE(rel.response.message.find("let go already"), std::string::npos) << rel.response.message;

  // The next samples: the bow line's top tension is gone; the other two still pull.
  const ros::Time t_last = kStart + ros::Duration(kDt * (kSamples - 1));
  std::vector<ros::Time> stamps;
  for (int k = 5; k <= 8; ++k) stamps.push_back(t_last + ros::Duration(0.1 * k));
  for (const ros::Time& st : stamps) {
    geometry_msgs::PoseStamped m;
    m.header.stamp = st;
    m.header.frame_id = "world";
    m.pose.orientation.w = 1.0;
    pub.publish(m);
    l.spinUntil([&] { return l.has(st); }, 20.0);
    ASSERT_TRUE(l.has(st)) << "no answer after the release";
  }
  const uint64_t last = stamps.back().toNSec();
  l.spinUntil([&] { return l.top[0].count(last) && l.top[1].count(last); }, 10.0);
  ASSERT_TRUE(l.top[0].count(last) && l.top[1].count(last));
  // Free end: the internal force at the top is zero to the Newton tolerance (1e-6 of the scale).
  EXPECT_LT(std::abs(l.top[0][last]), 1e-3 * l.top[1][last]) << "bow top tension after the release";
  EXPECT_GT(l.top[1][last], 1000.0);
  // The winch ran from the last sample before the command to the last one (solver time = stamps).
  l.spinUntil([&] { return l.length[1].count(last) > 0; }, 10.0);
  ASSERT_TRUE(l.length[1].count(last));
  EXPECT_NEAR(l.length[1][last], L0 - 0.5 * 1e-9 * static_cast<double>(last - commanded), 1e-6);
  EXPECT_EQ(l.length[2][last], l.length[2].begin()->second) << "the other quarter line keeps its length";
  ASSERT_EQ(l.events[0].size(), 1u);
  EXPECT_NE(l.events[0][0].find("released top"), std::string::npos) << l.events[0][0];
  EXPECT_TRUE(l.events[1].empty());
  const geometry_msgs::Wrench& w = l.body[last].wrench;
  for (double v : {w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z}) EXPECT_TRUE(std::isfinite(v));
  // The two quarter lines pull aft (-x) with nothing to balance them forward.
  EXPECT_LT(w.force.x, -1000.0);
  l.spinUntil([&] { return overall.count("line events") && overall["line events"] == "1"; }, 10.0);
  EXPECT_EQ(overall["line events"], "1");
  EXPECT_NE(overall["last line event"].find("bow released top"), std::string::npos) << overall["last line event"];
}

int main(int argc, char** argv) { return testMain(argc, argv, "test_vessel_node"); }
