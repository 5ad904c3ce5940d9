// rostest: the lockstep node with ~motion_source gnss (test/data/gnss_line.yaml) follows
// sensor_msgs/NavSatFix fixes and geometry_msgs/QuaternionStamped headings:
//   * at every accepted fix it publishes the same top tension, to the 12 digits cable_sim writes,
//     as `cable_sim dynamic` on the same track as a CSV (t, latitude, longitude, heading);
//   * a NO_FIX fix, a NaN latitude, a 1 km jump and a NaN heading are rejected, counted under
//     their names in /diagnostics, and change nothing (the good fixes after them match the CLI).
// GnssVesselNode (test_gnss_node.vessel.test): the moored-vessel node on test/data/gnss_vessel.yaml
// with the same fixes publishes, at every accepted fix, the world wrench cable_sim writes.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>

#include "mooring_dynamics/CableState.h"

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLat0 = 41.5, kLon0 = -70.6;   // [deg]
constexpr double kSpeed = 0.3;                  // [m/s] toward the heading
constexpr double kHeadingDeg = 45.0;            // compass: north-east
constexpr int kFixes = 21;                      // one a second from t0
constexpr double kT0 = 1000.0;                  // [s] first stamp (exact in both doubles and ros::Time)
const double kR = 6371000.0;                    // the test's own spherical track; the node and the CLI read the same numbers

std::string g_node = "/gnss_node";
// The node's tally of rejected GNSS input ("<window> / <total>"): 4 are sent.
constexpr const char* kRejectedKey = "dropped: GNSS input rejected (window / total)";

