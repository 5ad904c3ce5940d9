// The validation messages of Problem and StaticOptions (src/core/model/model_validation.cpp):
// a valid problem has none; every other names the field, its value and the constraint.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mooring_dynamics/core/model/model.hpp"

using namespace mooring_dynamics::core;

namespace {

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\" does not contain \"" << part << "\"";
}

/// A problem that validates: one chain segment, anchor on a flat bottom, top inside reach.
Problem validProblem() {
  Problem p;
  p.environment.depth = 100.0;
  Material m;
  m.name = "chain";
  m.EA = 1e8;
  m.EI = 1.0;
  m.mass = 50.0;
  m.wet_weight = 400.0;
  m.diameter = 0.1;
  m.cdn = 2.4;
  m.cdt = 1.15;
  p.materials = {m};
  Body b;
  b.name = "float";
  b.wet_weight = -500.0;
  b.diameter = 0.5;
  p.bodies = {b};
  Segment s;
  s.material = 0;
  s.length = 150.0;
  s.spacing = 1.0;
  s.bodies = {{0, 75.0}};
  p.segments = {s};
  p.anchor_x = 0.0;
  p.anchor_z = -100.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = 100.0;
  p.top.z = 0.0;
  return p;
}

}  // namespace

TEST(Validation, ValidProblemHasNoMessage) {
  EXPECT_EQ(validProblem().validate(), "");
  EXPECT_EQ(StaticOptions().validate(), "");
}

TEST(Validation, NegativeEANamesFieldAndValue) {
  Problem p = validProblem();
  p.materials[0].EA = -5.0;
  const std::string e = p.validate();
  EXPECT_TRUE(contains(e, "materials.chain.EA"));
  EXPECT_TRUE(contains(e, "-5"));
}

TEST(Validation, TableMaterialDoesNotNeedEA) {
  Problem p = validProblem();
  p.materials[0].EA = 0.0;
  p.materials[0].tension_strain = {{0.0, 0.0}, {0.01, 1e6}};
  EXPECT_EQ(p.validate(), "");
  p.materials[0].tension_strain = {{0.0, 0.0}, {0.01, 1e6}, {0.005, 2e6}};
  const std::string e = p.validate();
  EXPECT_TRUE(contains(e, "materials.chain.tension_strain[2]"));
  EXPECT_TRUE(contains(e, "0.005"));
}

TEST(Validation, ZeroBendingStiffnessIsRejected) {
  Problem p = validProblem();
  p.materials[0].EI = 0.0;
  EXPECT_TRUE(contains(p.validate(), "materials.chain.EI"));
}

TEST(Validation, TopBeyondReach) {
  Problem p = validProblem();
  // 150 m at max_strain 0.2 reaches 180 m; the top is 200 m away horizontally.
  p.top.x = 200.0;
  const std::string e = p.validate();
  EXPECT_TRUE(contains(e, "top.position"));
  EXPECT_TRUE(contains(e, "reach"));
  EXPECT_TRUE(contains(e, "200"));
  // 170 m away is within reach.
  p.top.x = std::sqrt(170.0 * 170.0 - 100.0 * 100.0);
  EXPECT_EQ(p.validate(), "");
}

TEST(Validation, SegmentAndPlacementFields) {
  {
    Problem p = validProblem();
    p.segments[0].length = -3.0;
    const std::string e = p.validate();
    EXPECT_TRUE(contains(e, "line[0].length"));
    EXPECT_TRUE(contains(e, "-3"));
  }
  {
    Problem p = validProblem();
    p.segments[0].bodies[0].at = 151.0;
    const std::string e = p.validate();
    EXPECT_TRUE(contains(e, "line[0].bodies[0].at"));
    EXPECT_TRUE(contains(e, "151"));
  }
  {
    Problem p = validProblem();
    p.segments[0].material = 4;
    EXPECT_TRUE(contains(p.validate(), "line[0].material"));
  }
  {
    Problem p = validProblem();
    p.segments[0].bodies[0].body = 3;
    EXPECT_TRUE(contains(p.validate(), "line[0].bodies[0].body"));
  }
}

