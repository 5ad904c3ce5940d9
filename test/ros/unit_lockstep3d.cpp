// Unit tests of the lockstep driver on the 3-D solver (makeSolver3D, chosen by model: 3d) and of
// the model-dependent y handling (driver, SolveStatic conversion, markers); no master needed.
// Problem: test/data/small_catenary.yaml (150 m of chain, anchor (0, 0, -100) m, static top
// (100, 0, 0) m, 76 nodes) with formulation set to 3d or left 2d; dt = 0.1 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/nodes/lockstep.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"

using namespace mooring_dynamics;
using ros_bridge::LockstepDriver;
using O = LockstepDriver::Outcome;

namespace {

constexpr double kDt = 0.1;      // [s] base step = sample spacing
constexpr double kTopX = 100.0;  // [m] static top of the test problem
constexpr double kTopZ = 0.0;
constexpr double kPi = 3.141592653589793;
// A top re-solved in statics at a given position sits there to the static solver's tolerance
// (1e-9 on the scaled update): 1e-6 m is far above that and far below any commanded motion.
constexpr double kHeldAt = 1e-6;
// The top follows a commanded track through velocity with position feedback (docs/method.md):
// it lags by a fraction of the per-sample motion. Half the sway amplitude is a loose bound that a
// top which ignores y (stays at y = 0) fails by a factor of two.
constexpr double kFollowFraction = 0.5;
// 3-D vs 2-D on the same in-plane track: the 3-D equations restricted to the plane are the 2-D
// ones, discretised differently in time (mass matrix averaged by alpha_k; core test_dynamics3d
// measures a difference second order in dt, 1.8e-2 N on kN tensions). This 1 s run shows 1e-6
// relative; 1e-4 leaves room for other platforms' rounding and stays far below the effect of the
// 0.2 m surge it carries (checked below to be over 1e-3).
constexpr double kPlanarAgreement = 1e-4;

core::Problem problem(core::Formulation f) {
  core::Problem p = core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/test/data/small_catenary.yaml");
  p.formulation = f;
  return p;
}
core::Problem problem3d() { return problem(core::Formulation::ThreeD); }

}  // namespace

TEST(Lockstep3D, ModelChoosesTheSolver) {
  // model: 3d no longer refused: the default factory is makeSolver3D.
  LockstepDriver d(problem3d(), kDt);
  EXPECT_TRUE(d.threeD());
  EXPECT_NEAR(d.staticTopX(), kTopX, kHeldAt);
  EXPECT_NEAR(d.staticTopY(), 0.0, kHeldAt);
  EXPECT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).outcome, O::Started);
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ + 0.01).outcome, O::Advanced);
  // The adapters refuse the other model with a message naming it.
  try {
    ros_bridge::makeSolver2D()(problem3d());
    ADD_FAILURE() << "makeSolver2D accepted model: 3d";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("model = 3d"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ros_bridge::makeSolver3D()(problem(core::Formulation::TwoD)), std::invalid_argument);
}

TEST(Lockstep3D, SwayMovesTheTopInY) {
  LockstepDriver d(problem3d(), kDt);
  constexpr double kSway = 0.5;  // [m] amplitude, period 2 s
  ASSERT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).outcome, O::Started);
  double worst_lag = 0.0;
  for (int k = 1; k <= 10; ++k) {  // a half period: y goes 0 -> 0.5 -> 0
    const double t = kDt * k, y = kSway * std::sin(kPi * t);
    const auto r = d.onSample(t, kTopX, y, kTopZ);
    ASSERT_EQ(r.outcome, O::Advanced) << "k = " << k << ": " << r.message;
    worst_lag = std::max(worst_lag, std::abs(d.state().nodes.back().y - y));
    if (k == 5) {
      // At the crest the platform pulls the line toward +y, the line pulls the anchor toward +y,
      // and the line lies between the anchor's plane and the top.
      const core::StaticResult& s = d.state();
      EXPECT_GT(s.nodes.back().y, (1.0 - kFollowFraction) * kSway);
      EXPECT_GT(s.top_force_y, 0.0);
      EXPECT_GT(s.anchor_force_y, 0.0);
      for (const core::NodeState& n : s.nodes) {
        EXPECT_GE(n.y, -kHeldAt) << "s = " << n.s;
        EXPECT_LE(n.y, s.nodes.back().y + kHeldAt) << "s = " << n.s;
      }
      EXPECT_GT(s.nodes[s.nodes.size() / 2].y, 0.0) << "the middle of the line did not move in y";
    }
  }
  EXPECT_LT(worst_lag, kFollowFraction * kSway);
  RecordProperty("worst_y_lag_m", std::to_string(worst_lag));
}

