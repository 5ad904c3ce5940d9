// cable_sim on a moored vessel (src/cli/cmd_vessel.cpp, cmd_system.cpp): the static wrench, the
// stiffness and offset commands, and a dynamic run on a motion table whose series does not depend
// on --threads. Runs the built binary (CABLE_SIM_EXE).
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace md_cli_test;

namespace {

/// Two chain lines fore and aft of a 40 m hull in 100 m of water, and a motion table: the vessel
/// surges 1 m and yaws 2 deg over 4 s.
const char* const kVessel = R"(
name: two-line vessel
model: 3d
environment: {depth: 100}
materials:
  chain: {EA: 5.0e8, EI: 10, GJ: 1, mass: 40, added_mass: 5, wet_weight: 300, diameter: 0.08, cdn: 2.4, cdt: 1.15}
vessel:
  frame: hull
  pose: {position: [0, 0, 0], yaw_deg: 0}
  motion_table: motion.csv
  lines:
    - {name: fwd, fairlead: [20, 0, -5], anchor: [270, 0, -100], segments: [{material: chain, length: 300, spacing: 10}]}
    - {name: aft, fairlead: [-20, 0, -5], anchor: [-270, 0, -100], segments: [{material: chain, length: 300, spacing: 10}]}
dynamics: {dt: 0.25, lambda_inf: -0.5}
)";

class CliVessel : public CliFixture {
 protected:
  CliVessel() : CliFixture("test_cli_vessel") {}
  void SetUp() override {
    CliFixture::SetUp();
    if (HasFatalFailure()) return;
    std::ofstream(dir_ / "vessel.yaml") << kVessel;
    std::ofstream m(dir_ / "motion.csv");
    m << "t,x,y,z,qx,qy,qz,qw\n";
    for (int k = 0; k <= 16; ++k) {
      const double t = 0.25 * k, s = t / 4.0, yaw = 2.0 * 3.14159265358979323846 / 180.0 * s;
      m << t << "," << s << ",0,0,0,0," << std::sin(yaw / 2) << "," << std::cos(yaw / 2) << "\n";
    }
  }
  std::string file() const { return (dir_ / "vessel.yaml").string(); }
};

}  // namespace

