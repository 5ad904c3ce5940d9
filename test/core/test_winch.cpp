// The winch's program L(t) and its checks (core/model/winch.hpp): the length and rate of
// piecewise-linear programs against hand values, the commands' programs, where a program
// leaves its limits, and the errors for bad `dynamics.winch` keys, each naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/winch.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kExact = 1e-12;  // piecewise-linear arithmetic on round numbers [m], [m/s]
const double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(WinchProgram, TableIsLinearAndHeldAfterItsLastRow) {
  Winch w;
  w.given = true;
  w.table = {{0.0, 50.0}, {100.0, 150.0}, {110.0, 150.0}, {200.0, 60.0}};
  const WinchProgram p = w.program(50.0);
  EXPECT_NEAR(p.lengthAt(-1.0), 50.0, kExact);
  EXPECT_NEAR(p.lengthAt(50.0), 100.0, kExact);
  EXPECT_NEAR(p.lengthAt(105.0), 150.0, kExact);
  EXPECT_NEAR(p.lengthAt(155.0), 105.0, kExact);
  EXPECT_NEAR(p.lengthAt(500.0), 60.0, kExact);
  // The rate of the piece that ends at t (the step ending there): 1 m/s up to 100 s inclusive.
  EXPECT_NEAR(p.rateAt(100.0), 1.0, kExact);
  EXPECT_NEAR(p.rateAt(100.5), 0.0, kExact);
  EXPECT_NEAR(p.rateAt(150.0), -1.0, kExact);
  EXPECT_NEAR(p.rateAt(300.0), 0.0, kExact);
}

TEST(WinchProgram, RateRunsForEverAndATargetStops) {
  Winch w;
  w.given = true;
  w.rate = -0.25;
  const WinchProgram p = w.program(80.0);
  EXPECT_NEAR(p.lengthAt(40.0), 70.0, kExact);
  EXPECT_NEAR(p.rateAt(1000.0), -0.25, kExact);
  const WinchProgram to = WinchProgram::toward(10.0, 80.0, -2.0, 100.0);  // the speed is |rate|
  EXPECT_NEAR(to.lengthAt(15.0), 90.0, kExact);
  EXPECT_NEAR(to.lengthAt(30.0), 100.0, kExact);
  EXPECT_NEAR(to.lengthAt(60.0), 100.0, kExact);
  EXPECT_NEAR(to.rateAt(20.0), 2.0, kExact);
  EXPECT_NEAR(to.rateAt(31.0), 0.0, kExact);
}

TEST(WinchProgram, LimitCrossingIsWhereTheLineMeetsTheBound) {
  const WinchProgram p = WinchProgram::toward(0.0, 50.0, 0.5, kNaN);
  EXPECT_NEAR(winchLimitCrossing(p, 10.0, 100.0, 0.0, 200.0), 100.0, 1e-9);
  EXPECT_TRUE(std::isnan(winchLimitCrossing(p, 10.0, 100.0, 0.0, 99.0)));
  const WinchProgram down = WinchProgram::toward(5.0, 50.0, -1.0, kNaN);
  EXPECT_NEAR(winchLimitCrossing(down, 20.0, 100.0, 0.0, 100.0), 35.0, 1e-9);
}

/// A 3-D vertical line with a winch block `winch` (YAML flow map) and dynamics `extra`.
std::string lineWith(const std::string& winch, const std::string& top = "position: {x: 0, y: 0, z: 0}",
                     const std::string& model = "3d") {
  return "model: " + model +
         "\n"
         "environment: {depth: 1000}\n"
         "materials: {w: {EA: 1.0e7, EI: 1, GJ: 1, mass: 1, wet_weight: 7, diameter: 0.02, cdn: 1.5, cdt: 0.05}}\n"
         "bodies: {clump: {mass: 100, wet_weight: 500, diameter: 0.5, cd: 1.0}}\n"
         "line: [{material: w, length: 20, spacing: 2}, {material: w, length: 30, spacing: 5}]\n"
         "free_end: {body: clump}\n"
         "top: {" +
         top +
         "}\n"
         "dynamics: {duration: 100, dt: 0.5, winch: " +
         winch + "}\n";
}

