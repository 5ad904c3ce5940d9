// Dynamics of systems of lines (system_dynamics.hpp): the heave natural frequency of a free body
// on an elastic tether (sqrt(k / M), the same physics as test_subsurface's top body, here through
// the partitioned point coupling), a symmetric three-leg buoy held still (a fixed point) and
// heaved by a vertical pull (it stays on the axis, the legs stay equal), and the input checks.
#include <gtest/gtest.h>

#include <stdexcept>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/system_dynamics.hpp"
#include "system_test_util.hpp"

using namespace mooring_dynamics::core;
using mooring_dynamics::core::testing_util::line;
using mooring_dynamics::core::testing_util::point;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFrequencyRelTol = 0.02;  // zero crossings at 80 steps per period (test_dynamics2d)
// Held still: every step starts on the static state; the lines' Newton tolerance (1e-6 scaled)
// and the point iteration's (1e-7 of the largest force) leave the buoy within 1e-4 m.
constexpr double kFixedPointTol = 1e-4;  // [m]
// Symmetry: three copies of one problem turned by 120 deg, each solved to its tolerances.
constexpr double kSymmetryRelTol = 1e-4;
constexpr double kAxisTol = 1e-3;  // [m]


}  // namespace

TEST(SystemDynamics, BodyOnAnElasticTetherHeavesAtSqrtKOverM) {
  SystemProblem s;
  s.environment.depth = 300.0;
  Material m;
  m.EA = 2.0e5;
  m.EI = 1.0e-2;
  m.GJ = 1.0e-2;
  m.mass = 0.1;
  m.diameter = 0.012;
  s.materials = {m};
  Body b;
  b.mass = 800.0;
  b.added_mass = 200.0;
  b.wet_weight = -3000.0;
  b.diameter = 1.2;
  s.bodies = {b};
  SystemPoint body = point("float", SystemPoint::Type::Body, 0.0, 0.0, -180.0, true);
  body.body = 0;
  s.points = {point("anchor", SystemPoint::Type::Anchor, 0.0, 0.0, -200.0), body};
  s.lines = {line("tether", 0, 1, 20.0, 1.0)};
  const double k = m.EA / 20.0, M = b.mass + b.added_mass + m.mass * 20.0 / 3.0;
  const double f1 = std::sqrt(k / M) / (2.0 * kPi), P = 1.0 / f1;
  DynamicOptions o;
  o.dt = P / 80.0;
  o.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  SystemDynamics sim(s, o);
  sim.setPointForce(1, [P](double t) {
    const double up = t < 0.1 * P ? 5000.0 * t / (0.1 * P) : t < 0.2 * P ? 5000.0 * (0.2 * P - t) / (0.1 * P) : 0.0;
    return std::array<double, 3>{0.0, 0.0, up};
  });
  const double z0 = sim.points()[1].z;
  std::vector<double> t{0.0}, z{0.0};
  for (int i = 1; i <= 800; ++i) {
    std::string why;
    ASSERT_TRUE(sim.advanceTo(i * o.dt, &why)) << why;
    t.push_back(sim.time());
    z.push_back(sim.points()[1].z - z0);
  }
  std::vector<double> up;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i - 1] > 0.5 * P && z[i - 1] < 0.0 && z[i] >= 0.0)
      up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-z[i - 1]) / (z[i] - z[i - 1]));
  ASSERT_GE(up.size(), 8u);
  const double f = (up.size() - 1) / (up.back() - up.front());
  std::printf("system heave: measured %.4f Hz, sqrt(k/M)/2pi %.4f Hz (%ld point iterations, %ld line steps)\n", f,
              f1, sim.pointIterations(), sim.lineSteps());
  EXPECT_NEAR(f, f1, kFrequencyRelTol * f1);
}

namespace {
/// The three-leg buoy of system_test_util.hpp at 10 m spacing, with seabed damping and the buoy's
/// added mass (dynamics).
SystemProblem threeLeg() {
  SystemProblem s = testing_util::threeLegBuoy(10.0);
  s.environment.seabed.damping = 1.0e3;
  s.points[0].buoy.added_mass = 3000.0;
  return s;
}
}  // namespace

