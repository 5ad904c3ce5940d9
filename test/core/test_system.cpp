// Systems of lines (issue 6: multi-leg and branched arrays) against independent answers: a
// symmetric three-leg buoy mooring (equal leg tensions, no offset in still water), two legs on a
// fixed junction (two independent Irvine catenaries), a branched array's junction force balance
// checked by hand, and the topology checks.
#include <gtest/gtest.h>

#include <fstream>
#include <unistd.h>

#include <cmath>

#include "mooring_dynamics/core/equations/catenary.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "system_test_util.hpp"

using namespace mooring_dynamics::core;
using mooring_dynamics::core::testing_util::line;
using mooring_dynamics::core::testing_util::point;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Symmetry: the three legs are the same problem turned by 120 deg; the point iteration stops
// on a force residual of 1e-6 of the tension, which bounds the asymmetry.
constexpr double kSymmetryRelTol = 1e-5;
constexpr double kOffsetTol = 1e-3;  // [m] buoy offset of a symmetric mooring
// Irvine at 1 m spacing: the box scheme's O(h^2) error, about 1e-4 relative.
constexpr double kCatenaryRelTol = 1e-3;
// Force balances hold to the point iteration's tolerance (1e-6 of the largest tension).
constexpr double kBalanceRelTol = 1e-5;

Material chain() {
  Material m;
  m.name = "chain";
  m.EA = 5.0e8;
  m.EI = 10.0;
  m.GJ = 1.0;
  m.mass = 40.0;
  m.added_mass = 5.0;
  m.wet_weight = 300.0;
  m.diameter = 0.08;
  m.cdn = 2.4;
  m.cdt = 1.15;
  return m;
}


/// The three-leg buoy of system_test_util.hpp at 5 m spacing, in a uniform current [m/s] toward +x.
SystemProblem threeLeg(double current) {
  SystemProblem s = testing_util::threeLegBuoy(5.0);
  if (current > 0.0) s.environment.current = {{0.0, current, 0.0}};
  return s;
}

}  // namespace

TEST(System, SymmetricThreeLegMooringHasEqualLegsAndNoOffset) {
  const SystemStaticResult r = solveSystemStatic(threeLeg(0.0));
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  const double T0 = r.lines[0].topTension();
  for (int k = 1; k < 3; ++k) EXPECT_NEAR(r.lines[k].topTension(), T0, kSymmetryRelTol * T0) << k;
  EXPECT_NEAR(r.points[0].x, 0.0, kOffsetTol);
  EXPECT_NEAR(r.points[0].y, 0.0, kOffsetTol);
  // The buoy carries the three legs' vertical pulls by its draft.
  double Fz = 0.0;
  for (const auto& l : r.lines) Fz += l.top_force_z;
  const SystemProblem sys = threeLeg(0.0);  // (a reference into a temporary would dangle: ASan)
  const SurfaceBuoy& b = sys.points[0].buoy;
  const double draft = r.points[0].buoy_draft;
  EXPECT_NEAR(1025.0 * 9.81 * b.submergedVolume(draft) - b.mass * 9.81, Fz, kBalanceRelTol * T0);
  EXPECT_GT(draft, 0.0);
  EXPECT_LT(draft, b.height);
}

TEST(System, CurrentPushesTheBuoyDownstreamAndLoadsTheUpstreamLeg) {
  const SystemStaticResult r = solveSystemStatic(threeLeg(0.5));
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  EXPECT_GT(r.points[0].x, 0.1);                                  // downstream (+x)
  EXPECT_NEAR(r.points[0].y, 0.0, kOffsetTol);                    // symmetric about the x axis
  // Legs 1 and 2 (anchors at 120 and 240 deg, upstream) hold the buoy; leg 0 slackens.
  EXPECT_GT(r.lines[1].topTension(), r.lines[0].topTension());
  EXPECT_NEAR(r.lines[1].topTension(), r.lines[2].topTension(), kSymmetryRelTol * r.lines[1].topTension());
}

