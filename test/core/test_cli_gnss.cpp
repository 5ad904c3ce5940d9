// cable_sim dynamic on a real ship track (src/cli/gnss_input.cpp, dynamics.gnss.track): a line's
// top follows the fixes (against a position table of the displacements the fixes mean by the
// ellipsoid's meridian radius; a jump rejected and counted), a vessel turns as its compass heading says (wrench series against a
// motion table written from the closed-form yaw), and misuse exits 3 naming the key.
// Runs the built binary (CABLE_SIM_EXE).
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

constexpr double kPi = 3.14159265358979323846;
constexpr double kLat = 41.5;                                // [deg]
// WGS84 meridian radius of curvature at kLat [m]: a (1 - e^2) / (1 - e^2 sin^2)^1.5.
double meridianRadius() {
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f), s = std::sin(kLat * kPi / 180.0);
  return a * (1.0 - e2) / std::pow(1.0 - e2 * s * s, 1.5);
}

std::vector<std::vector<double>> csvRows(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> r;
    std::stringstream cells(line);
    std::string c;
    while (std::getline(cells, c, ',')) r.push_back(std::stod(c));
    rows.push_back(r);
  }
  return rows;
}

/// A 3-D rope from 100 m depth to a top at the surface 60 m away.
const char* const kLine = R"(
model: 3d
environment: {depth: 100}
materials:
  rope: {EA: 2.0e6, EI: 1, GJ: 1, mass: 2, added_mass: 1, wet_weight: 10, diameter: 0.03, cdn: 1.5, cdt: 0.01}
line: [{material: rope, length: 125, spacing: 5}]
anchor: {x: 0, z: -100}
top: {position: {x: 60, y: 0, z: 0}}
)";

/// Two chain lines fore and aft of a hull, as in test_cli_vessel.
const char* const kVessel = R"(
model: 3d
environment: {depth: 100}
materials:
  chain: {EA: 5.0e8, EI: 10, GJ: 1, mass: 40, added_mass: 5, wet_weight: 300, diameter: 0.08, cdn: 2.4, cdt: 1.15}
vessel:
  frame: hull
  pose: {position: [0, 0, 0], yaw_deg: 0}
  lines:
    - {name: fwd, fairlead: [20, 0, -5], anchor: [270, 0, -100], segments: [{material: chain, length: 300, spacing: 10}]}
    - {name: aft, fairlead: [-20, 0, -5], anchor: [-270, 0, -100], segments: [{material: chain, length: 300, spacing: 10}]}
)";

class CliGnss : public CliFixture {
 protected:
  CliGnss() : CliFixture("test_cli_gnss") {}
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
};

}  // namespace

TEST_F(CliGnss, LineTopFollowsTheFixesAndAJumpIsRejected) {
  // North at 0.5 m/s for 8 s, fixes every second; the fix at t = 4 s jumps 0.01 deg (~1.1 km).
  std::ostringstream track;
  track.precision(12);
  track << "t,latitude,longitude,heading\n";
  for (int k = 0; k <= 8; ++k) {
    const double lat = kLat + (k == 4 ? 0.01 : 0.5 * k / meridianRadius() * 180.0 / kPi);
    track << k << "," << lat << ",-70.6,0\n";
  }
  write("track.csv", track.str());
  const std::string p =
      write("line.yaml", std::string(kLine) + "dynamics: {dt: 0.5, gnss: {track: track.csv, smoothing_time: 0}}\n");
  RunResult r = run({"dynamic", p, "--out", (dir_ / "out").string(), "--no-progress"});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("9 fixes, 8 accepted, 1 jump"), std::string::npos) << r.out;
  // The same line on the position table the track means: 0.5 m/s north from the static top,
  // without the rejected row.
  std::ostringstream rows_yaml;
  rows_yaml << "dynamics: {dt: 0.5, duration: 8, top_motion: {type: position_table, prescribe: position, table: [";
  for (int k = 0; k <= 8; ++k)
    if (k != 4) rows_yaml << (k ? ", " : "") << "[" << k << ", 60, " << 0.5 * k << ", 0]";
  rows_yaml << "]}}\n";
  const std::string q = write("table.yaml", std::string(kLine) + rows_yaml.str());
  r = run({"dynamic", q, "--out", (dir_ / "table").string(), "--no-progress"});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const auto g = csvRows(readText(dir_ / "out" / "timeseries.csv"));
  const auto t = csvRows(readText(dir_ / "table" / "timeseries.csv"));
  ASSERT_EQ(g.size(), t.size());
  EXPECT_DOUBLE_EQ(g.back()[0], 8.0);  // duration: the track's, from its first fix
  // Positions from the fixes agree with the table's to the 12 printed digits of the latitude
  // (~1e-7 m) and the local plane against the meridian arc (~1e-9 m over 4 m): 1e-5 m, and the
  // tensions to what such a difference in the top's path makes of them, 1e-5 relative.
  constexpr double kPositionTol = 1e-5, kTensionRel = 1e-5;
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_NEAR(g[i][1], t[i][1], kTensionRel * t[i][1]) << "t = " << t[i][0];
    for (int c : {3, 4, 5}) EXPECT_NEAR(g[i][c], t[i][c], kPositionTol) << "t = " << t[i][0] << " column " << c;
  }
}