TEST_F(CliVessel, StaticPrintsTheWrenchInBothFrames) {
  const RunResult r = run({"static", file()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("vessel hull at (0.00, 0.00, 0.00) m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("world frame  force"), std::string::npos);
  EXPECT_NE(r.out.find("body frame   force"), std::string::npos);
  EXPECT_NE(r.out.find("fwd/fairlead (vessel)"), std::string::npos);
}

TEST_F(CliVessel, StiffnessAndOffsetCommands) {
  RunResult r = run({"stiffness", file(), "--out", (dir_ / "k").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mooring stiffness"), std::string::npos);
  const std::string csv = readText(dir_ / "k" / "stiffness.csv");
  EXPECT_EQ(csv.rfind("row,surge,sway,heave,roll,pitch,yaw\nsurge,", 0), 0u) << csv;
  r = run({"offset", file(), "--dof", "surge", "--range", "5", "--steps", "3"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("offset curve in surge"), std::string::npos);
  // Bad values name the option.
  r = run({"offset", file(), "--dof", "twist"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--dof"), std::string::npos) << r.err;
  r = run({"offset", file(), "--dof", "yaw", "--range", "120"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--range"), std::string::npos) << r.err;
  // A file without a vessel is refused with a clear message.
  std::ofstream(dir_ / "line.yaml") << "materials: {w: {EA: 1e8, EI: 1, mass: 1, wet_weight: 10, diameter: 0.02, cdn: 1, cdt: 0.1}}\n"
                                       "line: [{material: w, length: 100, spacing: 10}]\nanchor: {x: 0, z: -60}\n"
                                       "top: {position: {x: 80, z: 0}}\n";
  r = run({"stiffness", (dir_ / "line.yaml").string()});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("vessel"), std::string::npos) << r.err;
}

TEST_F(CliVessel, DynamicRunFollowsTheTableWithTheSameBitsOnOneAndTwoThreads) {
  RunResult r1 = run({"dynamic", file(), "--threads", "1", "--out", (dir_ / "t1").string(), "--no-progress"});
  ASSERT_EQ(r1.code, 0) << r1.out << r1.err;
  EXPECT_NE(r1.out.find("vessel dynamic run completed"), std::string::npos) << r1.out;
  EXPECT_NE(r1.out.find("17 samples"), std::string::npos) << r1.out;
  RunResult r2 = run({"dynamic", file(), "--threads", "2", "--out", (dir_ / "t2").string(), "--no-progress"});
  ASSERT_EQ(r2.code, 0) << r2.err;
  const std::string a = readText(dir_ / "t1" / "vessel_timeseries.csv"), b = readText(dir_ / "t2" / "vessel_timeseries.csv");
  EXPECT_EQ(a.rfind("t,fx_body,fy_body,fz_body,mx_body,my_body,mz_body,fx_world", 0), 0u) << a.substr(0, 200);
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
  // A malformed table row is an error naming the row and column.
  std::ofstream(dir_ / "motion.csv", std::ios::app) << "4.5,1,abc,0,0,0,0,1\n";
  const RunResult bad = run({"dynamic", file(), "--no-progress"});
  EXPECT_EQ(bad.code, 3);
  EXPECT_NE(bad.err.find("column y = \"abc\""), std::string::npos) << bad.err;
}

// A step that fails at its smallest cut (4 Newton iterations, no cutting, no fallback step: the
// forced failure) stops
// the run as it stops a single line's: the series up to the last good sample is written, the
// summary says "completed": false, and the exit code is 4 (docs/cli.md, "Exit codes").
TEST_F(CliVessel, DynamicRunThatStopsExitsFourAndWritesUpToTheLastGoodSample) {
  std::string text = kVessel;
  text.replace(text.find("dynamics: {dt: 0.25, lambda_inf: -0.5}"), 38,
               "dynamics: {dt: 0.25, lambda_inf: -0.5, max_iterations: 4, max_cut_levels: 0, fallback: false}");
  std::ofstream(dir_ / "vessel.yaml") << text;
  {
    // The table of SetUp, but the vessel lurches 5 m at t = 2.25 s (20 m/s: under max_speed, so
    // it reaches the lines).
    std::ofstream m(dir_ / "motion.csv");
    m << "t,x,y,z,qx,qy,qz,qw\n";
    for (int k = 0; k <= 16; ++k) {
      const double t = 0.25 * k, s = t / 4.0 + (k >= 9 ? 5.0 : 0.0);
      m << t << "," << s << ",0,0,0,0,0,1\n";
    }
  }
  const RunResult r = run({"dynamic", file(), "--out", (dir_ / "o").string(), "--no-progress"});
  EXPECT_EQ(r.code, 4) << r.out << r.err;
  EXPECT_NE(r.out.find("vessel dynamic run STOPPED"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("last good      t = 2 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line fwd"), std::string::npos) << "names the failed line: " << r.out;
  EXPECT_NE(r.err.find("stopped at t = 2 s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"completed\": false"), std::string::npos) << r.err;
  const std::string ts = readText(dir_ / "o" / "vessel_timeseries.csv");
  std::istringstream lines(ts);
  std::string line, last;
  int n = 0;
  while (std::getline(lines, line)) {
    ++n;
    last = line;
  }
  EXPECT_EQ(n, 1 + 9) << "header and t = 0 ... 2 s:\n" << ts;
  EXPECT_EQ(last.rfind("2,", 0), 0u) << last;
  const std::string js = readText(dir_ / "o" / "dynamic_summary.json");
  EXPECT_NE(js.find("\"completed\": false"), std::string::npos) << js;
  EXPECT_NE(js.find("\"simulated_time\": 2,"), std::string::npos) << js;
  EXPECT_NE(js.find("\"kind\": \"vessel\""), std::string::npos) << js;
}

// vessel.sea_state with RAOs: a hull that heaves with the surface (heave RAO 1, phase 0, the rest
// 0) in a regular wave of H 2 m, T 8 s travelling along +x has z(t) = cos(2 pi t / 8) at its
// origin, and vz = -w sin(w t), by hand. The run on the sea state and the run on that hand-written
// table (with the same wave on the lines) give the same series bit for bit: the vessel moves as
// the RAO says and the lines see the sea the vessel sees.
TEST_F(CliVessel, SeaStateRunIsTheRunOnItsHandWrittenMotionTable) {
  {
    std::ofstream csv(dir_ / "hull.csv");
    csv << "omega,heading_deg,dof,amplitude,phase_deg\n";
    for (double w : {0.2, 0.5, 1.0, 2.0})
      for (int h : {0, 90, 180, 270})
        for (int d = 1; d <= 6; ++d) csv << w << "," << h << "," << d << "," << (d == 3 ? 1 : 0) << ",0\n";
    std::ofstream m(dir_ / "heave.csv");
    m << "t,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz\n";
    m.precision(17);
    const double w = 2.0 * 3.14159265358979323846 / 8.0;
    for (int k = 0; k <= 16; ++k) {
      const double t = static_cast<double>(k) * 0.25;
      m << t << ",0,0," << std::cos(w * t) << ",0,0,0,1,0,0," << -w * std::sin(w * t) << ",0,0,0\n";
    }
  }
  const std::string wave = "{type: regular, height: 2, period: 8, direction_deg: 0}";
  std::string sea = kVessel;
  sea.replace(sea.find("  motion_table: motion.csv\n"), 27, "  sea_state: " + wave + "\n  raos: {file: hull.csv}\n");
  sea.replace(sea.find("dynamics: {dt: 0.25,"), 20, "dynamics: {duration: 4, dt: 0.25,");
  std::ofstream(dir_ / "sea.yaml") << sea;
  std::string table = kVessel;
  table.replace(table.find("motion_table: motion.csv"), 24, "motion_table: heave.csv");
  table.replace(table.find("environment: {depth: 100}"), 25, "environment: {depth: 100, waves: " + wave + "}");
  std::ofstream(dir_ / "table.yaml") << table;
  const RunResult a = run({"dynamic", (dir_ / "sea.yaml").string(), "--out", (dir_ / "a").string(), "--no-progress"});
  ASSERT_EQ(a.code, 0) << a.out << a.err;
  EXPECT_NE(a.out.find("regular wave H 2 m, T 8 s, toward 0 deg, RAOs"), std::string::npos) << a.out;
  const RunResult b = run({"dynamic", (dir_ / "table.yaml").string(), "--out", (dir_ / "b").string(), "--no-progress"});
  ASSERT_EQ(b.code, 0) << b.out << b.err;
  const std::string sa = readText(dir_ / "a" / "vessel_timeseries.csv"), sb = readText(dir_ / "b" / "vessel_timeseries.csv");
  EXPECT_GT(sa.size(), 1000u);
  EXPECT_EQ(sa, sb);
  // Without the wave on the lines the series differ: the lines do feel the sea.
  table.replace(table.find(", waves: " + wave), 9 + wave.size(), "");
  std::ofstream(dir_ / "table.yaml") << table;
  const RunResult c = run({"dynamic", (dir_ / "table.yaml").string(), "--out", (dir_ / "c").string(), "--no-progress"});
  ASSERT_EQ(c.code, 0) << c.out << c.err;
  EXPECT_NE(readText(dir_ / "c" / "vessel_timeseries.csv"), sa);

  // With low_frequency and a drift table of -1000 N/m^2 in surge everywhere: a regular wave of
  // amplitude 1 m pushes the hull with a^2 D = -1000 N at every sample (the drift columns), and
  // the hull moves aft (-x) from rest.
  {
    std::ofstream d(dir_ / "drift.csv");
    d << "omega,heading_deg,surge,sway,yaw\n";
    for (double w : {0.2, 2.0})
      for (int h : {0, 90, 180, 270}) d << w << "," << h << ",-1000,0,0\n";
  }
  std::string slow = sea;
  slow.replace(slow.find("  raos: {file: hull.csv}\n"), 25,
               "  raos: {file: hull.csv}\n  low_frequency: {mass: 1.0e5, yaw_inertia: 1.0e7, wave_drift: {file: drift.csv}}\n");
  std::ofstream(dir_ / "slow.yaml") << slow;
  const RunResult e = run({"dynamic", (dir_ / "slow.yaml").string(), "--out", (dir_ / "e").string(), "--no-progress"});
  ASSERT_EQ(e.code, 0) << e.out << e.err;
  EXPECT_NE(e.out.find("slow drift with Newman's wave drift"), std::string::npos) << e.out;
  std::istringstream ts(readText(dir_ / "e" / "vessel_timeseries.csv"));
  std::string line;
  std::getline(ts, line);
  ASSERT_EQ(line.substr(line.size() - 23), "drift_x,drift_y,drift_n");
  int rows = 0;
  double x_last = 0.0;
  while (std::getline(ts, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    std::string c;
    while (std::getline(cells, c, ',')) v.push_back(std::stod(c));
    ASSERT_GE(v.size(), 9u);
    EXPECT_DOUBLE_EQ(v[v.size() - 3], -1000.0) << line;
    EXPECT_DOUBLE_EQ(v[v.size() - 2], 0.0);
    x_last = v[v.size() - 9];  // vessel_x
    ++rows;
  }
  EXPECT_EQ(rows, 17);
  EXPECT_LT(x_last, 0.0) << "the drift pushes the hull aft";
}
