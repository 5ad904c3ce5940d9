// YAML problem loader, a problem given as text: a good file parses into the expected structs; every
// class of bad input raises ProblemError whose message names the key path, the value found and the
// constraint; explicit YAML tags, segment spacing, the limits section and the input size (issue 22).
// Files (problem, seabed grid, current table, config/, docs): test_problem_io_files.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_io_test_util.hpp"

using namespace mooring_dynamics::core;
using namespace mooring_dynamics::core::testing_util;

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST(ProblemIo, ParsesGoodFile) {
  const Problem p = loadProblemFromString(kGood);
  EXPECT_EQ(p.name, "test mooring");
  const Environment& e = p.environment;
  EXPECT_DOUBLE_EQ(e.water_density, 1025);
  EXPECT_DOUBLE_EQ(e.air_density, 1.2);
  EXPECT_DOUBLE_EQ(e.gravity, 9.8);
  EXPECT_DOUBLE_EQ(e.depth, 100);
  EXPECT_DOUBLE_EQ(e.seabed.stiffness, 2.0e5);
  EXPECT_DOUBLE_EQ(e.seabed.damping, 10);
  ASSERT_EQ(e.seabed.profile.size(), 3u);
  EXPECT_DOUBLE_EQ(e.seabed.profile[2].first, 200);
  EXPECT_DOUBLE_EQ(e.seabed.profile[2].second, 80);
  ASSERT_EQ(e.current.size(), 2u);
  EXPECT_DOUBLE_EQ(e.current[0].speed, 0.5);
  EXPECT_NEAR(e.current[0].direction, kPi / 2, 1e-15);  // degrees in the file, radians in the struct
  EXPECT_DOUBLE_EQ(e.current[1].depth, 100);
  EXPECT_DOUBLE_EQ(e.current[1].direction, 0.0);  // default
  EXPECT_DOUBLE_EQ(e.wind_speed, 20);
  EXPECT_NEAR(e.wind_direction, kPi, 1e-15);

  ASSERT_EQ(p.materials.size(), 2u);
  const Material& c = p.materials[0];
  EXPECT_EQ(c.name, "chain");
  EXPECT_DOUBLE_EQ(c.EA, 6.44e7);
  EXPECT_DOUBLE_EQ(c.EI, 10);
  EXPECT_DOUBLE_EQ(c.GJ, 0.1);
  EXPECT_DOUBLE_EQ(c.mass, 3.73);
  EXPECT_DOUBLE_EQ(c.added_mass, 0.48);
  EXPECT_DOUBLE_EQ(c.wet_weight, 31.85);
  EXPECT_DOUBLE_EQ(c.diameter, 0.0495);
  EXPECT_DOUBLE_EQ(c.cdn, 0.5);
  EXPECT_DOUBLE_EQ(c.cdt, 0.05);
  EXPECT_DOUBLE_EQ(c.max_strain, 0.1);
  const Material& r = p.materials[1];
  EXPECT_EQ(r.name, "rope");
  ASSERT_EQ(r.tension_strain.size(), 3u);
  EXPECT_DOUBLE_EQ(r.tension_strain[1].first, 0.01);
  EXPECT_DOUBLE_EQ(r.tension_strain[1].second, 2.0e4);
  EXPECT_DOUBLE_EQ(r.GJ, 0.0);          // default
  EXPECT_DOUBLE_EQ(r.added_mass, 0.0);  // default
  EXPECT_DOUBLE_EQ(r.max_strain, 0.2);  // default

  ASSERT_EQ(p.bodies.size(), 2u);
  EXPECT_EQ(p.bodies[0].name, "float");
  EXPECT_DOUBLE_EQ(p.bodies[0].wet_weight, -214.8);
  EXPECT_EQ(p.bodies[1].name, "clump");
  EXPECT_DOUBLE_EQ(p.bodies[1].added_mass, 0.0);

  ASSERT_EQ(p.segments.size(), 2u);
  const Segment& s0 = p.segments[0];
  EXPECT_EQ(s0.material, 0u);
  EXPECT_DOUBLE_EQ(s0.length, 45.0);
  EXPECT_DOUBLE_EQ(s0.spacing, 0.5);
  // clump (first item) at 0 of the next segment, inline float at 5, float item at the end (45).
  ASSERT_EQ(s0.bodies.size(), 3u);
  EXPECT_EQ(s0.bodies[0].body, 1u);
  EXPECT_DOUBLE_EQ(s0.bodies[0].at, 0.0);
  EXPECT_EQ(s0.bodies[1].body, 0u);
  EXPECT_DOUBLE_EQ(s0.bodies[1].at, 5.0);
  EXPECT_EQ(s0.bodies[2].body, 0u);
  EXPECT_DOUBLE_EQ(s0.bodies[2].at, 45.0);
  const Segment& s1 = p.segments[1];
  EXPECT_EQ(s1.material, 1u);
  EXPECT_DOUBLE_EQ(s1.spacing, 1.0);  // default
  ASSERT_EQ(s1.bodies.size(), 4u);    // count: 4 from at 10 every 20
  for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(s1.bodies[k].at, 10.0 + 20.0 * k);

  EXPECT_DOUBLE_EQ(p.anchor_x, -1.5);
  EXPECT_DOUBLE_EQ(p.anchor_z, -100.0);  // seabed elevation at x = -1.5 from the profile
  EXPECT_EQ(p.top.type, TopBoundary::Type::Position);
  EXPECT_DOUBLE_EQ(p.top.x, 80);
  EXPECT_DOUBLE_EQ(p.top.z, -2);
  EXPECT_DOUBLE_EQ(p.static_options.tolerance, 1e-8);
  EXPECT_EQ(p.static_options.max_iterations, 200);
  EXPECT_DOUBLE_EQ(p.static_options.relaxation, 0.5);
  EXPECT_FALSE(p.static_options.adaptive_relaxation);
  EXPECT_DOUBLE_EQ(p.static_options.R1, 1.2);
  EXPECT_DOUBLE_EQ(p.static_options.R2, 1.05);
}

