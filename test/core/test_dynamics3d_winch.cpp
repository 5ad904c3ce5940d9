// The winch of the 3-D dynamic solver (dynamics3d_winch.cpp; docs/method.md "Winch") against
// independent answers: an instrument lowered and hauled in at a constant rate carries the closed
// form of a slender vertical line (weights less or plus the drags of the motion), a line at rest
// after the winch stops weighs w L of the new length (mass conserved through the added and
// removed nodes), a catenary paid out or hauled in settles on the static solution of its new
// length, and the commands stop at their limits or refuse what is outside them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"

using namespace mooring_dynamics::core;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.141592653589793;

// Steady lowering: the closed form leaves out the stretch's sqrt(1 + eps) on the line's drag
// (eps ~ 1e-4 here) and the drag's speed floors; measured 1.4e-5 of the top tension.
constexpr double kLoweringRelTol = 1e-3;
// At rest the top carries the clump and the line's wet weight w L: the line's mass is that of
// its length, whatever nodes were added and taken out. The static balance, to the Newton
// tolerance; the still-ringing line adds ~1e-5 (measured).
constexpr double kRestRelTol = 1e-4;
// Mesh bookkeeping: the intervals below the top keep the spacing to rounding.
constexpr double kSpacingTol = 1e-9;  // [m]
// A length read back: sums and differences of the program's round values, to rounding.
constexpr double kLengthTol = 1e-9;  // [m]
// The program's rate read back (a difference of lengths over a time), to rounding.
constexpr double kRateTol = 1e-12;  // [m/s]
// A run stopped at a limit: the last step lands on it up to the rounding of t_end - t.
constexpr double kStopTol = 1e-6;  // [m]
// Settling on the static shape: the line still sways after the winch's stop (a lightly damped
// mode in still water): 8 mm at 100 s, 4 mm at 200 s after a 10 m payout (measured). 1.5 cm
// still catches a top that drifted (2.6 cm without the position feedback).
constexpr double kShapeTol = 0.015;        // [m]
constexpr double kShapeTensionRelTol = 1e-3;

/// An instrument (a clump on a free lower end) hanging from a winch at the surface on a tether
/// of 50 m (spacing 5 m), lowered by `winch`.
std::string lowering(const std::string& winch, double duration) {
  return "model: 3d\n"
         "environment: {water_density: 1025, depth: 1000}\n"
         "materials: {tether: {EA: 2.0e7, EI: 5, GJ: 5, mass: 1.0, added_mass: 0.3, wet_weight: 7.0,"
         " diameter: 0.02, cdn: 1.5, cdt: 0.05}}\n"
         "bodies: {instrument: {mass: 200, added_mass: 100, wet_weight: 1500, diameter: 0.8, cd: 1.0}}\n"
         "line: [{material: tether, length: 50, spacing: 5}]\n"
         "free_end: {body: instrument}\n"
         "top: {position: {x: 0, y: 0, z: 0}}\n"
         "dynamics: {duration: " +
         std::to_string(duration) + ", dt: 0.5, lambda_inf: -0.5, winch: " + winch + "}\n";
}

/// Top tension of the vertical line of lowering() of length L moving down at v [m/s] in steady
/// state: w L + W - (D_body + D_line) sign(v), D = 1/2 rho Cd A v^2 (the instrument's sphere of
/// diameter 0.8 m, the tether's tangential drag 1/2 rho pi d Cdt per metre).
double loweringTension(double L, double v) {
  const double rho = 1025.0;
  const double body = 0.5 * rho * 1.0 * 0.25 * kPi * 0.8 * 0.8;
  const double line = 0.5 * rho * kPi * 0.02 * 0.05;
  return 7.0 * L + 1500.0 - (body + line * L) * v * std::abs(v);
}

/// The intervals below the top interval have the top segment's spacing h0, the top one is
/// within [0.5, 1.5] h0 (the split and merge thresholds) and they add up to the line's length.
void expectWinchMesh(const DynamicSolver3D& s, double h0) {
  const std::vector<double> nodes = s.nodeArclengths();
  for (std::size_t j = 1; j + 1 < nodes.size(); ++j) EXPECT_NEAR(nodes[j] - nodes[j - 1], h0, kSpacingTol) << j;
  const double top = nodes.back() - nodes[nodes.size() - 2];
  EXPECT_GE(top, 0.5 * h0 - kSpacingTol);
  EXPECT_LE(top, 1.5 * h0 + kSpacingTol);
  EXPECT_NEAR(nodes.back(), s.lineLength(), kSpacingTol);
}

