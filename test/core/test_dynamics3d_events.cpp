// The 3-D solver's line events (src/core/solvers/dynamics3d_events.cpp, issue 21) against
// independent answers: a rope let go at its top or parted in the middle unloads at the elastic
// wave speed sqrt(EA / m); a break on tension happens at the first step over the limit, at the
// largest tension, the run before it bit-identical to the whole run; the step Jacobian of a
// parted, let-go line against finite differences; a saved state before an event undoes it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "dynamics3d_test_util.hpp"

using namespace mooring_dynamics::core;
using mooring_dynamics::core::testing_util::chainMooring;

namespace {
// Exact step Jacobian (AutoDiff) against central differences, as test_dynamics3d.
constexpr double kJacobianTol = 1e-5;
}  // namespace

namespace {

// A taut vertical rope, anchor 100 m down, its 99 m stretched to the surface (strain 1/99):
// EA = 1e6 N and m = 1 kg/m (no added mass, no drag), so the axial wave runs at c = sqrt(EA/m)
// = 1000 m/s along the unstretched length.
Problem tautRope() {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 100.0;
  Material m;
  m.name = "rope";
  m.EA = 1.0e6;
  m.EI = 0.1;
  m.GJ = 0.1;
  m.mass = 1.0;
  m.wet_weight = 1.0;
  m.diameter = 0.02;
  m.cdn = 0.0;
  m.cdt = 0.0;
  p.materials.push_back(m);
  Segment s;
  s.length = 99.0;
  s.spacing = 0.5;
  p.segments.push_back(s);
  p.anchor_z = -100.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.z = 0.0;
  // One cell's wave transit, 0.5 m / 1000 m/s: Courant number 1, where the box scheme carries a
  // front without the dispersive ripples it has at smaller steps (at 2.5e-4 s they run ahead of
  // the front and reach the anchor 60 ms early, up to 60 % of T0; docs/validation.md).
  p.dynamics.dt = 5.0e-4;
  p.dynamics.duration = 0.1;
  return p;
}

/// Time the series v (on times t) first falls below `level` after t0, linear in between [s].
double firstCrossingBelow(const std::vector<double>& t, const std::vector<double>& v, double level, double t0) {
  for (std::size_t k = 1; k < t.size(); ++k)
    if (t[k] > t0 && v[k - 1] >= level && v[k] < level) return t[k - 1] + (v[k - 1] - level) / (v[k - 1] - v[k]) * (t[k] - t[k - 1]);
  return -1.0;
}

}  // namespace

TEST(Dynamics3D, RopeLetGoAtTheTopUnloadsAtTheElasticWaveSpeed) {
  // Released at t_r, the top end carries no force; the unloading front runs down the 99 m of
  // rope at c = sqrt(EA / m) and reaches the anchor at t_r + L / c = t_r + 0.099 s. The anchor
  // tension crosses the midpoint between before (T0) and after (about 0: the front unloads
  // the strain; only the weight of the rope, 99 N, is left behind it) at the front's arrival.
  constexpr double kRelease = 0.001;                // [s]
  constexpr double kArrival = kRelease + 99.0 / 1000.0;
  // Generalized-alpha (lambda_inf = -0.5) damps the front's highest wavenumbers and smears it
  // over a few cells; its midpoint arrives within 1 % of the travel time (measured 0.14 % early),
  // and a wave speed wrong by sqrt(2) (EA / m off by 2) misses by 29 %.
  constexpr double kArrivalRelTol = 0.01;
  Problem p = tautRope();
  // Until just after the front arrives: reflected at the anchor, the unloading turns the rope
  // into compression, and a rope of EI = 0.1 N m2 buckles (the solver stops there).
  p.dynamics.duration = kArrival + 0.003;
  // The front arrives unannounced: before it, the anchor tension has not moved (no precursor).
  constexpr double kQuietBeforeFront = 1e-3;  // [N] of 1e4 N
  LineEvent e;
  e.type = LineEvent::Type::Release;
  e.end = LineEvent::End::Top;
  e.t = kRelease;
  p.dynamics.events = {e};
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  const double T0 = r.anchor_tension.front();
  EXPECT_NEAR(T0, 1.0e6 / 99.0 - 0.5 * 99.0, 1e-3) << "EA * mean strain less half the rope's weight";
  const double arrival = firstCrossingBelow(r.t, r.anchor_tension, 0.5 * T0, kRelease);
  std::printf("let-go rope: anchor tension %.1f N halves at t = %.5f s (front expected at %.5f s)\n", T0, arrival,
              kArrival);
  EXPECT_NEAR(arrival - kRelease, kArrival - kRelease, kArrivalRelTol * (kArrival - kRelease));
  for (std::size_t k = 0; k < r.t.size(); ++k)
    if (r.t[k] < kArrival - 0.1 * (kArrival - kRelease)) {
      EXPECT_NEAR(r.anchor_tension[k], T0, kQuietBeforeFront) << r.t[k];
    }
  // The top is free from the release on.
  for (std::size_t k = 0; k < r.t.size(); ++k)
    if (r.t[k] > kRelease + 1e-9) {
      EXPECT_NEAR(r.top_tension[k], 0.0, 1e-6 * T0) << "t = " << r.t[k];
    }
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].what, "released top");
  EXPECT_NEAR(r.events[0].t, kRelease, 1e-12);
}