TEST(ProblemIo, DefaultsFromModel) {
  const Problem p = loadProblemFromString(kMinimal);
  const Problem d;
  EXPECT_EQ(p.name, "");
  EXPECT_DOUBLE_EQ(p.environment.water_density, d.environment.water_density);
  EXPECT_DOUBLE_EQ(p.environment.depth, d.environment.depth);
  EXPECT_DOUBLE_EQ(p.environment.seabed.stiffness, d.environment.seabed.stiffness);
  EXPECT_TRUE(p.environment.current.empty());
  EXPECT_TRUE(p.bodies.empty());
  EXPECT_DOUBLE_EQ(p.anchor_x, 0.0);
  EXPECT_DOUBLE_EQ(p.anchor_z, -d.environment.depth);  // on the flat seabed
  EXPECT_DOUBLE_EQ(p.static_options.tolerance, d.static_options.tolerance);
  EXPECT_EQ(p.static_options.max_iterations, d.static_options.max_iterations);
  EXPECT_TRUE(p.static_options.adaptive_relaxation);
}

TEST(ProblemIo, TopForceAndBuoyAndUniformCurrent) {
  std::string s = kMinimal;
  s.replace(s.find("position: {x: 100, z: 0}"), 24, "force: {x: 1000, z: 5000}");
  Problem p = loadProblemFromString(s);
  EXPECT_EQ(p.top.type, TopBoundary::Type::Force);
  EXPECT_DOUBLE_EQ(p.top.fx, 1000);
  EXPECT_DOUBLE_EQ(p.top.fz, 5000);

  s = kMinimal;
  s.replace(s.find("position: {x: 100, z: 0}"), 24,
            "buoy: {shape: cylinder, diameter: 2.5, height: 1.5, mass: 1500, cd: 0.9, wind_area: 3}");
  p = loadProblemFromString(s + "environment: {depth: 120, current: {speed: 0.5, direction_deg: 180}}\n");
  EXPECT_EQ(p.top.type, TopBoundary::Type::Buoy);
  EXPECT_EQ(p.top.buoy.shape, SurfaceBuoy::Shape::Cylinder);
  EXPECT_DOUBLE_EQ(p.top.buoy.diameter, 2.5);
  EXPECT_DOUBLE_EQ(p.top.buoy.height, 1.5);
  EXPECT_DOUBLE_EQ(p.top.buoy.mass, 1500);
  EXPECT_DOUBLE_EQ(p.top.buoy.added_mass, 0.0);
  EXPECT_DOUBLE_EQ(p.top.buoy.cd, 0.9);
  EXPECT_DOUBLE_EQ(p.top.buoy.wind_area, 3.0);
  EXPECT_DOUBLE_EQ(p.top.buoy.wind_cd, 1.0);
  // Uniform shorthand -> two points, surface and bottom, same speed.
  ASSERT_EQ(p.environment.current.size(), 2u);
  EXPECT_DOUBLE_EQ(p.environment.current[0].depth, 0.0);
  EXPECT_DOUBLE_EQ(p.environment.current[1].depth, 120.0);
  EXPECT_DOUBLE_EQ(p.environment.current[1].speed, 0.5);
  EXPECT_NEAR(p.environment.current[1].direction, kPi, 1e-15);
  double ux = 0, uy = 0;
  p.environment.currentAt(-60.0, ux, uy);
  EXPECT_NEAR(ux, -0.5, 1e-12);
}

