// YAML problem loader, dynamics and environment.waves sections (split from test_problem_io.cpp):
// good sections parse into the expected options; every class of bad input raises ProblemError whose
// message names the key path, the value found, the constraint and the line.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_io_test_util.hpp"

using namespace mooring_dynamics::core;
using namespace mooring_dynamics::core::testing_util;

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

// ---- dynamics section -------------------------------------------------------------------------

TEST(ProblemIo, DynamicsAbsentOrEmptyKeepsDefaults) {
  for (const std::string extra : {"", "dynamics:\n"}) {
    const Problem p = loadProblemFromString(minimalWith(extra));
    const DynamicOptions def;
    EXPECT_EQ(p.dynamics.duration, 0.0);
    EXPECT_DOUBLE_EQ(p.dynamics.dt, def.dt);
    EXPECT_EQ(p.dynamics.scheme_name, def.scheme_name);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_k, def.scheme.alpha_k);
    EXPECT_EQ(p.dynamics.top_motion.type, TopMotion::Type::Hold);
    EXPECT_TRUE(p.dynamics.record_s.empty());
  }
}

TEST(ProblemIo, ParsesDynamicsSection) {
  const Problem p = loadProblemFromString(minimalWith(R"(dynamics:
  duration: 120
  dt: 0.05
  output_interval: 0.25
  snapshot_interval: 10
  record_s: [0, 75.5, 150]
  scheme: backward
  max_cut_levels: 3
  tolerance: 1e-7
  max_iterations: 40
  relaxation: 0.8
  adaptive_relaxation: false
  jacobian_reuse_rate: 0.5
  damp_two_cycles: true
  threads: 2
  adaptive_mesh: true
  mesh_weight: 15
  top_motion: {type: sinusoid, amplitude_x: 0.5, amplitude_z: 2.0, period: 8, phase_deg: 90, prescribe: position}
)"));
  const DynamicOptions& d = p.dynamics;
  EXPECT_DOUBLE_EQ(d.duration, 120);
  EXPECT_DOUBLE_EQ(d.dt, 0.05);
  EXPECT_DOUBLE_EQ(d.output_interval, 0.25);
  EXPECT_DOUBLE_EQ(d.snapshot_interval, 10);
  ASSERT_EQ(d.record_s.size(), 3u);
  EXPECT_DOUBLE_EQ(d.record_s[1], 75.5);
  EXPECT_EQ(d.scheme_name, "backward");
  EXPECT_DOUBLE_EQ(d.scheme.alpha_m, 0.0);
  EXPECT_DOUBLE_EQ(d.scheme.alpha_k, 0.0);
  EXPECT_DOUBLE_EQ(d.scheme.gamma, 1.0);
  EXPECT_EQ(d.max_cut_levels, 3);
  EXPECT_DOUBLE_EQ(d.tolerance, 1e-7);
  EXPECT_EQ(d.max_iterations, 40);
  EXPECT_EQ(d.threads, 2);
  EXPECT_DOUBLE_EQ(d.relaxation, 0.8);
  EXPECT_FALSE(d.adaptive_relaxation);
  EXPECT_DOUBLE_EQ(d.jacobian_reuse_rate, 0.5);
  EXPECT_TRUE(d.damp_two_cycles);
  EXPECT_TRUE(d.adaptive_mesh);
  EXPECT_DOUBLE_EQ(d.mesh_weight, 15);
  const TopMotion& tm = d.top_motion;
  EXPECT_EQ(tm.type, TopMotion::Type::Sinusoid);
  EXPECT_DOUBLE_EQ(tm.amplitude_x, 0.5);
  EXPECT_DOUBLE_EQ(tm.amplitude_z, 2.0);
  EXPECT_DOUBLE_EQ(tm.period, 8);
  EXPECT_NEAR(tm.phase, kPi / 2, 1e-15);  // degrees in the file, radians in the struct
  EXPECT_TRUE(tm.prescribe_position);
}

TEST(ProblemIo, DynamicsSchemeForms) {
  for (const char* name : {"box", "trapezoidal", "backward", "lambda0", "lambda-0.5", "lambda0.75"}) {
    SCOPED_TRACE(name);
    const Problem p = loadProblemFromString(minimalWith(std::string("dynamics: {scheme: ") + name + "}\n"));
    const GeneralizedAlpha g = GeneralizedAlpha::preset(name);
    EXPECT_EQ(p.dynamics.scheme_name, name);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_m, g.alpha_m);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_k, g.alpha_k);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.gamma, g.gamma);
  }
  {
    const Problem p = loadProblemFromString(minimalWith("dynamics: {lambda_inf: -0.3}\n"));
    const GeneralizedAlpha g = GeneralizedAlpha::fromLambdaInf(-0.3);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_m, g.alpha_m);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_k, g.alpha_k);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.gamma, g.gamma);
    EXPECT_NE(p.dynamics.scheme_name.find("-0.3"), std::string::npos) << p.dynamics.scheme_name;
  }
  EXPECT_NO_THROW(loadProblemFromString(minimalWith("dynamics: {lambda_inf: -1}\n")));  // = box
  {
    const Problem p = loadProblemFromString(minimalWith("dynamics: {alpha_m: 0.2, alpha_k: 0.3, gamma: 0.6}\n"));
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_m, 0.2);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.alpha_k, 0.3);
    EXPECT_DOUBLE_EQ(p.dynamics.scheme.gamma, 0.6);
    EXPECT_NE(p.dynamics.scheme_name.find("alpha_m=0.2"), std::string::npos) << p.dynamics.scheme_name;
  }
}