// A system's lines run on one thread: dynamics.threads = 2 is refused with the field named.
TEST(SystemDynamics, RefusesTwoThreads) {
  DynamicOptions o;
  o.threads = 2;
  try {
    SystemDynamics sim(threeLeg(), o);
    FAIL() << "threads = 2 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dynamics.threads = 2: the lines of a system run on one thread"),
              std::string::npos)
        << e.what();
  }
}

TEST(SystemDynamics, HeldThreeLegBuoyIsAFixedPoint) {
  DynamicOptions o;
  o.dt = 0.5;
  SystemDynamics sim(threeLeg(), o);
  const auto p0 = sim.points()[0];
  std::string why;
  ASSERT_TRUE(sim.advanceTo(20.0, &why)) << why;
  const auto p = sim.points()[0];
  EXPECT_NEAR(p.x, p0.x, kFixedPointTol);
  EXPECT_NEAR(p.y, p0.y, kFixedPointTol);
  EXPECT_NEAR(p.z, p0.z, kFixedPointTol);
}

TEST(SystemDynamics, PulledDownThreeLegBuoyStaysOnTheAxisWithEqualLegs) {
  DynamicOptions o;
  o.dt = 0.25;
  SystemDynamics sim(threeLeg(), o);
  sim.setPointForce(0, [](double t) {
    return std::array<double, 3>{0.0, 0.0, t < 2.0 ? -20000.0 * std::sin(kPi * t / 2.0) : 0.0};
  });
  const double z0 = sim.points()[0].z;
  double deepest = 0.0;
  for (int i = 1; i <= 60; ++i) {
    std::string why;
    ASSERT_TRUE(sim.advanceTo(0.25 * i, &why)) << why;
    const auto p = sim.points()[0];
    EXPECT_NEAR(p.x, 0.0, kAxisTol) << sim.time();
    EXPECT_NEAR(p.y, 0.0, kAxisTol) << sim.time();
    deepest = std::min(deepest, p.z - z0);
    const double T0 = sim.line(0).topTension();
    for (int k = 1; k < 3; ++k) EXPECT_NEAR(sim.line(k).topTension(), T0, kSymmetryRelTol * T0) << sim.time();
  }
  EXPECT_LT(deepest, -0.05);  // the pull did push the buoy down
  std::printf("three-leg heave: deepest %.3f m below the static draft; %ld point iterations, %ld line steps\n",
              -deepest, sim.pointIterations(), sim.lineSteps());
}

TEST(SystemDynamics, HeldBranchedArrayIsAFixedPoint) {
  // config/branched_array.yaml: lines hang below the junction float (moving anchors of the line
  // solver) as well as above it. Left alone, every point stays at its static position.
  SystemProblem s = loadSystemFromFile("config/branched_array.yaml");
  DynamicOptions o;
  o.dt = 0.5;
  SystemDynamics sim(s, o);
  const auto p0 = sim.points();
  std::string why;
  ASSERT_TRUE(sim.advanceTo(20.0, &why)) << why;
  const auto p = sim.points();
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_NEAR(p[k].x, p0[k].x, kFixedPointTol) << p[k].name;
    EXPECT_NEAR(p[k].y, p0[k].y, kFixedPointTol) << p[k].name;
    EXPECT_NEAR(p[k].z, p0[k].z, kFixedPointTol) << p[k].name;
  }
}