TEST(System, TwoLegsOnAFixedJunctionAreTwoIndependentCatenaries) {
  SystemProblem s;
  s.environment.depth = 300.0;
  Material w;
  w.name = "wire";
  w.EA = 1.0e7;
  w.EI = 1.0e-2;
  w.GJ = 1.0e-2;
  w.mass = 10.0;
  w.wet_weight = 100.0;
  w.diameter = 0.03;
  w.cdn = 1.2;
  w.cdt = 0.01;
  s.materials = {w};
  s.points = {point("junction", SystemPoint::Type::Fixed, 0.0, 0.0, -20.0),
              point("west", SystemPoint::Type::Anchor, -150.0, 0.0, -100.0),
              point("north", SystemPoint::Type::Anchor, 0.0, 120.0, -100.0)};
  s.lines = {line("a", 1, 0, 200.0, 1.0), line("b", 2, 0, 160.0, 1.0)};
  const SystemStaticResult r = solveSystemStatic(s);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  EXPECT_EQ(r.summary.iterations, 0);  // nothing free: the lines alone
  const CatenarySolution a = solveCatenary({200.0, 100.0, 1.0e7, 150.0, 80.0, false});
  const CatenarySolution b = solveCatenary({160.0, 100.0, 1.0e7, 120.0, 80.0, false});
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(r.lines[0].topTension(), a.topTension(), kCatenaryRelTol * a.topTension());
  EXPECT_NEAR(r.lines[1].topTension(), b.topTension(), kCatenaryRelTol * b.topTension());
  // The junction resists both pulls.
  EXPECT_NEAR(r.points[0].fz, -(a.V + b.V), kCatenaryRelTol * (a.V + b.V));
}

TEST(System, BranchedArrayJunctionBalancesByHand) {
  // Main line: anchor A -> junction float J -> fixed top F; a side branch from anchor B up to J.
  // At J the three lines' pulls and the float's net buoyancy (and drag) sum to zero.
  SystemProblem s;
  s.environment.depth = 100.0;
  s.environment.current = {{0.0, 0.3, 0.0}};
  s.materials = {chain()};
  s.materials[0].EA = 2.0e7;  // wire rope
  s.materials[0].wet_weight = 20.0;
  s.materials[0].diameter = 0.03;
  Body f;
  f.name = "float";
  f.mass = 300.0;
  f.added_mass = 300.0;
  f.wet_weight = -3000.0;
  f.diameter = 1.0;
  f.cdn = 0.5;
  f.cdt = 0.5;
  s.bodies = {f};
  SystemPoint J = point("J", SystemPoint::Type::Body, 40.0, 10.0, -45.0);
  J.body = 0;
  J.position_given = true;
  s.points = {point("A", SystemPoint::Type::Anchor, 0.0, 0.0, -100.0), J,
              point("F", SystemPoint::Type::Fixed, 90.0, 0.0, -5.0),
              point("B", SystemPoint::Type::Anchor, 60.0, 40.0, -100.0)};
  s.lines = {line("main_lower", 0, 1, 75.0, 1.0), line("main_upper", 1, 2, 75.0, 1.0), line("branch", 3, 1, 75.0, 1.0)};
  const SystemStaticResult r = solveSystemStatic(s);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  // Hand balance at J: -top force of the lines ending there, + anchor force of the one starting.
  const StaticResult &lo = r.lines[0], &up = r.lines[1], &br = r.lines[2];
  const double U = 0.3, q = 0.5 * 1025.0 * 0.25 * kPi * 1.0 * 0.5 * U * U;
  const double Fx = -lo.top_force_x - br.top_force_x + up.anchor_force_x + q;
  const double Fy = -lo.top_force_y - br.top_force_y + up.anchor_force_y;
  const double Fz = -lo.top_force_z - br.top_force_z + up.anchor_force_z + 3000.0;
  const double T = std::max({lo.topTension(), up.topTension(), br.topTension()});
  EXPECT_NEAR(Fx, 0.0, kBalanceRelTol * T);
  EXPECT_NEAR(Fy, 0.0, kBalanceRelTol * T);
  EXPECT_NEAR(Fz, 0.0, kBalanceRelTol * T);
  // The lines meet at J: every end is where the point is.
  EXPECT_NEAR(lo.nodes.back().x, r.points[1].x, 1e-6);
  EXPECT_NEAR(up.nodes.front().z, r.points[1].z, 1e-6);
  EXPECT_NEAR(br.nodes.back().y, r.points[1].y, 1e-6);
  EXPECT_GT(r.points[1].y, 0.5);  // the branch pulls J toward B's side
}