TEST(ProblemIo, DynamicsSchemeErrors) {
  EXPECT_ERROR_HAS(minimalWith("dynamics: {scheme: boxx}\n"), "dynamics.scheme = \"boxx\"", "unknown scheme",
                   "lambda-0.5", "(line 8)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {lambda_inf: 1}\n"), "dynamics.lambda_inf = 1", "[-1, 1)", "(line 8)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {lambda_inf: -1.5}\n"), "dynamics.lambda_inf = -1.5", "[-1, 1)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {lambda_inf: soft}\n"), "dynamics.lambda_inf", "expected a number");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {scheme: box, lambda_inf: -0.5}\n"), "dynamics: has scheme, lambda_inf",
                   "exactly one of");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {lambda_inf: -0.5, gamma: 0.5}\n"), "exactly one of");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {alpha_m: 0.2, alpha_k: 0.3}\n"), "dynamics.gamma", "required key missing");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {alpha_m: 0.2, alpha_k: 0.3, gamma: 0}\n"), "gamma", "> 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {alpha_m: 1, alpha_k: 0.3, gamma: 0.5}\n"), "alpha_m", "may be 1");
}

TEST(ProblemIo, DynamicsValueErrorsNameKeyValueAndLine) {
  EXPECT_ERROR_HAS(minimalWith("dynamics: {durration: 10}\n"), "dynamics.durration", "unknown key",
                   "did you mean \"duration\"", "(line 8)");
  EXPECT_ERROR_HAS(minimalWith("dynamics:\n  dt: 0.1\n  duration: -5\n"), "dynamics.duration = -5", "must be > 0",
                   "(line 10)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {dt: 0}\n"), "dynamics.dt = 0", "must be > 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {dt: 0.1, output_interval: 0.25}\n"), "dynamics.output_interval = 0.25",
                   "whole multiple of dt = 0.1");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {snapshot_interval: -1}\n"), "dynamics.snapshot_interval", ">= 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {record_s: [10, 151]}\n"), "dynamics.record_s[1] = 151", "beyond",
                   "150");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {record_s: [-1]}\n"), "dynamics.record_s[0] = -1", ">= 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {record_s: 10}\n"), "dynamics.record_s", "expected a list");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {max_cut_levels: 9}\n"), "dynamics.max_cut_levels = 9", "[0, 8]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {max_cut_levels: 1.5}\n"), "dynamics.max_cut_levels", "integer");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {threads: 4}\n"), "dynamics.threads = 4", "1 or 2");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {threads: two}\n"), "dynamics.threads", "integer");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {max_iterations: 0}\n"), "dynamics.max_iterations = 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {tolerance: 0}\n"), "dynamics.tolerance = 0", "> 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {relaxation: 1.5}\n"), "dynamics.relaxation = 1.5", "(0, 1]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {jacobian_reuse_rate: 1}\n"), "dynamics.jacobian_reuse_rate = 1", "(0, 1)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {jacobian_reuse_rate: 0}\n"), "dynamics.jacobian_reuse_rate = 0", "(0, 1)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {adaptive_mesh: maybe}\n"), "dynamics.adaptive_mesh", "true or false");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {mesh_weight: -2}\n"), "dynamics.mesh_weight = -2", ">= 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: [1, 2]\n"), "dynamics", "expected a map");
}