TEST(SystemDynamics, BranchedJunctionFloatPulledAsideSwingsBack) {
  // A 1 kN sideways pull on the junction float for 10 s: it moves toward +y, the lines below and
  // above it follow it (the ends stay on the float), and it returns after the pull.
  SystemProblem s = loadSystemFromFile("config/branched_array.yaml");
  DynamicOptions o;
  o.dt = 0.5;
  o.dt = 1.0;
  SystemDynamics sim(s, o);
  const std::size_t J = 2;  // the float
  sim.setPointForce(J, [](double t) { return std::array<double, 3>{0.0, t < 10.0 ? 1000.0 : 0.0, 0.0}; });
  const double y0 = sim.points()[J].y;
  double ymax = y0;
  for (int i = 1; i <= 60; ++i) {
    std::string why;
    ASSERT_TRUE(sim.advanceTo(1.0 * i, &why)) << why;
    const auto p = sim.points();
    ymax = std::max(ymax, p[J].y);
    // Position continuity at the junction: every line's end is on the float.
    EXPECT_NEAR(sim.line(0).nodes.back().y, p[J].y, 0.05) << sim.time();   // main_lower's top
    EXPECT_NEAR(sim.line(1).nodes.front().y, p[J].y, 1e-6) << sim.time();  // main_upper's anchor
  }
  EXPECT_GT(ymax, y0 + 0.5);
  EXPECT_LT(std::abs(sim.points()[J].y - y0), 0.5 * (ymax - y0));  // on its way back
  std::printf("branched float: swung %.2f m aside, %.2f m off after 50 s; %ld point iterations, %ld line steps\n",
              ymax - y0, sim.points()[J].y - y0, sim.pointIterations(), sim.lineSteps());
}

// --- A moored vessel: fairleads on a rigid body with a prescribed pose -------------------------

namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;

/// The vessel surges 3 m and yaws 3 deg over 10 s, then holds; the wrench every 0.5 s to 15 s.
std::vector<VesselWrench> surgeAndYaw(int threads, std::vector<double>* moment_by_hand = nullptr) {
  const SystemProblem s = testing_util::fourLegVessel(10.0);
  DynamicOptions o;
  o.dt = 0.25;
  o.duration = 15.0;
  SystemDynamics d(s, o, threads);
  const RigidPose a = s.vessel.pose, b = RigidPose::fromRollPitchYaw({3.0, 0.0, 0.0}, 0.0, 0.0, 3.0 * kDegree);
  const RigidSegment seg(0.0, a, 10.0, b);
  d.setVesselMotion([seg](double t) { return seg.at(t); });
  std::vector<VesselWrench> out;
  for (int k = 1; k <= 30; ++k) {
    EXPECT_TRUE(d.advanceTo(0.5 * k));
    out.push_back(d.vesselWrench());
    if (moment_by_hand) {
      // M = sum (R r_i) x F_i from the lines' own states and the pose, summed here.
      Eigen::Vector3d M = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < s.lines.size(); ++i) {
        const StaticResult l = d.line(i);
        const Eigen::Vector3d arm = d.vesselPose().orientation.toRotationMatrix() * s.points[s.lines[i].to].body_offset;
        M += arm.cross(Eigen::Vector3d(-l.top_force_x, -l.top_force_y, -l.top_force_z));
      }
      moment_by_hand->push_back(M.z());
    }
  }
  return out;
}
}  // namespace

TEST(SystemDynamics, HeldVesselKeepsItsStaticWrench) {
  const SystemProblem s = testing_util::fourLegVessel(10.0);
  DynamicOptions o;
  o.dt = 0.5;
  o.duration = 5.0;
  SystemDynamics d(s, o);
  const VesselWrench w0 = vesselWrench(s, s.vessel.pose, d.initialStatic().lines);
  ASSERT_TRUE(d.advanceTo(5.0));
  const VesselWrench w = d.vesselWrench();
  // [N] a held system stays at its statics up to the dynamic Newton tolerance (1e-6 on eq. 39).
  const double tol = 1e-5 * std::abs(w0.force_world.z());
  EXPECT_NEAR((w.force_world - w0.force_world).norm(), 0.0, tol);
  EXPECT_NEAR(w.moment_world.z(), 0.0, 20.0 * tol);
}

TEST(SystemDynamics, MovingVesselSameBitsOnOneAndThreeThreadsAndTheMomentIsTheHandSum) {
  std::vector<double> by_hand;
  const std::vector<VesselWrench> one = surgeAndYaw(1, &by_hand), three = surgeAndYaw(3);
  ASSERT_EQ(one.size(), three.size());
  for (std::size_t k = 0; k < one.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(one[k].force_world[c], three[k].force_world[c]) << "sample " << k;
      EXPECT_EQ(one[k].moment_world[c], three[k].moment_world[c]) << "sample " << k;
    }
  for (std::size_t k = 0; k < one.size(); ++k)
    EXPECT_NEAR(one[k].moment_world.z(), by_hand[k], 1e-9 * std::abs(one[k].force_world.z()) * 30.0) << k;
  // Surged forward and yawed to port: pulled back and turned back (the last, held samples).
  EXPECT_LT(one.back().force_body.x(), 0.0);
  EXPECT_LT(one.back().moment_body.z(), 0.0);
}