TEST(Lockstep3D, PlanarTrackAgreesWith2D) {
  LockstepDriver d2(problem(core::Formulation::TwoD), kDt), d3(problem3d(), kDt);
  double worst = 0.0, moved = 0.0, t_start = 0.0;
  for (int k = 0; k <= 10; ++k) {
    const double t = kDt * k, x = kTopX - 0.2 * std::sin(kPi * t);
    const auto r2 = d2.onSample(t, x, 0.0, kTopZ), r3 = d3.onSample(t, x, 0.0, kTopZ);
    ASSERT_TRUE(r2.publish && r3.publish) << r2.message << " / " << r3.message;
    const double t2 = d2.state().nodes.back().tension, t3 = d3.state().nodes.back().tension;
    if (k == 0) t_start = t2;
    worst = std::max(worst, std::abs(t3 - t2) / std::abs(t2));
    moved = std::max(moved, std::abs(t2 - t_start) / std::abs(t_start));
    EXPECT_NEAR(d3.state().nodes.back().y, 0.0, kHeldAt);
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
  EXPECT_LT(worst, kPlanarAgreement);
  EXPECT_GT(moved, 10.0 * kPlanarAgreement) << "the surge does not change the tension: the comparison is empty";
}

TEST(Lockstep3D, PolicyIn3DDistances) {
  LockstepDriver d(problem3d(), kDt);
  // First sample 1 m off in y (> start_tolerance 0.01 m): statics re-solved with the top there.
  const auto s = d.onSample(0.0, kTopX, 1.0, kTopZ);
  ASSERT_EQ(s.outcome, O::Started) << s.message;
  EXPECT_NE(s.message.find("(100, 1, 0) m"), std::string::npos) << s.message;
  EXPECT_NEAR(d.state().nodes.back().y, 1.0, kHeldAt);
  EXPECT_EQ(d.onSample(0.1, kTopX, 1.0, kTopZ).outcome, O::Advanced);
  // A jump along y only: 20 m in 0.1 s = 200 m/s > max_speed: dropped, named in 3-D.
  const auto j = d.onSample(0.2, kTopX, 21.0, kTopZ);
  EXPECT_EQ(j.outcome, O::Dropped);
  EXPECT_NE(j.message.find("to (100, 21, 0) m in 0.1 s: 200 m/s"), std::string::npos) << j.message;
  // NaN in y: dropped, state kept.
  const double t_before = d.solverTime();
  const auto n = d.onSample(0.3, kTopX, std::nan(""), kTopZ);
  EXPECT_EQ(n.outcome, O::Dropped);
  EXPECT_NE(n.message.find("non-finite"), std::string::npos) << n.message;
  EXPECT_DOUBLE_EQ(d.solverTime(), t_before);
  // reinitialiseAt and reset keep y.
  const auto r = d.reinitialiseAt(kTopX - 1.0, -2.0, kTopZ, "test");
  ASSERT_TRUE(r.publish) << r.message;
  EXPECT_NEAR(d.state().nodes.back().y, -2.0, kHeldAt);
  EXPECT_EQ(d.onSample(0.4, kTopX - 1.0, -2.0, kTopZ).outcome, O::Advanced);
  ASSERT_TRUE(d.reset().publish);
  EXPECT_NEAR(d.state().nodes.back().y, -2.0, kHeldAt);
}

TEST(Lockstep2D, OutOfPlaneSampleRejected) {
  LockstepDriver d(problem(core::Formulation::TwoD), kDt);
  EXPECT_FALSE(d.threeD());
  // Before the start: not started from an out-of-plane sample.
  const auto first = d.onSample(0.0, kTopX, 0.5, kTopZ);
  EXPECT_EQ(first.outcome, O::Dropped);
  EXPECT_FALSE(d.started());
  EXPECT_NE(first.message.find("y = 0.5 m: the problem is model: 2d"), std::string::npos) << first.message;
  EXPECT_NE(first.message.find("model: 3d"), std::string::npos) << first.message;
  ASSERT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).outcome, O::Started);
  ASSERT_EQ(d.onSample(0.2, kTopX, 0.0, kTopZ + 0.01).outcome, O::Advanced);
  // Running: dropped, state kept (time and top unchanged).
  const core::StaticResult before = d.state();
  const auto r = d.onSample(0.3, kTopX, -0.2, kTopZ);
  EXPECT_EQ(r.outcome, O::Dropped);
  EXPECT_FALSE(r.publish);
  EXPECT_NE(r.message.find("y = -0.2 m"), std::string::npos) << r.message;
  EXPECT_NEAR(d.solverTime(), 0.1, 1e-12);
  EXPECT_EQ(d.state().nodes.back().z, before.nodes.back().z);
  EXPECT_EQ(d.lastTime(), 0.2);
  // Within kPlanarTolerance (tf rounding): taken as y = 0 and advanced.
  const auto ok = d.onSample(0.3, kTopX, 0.5 * ros_bridge::kPlanarTolerance, kTopZ);
  EXPECT_EQ(ok.outcome, O::Advanced) << ok.message;
  EXPECT_EQ(d.state().nodes.back().y, 0.0);
  // A re-initialisation off the plane is refused the same way, the run goes on.
  const auto re = d.reinitialiseAt(kTopX, 1.0, kTopZ, "test");
  EXPECT_FALSE(re.publish);
  EXPECT_TRUE(d.started());
  EXPECT_NE(re.message.find("y = 1 m"), std::string::npos) << re.message;
  EXPECT_EQ(d.onSample(0.4, kTopX, 0.0, kTopZ).outcome, O::Advanced);
}