TEST(ProblemIo, DynamicsTopMotionTables) {
  {
    const Problem p = loadProblemFromString(minimalWith(
        "dynamics:\n  top_motion:\n    type: position_table\n    table: [[0, 100, 0], [5, 101, 0.5], [10, 100, 0]]\n"));
    const TopMotion& tm = p.dynamics.top_motion;
    EXPECT_EQ(tm.type, TopMotion::Type::PositionTable);
    ASSERT_EQ(tm.table.size(), 3u);
    EXPECT_DOUBLE_EQ(tm.table[1].t, 5);
    EXPECT_DOUBLE_EQ(tm.table[1].x, 101);
    EXPECT_EQ(tm.table[1].y, 0.0);  // a 3-column row lies in the x-z plane
    EXPECT_DOUBLE_EQ(tm.table[1].z, 0.5);
    EXPECT_FALSE(tm.prescribe_position);  // velocity BCs by default (eq. 34)
  }
  EXPECT_EQ(loadProblemFromString(minimalWith("dynamics: {top_motion: {type: velocity_table, table: [[0, 0, 1]]}}\n"))
                .dynamics.top_motion.type,
            TopMotion::Type::VelocityTable);
  EXPECT_EQ(loadProblemFromString(minimalWith("dynamics: {top_motion: {type: force_table, table: [[0, 1e3, 2e3]]}}\n"))
                .dynamics.top_motion.type,
            TopMotion::Type::ForceTable);
  EXPECT_EQ(loadProblemFromString(minimalWith("dynamics: {top_motion: {type: wave_follower}}\n"))
                .dynamics.top_motion.type,
            TopMotion::Type::WaveFollower);
  EXPECT_EQ(loadProblemFromString(minimalWith("dynamics: {top_motion: {type: hold, prescribe: velocity}}\n"))
                .dynamics.top_motion.type,
            TopMotion::Type::Hold);
}

TEST(ProblemIo, DynamicsTopMotion3D) {
  {
    const Problem p = loadProblemFromString(minimalWith(
        "dynamics:\n  top_motion:\n    type: position_table\n    table: [[0, 100, 0, 0], [5, 101, -2, 0.5]]\n"));
    const TopMotion& tm = p.dynamics.top_motion;
    ASSERT_EQ(tm.table.size(), 2u);
    EXPECT_EQ(tm.table[1].t, 5.0);
    EXPECT_EQ(tm.table[1].x, 101.0);
    EXPECT_EQ(tm.table[1].y, -2.0);
    EXPECT_EQ(tm.table[1].z, 0.5);
  }
  for (const char* type : {"velocity_table", "force_table"}) {
    const Problem p = loadProblemFromString(minimalWith(std::string("dynamics: {top_motion: {type: ") + type +
                                                        ", table: [[0, 1, 2, 3], [1, 4, 5, 6]]}}\n"));
    const TopMotion::Row& r = p.dynamics.top_motion.table[1];
    EXPECT_EQ(r.x, 4.0) << type;
    EXPECT_EQ(r.y, 5.0) << type;
    EXPECT_EQ(r.z, 6.0) << type;
  }
  const Problem p = loadProblemFromString(
      minimalWith("dynamics: {top_motion: {type: sinusoid, amplitude_x: 1, amplitude_y: -2, amplitude_z: 3, period: 8}}\n"));
  EXPECT_EQ(p.dynamics.top_motion.amplitude_y, -2.0);
  EXPECT_EQ(loadProblemFromString(minimalWith("dynamics: {top_motion: {type: sinusoid, period: 8}}\n"))
                .dynamics.top_motion.amplitude_y,
            0.0);
  // Errors: mixed row widths name the row, rows of other widths name both layouts.
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: velocity_table, table: [[0, 1, 2], [1, 1, 2, 3]]}}\n"),
                   "dynamics.top_motion.table[1] = [1, 1, 2, 3]", "has 4 values, the first row 3",
                   "all rows are [t, vx, vz]", "(line 8)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: force_table, table: [[0, 1, 2, 3], [1, 1, 2]]}}\n"),
                   "dynamics.top_motion.table[1] = [1, 1, 2]", "has 3 values, the first row 4",
                   "all rows are [t, fx, fy, fz]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: position_table, table: [[0, 1, 2, 3, 4]]}}\n"),
                   "dynamics.top_motion.table[0]", "a row [t, x, z] or [t, x, y, z]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: position_table, table: [[0, 1, .nan, 3]]}}\n"),
                   "dynamics.top_motion.table[0][2]", "finite");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: hold, amplitude_y: 1}}\n"),
                   "dynamics.top_motion.amplitude_y = 1", "only used with type: sinusoid");
}