TEST(System, TopologyErrorsNameTheProblem) {
  SystemProblem s = threeLeg(0.0);
  s.points.push_back(point("spare", SystemPoint::Type::Anchor, 0, 0, -100));
  EXPECT_NE(s.validate().find("points.spare: not joined"), std::string::npos) << s.validate();
  s = threeLeg(0.0);
  s.points.push_back(point("far", SystemPoint::Type::Anchor, 900, 0, -100));
  s.points.push_back(point("far_buoy", SystemPoint::Type::Buoy, 900, 0, 0));
  s.lines.push_back(line("separate", 4, 5, 120.0, 5.0));
  EXPECT_NE(s.validate().find("falls apart in 2 pieces"), std::string::npos) << s.validate();
  s = threeLeg(0.0);
  for (auto& p : s.points) p.type = SystemPoint::Type::Buoy;
  EXPECT_NE(s.validate().find("no anchor or fixed point"), std::string::npos) << s.validate();
  s = threeLeg(0.0);
  s.lines[0].from = 0;
  EXPECT_NE(s.validate().find("same point"), std::string::npos) << s.validate();
  EXPECT_THROW(solveSystemStatic(s), std::invalid_argument);
}

#include "mooring_dynamics/core/io/problem_io.hpp"

TEST(System, ShippedThreeLegFileLoadsAndSolves) {
  ASSERT_TRUE(isSystemFile("config/three_leg_buoy.yaml"));
  EXPECT_FALSE(isSystemFile("config/chain_mooring.yaml"));
  const SystemProblem s = loadSystemFromFile("config/three_leg_buoy.yaml");
  ASSERT_EQ(s.lines.size(), 3u);
  const SystemStaticResult r = solveSystemStatic(s);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  // Current toward +x and wind toward +x+y push the buoy east and a little north.
  EXPECT_GT(r.points[0].x, 0.0);
  EXPECT_GT(r.points[0].y, 0.0);
  EXPECT_LT(r.points[0].residual, 1e-3);
}

TEST(System, FileErrorsNameTheKey) {
  const std::string good = R"(model: 3d
environment: {depth: 100}
materials:
  chain: {EA: 5.0e8, EI: 10, GJ: 1, mass: 40, added_mass: 5, wet_weight: 300, diameter: 0.08, cdn: 2.4, cdt: 1.15}
points:
  buoy: {type: buoy, buoy: {diameter: 4, mass: 5000}}
  a: {type: anchor, position: [250, 0, -100]}
lines:
  - {name: leg, from: a, to: buoy, segments: [{material: chain, length: 300, spacing: 5}]}
)";
  EXPECT_NO_THROW(loadSystemFromString(good));
  auto expectError = [](const std::string& text, const std::string& want) {
    try {
      loadSystemFromString(text);
      ADD_FAILURE() << "loaded; expected an error with " << want;
    } catch (const ProblemError& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  };
  std::string t = good;
  t.replace(t.find("to: buoy"), 8, "to: bouy");
  expectError(t, "lines[0].to");
  t = good;
  t.replace(t.find("type: anchor"), 12, "type: sinker");
  expectError(t, "points.a.type = \"sinker\"");
  t = good;
  t.replace(t.find(", position: [250, 0, -100]"), 26, "");
  expectError(t, "points.a.position");
  t = good + "  - {name: stray, from: a, to: a, segments: [{material: chain, length: 10}]}\n";
  expectError(t, "same point");
}

TEST(System, ShippedBranchedArraySolvesWithItsFreeTail) {
  const SystemProblem s = loadSystemFromFile("config/branched_array.yaml");
  const SystemStaticResult r = solveSystemStatic(s);
  ASSERT_TRUE(r.summary.converged) << r.summary.message;
  // The tail hangs from the float with the 400 N sinker at its free end: tension 400 N there and
  // 400 N + 20 m x 5 N/m at the float, less the slight tilt of the current's drag.
  const StaticResult& tail = r.lines[3];
  // (0.1 N: the sinker's 3 N of drag in the current and the tail's bending share the end force.)
  EXPECT_NEAR(tail.nodes.front().tension, 400.0, 0.1);
  EXPECT_NEAR(tail.topTension(), 500.0, 0.01 * 500.0);
  EXPECT_NEAR(tail.nodes.back().z, r.points[2].z, 1e-6);
  EXPECT_LT(r.points[2].residual, 0.01);
}