TEST(Winch, LoweredAndHauledInAtAConstantRateCarriesTheClosedForm) {
  // 50 -> 150 m at 1 m/s, held 10 s, hauled in to 60 m at 1 m/s, held 40 s.
  const Problem p =
      loadProblemFromString(lowering("{table: [[0, 50], [100, 150], [110, 150], [200, 60]], max_length: 200}", 240));
  DynamicSolver3D s(p);
  ASSERT_TRUE(s.hasWinch());
  double worst_out = 0.0, worst_in = 0.0;
  for (double t = 2.0; t <= 240.0 + 1e-9; t += 2.0) {
    const StepReport r = s.advanceTo(t);
    ASSERT_TRUE(r.ok) << r.message;
    const StaticResult now = s.snapshot();
    const double L = s.lineLength();
    // Away from the rate's jumps (the line's elastic and the clump's transients die in ~20 s).
    if (t >= 40.0 && t <= 100.0) {
      EXPECT_NEAR(L, 50.0 + t, kLengthTol);
      worst_out = std::max(worst_out, std::abs(now.nodes.back().tension / loweringTension(L, 1.0) - 1.0));
    }
    if (t >= 140.0 && t <= 200.0) {
      EXPECT_NEAR(L, 150.0 - (t - 110.0), kLengthTol);
      worst_in = std::max(worst_in, std::abs(now.nodes.back().tension / loweringTension(L, -1.0) - 1.0));
    }
    expectWinchMesh(s, 5.0);
  }
  EXPECT_LT(worst_out, kLoweringRelTol);
  EXPECT_LT(worst_in, kLoweringRelTol);
  // At rest: the top holds the clump and w L of the 60 m left, the clump its wet weight.
  const StaticResult rest = s.snapshot();
  EXPECT_NEAR(s.lineLength(), 60.0, kLengthTol);
  EXPECT_NEAR(rest.nodes.back().tension, 7.0 * 60.0 + 1500.0, kRestRelTol * (7.0 * 60.0 + 1500.0));
  EXPECT_NEAR(rest.nodes.back().tension - rest.nodes.front().tension, 7.0 * 60.0, kRestRelTol * 1920.0);
  EXPECT_NEAR(s.winchRate(), 0.0, kRateTol);
}

/// A suspended rope from a mid-water anchor to a fixed top: 85 m (spacing 1 m) or `L0`.
std::string catenary(double L0, const std::string& winch) {
  return "model: 3d\n"
         "environment: {depth: 100}\n"
         "materials: {rope: {EA: 1.0e7, EI: 10, GJ: 10, mass: 10, added_mass: 3, wet_weight: 80, diameter: 0.05,"
         " cdn: 1.5, cdt: 0.05}}\n"
         "line: [{material: rope, length: " +
         std::to_string(L0) +
         ", spacing: 1}]\n"
         "anchor: {x: 0, y: 0, z: -50}\n"
         "top: {position: {x: 60, y: 0, z: 0}}\n"
         "dynamics: {duration: 150, dt: 0.2, lambda_inf: -0.5" +
         (winch.empty() ? std::string() : ", winch: " + winch) + "}\n";
}

void expectSettlesOnStatics(double L0, double L1) {
  const Problem p = loadProblemFromString(
      catenary(L0, "{table: [[0, " + std::to_string(L0) + "], [20, " + std::to_string(L1) + "]]}"));
  DynamicSolver3D s(p);
  const StepReport r = s.advanceTo(150.0);
  ASSERT_TRUE(r.ok) << r.message;
  const StaticResult want = solveStatic3D(loadProblemFromString(catenary(L1, "")));
  ASSERT_TRUE(want.summary.converged);
  const StaticResult got = s.snapshot();
  ASSERT_EQ(got.nodes.size(), want.nodes.size());  // the paid-out line has the static line's mesh
  double worst = 0.0;
  for (std::size_t j = 0; j < got.nodes.size(); ++j) {
    EXPECT_NEAR(got.nodes[j].s, want.nodes[j].s, kSpacingTol);
    worst = std::max(worst, std::hypot(got.nodes[j].x - want.nodes[j].x, got.nodes[j].z - want.nodes[j].z));
  }
  EXPECT_LT(worst, kShapeTol) << L0 << " -> " << L1;
  EXPECT_NEAR(got.nodes.back().tension, want.nodes.back().tension, kShapeTensionRelTol * want.nodes.back().tension);
}