TEST(Converter, SolveStaticYDependsOnTheModel) {
  core::TopBoundary def;
  def.type = core::TopBoundary::Type::Position;
  def.x = kTopX;
  mooring_dynamics::SolveStatic::Request req;
  req.mode = mooring_dynamics::SolveStatic::Request::TOP_POSITION;
  req.top_position.x = 90.0;
  req.top_position.y = 5.0;
  req.top_position.z = -1.0;
  auto t2 = ros_bridge::topBoundaryFromRequest(req, def, core::Formulation::TwoD);
  EXPECT_FALSE(t2.ok);
  EXPECT_NE(t2.error.find("top_position.y = 5: must be 0; the problem is model: 2d"), std::string::npos) << t2.error;
  auto t3 = ros_bridge::topBoundaryFromRequest(req, def, core::Formulation::ThreeD);
  ASSERT_TRUE(t3.ok) << t3.error;
  EXPECT_EQ(t3.top.y, 5.0);
  EXPECT_EQ(t3.summary, "top position (x, y, z) = (90, 5, -1) m");
  req.mode = mooring_dynamics::SolveStatic::Request::TOP_FORCE;
  req.top_force.x = 1000.0;
  req.top_force.y = -200.0;
  req.top_force.z = 3000.0;
  t3 = ros_bridge::topBoundaryFromRequest(req, def, core::Formulation::ThreeD);
  ASSERT_TRUE(t3.ok) << t3.error;
  EXPECT_EQ(t3.top.fy, -200.0);
  req.top_force.y = std::nan("");
  t3 = ros_bridge::topBoundaryFromRequest(req, def, core::Formulation::ThreeD);
  EXPECT_FALSE(t3.ok);
  EXPECT_EQ(t3.error, "top_force.y = nan: must be finite");
}