TEST(ProblemIo, MissingKey) {
  EXPECT_ERROR_HAS(mutate("mass: 3.73, ", ""), "materials.chain.mass", "required key missing");
  EXPECT_ERROR_HAS(mutate("EA: 6.44e7, ", ""), "materials.chain.EA", "tension_strain");
  EXPECT_ERROR_HAS(mutate("{material: chain, length: 45.0, ", "{material: chain, "), "line[1].length",
                   "required");
  EXPECT_ERROR_HAS(mutate("position: {x: 80, z: -2}", "position: {x: 80}"), "top.position.z", "missing");
  EXPECT_ERROR_HAS("materials: {}\n", "materials");
  EXPECT_ERROR_HAS("name: x\n", "materials", "missing");
  EXPECT_ERROR_HAS("", "empty");
}

TEST(ProblemIo, WrongType) {
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: deep"), "environment.depth", "\"deep\"", "expected a number");
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: \"100\""), "environment.depth", "quoted");
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: [100]"), "environment.depth", "expected a number",
                   "a list");
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth:"), "environment.depth", "empty");
  EXPECT_ERROR_HAS(mutate("max_iterations: 200", "max_iterations: 200.5"),
                   "solver.static.max_iterations = 200.5", "integer");
  EXPECT_ERROR_HAS(mutate("adaptive_relaxation: false", "adaptive_relaxation: maybe"),
                   "solver.static.adaptive_relaxation = maybe", "true or false");
  {
    std::string s = kMinimal;
    s.replace(s.find("line:\n  - {material: chain, length: 150}"), 40, "line: 5");
    EXPECT_ERROR_HAS(s, "line = 5", "expected a list");
  }
  EXPECT_ERROR_HAS(mutate("[[-100, 100], [0, 100], [200, 80]]", "[[-100, 100], [0, 100, 3], [200, 80]]"),
                   "environment.seabed.profile[1]", "pair");
  EXPECT_ERROR_HAS(mutate("material: chain, length: 45.0", "material: [chain], length: 45.0"),
                   "line[1].material", "expected a string");
}

TEST(ProblemIo, NonFiniteNumbers) {
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: .nan"), "environment.depth = .nan", "finite");
  EXPECT_ERROR_HAS(mutate("EA: 6.44e7", "EA: .inf"), "materials.chain.EA = .inf", "finite");
  EXPECT_ERROR_HAS(mutate("wet_weight: 31.85", "wet_weight: -.Inf"), "materials.chain.wet_weight = -.Inf",
                   "finite");
  EXPECT_ERROR_HAS(mutate("x: 80", "x: nan"), "top.position.x = nan", "finite");
  EXPECT_ERROR_HAS(mutate("gravity: 9.8", "gravity: 1e999"), "environment.gravity = 1e999", "range");
}