TEST(System, PlanarSystemSolvesTheSameIn2DAnd3D) {
  // Two chain legs from anchors on either side of a buoy, all in the plane y = 0: the 2-D lines
  // (model: 2d) and the 3-D lines give the same equilibrium (the planar 3-D rows are the 2-D rows).
  SystemProblem s = threeLeg(0.0);
  s.points.resize(3);
  s.points[1].x = 250.0;
  s.points[1].y = 0.0;
  s.points[2].x = -250.0;
  s.points[2].y = 0.0;
  s.lines.resize(2);
  s.environment.current = {{0.0, 0.4, 0.0}};
  const SystemStaticResult r3 = solveSystemStatic(s);
  s.formulation = Formulation::TwoD;
  const SystemStaticResult r2 = solveSystemStatic(s);
  ASSERT_TRUE(r3.summary.converged && r2.summary.converged) << r3.summary.message << r2.summary.message;
  EXPECT_NEAR(r2.points[0].x, r3.points[0].x, 1e-4);
  EXPECT_NEAR(r2.points[0].z, r3.points[0].z, 1e-5);
  for (int k = 0; k < 2; ++k)
    EXPECT_NEAR(r2.lines[k].topTension(), r3.lines[k].topTension(), kSymmetryRelTol * r3.lines[k].topTension());
  EXPECT_GT(r3.points[0].x, 0.1);  // the current pushes the buoy toward +x
}

#include <filesystem>

TEST(System, ShippedSystemConfigsLoad) {
  // Every config/*.yaml with points and lines is a system file that loads and validates.
  namespace fs = std::filesystem;
  int n = 0;
  for (const auto& entry : fs::directory_iterator("config")) {
    if (entry.path().extension() != ".yaml" || !isSystemFile(entry.path().string())) continue;
    ++n;
    SCOPED_TRACE(entry.path().string());
    SystemProblem s;
    EXPECT_NO_THROW(s = loadSystemFromFile(entry.path().string()));
    EXPECT_FALSE(s.name.empty());
    EXPECT_FALSE(s.lines.empty());
    EXPECT_EQ(s.validate(), "");
  }
  EXPECT_GE(n, 2);
}

// vessel.sea_state with vessel.raos (issue "Design storms"): the sea becomes the lines' waves too
// (one sea for hull and lines), the table is read with its conventions, and the errors name the key.
TEST(System, VesselSeaStateSetsTheLinesWavesAndReadsTheRaos) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("md_test_system_raos_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "hull.csv");
    csv << "omega,heading_deg,dof,amplitude,phase_deg\n";
    for (double w : {0.2, 1.0, 3.0})
      for (int h : {0, 90, 180, 270})
        for (int d = 1; d <= 6; ++d) csv << w << "," << h << "," << d << "," << (d == 3 ? 1.0 : 0.5) << ",30\n";
  }
  const std::string head = R"(model: 3d
environment: {depth: 100}
materials:
  chain: {EA: 5.0e8, EI: 10, GJ: 1, mass: 40, added_mass: 5, wet_weight: 300, diameter: 0.08, cdn: 2.4, cdt: 1.15}