TEST(Winch, PaidOutCatenarySettlesOnTheStaticShapeOfTheLongerLine) { expectSettlesOnStatics(85.0, 95.0); }
TEST(Winch, HauledInCatenarySettlesOnTheStaticShapeOfTheShorterLine) { expectSettlesOnStatics(95.0, 85.0); }

TEST(Winch, PlanarProblemRunsOnTheThreeDimensionalEquations) {
  std::string yaml = catenary(85.0, "{table: [[0, 85], [20, 95]]}");
  auto swap = [&yaml](const std::string& from, const std::string& to) { yaml.replace(yaml.find(from), from.size(), to); };
  swap("model: 3d", "model: 2d");
  swap("anchor: {x: 0, y: 0, z: -50}", "anchor: {x: 0, z: -50}");
  swap("position: {x: 60, y: 0, z: 0}", "position: {x: 60, z: 0}");
  swap("EI: 10, GJ: 10,", "EI: 10,");
  swap("duration: 150", "duration: 30");
  const Problem p = loadProblemFromString(yaml);
  ASSERT_EQ(p.formulation, Formulation::TwoD);
  const DynamicSeries r = runDynamicModel(p);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_EQ(r.line_length.size(), r.t.size());
  EXPECT_NEAR(r.line_length.front(), 85.0, kLengthTol);
  EXPECT_NEAR(r.line_length.back(), 95.0, kLengthTol);
  // In its plane: nothing moves it off but the rounding of the frames' rotations (5.5e-12 m measured).
  constexpr double kPlaneTol = 1e-9;  // [m]
  for (double y : r.top_y) EXPECT_NEAR(y, 0.0, kPlaneTol);
  // The 2-D solver itself refuses the winch rather than ignore it.
  try {
    DynamicSolver2D two(p);
    ADD_FAILURE() << "the 2-D solver took a winch";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dynamics.winch: the 2-D solver's mesh is fixed"), std::string::npos) << e.what();
  }
}

TEST(Winch, CommandsStopAtTheirTargetOrLimitAndRefuseWhatIsOutside) {
  const Problem p = loadProblemFromString(lowering("{rate: 0.5, max_length: 60}", 20));
  DynamicSolver3D s(p);
  // A rate until the limit: 0.5 m/s stops at max_length 60 m, 20 s from now.
  const std::string note = s.commandWinch(0.5, kNaN);
  EXPECT_NE(note.find("stops at max_length 60 m at t = 20 s"), std::string::npos) << note;
  ASSERT_TRUE(s.advanceTo(30.0).ok);
  EXPECT_NEAR(s.lineLength(), 60.0, kLengthTol);
  EXPECT_EQ(s.winchRate(), 0.0);
  // To a target at a speed; haul-in to the top segment's shortest is refused below it.
  EXPECT_NE(s.commandWinch(-1.0, 55.0).find("there at t = 35 s"), std::string::npos);
  EXPECT_NEAR(s.winchRate(), -1.0, kRateTol);
  ASSERT_TRUE(s.advanceTo(40.0).ok);
  EXPECT_NEAR(s.lineLength(), 55.0, kLengthTol);
  EXPECT_THROW(s.commandWinch(1.0, 61.0), std::invalid_argument);  // above max_length
  EXPECT_THROW(s.commandWinch(1.0, 2.0), std::invalid_argument);   // below the shortest top segment
  EXPECT_THROW(s.commandWinch(kNaN, kNaN), std::invalid_argument);
  EXPECT_THROW(s.commandWinch(0.0, 50.0), std::invalid_argument);  // a target needs a speed
  EXPECT_NEAR(s.lineLength(), 55.0, kLengthTol);                        // nothing changed
  try {
    s.commandWinch(1.0, 61.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("target length = 61 m: outside [2.5, 60] m"), std::string::npos) << e.what();
  }
  s.releaseEnd(LineEvent::End::Top, "test");
  EXPECT_THROW(s.commandWinch(0.5, kNaN), std::invalid_argument);  // off the winch
}