TEST(Validation, EnvironmentAndAnchorFields) {
  {
    Problem p = validProblem();
    p.anchor_z = -120.0;  // 20 m under the 100 m deep flat bottom
    const std::string e = p.validate();
    EXPECT_TRUE(contains(e, "anchor.z"));
    EXPECT_TRUE(contains(e, "-120"));
  }
  {
    Problem p = validProblem();
    p.environment.current = {{0.0, 1.0, 0.0}, {-4.0, 1.0, 0.0}};
    const std::string e = p.validate();
    EXPECT_TRUE(contains(e, "environment.current[1].depth"));
    EXPECT_TRUE(contains(e, "-4"));
  }
  {
    Problem p = validProblem();
    p.environment.water_density = 0.0;
    EXPECT_TRUE(contains(p.validate(), "environment.water_density"));
  }
}

TEST(Validation, SeabedGridFields) {
  auto grid = [] {
    SeabedGrid g;
    g.nx = 3;
    g.ny = 2;
    g.dx = g.dy = 10.0;
    g.depths = {100, 100, 100, 100, 100, 100};
    return g;
  };
  Problem p = validProblem();
  p.environment.seabed.grid = grid();
  EXPECT_EQ(p.validate(), "");
  p.environment.seabed.grid.dx = 0.0;
  EXPECT_TRUE(contains(p.validate(), "environment.seabed.grid.dx = 0: must be > 0"));
  p.environment.seabed.grid = grid();
  p.environment.seabed.grid.dy = std::nan("");
  EXPECT_TRUE(contains(p.validate(), "environment.seabed.grid.dy = nan: must be > 0"));
  p.environment.seabed.grid = grid();
  p.environment.seabed.grid.ny = 1;
  p.environment.seabed.grid.depths.resize(3);
  EXPECT_TRUE(contains(p.validate(), "environment.seabed.grid.ny = 1: must be >= 2"));
  p.environment.seabed.grid = grid();
  p.environment.seabed.grid.depths.pop_back();
  EXPECT_TRUE(contains(p.validate(), "environment.seabed.grid.depths has 5 values: must have nx * ny = 6"));
  p.environment.seabed.grid = grid();
  p.environment.seabed.grid.depths[4] = -3.0;
  p.environment.seabed.grid.source = "bay.grid";
  EXPECT_TRUE(contains(p.validate(), "environment.seabed.grid (bay.grid).depths[4] (ix = 1, iy = 1) = -3: must be > 0"));
  p.environment.seabed.grid = grid();
  p.environment.seabed.profile = {{0.0, 100.0}, {100.0, 50.0}};
  EXPECT_TRUE(contains(p.validate(), "environment.seabed: has both a profile and a grid"));
}

TEST(Validation, SolverOptions) {
  {
    Problem p = validProblem();
    p.static_options.relaxation = 0.0;
    const std::string e = p.validate();
    EXPECT_TRUE(contains(e, "solver.static.relaxation"));
    EXPECT_TRUE(contains(e, "= 0"));
  }
  StaticOptions o;
  o.relaxation = 1.5;
  EXPECT_TRUE(contains(o.validate(), "solver.static.relaxation"));
  EXPECT_TRUE(contains(o.validate(), "1.5"));
  o = StaticOptions();
  o.tolerance = -1e-3;
  EXPECT_TRUE(contains(o.validate(), "solver.static.tolerance"));
  EXPECT_TRUE(contains(o.validate(), "-0.001"));
  o = StaticOptions();
  o.max_iterations = 0;
  EXPECT_TRUE(contains(o.validate(), "solver.static.max_iterations"));
  o = StaticOptions();
  o.R2 = 1.0;  // must exceed 1
  EXPECT_TRUE(contains(o.validate(), "solver.static.R2"));
  o = StaticOptions();
  o.R1 = 1.01;  // must exceed R2 = 1.02
  EXPECT_TRUE(contains(o.validate(), "solver.static.R1"));
  EXPECT_TRUE(contains(o.validate(), "1.01"));
}

// atAndAround (one search for the 2-D solver's value and finite-difference slope) gives what
// three calls of at() give, bit for bit: through every table point, just either side of each
// (a neighbour in the next interval), at the held ends and above the surface.