std::string csv12(double v) {
  char buf[40];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

struct Fix {
  double t, lat, lon;
};

Fix goodFix(int k) {
  const double d = kSpeed * k, e = d * std::sin(kHeadingDeg * kPi / 180), n = d * std::cos(kHeadingDeg * kPi / 180);
  return {kT0 + k, kLat0 + n / kR * 180 / kPi, kLon0 + e / (kR * std::cos(kLat0 * kPi / 180)) * 180 / kPi};
}

sensor_msgs::NavSatFix fixMsg(double t, double lat, double lon, int8_t status = sensor_msgs::NavSatStatus::STATUS_FIX) {
  sensor_msgs::NavSatFix m;
  m.header.stamp = ros::Time(t);
  m.header.frame_id = "gps";
  m.status.status = status;
  m.latitude = lat;
  m.longitude = lon;
  m.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN;
  return m;
}

geometry_msgs::QuaternionStamped headingMsg(double t, double yaw) {
  geometry_msgs::QuaternionStamped q;
  q.header.stamp = ros::Time(t);
  q.header.frame_id = "world";
  q.quaternion.z = std::sin(yaw / 2);
  q.quaternion.w = std::cos(yaw / 2);
  return q;
}

// The total of a "<window> / <total>" value.
std::string total(const std::string& v) {
  const std::size_t slash = v.find(" / ");
  return slash == std::string::npos ? std::string() : v.substr(slash + 3);
}

// Sends the track (with its bad fixes and heading) to the node at `node`, one message at a time,
// and waits until the state of the last fix and the diagnostics' count of accepted input are in.
// `states` is filled by the caller's subscription (by stamp in ns).
template <typename States>
std::map<std::string, std::string> sendTrack(ros::NodeHandle& nh, const std::string& node, const ros::Subscriber& state_sub,
                                             const States& states) {
  std::map<std::string, std::string> diag;
  auto diag_sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& a) {
    for (const auto& st : a->status)
      if (st.name.find(node) != std::string::npos)
        for (const auto& kv : st.values) diag[kv.key] = kv.value;
  });
  ros::Publisher fix_pub = nh.advertise<sensor_msgs::NavSatFix>(node + "/fix", 100);
  ros::Publisher heading_pub = nh.advertise<geometry_msgs::QuaternionStamped>(node + "/heading", 100);
  const ros::WallTime wait = ros::WallTime::now() + ros::WallDuration(30.0);
  while ((fix_pub.getNumSubscribers() == 0 || heading_pub.getNumSubscribers() == 0 || state_sub.getNumPublishers() == 0) &&
         ros::WallTime::now() < wait) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_GT(fix_pub.getNumSubscribers(), 0u);
  const double yaw = (90.0 - kHeadingDeg) * kPi / 180.0;
  auto send = [&](auto& pub, const auto& msg) {
    pub.publish(msg);
    ros::WallDuration(0.03).sleep();  // one message at a time: the order the node sees is the order sent
    ros::spinOnce();
  };
  for (int k = 0; k < kFixes; ++k) {
    const Fix f = goodFix(k);
    send(heading_pub, headingMsg(f.t, yaw));
    send(fix_pub, fixMsg(f.t, f.lat, f.lon));
    if (k == 5) send(fix_pub, fixMsg(f.t + 0.5, f.lat, f.lon, sensor_msgs::NavSatStatus::STATUS_NO_FIX));
    if (k == 10) send(fix_pub, fixMsg(f.t + 0.5, std::nan(""), f.lon));
    if (k == 12) {
      geometry_msgs::QuaternionStamped bad = headingMsg(f.t + 0.25, yaw);
      bad.quaternion.w = std::nan("");
      send(heading_pub, bad);
    }
    if (k == 15) send(fix_pub, fixMsg(f.t + 0.5, f.lat + 0.01, f.lon));  // ~1.1 km in 0.5 s
  }
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(60.0);
  auto done = [&] {
    return states.count(static_cast<long long>(ros::Time(goodFix(kFixes - 1).t).toNSec())) &&
           diag["gnss accepted"] == std::to_string(2 * kFixes) && total(diag[kRejectedKey]) == "4";
  };
  while (!done() && ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_TRUE(done()) << "states received: " << states.size();
  for (const auto& kv : diag)
    if (kv.first.rfind("gnss", 0) == 0 || kv.first == kRejectedKey) std::cout << kv.first << " = " << kv.second << "\n";
  EXPECT_EQ(diag["gnss no_fix"], "1");
  EXPECT_EQ(diag["gnss bad_value"], "2");  // the NaN latitude and the NaN heading
  EXPECT_EQ(diag["gnss jump"], "1");
  EXPECT_EQ(diag["gnss accepted"], std::to_string(2 * kFixes));  // fixes and headings
  EXPECT_EQ(total(diag[kRejectedKey]), "4") << "the node's own tally of dropped input";
  return diag;
}

// The same track as a CSV in a fresh folder with `problem` (test/data) beside it, through
// cable_sim dynamic (the jump row included: it rejects it the same way); returns the folder.
fs::path runCableSim(const std::string& problem) {
  const fs::path dir = fs::temp_directory_path() / ("md_gnss_node_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream t(dir / "gnss_track.csv");
    t.precision(17);
    t << "t,latitude,longitude,heading\n";
    for (int k = 0; k < kFixes; ++k) {
      const Fix f = goodFix(k);
      t << f.t << "," << f.lat << "," << f.lon << "," << kHeadingDeg << "\n";
      if (k == 15) t << f.t + 0.5 << "," << f.lat + 0.01 << "," << f.lon << "," << kHeadingDeg << "\n";
    }
    fs::copy_file(fs::path(MD_SOURCE_DIR) / "test" / "data" / problem, dir / problem, fs::copy_options::overwrite_existing);
  }
  const std::string cmd = std::string(CABLE_SIM_EXE) + " dynamic " + (dir / problem).string() + " --out " +
                          (dir / "out").string() + " --no-progress >" + (dir / "log.txt").string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return dir;
}