TEST(ProblemIo, DynamicsShipTrack) {
  const Problem p = loadProblemFromString(minimalWith(
      "dynamics:\n  top_motion: {type: ship_track, speed: 9.52, heading_deg: 90, legs: [{straight: 200},\n"
      "    {turn: {radius: 640, angle_deg: 375}}, {heading_deg: 0}, {straight: 300}, {turn: {radius: 50, angle_deg: -90}}]}\n"));
  const TopMotion& tm = p.dynamics.top_motion;
  EXPECT_EQ(tm.type, TopMotion::Type::ShipTrack);
  const ShipTrack& st = tm.ship_track;
  EXPECT_EQ(st.speed, 9.52);
  EXPECT_NEAR(st.heading, kPi / 2, 1e-15);
  ASSERT_EQ(st.legs.size(), 5u);
  EXPECT_EQ(st.legs[0].type, ShipLeg::Type::Straight);
  EXPECT_EQ(st.legs[0].duration, 200.0);
  EXPECT_EQ(st.legs[1].type, ShipLeg::Type::Turn);
  EXPECT_EQ(st.legs[1].radius, 640.0);
  EXPECT_NEAR(st.legs[1].angle, 375.0 * kPi / 180.0, 1e-14);
  EXPECT_EQ(st.legs[2].type, ShipLeg::Type::Heading);
  EXPECT_EQ(st.legs[2].heading, 0.0);
  EXPECT_NEAR(st.legs[4].angle, -kPi / 2, 1e-15);
  // Defaults: heading 0, no legs (straight on).
  const Problem q = loadProblemFromString(minimalWith("dynamics: {top_motion: {type: ship_track, speed: 2}}\n"));
  EXPECT_EQ(q.dynamics.top_motion.ship_track.heading, 0.0);
  EXPECT_TRUE(q.dynamics.top_motion.ship_track.legs.empty());
}

TEST(ProblemIo, DocumentedShipTrackExampleLoads) {
  const std::string yaml = documentedYaml("#### Ship tracks");
  ASSERT_FALSE(yaml.empty());
  Problem p;
  ASSERT_NO_THROW(p = loadProblemFromString(minimalWith(yaml)));
  const ShipTrack& st = p.dynamics.top_motion.ship_track;
  ASSERT_EQ(st.legs.size(), 4u);
  // 200 s + the 375 deg turn (440 s, as the paper says) + 300 s = the example's duration.
  EXPECT_NEAR(st.legsDuration(), p.dynamics.duration, 0.1);
}