TEST(ProblemIo, NonPositiveValues) {
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: -5"), "environment.depth = -5: must be > 0");
  EXPECT_ERROR_HAS(mutate("length: 45.0", "length: -45"), "line[1].length = -45", "must be > 0");
  EXPECT_ERROR_HAS(mutate("length: 45.0", "length: 0"), "line[1].length = 0", "must be > 0");
  EXPECT_ERROR_HAS(mutate("spacing: 0.5", "spacing: 0"), "line[1].spacing = 0", "must be > 0");
  EXPECT_ERROR_HAS(mutate("diameter: 0.0495", "diameter: 0"), "materials.chain.diameter = 0", "must be > 0");
  EXPECT_ERROR_HAS(mutate("EA: 6.44e7", "EA: -5"), "materials.chain.EA = -5: must be > 0");
  EXPECT_ERROR_HAS(mutate("diameter: 0.58", "diameter: -0.58"), "bodies.float.diameter = -0.58", ">= 0");
  EXPECT_ERROR_HAS(mutate("speed: 0.5", "speed: -0.5"), "environment.current[0].speed = -0.5", ">= 0");
  EXPECT_ERROR_HAS(mutate("relaxation: 0.5", "relaxation: 1.5"), "solver.static.relaxation = 1.5", "(0, 1]");
  EXPECT_ERROR_HAS(mutate("R1: 1.2", "R1: 1.01"), "solver.static.R1 = 1.01", "R1 must be > R2");
  EXPECT_ERROR_HAS(mutate("at: 5.0", "at: 50"), "line[1].bodies[0].at = 50", "segment length 45");
  EXPECT_ERROR_HAS(mutate("every: 20, count: 4", "every: 30, count: 4"), "line[3].bodies[0]", "body 4 of 4",
                   "100");
}

TEST(ProblemIo, MaterialPhysicsKeys) {
  // Defaults: the law through zero (WHOI Cable's), a frictionless seabed.
  const Problem d = loadProblemFromString(kGood);
  EXPECT_TRUE(d.materials[0].compression);
  EXPECT_EQ(d.materials[0].mu_axial, 0.0);
  EXPECT_EQ(d.materials[0].mu_lateral, 0.0);
  const Problem p = loadProblemFromString(
      mutate("max_strain: 0.1}", "max_strain: 0.1, compression: false, mu_axial: 0.7, mu_lateral: 1.0}"));
  EXPECT_FALSE(p.materials[0].compression);
  EXPECT_EQ(p.materials[0].mu_axial, 0.7);
  EXPECT_EQ(p.materials[0].mu_lateral, 1.0);
  EXPECT_ERROR_HAS(mutate("max_strain: 0.1}", "max_strain: 0.1, mu_axial: -0.2}"), "materials.chain.mu_axial = -0.2",
                   ">= 0");
  EXPECT_ERROR_HAS(mutate("max_strain: 0.1}", "max_strain: 0.1, compression: maybe}"), "materials.chain.compression");
}

TEST(ProblemIo, UnknownNames) {
  EXPECT_ERROR_HAS(mutate("material: chain, length: 45.0", "material: chian, length: 45.0"),
                   "line[1].material = \"chian\": unknown material (known: chain, rope)");
  EXPECT_ERROR_HAS(mutate("{body: float, at: 5.0}", "{body: flaot, at: 5.0}"),
                   "line[1].bodies[0].body = \"flaot\": unknown body (known: float, clump)");
  EXPECT_ERROR_HAS(mutate("- {body: clump}", "- {body: anchorweight}"), "line[0].body = \"anchorweight\"",
                   "unknown body");
  std::string s = kMinimal;
  s.replace(s.find("position: {x: 100, z: 0}"), 24, "buoy: {shape: cube, diameter: 2, mass: 100}");
  EXPECT_ERROR_HAS(s, "top.buoy.shape = \"cube\"", "sphere, cylinder");
}

TEST(ProblemIo, UnknownKeys) {
  EXPECT_ERROR_HAS(mutate("depth: 100", "dpeth: 100"), "environment.dpeth", "unknown key", "did you mean \"depth\"");
  EXPECT_ERROR_HAS(mutate("cdn: 0.5", "cnd: 0.5"), "materials.chain.cnd", "unknown key");
  EXPECT_ERROR_HAS(mutate("stiffness: 2.0e5", "stifness: 2.0e5"), "environment.seabed.stifness", "unknown key");
  EXPECT_ERROR_HAS(mutate("{body: float, at: 5.0}", "{body: float, at: 5.0, side: left}"),
                   "line[1].bodies[0].side", "unknown key");
  EXPECT_ERROR_HAS(mutate("- {body: float}", "- {body: float, at: 3}"), "line[2].at", "unknown key");
  EXPECT_ERROR_HAS(mutate("tolerance: 1e-8", "tol: 1e-8"), "solver.static.tol", "unknown key");
  EXPECT_ERROR_HAS(mutate("static:", "statics:"), "solver.statics", "unknown key");
  EXPECT_ERROR_HAS(mutate("anchor: {x: -1.5}", "anchor: {x: -1.5, w: 0}"), "anchor.w", "unknown key");
  EXPECT_ERROR_HAS(mutate("name: test mooring", "nmae: test mooring"), "nmae", "unknown key",
                   "did you mean \"name\"");
  EXPECT_ERROR_HAS(mutate("water_density: 1025", "water_density: 1025\n  water_density: 1000"),
                   "environment.water_density", "duplicate");
}