TEST_F(CliGnss, VesselTurnsAsItsHeadingSays) {
  // The antenna at the body origin, the ship still, turning from east (090) to 080 in 4 s.
  std::ostringstream track, table;
  track.precision(12);
  table.precision(17);
  track << "t,latitude,longitude,heading\n";
  table << "t,x,y,z,qx,qy,qz,qw\n";
  for (int k = 0; k <= 16; ++k) {
    const double t = 0.25 * k, heading = 90.0 - 10.0 * t / 4.0;
    track << t << "," << kLat << ",-70.6," << heading << "\n";
    const double yaw = (90.0 - heading) * kPi / 180.0;  // REP 103: counter-clockwise from east
    table << t << ",0,0,0,0,0," << std::sin(yaw / 2) << "," << std::cos(yaw / 2) << "\n";
  }
  write("track.csv", track.str());
  write("motion.csv", table.str());
  const std::string gnss =
      write("gnss.yaml", std::string(kVessel) + "dynamics: {dt: 0.25, gnss: {track: track.csv, smoothing_time: 0}}\n");
  std::string tab = kVessel;
  tab.replace(tab.find("  lines:"), 0, "  motion_table: motion.csv\n");
  const std::string table_file = write("table.yaml", tab + "dynamics: {dt: 0.25}\n");
  RunResult r = run({"dynamic", gnss, "--out", (dir_ / "g").string(), "--no-progress"});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  r = run({"dynamic", table_file, "--out", (dir_ / "t").string(), "--no-progress"});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const auto g = csvRows(readText(dir_ / "g" / "vessel_timeseries.csv"));
  const auto t = csvRows(readText(dir_ / "t" / "vessel_timeseries.csv"));
  ASSERT_EQ(g.size(), t.size());
  ASSERT_GE(g.size(), 16u);
  // Same motion up to the rounding of two ways of writing the quaternion (1e-16 rad), which the
  // Newton iterations carry to ~1e-9 of the forces.
  constexpr double kSameRel = 1e-6;
  double yaw_moment = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i)
    for (std::size_t c = 0; c < g[i].size(); ++c) {
      const double scale = std::max({std::abs(t[i][c]), std::abs(t[i][3]), 1.0});
      EXPECT_NEAR(g[i][c], t[i][c], kSameRel * scale) << "row " << i << " column " << c;
      if (c == 6) yaw_moment = std::max(yaw_moment, std::abs(t[i][c]));
    }
  EXPECT_GT(yaw_moment, 1.0);  // the turn does load the mooring in yaw: the check has something to compare
}

TEST_F(CliGnss, MisuseExitsThreeNamingTheKey) {
  write("track.csv", "0,41.5,-70.6,0\n1,41.5,-70.6,0\n");
  RunResult r = run({"dynamic", write("a.yaml", std::string(kLine) + "dynamics: {dt: 0.5, gnss: {smoothing_time: 0}}\n")});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("dynamics.gnss.track"), std::string::npos) << r.err;
  std::string planar = kLine;
  planar.replace(planar.find("model: 3d"), 9, "model: 2d");
  planar.replace(planar.find("x: 60, y: 0, z: 0"), 17, "x: 60, z: 0");
  r = run({"dynamic", write("b.yaml", planar + "dynamics: {dt: 0.5, gnss: {track: track.csv}}\n")});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("model: 3d"), std::string::npos) << r.err;
  r = run({"dynamic", write("c.yaml", std::string(kLine) + "dynamics: {dt: 0.5, gnss: {track: track.csv}, "
                                                            "top_motion: {type: sinusoid, amplitude_z: 1, period: 5}}\n")});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("dynamics.top_motion"), std::string::npos) << r.err;
  r = run({"dynamic", write("d.yaml", std::string(kLine) + "dynamics: {dt: 0.5, gnss: {track: missing.csv}}\n")});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos) << r.err;
}