TEST(ProblemIo, DynamicsShipTrackErrors) {
  auto with = [](const std::string& motion) { return minimalWith("dynamics: {top_motion: " + motion + "}\n"); };
  EXPECT_ERROR_HAS(with("{type: ship_track}"), "dynamics.top_motion.speed", "required key missing");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 0}"), "dynamics.top_motion.speed = 0", "must be > 0", "(line 8)");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{straight: -3}]}"),
                   "dynamics.top_motion.legs[0].straight = -3", "must be >= 0");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{straight: 1}, {turn: {radius: -640, angle_deg: 90}}]}"),
                   "dynamics.top_motion.legs[1].turn.radius = -640", "must be > 0");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{turn: {radius: 640}}]}"),
                   "dynamics.top_motion.legs[0].turn.angle_deg", "required key missing");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{turn: {radius: 640, angle: 90}}]}"),
                   "dynamics.top_motion.legs[0].turn.angle", "unknown key", "angle_deg");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{straight: 10, heading_deg: 5}]}"),
                   "dynamics.top_motion.legs[0]: has straight, heading_deg at once", "exactly one of");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{}]}"), "dynamics.top_motion.legs[0]: no leg given");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [straight]}"), "dynamics.top_motion.legs[0]",
                   "a map");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, legs: [{heading_deg: .nan}]}"),
                   "dynamics.top_motion.legs[0].heading_deg", "finite");
  EXPECT_ERROR_HAS(with("{type: ship_track, speed: 1, period: 5}"), "dynamics.top_motion.period",
                   "only used with type: sinusoid");
  EXPECT_ERROR_HAS(with("{type: hold, speed: 1}"), "dynamics.top_motion.speed = 1", "only used with type: ship_track");
  EXPECT_ERROR_HAS(with("{type: sinusoid, period: 5, legs: []}"), "dynamics.top_motion.legs",
                   "only used with type: ship_track");
}

TEST(ProblemIo, DynamicsTopMotionErrors) {
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {amplitude_z: 1}}\n"), "dynamics.top_motion.type",
                   "required key missing", "sinusoid");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: heave}}\n"), "dynamics.top_motion.type = \"heave\"",
                   "unknown top motion type", "wave_follower");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: sinusoid, amplitude_z: 2}}\n"),
                   "dynamics.top_motion.period", "required key missing");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: sinusoid, amplitude_z: 2, period: 0}}\n"),
                   "dynamics.top_motion.period = 0", "> 0");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: hold, amplitude_z: 2}}\n"),
                   "dynamics.top_motion.amplitude_z = 2", "only used with type: sinusoid");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: sinusoid, period: 8, table: [[0, 1, 2]]}}\n"),
                   "dynamics.top_motion.table", "only used with type: position_table");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: position_table}}\n"), "dynamics.top_motion.table",
                   "required key missing", "[t, x, z]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: position_table, table: []}}\n"),
                   "dynamics.top_motion.table", "at least one row");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: velocity_table, table: [[0, 1]]}}\n"),
                   "dynamics.top_motion.table[0]", "a row [t, vx, vz]");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: force_table, table: [[0, 1, 2], [0, 3, 4]]}}\n"),
                   "dynamics.top_motion.table[1]", "t must increase", "(line 8)");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: position_table, table: [[0, x, 2]]}}\n"),
                   "dynamics.top_motion.table[0][1]", "expected a number");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: force_table, table: [[0, 1, 2]], prescribe: position}}\n"),
                   "dynamics.top_motion.prescribe", "not force_table");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {top_motion: {type: hold, prescribe: acceleration}}\n"),
                   "dynamics.top_motion.prescribe = \"acceleration\"", "velocity, position");
}

// ---------------------------------------------------------------------------------------------
// environment.waves