// cable_sim's series: t (as written) -> the row's fields (as written).
std::map<std::string, std::vector<std::string>> readSeries(const fs::path& file) {
  std::map<std::string, std::vector<std::string>> rows;
  std::ifstream f(file);
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string x;
    while (std::getline(ss, x, ',')) fields.push_back(x);
    if (!fields.empty()) rows[fields[0]] = fields;
  }
  return rows;
}

}  // namespace

TEST(GnssNode, FollowsTheFixesAsCableSimDoesAndCountsBadOnes) {
  ros::NodeHandle nh;
  std::map<long long, double> top_tension;  // by stamp [ns]
  bool finite = true;
  auto state_sub = nh.subscribe<mooring_dynamics::CableState>(
      g_node + "/cable_state", 100, [&](const mooring_dynamics::CableState::ConstPtr& m) {
        top_tension[static_cast<long long>(m->header.stamp.toNSec())] = m->tension.back();
        for (double t : m->tension) finite = finite && std::isfinite(t);
      });
  sendTrack(nh, g_node, state_sub, top_tension);
  EXPECT_TRUE(finite);
  const fs::path dir = runCableSim("gnss_line.yaml");
  const auto cli = readSeries(dir / "out" / "timeseries.csv");
  for (int k = 1; k < kFixes; ++k) {
    const long long ns = static_cast<long long>(ros::Time(goodFix(k).t).toNSec());
    ASSERT_TRUE(top_tension.count(ns)) << "no state at fix " << k;
    ASSERT_TRUE(cli.count(std::to_string(k))) << "no cable_sim row at t = " << k;
    EXPECT_EQ(csv12(top_tension[ns]), cli.at(std::to_string(k))[1]) << "fix " << k;
  }
  // The motion does something: the tension changes along the track.
  EXPECT_NE(cli.at("1")[1], cli.at(std::to_string(kFixes - 1))[1]);
  fs::remove_all(dir);
}

// The moored vessel on the same fixes: the world wrench (force and moment about the body origin)
// at every accepted fix, to the digits cable_sim writes in vessel_timeseries.csv (columns 7-12).
TEST(GnssVesselNode, FollowsTheFixesAsCableSimDoes) {
  ros::NodeHandle nh;
  std::map<long long, std::vector<double>> wrench;  // by stamp [ns]: fx, fy, fz, mx, my, mz (world)
  auto state_sub = nh.subscribe<geometry_msgs::WrenchStamped>(
      g_node + "/wrench_world", 100, [&](const geometry_msgs::WrenchStamped::ConstPtr& m) {
        const auto& f = m->wrench.force;
        const auto& t = m->wrench.torque;
        wrench[static_cast<long long>(m->header.stamp.toNSec())] = {f.x, f.y, f.z, t.x, t.y, t.z};
      });
  sendTrack(nh, g_node, state_sub, wrench);
  const fs::path dir = runCableSim("gnss_vessel.yaml");
  const auto cli = readSeries(dir / "out" / "vessel_timeseries.csv");
  for (int k = 1; k < kFixes; ++k) {
    const long long ns = static_cast<long long>(ros::Time(goodFix(k).t).toNSec());
    ASSERT_TRUE(wrench.count(ns)) << "no wrench at fix " << k;
    ASSERT_TRUE(cli.count(std::to_string(k))) << "no cable_sim row at t = " << k;
    const std::vector<std::string>& row = cli.at(std::to_string(k));
    ASSERT_GE(row.size(), 13u);
    for (int c = 0; c < 6; ++c) EXPECT_EQ(csv12(wrench[ns][static_cast<std::size_t>(c)]), row[7 + c]) << "fix " << k << " component " << c;
  }
  // The vessel moved the lines: the surge force changes along the track.
  EXPECT_NE(cli.at("1")[7], cli.at(std::to_string(kFixes - 1))[7]);
  fs::remove_all(dir);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_gnss_node");
  ros::NodeHandle p("~");
  p.param<std::string>("node", g_node, g_node);
  return RUN_ALL_TESTS();
}