TEST(ProblemIo, ModelKeyAndOutOfPlaneGeometry) {
  // y coordinates are 3-D geometry: the 2-D model (the default) names the key and the way out.
  EXPECT_ERROR_HAS(mutate("anchor: {x: -1.5}", "anchor: {x: -1.5, y: 2}"), "anchor.y = 2", "model: 3d");
  EXPECT_ERROR_HAS(mutate("name: test mooring", "name: test mooring\nmodel: 4d"), "model = \"4d\"", "2d, 3d");
  const Problem p = loadProblemFromString(
      mutate("name: test mooring", "name: test mooring\nmodel: 3d"));
  EXPECT_EQ(p.formulation, Formulation::ThreeD);
  const Problem q = loadProblemFromString(mutate("anchor: {x: -1.5}", "anchor: {x: -1.5, y: 2}")
                                              .insert(0, "model: 3d\n"));
  EXPECT_DOUBLE_EQ(q.anchor_y, 2.0);
}

TEST(ProblemIo, TablesMustIncrease) {
  EXPECT_ERROR_HAS(mutate("[[0, 0], [0.01, 2.0e4], [0.05, 2.0e5]]", "[[0, 0], [0.01, 2.0e4], [0.01, 2.0e5]]"),
                   "materials.rope.tension_strain[2]", "[0.01, 2.0e5]", "strain must increase");
  EXPECT_ERROR_HAS(mutate("[[0, 0], [0.01, 2.0e4], [0.05, 2.0e5]]", "[[0, 0], [0.01, 2.0e4], [0.05, 1.0e4]]"),
                   "materials.rope.tension_strain[2]", "tension must increase");
  EXPECT_ERROR_HAS(mutate("[[-100, 100], [0, 100], [200, 80]]", "[[-100, 100], [0, 100], [-50, 80]]"),
                   "environment.seabed.profile[2]", "x must increase");
  EXPECT_ERROR_HAS(mutate("{depth: 100, speed: 0.1}", "{depth: 0, speed: 0.1}"),
                   "environment.current[1].depth = 0", "depth must increase");
  EXPECT_ERROR_HAS(mutate("[[0, 0], [0.01, 2.0e4]", "[[0.001, 0], [0.01, 2.0e4]"),
                   "materials.rope.tension_strain[0]", "[0, 0]");
}

TEST(ProblemIo, TopBoundaryExactlyOne) {
  EXPECT_ERROR_HAS(mutate("position: {x: 80, z: -2}", "position: {x: 80, z: -2}\n  force: {x: 1, z: 2}"), "top",
                   "position, force", "exactly one");
  EXPECT_ERROR_HAS(mutate("  position: {x: 80, z: -2}", "  {}"), "top", "exactly one");
  std::string s = kMinimal;
  s.replace(s.find("position: {x: 100, z: 0}"), 24, "buoy: {shape: sphere, diameter: 2, height: 1, mass: 100}");
  EXPECT_ERROR_HAS(s, "top.buoy.height", "cylinder");
}

TEST(ProblemIo, LineStructure) {
  EXPECT_ERROR_HAS(mutate("- {body: clump}", "- {body: clump, material: chain}"), "line[0]", "both");
  EXPECT_ERROR_HAS(mutate("- {body: clump}", "- {length: 3}"), "line[0]", "neither");
  EXPECT_ERROR_HAS(mutate("- {body: clump}", "- clump"), "line[0] = clump", "expected a map");
  EXPECT_ERROR_HAS("materials: {c: {EA: 1, EI: 1, mass: 1, wet_weight: 1, diameter: 1, cdn: 1, cdt: 1}}\n"
                   "bodies: {b: {mass: 1, wet_weight: 1, diameter: 1, cdn: 1, cdt: 1}}\n"
                   "line: [{body: b}]\ntop: {force: {x: 0, z: 1}}\n",
                   "line", "at least one segment");
}