vessel:
  pose: {position: [0, 0, 0], yaw_deg: 0}
  lines:
    - {name: fwd, fairlead: [20, 0, -5], anchor: [270, 0, -100], segments: [{material: chain, length: 300, spacing: 10}]}
)";
  const std::string sea = "  sea_state: {type: jonswap, hs: 4, tp: 9, direction_deg: 180, seed: 3}\n";
  const std::string raos = "  raos: {file: hull.csv, rotation_unit: deg, reference_point: [0, 0, -2]}\n";
  const SystemProblem s = loadSystemFromString(head + sea + raos, dir.string());
  EXPECT_TRUE(s.vessel.sea_state);
  EXPECT_EQ(s.environment.waves.type, WaveSpec::Type::Jonswap) << "the lines see the vessel's sea";
  EXPECT_EQ(s.environment.waves.seed, 3u);
  EXPECT_NEAR(s.environment.waves.direction, kPi, 1e-12);
  ASSERT_EQ(s.vessel.rao_table.omega().size(), 3u);
  EXPECT_NEAR(std::abs(s.vessel.rao_table.value(4, 0, 0)), 0.5 * kPi / 180.0, 1e-15) << "pitch 0.5 deg/m";
  EXPECT_EQ(s.vessel.raos.reference_point.z(), -2.0);

  auto expectError = [&](const std::string& text, const std::string& want) {
    try {
      loadSystemFromString(text, dir.string());
      ADD_FAILURE() << "loaded; expected an error with " << want;
    } catch (const ProblemError& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  };
  expectError(head + sea, "needs vessel.raos");
  expectError(head + raos, "RAOs without vessel.sea_state");
  expectError(head + sea + raos + "  motion_table: m.csv\n", "give one motion of the vessel");
  std::string both = head + sea + raos;
  both.replace(both.find("environment: {depth: 100}"), 25, "environment: {depth: 100, waves: {type: regular, height: 1, period: 8}}");
  expectError(both, "give the sea once");
  expectError(head + sea + "  raos: {file: hull.4}\n", "ulen");
  expectError(head + sea + "  raos: {file: hull.txt}\n", "neither .4 nor .csv");
  expectError(head + sea + "  raos: {file: hull.csv, extend: guess}\n", "vessel.raos.extend = \"guess\": must be one of error, zero, hold");
  // A sea wider than the table (0.2 to 3 rad/s): Tp 40 s puts half the band below 0.2 rad/s.
  std::string wide = head + sea + raos;
  wide.replace(wide.find("tp: 9"), 5, "tp: 40");
  expectError(wide, "outside the RAO table's 0.2 to 3 rad/s");
  std::string held = wide;
  held.replace(held.find("reference_point"), 15, "extend: hold, reference_point");
  EXPECT_NO_THROW(loadSystemFromString(held, dir.string()));

  // low_frequency.wave_drift: a CSV in SI read as it stands; WAMIT values scaled by rho g ULEN.
  {
    std::ofstream csv(dir / "drift.csv");
    csv << "omega,heading_deg,surge,sway,yaw\n";
    for (double w : {0.2, 1.0, 3.0})
      for (int h : {0, 90, 180, 270}) csv << w << "," << h << "," << -1000.0 * w << "," << 500.0 << ",0\n";
    std::ofstream w8(dir / "drift.8");
    for (double per : {2.0, 6.0, 40.0})
      for (int h : {0, 90, 180, 270})
        for (int m : {1, 2, 6}) w8 << per << " " << h << " " << h << " " << m << " 0.5 0 0.5 0\n";
  }
  const std::string lf = "  low_frequency: {mass: 2.0e6, yaw_inertia: 1.0e9, wave_drift: {file: drift.csv}}\n";
  const SystemProblem d = loadSystemFromString(head + sea + raos + lf, dir.string());
  EXPECT_TRUE(d.vessel.wave_drift);
  EXPECT_TRUE(d.vessel.drift.newman);
  EXPECT_NEAR(d.vessel.drift_table.value(0, 2, 1).real(), -1000.0, 1e-9);
  const std::string lf8 = "  low_frequency: {mass: 2.0e6, yaw_inertia: 1.0e9, wave_drift: {file: drift.8, ulen: 2, "
                          "slowly_varying: none}}\n";
  const SystemProblem d8 = loadSystemFromString(head + sea + raos + lf8, dir.string());
  EXPECT_FALSE(d8.vessel.drift.newman);
  EXPECT_NEAR(d8.vessel.drift_table.value(5, 0, 0).real(), 0.5 * d8.environment.water_density * d8.environment.gravity * 4.0,
              1e-6) << "yaw moment / (rho g A^2 ULEN^2)";
  expectError(head + lf, "wave drift needs the sea");
  expectError(head + sea + raos + "  low_frequency: {mass: 2.0e6, yaw_inertia: 1.0e9, wave_drift: {file: drift.8}}\n",
              "ulen");
  expectError(head + sea + raos + "  low_frequency: {mass: 2.0e6, yaw_inertia: 1.0e9, wave_drift: {file: drift.csv, "
                                  "slowly_varying: full}}\n",
              "must be one of newman, none");
  fs::remove_all(dir);
}