TEST(ProblemIo, WavesRegularAndRandom) {
  EXPECT_EQ(loadProblemFromString(kMinimal).environment.waves.type, WaveSpec::Type::None);  // default
  {
    const Problem p = loadProblemFromString(minimalWith(
        "environment:\n  waves: {type: regular, height: 2.5, period: 9, direction_deg: 90, ramp: 20}\n"));
    const WaveSpec& w = p.environment.waves;
    EXPECT_EQ(w.type, WaveSpec::Type::Regular);
    EXPECT_DOUBLE_EQ(w.height, 2.5);
    EXPECT_DOUBLE_EQ(w.period, 9.0);
    EXPECT_NEAR(w.direction, kPi / 2, 1e-15);
    EXPECT_DOUBLE_EQ(w.ramp, 20.0);
  }
  {
    const Problem p = loadProblemFromString(minimalWith(
        "environment:\n  waves: {type: jonswap, hs: 9.8, tp: 16, gamma: 2, components: 300,\n"
        "          f_min_factor: 0.4, f_max_factor: 5, seed: 4294967295, direction_deg: -30}\n"));
    const WaveSpec& w = p.environment.waves;
    EXPECT_EQ(w.type, WaveSpec::Type::Jonswap);
    EXPECT_DOUBLE_EQ(w.hs, 9.8);
    EXPECT_DOUBLE_EQ(w.tp, 16.0);
    EXPECT_DOUBLE_EQ(w.gamma, 2.0);
    EXPECT_EQ(w.components, 300);
    EXPECT_DOUBLE_EQ(w.f_min_factor, 0.4);
    EXPECT_DOUBLE_EQ(w.f_max_factor, 5.0);
    EXPECT_EQ(w.seed, 4294967295u);
    EXPECT_NEAR(w.direction, -kPi / 6, 1e-15);
    EXPECT_DOUBLE_EQ(w.ramp, 0.0);  // default
  }
  {
    const Problem p = loadProblemFromString(
        minimalWith("environment:\n  waves: {type: pierson_moskowitz, hs: 3, tp: 10}\n"));
    const WaveSpec& w = p.environment.waves;
    const WaveSpec d;
    EXPECT_EQ(w.type, WaveSpec::Type::PiersonMoskowitz);
    EXPECT_EQ(w.components, d.components);  // defaults from core/model/waves.hpp
    EXPECT_DOUBLE_EQ(w.f_min_factor, d.f_min_factor);
    EXPECT_DOUBLE_EQ(w.f_max_factor, d.f_max_factor);
    EXPECT_EQ(w.seed, d.seed);
  }
}

TEST(ProblemIo, WavesErrors) {
  auto waves = [](const std::string& map) { return minimalWith("environment:\n  waves: " + map + "\n"); };
  EXPECT_ERROR_HAS(waves("{height: 1, period: 5}"), "environment.waves.type: required key missing");
  EXPECT_ERROR_HAS(waves("{type: swell, height: 1, period: 5}"),
                   "environment.waves.type = \"swell\": unknown wave type (known: regular, jonswap, pierson_moskowitz)");
  EXPECT_ERROR_HAS(waves("{type: regular, height: 1}"), "environment.waves.period: required key missing");
  EXPECT_ERROR_HAS(waves("{type: regular, height: -1, period: 5}"), "environment.waves.height = -1: must be > 0",
                   "(line ");
  EXPECT_ERROR_HAS(waves("{type: regular, height: 1, period: 0}"), "environment.waves.period = 0: must be > 0");
  EXPECT_ERROR_HAS(waves("{type: regular, height: 1, period: 5, hs: 2}"),
                   "environment.waves.hs = 2: only used with type: jonswap or pierson_moskowitz");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, period: 5}"),
                   "environment.waves.period = 5: only used with type: regular");
  EXPECT_ERROR_HAS(waves("{type: pierson_moskowitz, hs: 2, tp: 8, gamma: 3.3}"),
                   "environment.waves.gamma = 3.3: only used with type: jonswap");
  EXPECT_ERROR_HAS(waves("{type: jonswap, tp: 8}"), "environment.waves.hs: required key missing");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: -1, tp: 8}"), "environment.waves.hs = -1: must be > 0");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: .inf}"), "environment.waves.tp = .inf: must be a finite number");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, gamma: 0.5}"), "environment.waves.gamma = 0.5: must be >= 1");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, components: 0}"),
                   "environment.waves.components = 0: must be an integer in [1, 10000]");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, components: 2.5}"),
                   "environment.waves.components = 2.5: expected an integer");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, f_min_factor: 1}"),
                   "environment.waves.f_min_factor = 1: must be in (0, 1)");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, f_max_factor: 0.8}"),
                   "environment.waves.f_max_factor = 0.8: must be > 1");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, seed: -1}"),
                   "environment.waves.seed = -1: must be an integer in [0, 4294967295]");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, seed: 4294967296}"),
                   "environment.waves.seed = 4294967296: must be an integer in [0, 4294967295]");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, ramp: -5}"), "environment.waves.ramp = -5: must be >= 0");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, direction_deg: nan}"),
                   "environment.waves.direction_deg = nan: must be a finite number");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: 2, tp: 8, hs_m: 2}"), "environment.waves.hs_m: unknown key",
                   "did you mean \"hs\"?");
  EXPECT_ERROR_HAS(waves("[regular]"), "environment.waves", "expected a map");
  EXPECT_ERROR_HAS(waves("{type: jonswap, hs: \"2\", tp: 8}"), "environment.waves.hs = \"2\"", "expected a number");
}