TEST(ProblemIo, AnchorAndSemanticChecks) {
  EXPECT_ERROR_HAS(minimalWith("anchor: {x: 0, z: -150}\n"), "anchor.z = -150", "below the seabed");
  EXPECT_ERROR_HAS(minimalWith("anchor: {x: 0, z: 5}\n"), "anchor.z = 5", "<= 0");
  // Problem::validate() runs at the end: a top position out of reach of the line.
  std::string s = kMinimal;
  s.replace(s.find("position: {x: 100, z: 0}"), 24, "position: {x: 1000, z: 0}");
  EXPECT_ERROR_HAS(s, "top.position");
}

TEST(ProblemIo, YamlSyntaxErrorHasLine) {
  EXPECT_ERROR_HAS("materials: {chain: [1, 2\nline: x\n", "YAML syntax error", "line");
}

TEST(ProblemIo, SecondYamlDocumentIsAnError) {
  EXPECT_ERROR_HAS(minimalWith("---\nname: second\n"), "2 YAML documents");
}

TEST(ProblemIo, MessagesCarryLineNumbers) {
  // "depth" is on line 7 of the good file (line 1 is the empty line after R"().
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: -5"), "(line 7)");
}

TEST(ProblemIo, DynamicsSectionIsReserved) {
  EXPECT_NO_THROW(loadProblemFromString(minimalWith("dynamics: {duration: 600, lambda_inf: -0.5}\n")));
  EXPECT_ERROR_HAS(minimalWith("dynamic: {}\n"), "dynamic", "unknown key", "did you mean \"dynamics\"");
}

// ---- issue 22: tags, spacing, limits -----------------------------------------------------------

TEST(ProblemIo, ExplicitStringTagIsNotANumber) {
  // `!!str 5` is the text "5" (YAML core schema), refused where a number, integer or bool is due.
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: !!str 100"), "environment.depth", "!!str", "expected a number");
  EXPECT_ERROR_HAS(mutate("max_iterations: 200", "max_iterations: !!str 200"), "max_iterations", "!!str",
                   "expected an integer");
  EXPECT_ERROR_HAS(mutate("adaptive_relaxation: false", "adaptive_relaxation: !!str false"), "adaptive_relaxation",
                   "!!str");
  EXPECT_ERROR_HAS(mutate("depth: 100", "depth: !custom 100"), "environment.depth", "!custom");
  // The core schema's own number tags say what the plain scalar says: accepted.
  EXPECT_EQ(errorOf(mutate("depth: 100", "depth: !!float 100")), "");
  EXPECT_EQ(errorOf(mutate("max_iterations: 200", "max_iterations: !!int 200")), "");
}

TEST(ProblemIo, SpacingBeyondTheSegmentIsRefused) {
  EXPECT_ERROR_HAS(mutate("length: 45.0, spacing: 0.5", "length: 45.0, spacing: 50"), "line[1].spacing", "50",
                   "must be <=", "45");
  // Equal to the length is one interval, as asked.
  EXPECT_EQ(errorOf(mutate("length: 45.0, spacing: 0.5", "length: 45.0, spacing: 45")), "");
}

/// kMinimal with `from` replaced by `to` (first occurrence).
std::string minimalReplaced(const std::string& from, const std::string& to) {
  std::string s = kMinimal;
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST(ProblemIo, DefaultSpacingOfAShortSegmentIsTheSegment) {
  // The 1 m default on a 0.4 m segment: one interval either way; the default is not an error.
  const Problem p = loadProblemFromString(
      minimalReplaced("- {material: chain, length: 150}", "- {material: chain, length: 149.6}\n  - {material: chain, length: 0.4}"));
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_DOUBLE_EQ(p.segments[0].spacing, 1.0);
  EXPECT_DOUBLE_EQ(p.segments[1].spacing, 0.4);
}

TEST(ProblemIo, LimitsSectionRaisesAndLowersTheLimits) {
  // 150 m at 1 m: 151 nodes (150 intervals).
  EXPECT_ERROR_HAS(minimalWith("limits: {max_nodes: 150}\n"), "limits.max_nodes", "151 nodes");
  EXPECT_EQ(errorOf(minimalWith("limits: {max_nodes: 151}\n")), "");
  const Problem p = loadProblemFromString(minimalWith("limits: {max_nodes: 2e6, max_steps: 1e8, max_memory_mb: 100}\n"));
  EXPECT_EQ(p.limits.max_nodes, 2e6);
  EXPECT_EQ(p.limits.max_steps, 1e8);
  EXPECT_EQ(p.limits.max_memory_mb, 100);
  EXPECT_ERROR_HAS(minimalWith("limits: {max_nodes: -1}\n"), "limits.max_nodes", "must be > 0");
  EXPECT_ERROR_HAS(minimalWith("limits: {max_memory_mb: 1e12}\n"), "limits.max_memory_mb", "1e+12");
  EXPECT_ERROR_HAS(minimalWith("limits: {nodes: 5}\n"), "limits.nodes", "unknown key");
}

TEST(ProblemIo, StepCountBeyondTheLimitIsRefused) {
  // 5 s at 1e-6 s: 5e6 steps, within 1e7; at 1e-7 s: 5e7, beyond.
  EXPECT_EQ(errorOf(minimalWith("dynamics: {duration: 5, dt: 1e-6}\n")), "");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {duration: 5, dt: 1e-7}\n"), "dynamics.duration = 5", "dynamics.dt = 1e-07",
                   "5e+07", "limits.max_steps");
  EXPECT_ERROR_HAS(minimalWith("dynamics: {duration: 5, dt: 1e20}\n"), "dynamics.dt", "must be <= dynamics.duration");
}