TEST(Dynamics3D, ALinePartedInTheMiddleUnloadsBothWaysAtTheWaveSpeed) {
  // Parted at s = 49.5 m at t_b: two unloading fronts run from the cut, up and down, each
  // reaching its end after 49.5 m / c = 0.0495 s; the ends' tensions halve then.
  constexpr double kBreak = 0.001, kTravel = 49.5 / 1000.0;
  // Half the travel of the test above, the same smear in time: twice its tolerance.
  constexpr double kArrivalRelTol = 0.02;
  Problem p = tautRope();
  p.dynamics.duration = kBreak + kTravel + 0.003;  // until just after the fronts arrive (see above)
  LineEvent e;
  e.type = LineEvent::Type::Break;
  e.t = kBreak;
  e.s = 49.5;
  p.dynamics.events = {e};
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].what, "parted");
  EXPECT_NEAR(r.events[0].s, 49.5, 0.5) << "the cut is beside the node nearest to s";
  const double top = firstCrossingBelow(r.t, r.top_tension, 0.5 * r.top_tension.front(), kBreak);
  const double anchor = firstCrossingBelow(r.t, r.anchor_tension, 0.5 * r.anchor_tension.front(), kBreak);
  std::printf("parted rope: top halves after %.5f s, anchor after %.5f s (front: %.5f s)\n", top - kBreak,
              anchor - kBreak, kTravel);
  EXPECT_NEAR(top - kBreak, kTravel, kArrivalRelTol * kTravel);
  EXPECT_NEAR(anchor - kBreak, kTravel, kArrivalRelTol * kTravel);
}

TEST(Dynamics3D, ABreakOnTensionHappensAtTheFirstStepOverTheLimitAtTheLargestTension) {
  // The heaved chain mooring with a limit between its static and its peak top tension: it parts
  // at the top (the largest tension of a catenary), i.e. the top is let go, in the first step
  // whose tension is over the limit, and not before.
  Problem p = chainMooring();
  p.dynamics.tolerance = 1e-6;
  const DynamicSeries whole = runDynamic3D(p);
  ASSERT_TRUE(whole.completed) << whole.message;
  const double T0 = whole.top_tension.front();
  const double peak = *std::max_element(whole.top_tension.begin(), whole.top_tension.end());
  const double limit = 0.5 * (T0 + peak);
  double t_first = -1.0;
  for (std::size_t k = 0; k < whole.t.size() && t_first < 0.0; ++k)
    if (whole.top_tension[k] > limit) t_first = whole.t[k];
  ASSERT_GT(t_first, 0.0);
  LineEvent e;
  e.type = LineEvent::Type::Break;
  e.tension = limit;
  p.dynamics.events = {e};
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_EQ(r.events.size(), 1u) << r.message;
  EXPECT_EQ(r.events[0].what, "released top");
  // The output grid is the step grid (dt = 0.5 s): the break is at a sample time, the first over.
  EXPECT_NEAR(r.events[0].t, t_first, 1e-9);
  EXPECT_GT(r.events[0].tension, limit);
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    if (r.t[k] < t_first - 1e-9) {
      EXPECT_EQ(r.top_tension[k], whole.top_tension[k]) << "before the break: the same bits";
    }
    if (r.t[k] > t_first + 1e-9) {
      EXPECT_NEAR(r.top_tension[k], 0.0, 1e-6 * T0) << "after: a free top";
    }
  }
}

TEST(Dynamics3D, StepJacobianOfALinePartedAndLetGoMatchesFiniteDifferences) {
  // The rows of the released ends and of the parted interval (end_conditions.hpp) are exact.
  Problem p = chainMooring(0.7);
  p.anchor_z = -49.0;
  DynamicSolver3D solver(p);
  ASSERT_TRUE(solver.advanceTo(2.0).ok);
  solver.partAt(20, "test");
  EXPECT_LT(solver.jacobianFiniteDifferenceError(0.5), kJacobianTol);
  solver.releaseEnd(LineEvent::End::Anchor, "test");
  EXPECT_LT(solver.jacobianFiniteDifferenceError(0.5), kJacobianTol);
  solver.releaseEnd(LineEvent::End::Top, "test");
  EXPECT_LT(solver.jacobianFiniteDifferenceError(0.5), kJacobianTol);
  EXPECT_THROW(solver.releaseEnd(LineEvent::End::Top, "again"), std::logic_error);
  EXPECT_THROW(solver.partAt(10, "again"), std::logic_error);
  EXPECT_EQ(solver.eventLog().size(), 3u);
}

TEST(Dynamics3D, ASavedStateBeforeAnEventUndoesItOnRestore) {
  // A coupling re-runs a step from a saved state: the event must be undone with it, and the
  // re-run gives the same bits.
  Problem p = chainMooring();
  p.dynamics.tolerance = 1e-6;
  p.dynamics.dt = 0.05;
  DynamicSolver3D solver(p);
  ASSERT_TRUE(solver.advanceTo(1.0).ok);
  const auto saved = solver.save();
  // The anchor let go: the chain then hangs from its top (a chain let go at the top would fall
  // slack, its stiff elastic waves ringing in compression: the solver stops within 0.2 s).
  solver.releaseEnd(LineEvent::End::Anchor, "test");
  const StepReport rr = solver.advanceTo(1.2);
  ASSERT_TRUE(rr.ok) << rr.message;
  const double free_anchor = solver.snapshot().nodes.front().tension;
  solver.restore(*saved);
  EXPECT_TRUE(solver.eventLog().empty());
  ASSERT_TRUE(solver.advanceTo(1.2).ok);
  const double held_anchor = solver.snapshot().nodes.front().tension;
  EXPECT_NEAR(free_anchor, 0.0, 1e-6 * held_anchor);
  DynamicSolver3D fresh(p);  // the same calls (advanceTo lands on its end time exactly)
  ASSERT_TRUE(fresh.advanceTo(1.0).ok);
  ASSERT_TRUE(fresh.advanceTo(1.2).ok);
  EXPECT_EQ(held_anchor, fresh.snapshot().nodes.front().tension);
}