TEST(Markers, FollowTheLineInY) {
  // A 3-D state with the top at y = 6 (anchor at y = 0): the cable keeps its y, seabed and sea
  // surface are centred on the line's mid y and cover its y extent.
  LockstepDriver d(problem3d(), kDt);
  ASSERT_TRUE(d.onSample(0.0, kTopX - 5.0, 6.0, kTopZ).publish);
  const CableState cs = ros_bridge::toCableState(d.state(), "t", "world", ros::Time(1.0));
  EXPECT_NEAR(cs.positions.back().y, 6.0, kHeldAt);
  EXPECT_DOUBLE_EQ(cs.top_force.y, d.state().top_force_y);
  const double y_mid = 0.5 * (cs.positions.front().y + cs.positions.back().y);
  const auto arr = ros_bridge::makeMarkers(cs, problem3d().environment, ros_bridge::MarkerOptions());
  bool seen_cable = false, seen_bed = false;
  for (const auto& m : arr.markers) {
    if (m.ns == "cable") {
      seen_cable = true;
      EXPECT_NEAR(m.points.back().y, 6.0, kHeldAt);
    }
    if (m.ns == "seabed" || m.ns == "sea_surface") {
      seen_bed = seen_bed || m.ns == "seabed";
      EXPECT_NEAR(m.pose.position.y, y_mid, 1e-9) << m.ns;
      EXPECT_GT(m.scale.y, 6.0) << m.ns;
    }
  }
  EXPECT_TRUE(seen_cable && seen_bed);
}

// A towed line (free_end, top.tow_velocity) in lockstep starts from the steady tow: samples on
// that velocity keep it steady (paper section 7.1: the steady tow is a steady state of the dynamic
// equations), so the top tension stays at the static steady-tow value. The same samples on a
// line started at rest (no tow_velocity) jerk it into motion: the tension departs by far more.
TEST(Lockstep3D, TowStartsFromTheSteadyTow) {
  core::Problem p = core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/test/data/gnss_tow.yaml");
  const double v = p.top.tow_vx;
  ASSERT_GT(v, 0.0);
  ASSERT_EQ(p.top.tow_vy, 0.0);
  // The steady tow, followed at 5 Hz for 20 s: measured 2.3e-6 relative drift of the top tension;
  // the generalized-alpha steps of a steady state change it only by the solver's tolerances.
  constexpr double kSteady = 1e-4;
  constexpr double kStep = 0.2;  // [s] sample spacing
  auto run = [&](const core::Problem& prob, double& t_static) {
    LockstepDriver d(prob, 0.5);
    double worst = 0.0;
    for (int k = 0; k <= 100; ++k) {
      const double t = kStep * k;
      const auto r = d.onSample(t, d.staticTopX() + v * t, d.staticTopY(), d.staticTopZ());
      EXPECT_TRUE(r.publish) << "k = " << k << ": " << r.message;
      const double tension = d.state().nodes.back().tension;
      if (k == 0) t_static = tension;
      worst = std::max(worst, std::abs(tension - t_static) / t_static);
    }
    return worst;
  };
  double steady_tension = 0.0, rest_tension = 0.0;
  const double steady = run(p, steady_tension);
  core::Problem rest = p;
  rest.top.tow_vx = 0.0;
  const double jerked = run(rest, rest_tension);
  std::printf("steady tow: %.3g N, worst drift %.3g; started at rest: %.3g N, worst departure %.3g\n", steady_tension,
              steady, rest_tension, jerked);
  EXPECT_LT(steady, kSteady);
  EXPECT_GT(jerked, 100.0 * kSteady) << "a tow started at rest should not look steady";
  EXPECT_GT(steady_tension, rest_tension) << "the steady tow's drag adds to the hanging weight";
}