// --- Failures: one group restarts alone from statics, the others go on bit for bit -------------

namespace {
/// Every node's position and tension of line i: compared bit for bit.
std::vector<double> lineBits(const SystemDynamics& d, std::size_t i) {
  std::vector<double> v;
  const StaticResult r = d.line(i);
  for (const auto& n : r.nodes) v.insert(v.end(), {n.x, n.y, n.z, n.tension});
  v.insert(v.end(), {r.top_force_x, r.top_force_y, r.top_force_z});
  return v;
}
bool at(double t1, double t) { return std::abs(t1 - t) < 1e-9; }

/// Two three-leg buoys 500 m apart sharing the anchor between them: one connected system (through
/// the shared anchor), two independent groups (each buoy with its legs). A 2 kN pull to the east
/// on buoy A and 3 kN to the north on buoy B set both in motion.
SystemProblem twoBuoys() {
  SystemProblem s = threeLeg();
  SystemPoint b = s.points[0];
  b.name = "buoy_b";
  b.x = 500.0;
  s.points.push_back(b);  // 4
  constexpr double kTwoPi = 6.283185307179586;
  for (int k = 1; k < 3; ++k) {
    const double a = kTwoPi * k / 3.0 + kPi;
    s.points.push_back(point("anchor_b" + std::to_string(k), SystemPoint::Type::Anchor, 500.0 + 250.0 * std::cos(a),
                             250.0 * std::sin(a), -100.0));
  }
  s.lines.push_back(line("leg_b0", 1, 4, 300.0, 10.0));  // from the shared anchor (250, 0, -100)
  s.lines.push_back(line("leg_b1", 5, 4, 300.0, 10.0));
  s.lines.push_back(line("leg_b2", 6, 4, 300.0, 10.0));
  return s;
}
}  // namespace