// ---- dynamics.events (issue 21) ---------------------------------------------------------------

TEST(ProblemIo, DynamicsEvents) {
  const Problem p = loadProblemFromString("model: 3d\n" + minimalWith(R"(dynamics:
  duration: 60
  events:
    - {type: release, end: anchor, t: 12.5}
    - {type: break, tension: 2.0e5}
)"));
  ASSERT_EQ(p.dynamics.events.size(), 2u);
  EXPECT_EQ(p.dynamics.events[0].type, LineEvent::Type::Release);
  EXPECT_EQ(p.dynamics.events[0].end, LineEvent::End::Anchor);
  EXPECT_EQ(p.dynamics.events[0].t, 12.5);
  EXPECT_EQ(p.dynamics.events[1].type, LineEvent::Type::Break);
  EXPECT_EQ(p.dynamics.events[1].tension, 2.0e5);
  EXPECT_LT(p.dynamics.events[1].t, 0.0);
  EXPECT_TRUE(p.dynamics.events[1].onTension());
  const Problem q = loadProblemFromString(R"(model: 3d
materials:
  chain: {EA: 6.44e7, EI: 10, mass: 3.73, wet_weight: 31.85, diameter: 0.0495, cdn: 0.5, cdt: 0.05, mbl: 3.0e6}
line:
  - {material: chain, length: 150}
top:
  position: {x: 100, z: 0}
dynamics: {duration: 60, events: [{type: break, tension: mbl}, {type: release, end: top, t: 0}]}
)");
  EXPECT_TRUE(q.dynamics.events[0].at_mbl);
  const Problem r = loadProblemFromString("model: 3d\n" + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 3, s: 75}]}\n"));
  EXPECT_EQ(r.dynamics.events[0].s, 75.0);
}

TEST(ProblemIo, DynamicsEventErrorsNameTheEventAndTheConstraint) {
  const std::string m3 = "model: 3d\n";
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: snap, t: 1}]}\n"),
                   "dynamics.events[0].type = \"snap\"", "release, break");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: release, t: 1}]}\n"),
                   "dynamics.events[0].end", "required");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: release, end: middle, t: 1}]}\n"),
                   "dynamics.events[0].end = \"middle\"", "top or anchor");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: release, end: top}]}\n"),
                   "dynamics.events[0].t", "required for a release");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1, tension: 5}]}\n"),
                   "dynamics.events[0]", "exactly one of t");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break}]}\n"), "exactly one of t");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, tension: -5}]}\n"),
                   "dynamics.events[0].tension = -5", "> 0");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, tension: 5, s: 3}]}\n"),
                   "dynamics.events[0].s", "goes with t");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1, end: top}]}\n"),
                   "dynamics.events[0].end", "goes with a release");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: release, end: top, t: 61}]}\n"),
                   "dynamics.events[0].t = 61", "after dynamics.duration");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1}, {type: break, t: 2}]}\n"),
                   "dynamics.events[1]", "a second break");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: release, end: top, t: 1}, "
                                    "{type: release, end: top, t: 2}]}\n"),
                   "dynamics.events[1]", "released by events[0]");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1, s: 151}]}\n"),
                   "dynamics.events[0].s = 151", "beyond the top");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, tension: mbl}]}\n"),
                   "dynamics.events[0].tension = mbl", "no material of the line has an mbl");
  EXPECT_ERROR_HAS(m3 + minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1, line: leg}]}\n"),
                   "dynamics.events[0].line = leg", "only a system file");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {duration: 60, events: [{type: break, t: 1}]}\n"),
                   "dynamics.events[0]", "3-D solver", "formulation: 3d");
}