TEST(Winch, SaveAndRestoreUndoAddedNodes) {
  const Problem p = loadProblemFromString(lowering("{rate: 1.0}", 100));
  DynamicSolver3D s(p);
  ASSERT_TRUE(s.advanceTo(3.0).ok);
  const auto saved = s.save();
  const std::size_t before = s.nodeArclengths().size();
  ASSERT_TRUE(s.advanceTo(12.0).ok);  // 9 m more: nodes added
  const StaticResult first = s.snapshot();
  ASSERT_GT(first.nodes.size(), before);
  s.restore(*saved);
  EXPECT_EQ(s.nodeArclengths().size(), before);
  EXPECT_NEAR(s.lineLength(), 53.0, kLengthTol);
  ASSERT_TRUE(s.advanceTo(12.0).ok);
  const StaticResult again = s.snapshot();
  ASSERT_EQ(again.nodes.size(), first.nodes.size());
  for (std::size_t j = 0; j < first.nodes.size(); ++j) {
    EXPECT_EQ(again.nodes[j].x, first.nodes[j].x);
    EXPECT_EQ(again.nodes[j].z, first.nodes[j].z);
    EXPECT_EQ(again.nodes[j].tension, first.nodes[j].tension);
  }
}

// A state saved before any winch program, restored after a command added nodes: the mesh, the
// program and the length go back with the state (the line as it was, no winch running).
TEST(Winch, RestoreToBeforeTheFirstCommandUndoesIt) {
  Problem p = loadProblemFromString(lowering("{rate: 1.0}", 100));
  p.dynamics.winch = Winch();  // no program in the file: the winch waits for a command
  DynamicSolver3D s(p);
  ASSERT_TRUE(s.advanceTo(2.0).ok);
  const auto saved = s.save();
  const StaticResult before = s.snapshot();
  s.commandWinch(1.0, kNaN);
  ASSERT_TRUE(s.advanceTo(14.0).ok);
  ASSERT_GT(s.nodeArclengths().size(), before.nodes.size());
  s.restore(*saved);
  EXPECT_NEAR(s.lineLength(), 50.0, kLengthTol);
  EXPECT_EQ(s.winchRate(), 0.0);
  const StaticResult after = s.snapshot();
  ASSERT_EQ(after.nodes.size(), before.nodes.size());
  for (std::size_t j = 0; j < before.nodes.size(); ++j) EXPECT_EQ(after.nodes[j].tension, before.nodes[j].tension);
  ASSERT_TRUE(s.advanceTo(14.0).ok);  // held: the line as at the start
  EXPECT_NEAR(s.lineLength(), 50.0, kLengthTol);
  EXPECT_EQ(s.nodeArclengths().size(), before.nodes.size());
}

TEST(Winch, AProgramPastItsLimitStopsTheRunAndSaysWhy) {
  // The file's checks cover [0, duration]; a run driven past it (a lockstep node) stops there.
  const Problem p = loadProblemFromString(lowering("{rate: 1.0, max_length: 70}", 20));
  DynamicSolver3D s(p);
  ASSERT_TRUE(s.advanceTo(20.0).ok);
  const StepReport r = s.advanceTo(25.0);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("passes max_length = 70 m"), std::string::npos) << r.message;
  EXPECT_NEAR(s.time(), 20.0, kLengthTol);  // [s] as exact
  EXPECT_NEAR(s.lineLength(), 70.0, kStopTol);
}

}  // namespace

namespace {
// Two threads split the line at the Newton matrix's meeting node, which moves as nodes come and
// go: the results are the same bits as on one thread (docs/performance.md, threads).
TEST(Winch, SameBitsOnOneAndTwoThreads) {
  const std::string yaml = lowering("{table: [[0, 50], [30, 80], [60, 55]]}", 60);
  Problem one = loadProblemFromString(yaml), two = one;
  two.dynamics.threads = 2;
  const DynamicSeries a = runDynamic3D(one), b = runDynamic3D(two);
  ASSERT_TRUE(a.completed && b.completed) << a.message << b.message;
  ASSERT_EQ(a.t.size(), b.t.size());
  for (std::size_t k = 0; k < a.t.size(); ++k) {
    EXPECT_EQ(a.top_tension[k], b.top_tension[k]) << a.t[k];
    EXPECT_EQ(a.anchor_tension[k], b.anchor_tension[k]) << a.t[k];
    EXPECT_EQ(a.line_length[k], b.line_length[k]) << a.t[k];
  }
}
}  // namespace