std::string errorOf(const std::string& yaml) {
  try {
    (void)loadProblemFromString(yaml);
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

TEST(WinchInput, AGoodWinchLoads) {
  const Problem p = loadProblemFromString(lineWith("{rate: 0.5, max_length: 120}"));
  EXPECT_TRUE(p.dynamics.winch.given);
  EXPECT_EQ(p.dynamics.winch.rate, 0.5);
  EXPECT_EQ(p.dynamics.winch.max_length, 120.0);
  // 2-D problems take a winch too (they run on the 3-D equations in their plane).
  const std::string planar = "model: 2d\nenvironment: {depth: 100}\n"
                             "materials: {r: {EA: 1.0e7, EI: 1, mass: 1, wet_weight: 7, diameter: 0.02, cdn: 1.5, cdt: 0.05}}\n"
                             "line: [{material: r, length: 120, spacing: 5}]\nanchor: {x: 0, z: -100}\n"
                             "top: {position: {x: 50, z: 0}}\n"
                             "dynamics: {duration: 10, dt: 0.5, winch: {table: [[0, 120], [10, 125]]}}\n";
  EXPECT_TRUE(loadProblemFromString(planar).dynamics.winch.given);
}

TEST(WinchInput, BadWinchesNameTheFieldAndTheConstraint) {
  struct Case {
    std::string winch, expect;
  };
  const Case cases[] = {
      {"{}", "dynamics.winch.rate / table"},
      {"{rate: 0.5, table: [[0, 50], [10, 55]]}", "give one of them"},
      {"{table: [[0, 50], [0, 55]]}", "t must increase"},
      {"{table: [[0, 51], [10, 55]]}", "table[0] length = 51: must be the line's length in the file, 50 m"},
      {"{table: [[0, 50], [10, -5]]}", "length = -5: must be > 0"},
      {"{rate: 1.0, max_length: 120}", "max_length = 120 m: the winch passes it at t = 70 s"},
      {"{rate: -0.5, min_length: 40}", "min_length = 40 m: the winch passes it at t = 20 s"},
      {"{rate: -1.0}", "take in the whole top segment at t = 27.5 s"},
      {"{rate: 0.5, min_length: 60}", "min_length = 60: is above the line's length 50 m"},
      {"{rate: 0.5, max_length: 10, min_length: 20}", "max_length = 10: must be > min_length = 20 m"},
      {"{rate: 0.5, line: a}", "only a system file names the line"},
      {"{rate: 0.5, speed: 2}", "speed"},
  };
  for (const Case& c : cases) {
    const std::string e = errorOf(lineWith(c.winch));
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.winch << " gave: " << e;
    EXPECT_NE(e.find("winch"), std::string::npos) << c.winch << " gave: " << e;
  }
  // A top that moves by its forces takes no winch.
  std::string anchored = lineWith("{rate: 0.5}", "force: {x: 100, y: 0, z: 800}");
  const std::string free_end = "free_end: {body: clump}";
  anchored.replace(anchored.find(free_end), free_end.size(), "anchor: {x: 0, y: 0, z: -1000}");
  const std::string force = errorOf(anchored);
  EXPECT_NE(force.find("dynamics.winch: top: force: the winch sits at a top whose motion is prescribed"),
            std::string::npos)
      << force;
  // Nor does a position top driven by a force table.
  std::string table = lineWith("{rate: 0.5}");
  table.replace(table.find("winch:"), 6, "top_motion: {type: force_table, table: [[0, 0, 0, 0]]}, winch:");
  const std::string ft = errorOf(table);
  EXPECT_NE(ft.find("dynamics.top_motion.type = force_table"), std::string::npos) << ft;
}

}  // namespace