TEST(ProblemIo, TopBelowTheSeabedNamesTopZAndTheDepth) {
  EXPECT_ERROR_HAS(minimalReplaced("z: 0", "z: -90") + "environment: {depth: 80}\n", "top.position.z = -90",
                   "environment.depth = 80", "below the seabed");
}

TEST(ProblemIo, CommaStartingALineIsASyntaxErrorNotAHang) {
  // yaml-cpp 0.7 loops without end on these (found by scripts/fuzz); refused before it sees them.
  EXPECT_ERROR_HAS(", x\n", "YAML syntax error at line 1", "','");
  EXPECT_ERROR_HAS("- a\n, b\n", "YAML syntax error at line 2");
  EXPECT_ERROR_HAS("a: 1\n---\n, x\n", "YAML syntax error at line 3");
  EXPECT_ERROR_HAS("\"x\", y\n", "YAML syntax error at line 1");
  // Commas inside flow collections, quotes and comments stay what they are.
  EXPECT_EQ(errorOf(minimalWith("# a comment \"with a quote\n# , and a comma\nname: \"x\n  , y\"\n")), "");
  EXPECT_EQ(errorOf(minimalWith("dynamics: {duration: 5\n  , dt: 0.1}\n")), "");
}

TEST(ProblemIo, TextOverMaxInputMbIsRefusedBeforeTheYamlReaderSeesIt) {
  // 5 MB of comment lines in front of a valid problem: over the default 4 MB. A syntax error
  // after the padding shows that the refusal comes first (the reader would report the error).
  std::string pad;
  for (int i = 0; i < 70000; ++i) pad += "# padding, a long current profile would be here ........................\n";
  ASSERT_GT(pad.size(), ResourceLimits::kDefaultMaxInputMb * 1024 * 1024);
  std::string m = errorOf(pad + kMinimal + "name: \"unterminated\n");
  EXPECT_NE(m.find("over limits.max_input_mb = 4 MB"), std::string::npos) << m;
  EXPECT_NE(m.find("environment.current: {file: ...}"), std::string::npos) << m;
  // The file's own limits section raises it (read alone, before the rest), block or flow style.
  EXPECT_EQ(errorOf(pad + kMinimal + "limits:\n  max_input_mb: 8   # a long profile\n"), "");
  EXPECT_EQ(errorOf(pad + "limits: {max_input_mb: 8}\n" + kMinimal), "");
  // Raised too little, or to a value out of range: refused, naming the key.
  m = errorOf(pad + kMinimal + "limits: {max_input_mb: 4.5}\n");
  EXPECT_NE(m.find("over limits.max_input_mb = 4.5 MB"), std::string::npos) << m;
  m = errorOf(pad + kMinimal + "limits: {max_input_mb: 1000}\n");
  EXPECT_NE(m.find("limits.max_input_mb = 1000: must be a number in [0.01, 256]"), std::string::npos) << m;
  // Lowered: a small file over it is refused too.
  m = errorOf(minimalWith("limits: {max_input_mb: 0.01}\n#" + std::string(20000, '.') + "\n"));
  EXPECT_NE(m.find("over limits.max_input_mb = 0.01 MB"), std::string::npos) << m;
}