TEST(SystemDynamics, LineGroupsAreTheLinesJoinedThroughFreePoints) {
  DynamicOptions o;
  o.dt = 0.5;
  SystemDynamics two(twoBuoys(), o);
  ASSERT_EQ(two.lineGroups().size(), 2u);
  EXPECT_EQ(two.lineGroups()[0], (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(two.lineGroups()[1], (std::vector<std::size_t>{3, 4, 5}));
  SystemDynamics vessel(testing_util::fourLegVessel(10.0), o);
  EXPECT_EQ(vessel.lineGroups().size(), 4u) << "vessel legs touching no free point: one group each";
  SystemDynamics branched(loadSystemFromFile("config/branched_array.yaml"), o);
  EXPECT_EQ(branched.lineGroups().size(), 1u) << "every line of the branched array meets the junction float";
}

// A vessel leg that fails (injected at t = 2 s) restarts alone from the statics at the vessel's
// pose at 2 s; the three others go on with exactly the bits of a run without the failure.
TEST(SystemDynamics, FailedVesselLegRestartsAloneTheOthersKeepTheirBits) {
  const SystemProblem s = testing_util::fourLegVessel(10.0);
  DynamicOptions o;
  o.dt = 0.25;
  const RigidPose a = s.vessel.pose, b = RigidPose::fromRollPitchYaw({3.0, 0.0, 0.0}, 0.0, 0.0, 3.0 * kDegree);
  const RigidSegment seg(0.0, a, 10.0, b);
  SystemDynamics clean(s, o), failing(s, o);
  clean.setVesselMotion([seg](double t) { return seg.at(t); });
  failing.setVesselMotion([seg](double t) { return seg.at(t); });
  failing.setFailureInjection([](std::size_t line, double t1) { return line == 1 && at(t1, 2.0); });
  for (int k = 1; k <= 16; ++k) {
    const double t = 0.5 * k;
    std::string why;
    ASSERT_TRUE(clean.advanceTo(t, &why)) << why;
    ASSERT_TRUE(failing.advanceTo(t, &why)) << why;
    if (at(t, 2.0)) {
      ASSERT_EQ(failing.lastRestarts().size(), 1u);
      EXPECT_EQ(failing.lastRestarts()[0].lines, std::vector<std::size_t>{1});
      EXPECT_DOUBLE_EQ(failing.lastRestarts()[0].time, 2.0);
      EXPECT_NE(failing.lastRestarts()[0].reason.find("line leg1: failure injected (test hook)"), std::string::npos)
          << failing.lastRestarts()[0].reason;
      // Restarted from the statics at the pose at 2 s: the vessel statics there (solved
      // independently) give its top tension, to the static solver's tolerance.
      const VesselStaticResult st = solveVesselStatic(s, seg.at(2.0).pose);
      EXPECT_NEAR(failing.line(1).topTension(), st.system.lines[1].topTension(),
                  1e-6 * st.system.lines[1].topTension());
    } else {
      EXPECT_TRUE(failing.lastRestarts().empty()) << "t " << t;
    }
    for (std::size_t i : {0u, 2u, 3u}) EXPECT_EQ(lineBits(failing, i), lineBits(clean, i)) << "line " << i << " t " << t;
    if (t > 2.0) {
      EXPECT_NE(lineBits(failing, 1), lineBits(clean, 1)) << "the restarted leg is on its own path";
    }
  }
}

// A buoy's leg that fails restarts with the buoy and its other legs (they share the buoy's force
// balance); the other buoy and its legs go on with exactly the bits of a run without the failure.
TEST(SystemDynamics, FailedBuoyLegRestartsItsGroupTheOtherGroupKeepsItsBits) {
  const SystemProblem s = twoBuoys();
  DynamicOptions o;
  o.dt = 0.5;
  auto pulls = [](SystemDynamics& d) {
    d.setPointForce(0, [](double) { return std::array<double, 3>{2000.0, 0.0, 0.0}; });
    d.setPointForce(4, [](double) { return std::array<double, 3>{0.0, 3000.0, 0.0}; });
  };
  SystemDynamics clean(s, o), failing(s, o);
  pulls(clean);
  pulls(failing);
  failing.setFailureInjection([](std::size_t line, double t1) { return line == 4 && at(t1, 3.0); });
  for (int k = 1; k <= 12; ++k) {
    const double t = 0.5 * k;
    std::string why;
    ASSERT_TRUE(clean.advanceTo(t, &why)) << why;
    ASSERT_TRUE(failing.advanceTo(t, &why)) << why;
    if (at(t, 3.0)) {
      ASSERT_EQ(failing.lastRestarts().size(), 1u);
      EXPECT_EQ(failing.lastRestarts()[0].lines, (std::vector<std::size_t>{3, 4, 5}));
      EXPECT_NE(failing.lastRestarts()[0].reason.find("line leg_b1"), std::string::npos);
      // Buoy B back at its static position (the file's, no pull in statics), at rest.
      const auto p = failing.points()[4];
      const auto p0 = failing.initialStatic().points[4];
      EXPECT_NEAR(p.x, p0.x, kFixedPointTol);
      EXPECT_NEAR(p.y, p0.y, kFixedPointTol);
      EXPECT_EQ(failing.pointVelocity(4), (std::array<double, 3>{0.0, 0.0, 0.0}));
    }
    for (std::size_t i : {0u, 1u, 2u}) EXPECT_EQ(lineBits(failing, i), lineBits(clean, i)) << "line " << i << " t " << t;
    const auto pa = failing.points()[0], ca = clean.points()[0];
    EXPECT_EQ(pa.x, ca.x);
    EXPECT_EQ(pa.y, ca.y);
    EXPECT_EQ(pa.z, ca.z);
  }
  // Buoy A really moved (the comparison is not between two resting states).
  EXPECT_GT(clean.points()[0].x - clean.initialStatic().points[0].x, 0.01);
}

// Line events (issue 21): a three-leg buoy loses leg0 (its anchor on +x) at t = 1 s. The two
// legs left pull it toward -x, on the axis by symmetry, and it settles on the two-leg static
// equilibrium (solved independently, the system without leg0: x = -125 m between their anchors,
// where both legs pull along y); the let-go leg pulls nothing from the release on (and, a chain
// collapsing slack onto the seabed, is retired when its solver gives up), and the event is
// reported.
TEST(SystemDynamics, ThreeLegBuoyLosingALegSettlesOnTheTwoLegEquilibrium) {
  constexpr double kRelease = 1.0, kEnd = 800.0;  // [s]
  // Symmetry about the x axis: legs 1 and 2 are mirror images, as in the pulled-down test.
  constexpr double kMirrorRelTol = 1e-6;
  // The approach is slow (the legs' pull along x fades as the buoy nears the equilibrium: 31 m in
  // the first 39 s, 125 m by 740 s) and overshoots into the slow surge mode about it, which
  // quadratic drag barely damps at these speeds: 0.36 m at 800 s (measured; 0.05 m at 1000 s).
  constexpr double kSettleTol = 1.0;  // [m] of the 125 m move
  // The legs pull along y there: their tension is flat in x (measured 3e-6 of it at 800 s), and
  // the draft is the statics' to the tension's 1e-3 over the waterplane (rho g A_w = 126 kN/m).
  constexpr double kSettledTensionRelTol = 1e-3;
  constexpr double kSettledDraftTol = 1e-3;  // [m]
  SystemProblem two = threeLeg();
  two.lines.erase(two.lines.begin());
  two.points.erase(two.points.begin() + 1);
  for (SystemLine& l : two.lines) --l.from;
  const SystemStaticResult eq2 = solveSystemStatic(two);
  ASSERT_TRUE(eq2.summary.converged) << eq2.summary.message;
  const double x2 = eq2.points[0].x, T2 = eq2.lines[0].topTension();

  DynamicOptions o;
  o.dt = 1.0;  // the 800 s in about 3 s; the release's transient (not checked here) at 0.5 s peaks 9 % higher
  o.duration = kEnd;
  // The retirement of a let-go leg whose solver gives up is what this test covers: without the
  // fallback step (which would carry the collapsing chain on, see test_dynamics3d_fallback.cpp).
  o.fallback = false;
  LineEvent e;
  e.type = LineEvent::Type::Release;
  e.end = LineEvent::End::Top;
  e.t = kRelease;
  e.line = "leg0";
  o.events = {e};
  SystemDynamics sim(threeLeg(), o);
  const double x0 = sim.points()[0].x, T1_static = sim.line(1).topTension();
  ASSERT_LT(x2, x0 - 100.0) << "the two legs' equilibrium lies far toward -x";
  double peak1 = 0.0, last_x = x0, x_39 = 0.0, t_arrival = 0.0;
  for (int i = 1; i <= static_cast<int>(kEnd / o.dt); ++i) {
    std::string why;
    ASSERT_TRUE(sim.advanceTo(o.dt * i, &why)) << why;
    const auto p = sim.points()[0];
    const double T1 = sim.line(1).topTension(), T2 = sim.line(2).topTension();
    EXPECT_NEAR(T1, T2, kMirrorRelTol * T1) << sim.time();
    EXPECT_NEAR(p.y, 0.0, kMirrorRelTol * std::abs(x0 - x2)) << sim.time();
    if (sim.time() > kRelease + 1e-9) {
      EXPECT_NEAR(sim.line(0).topTension(), 0.0, 1e-6 * T1_static) << "let go at " << sim.time();
      if (t_arrival == 0.0) {
        EXPECT_LE(p.x, last_x + 1e-6) << "drifts toward -x without coming back (overdamped by the chain), t = "
                                      << sim.time();
      }
    }
    if (t_arrival == 0.0 && p.x <= x2) t_arrival = sim.time();
    if (std::abs(sim.time() - (kRelease + 39.0)) < 1e-9) x_39 = p.x;
    peak1 = std::max(peak1, T1);
    last_x = p.x;
  }
  const auto events = sim.lineEvents();
  ASSERT_GE(events.size(), 1u);
  EXPECT_EQ(events[0].line, "leg0");
  EXPECT_EQ(events[0].what, "released top");
  EXPECT_NEAR(events[0].t, kRelease, 1e-9);
  const auto p = sim.points()[0];
  std::printf("three-leg buoy losing leg0: x %.2f -> %.2f m at 40 s, %.3f m at %.0f s (two-leg equilibrium %.3f m, "
              "first reached at %.0f s); draft %.4f m (statics %.4f m); leg1 static %.0f N, peak %.0f N, end %.1f N "
              "(two-leg statics %.1f N); %zu events\n",
              x0, x_39, p.x, kEnd, x2, t_arrival, -p.z, -eq2.points[0].z, T1_static, peak1, sim.line(1).topTension(),
              T2, events.size());
  EXPECT_GT(t_arrival, 0.0) << "the buoy reached the two-leg equilibrium";
  EXPECT_NEAR(p.x, x2, kSettleTol);
  EXPECT_NEAR(p.y, 0.0, kMirrorRelTol * std::abs(x0 - x2));
  EXPECT_NEAR(p.z, eq2.points[0].z, kSettledDraftTol);
  EXPECT_NEAR(sim.line(1).topTension(), T2, kSettledTensionRelTol * T2);
  EXPECT_NEAR(sim.line(2).topTension(), eq2.lines[1].topTension(), kSettledTensionRelTol * T2);
}

// A winch at leg0's top (dynamics.winch with line:) hauls it in 10 m over 20 s: the buoy moves
// toward leg0's anchor (+x), stays on the axis (legs 1 and 2 mirror each other), and settles on
// the statics of the system with leg0 10 m shorter. The other legs keep their length.
TEST(SystemDynamics, WinchHaulsALegInAndTheBuoySettlesOnTheShorterLegsStatics) {
  // The buoy swings about the new equilibrium in its slow surge mode (period ~70 s): +5.5 cm at
  // 60 s, within 5 mm by 200 s (measured). At 60 s, against a 6.2 m move.
  constexpr double kSettleTol = 0.08;  // [m]
  constexpr double kMirrorRelTol = 1e-6;  // legs 1 and 2 are mirror images, as in the tests above
  constexpr double kLengthTol = 1e-9;     // [m] the program's round lengths, to rounding
  SystemProblem shorter = threeLeg();
  shorter.lines[0].segments.back().length -= 10.0;
  const SystemStaticResult eq = solveSystemStatic(shorter);
  ASSERT_TRUE(eq.summary.converged) << eq.summary.message;

  SystemProblem s = threeLeg();
  s.dynamics.dt = 0.5;
  s.dynamics.duration = 60.0;
  s.dynamics.winch.given = true;
  s.dynamics.winch.line = "leg0";
  s.dynamics.winch.table = {{0.0, 300.0}, {20.0, 290.0}};
  ASSERT_EQ(s.validate(), "");
  SystemDynamics sim(s, s.dynamics);
  const double x0 = sim.points()[0].x;
  ASSERT_GT(eq.points[0].x, x0 + 2.0) << "the shorter leg pulls the buoy toward +x";
  for (int i = 1; i <= 120; ++i) {
    std::string why;
    ASSERT_TRUE(sim.advanceTo(0.5 * i, &why)) << why;
    EXPECT_NEAR(sim.line(1).topTension(), sim.line(2).topTension(), kMirrorRelTol * sim.line(1).topTension());
  }
  EXPECT_NEAR(sim.lineLength(0), 290.0, kLengthTol);
  EXPECT_EQ(sim.lineLength(1), 300.0);
  EXPECT_NEAR(sim.points()[0].x, eq.points[0].x, kSettleTol);
  EXPECT_NEAR(sim.points()[0].y, 0.0, kMirrorRelTol * eq.points[0].x);
  // A winch naming no line of the file, or none at all, is refused by the system's validation.
  s.dynamics.winch.line = "leg9";
  EXPECT_NE(s.validate().find("dynamics.winch.line = leg9: no line of that name"), std::string::npos);
  s.dynamics.winch.line.clear();
  EXPECT_NE(s.validate().find("dynamics.winch.line: required"), std::string::npos);
}
