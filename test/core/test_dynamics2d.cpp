// Dynamic solver (paper sections 2, 4, 5.2) against independent answers: the transverse and
// longitudinal natural frequencies of a taut string (wave equation; added mass acts across the
// line only); the measured order of accuracy in time of the generalized-alpha schemes on a cable
// against a fine-step reference; a prescribed top on its path; adaptive time stepping (4.3) and
// how a failure is reported; the step Jacobian; a sphere body's drag; a heaved rope's slack and
// snap. The start (dynamics2d_start.cpp: held moorings as fixed points, the top motions the 2-D
// solver takes or refuses, the thread count): test_dynamics2d_start.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "dynamics2d_test_util.hpp"

using namespace mooring_dynamics::core;

namespace {

// Natural frequencies: at 80 steps per period and 40 intervals the time step's phase error and
// the box scheme's dispersion ((k h)^2 / 12 ~ 5e-4) are a few 1e-3; the zero-crossing estimate
// scatters by +-0.5% with the pulse's harmonics. A missing or misplaced added mass (ratio
// sqrt(2) with ma = m below) is 41%.
constexpr double kFrequencyRelTol = 0.02;
// Measured order: least-squares slope over dt, dt/2, dt/4 against a dt/32 reference; the
// reference's own error biases a first-order slope by up to +0.07.
constexpr double kSecondOrderBand = 0.2;
constexpr double kFirstOrderBand = 0.2;
// Output grid: a prescribed top position is met to the Newton tolerance (scale 1 m, 1e-6).
// The velocity-driven top drifts from the integral of its prescribed velocity by an O(h^2) rate
// (see PrescribedTopPositionTracksThePath): 1.3 cm over this chain's 32 s at a 1 s base step.
constexpr double kGridPositionTol = 0.05;  // [m]

constexpr double kTwoPi = 6.283185307179586;

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Mean period of a sampled signal from its upward zero crossings (linear interpolation) after
/// t_start: (last - first crossing) / (number of crossings - 1). Exact for a periodic signal with
/// one upward crossing per period, whatever its harmonics.
double periodFromUpwardCrossings(const std::vector<double>& t, const std::vector<double>& y, double t_start,
                                 int* crossings) {
  std::vector<double> up;
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (t[k - 1] < t_start) continue;
    if (y[k - 1] < 0.0 && y[k] >= 0.0) up.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-y[k - 1]) / (y[k] - y[k - 1]));
  }
  *crossings = static_cast<int>(up.size());
  if (up.size() < 2) return 0.0;
  return (up.back() - up.front()) / static_cast<double>(up.size() - 1);
}

// --- Chain mooring in a current (dynamics2d_test_util.hpp) ---------------------------------------

Problem chainMooring(bool grounded) { return mooring_dynamics::core::testing_util::chainMooring2D(grounded); }

// --- Taut string ---------------------------------------------------------------------------------
// A weightless line without drag, stretched vertically between the anchor and a fixed top
// directly above it. Unstretched length L, strain eps: T = EA eps all along.
constexpr double kStringL = 20.0;         // [m] unstretched
constexpr int kStringIntervals = 40;
constexpr double kStringStrain = 0.01;    // [-]
constexpr double kStringEA = 1.0e5;       // [N]
constexpr double kStringMass = 1.0;       // [kg/m] per unstretched length
constexpr double kStringAddedMass = 1.0;  // [kg/m] per unstretched length, normal direction only

Problem tautString() {
  Problem p;
  p.name = "taut string";
  p.environment.depth = 200.0;  // the anchor floats 100 m above the seabed: no contact
  Material m;
  m.name = "string";
  m.EA = kStringEA;
  m.EI = 1.0e-2;  // bending against tension: EI (pi / L)^2 / T ~ 2.5e-7
  m.mass = kStringMass;
  m.added_mass = kStringAddedMass;
  m.wet_weight = 0.0;
  m.diameter = 0.02;
  m.cdn = 0.0;
  m.cdt = 0.0;
  p.materials.push_back(m);
  Segment s;
  s.material = 0;
  s.length = kStringL;
  s.spacing = kStringL / kStringIntervals;
  p.segments.push_back(s);
  p.anchor_x = 0.0;
  p.anchor_z = -100.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = 0.0;
  p.top.z = p.anchor_z + kStringL * (1.0 + kStringStrain);
  p.dynamics.scheme = GeneralizedAlpha::fromLambdaInf(-0.5);
  p.dynamics.record_s = {0.5 * kStringL};
  return p;
}

/// Top velocity pulse with no net displacement: up to `peak` at tau, down to -peak at 2 tau, back
/// to 0 at 3 tau, then held: the top is fixed again at its static position. With 3 tau = half the
/// period the line swings mostly in its first mode, one upward zero crossing per period.
std::vector<TopMotion::Row> zeroNetPulse(double tau, double peak, bool along_x) {
  auto row = [&](double t, double v) { return along_x ? TopMotion::Row{t, v, 0.0} : TopMotion::Row{t, 0.0, v}; };
  return {row(0.0, 0.0), row(tau, peak), row(2.0 * tau, -peak), row(3.0 * tau, 0.0)};
}

/// Runs the string for 10 periods P of the expected mode after the pulse and measures the
/// frequency of the mid-line displacement (x across, z along) [Hz].
double stringFrequency(double P, bool transverse, double peak, int& crossings) {
  Problem p = tautString();
  p.dynamics.dt = P / 80.0;
  p.dynamics.duration = 10.0 * P;
  p.dynamics.top_motion.type = TopMotion::Type::VelocityTable;
  p.dynamics.top_motion.table = zeroNetPulse(P / 6.0, peak, transverse);
  const DynamicSeries r = runDynamic(p);
  EXPECT_TRUE(r.completed) << r.message;
  if (!r.completed || r.node_x.size() != 1) return 0.0;
  std::vector<double> y = transverse ? r.node_x[0] : r.node_z[0];
  const double y0 = y.front();
  for (double& v : y) v -= y0;
  const double measured = periodFromUpwardCrossings(r.t, y, 0.5 * P, &crossings);
  return measured > 0.0 ? 1.0 / measured : 0.0;
}

// --- Short taut line for the order in time -------------------------------------------------------
// 10 m of rope in a 1 m/s current, 6 nodes, its top moved sideways by a 4 s sinusoid of 0.1 m,
// faded in over 1.5 s by a C-infinity ramp so that the start from rest (all rates zero) is
// consistent and no transient is excited: an abrupt start would by itself cut the order to one.

constexpr double kOrderL = 10.0;          // [m]
constexpr double kOrderAmplitude = 0.1;   // [m]
constexpr double kOrderPeriod = 4.0;      // [s]
constexpr double kOrderRamp = 1.5;        // [s]
constexpr double kOrderEnd = 3.3;         // [s]
constexpr double kOrderSample = 0.1;      // [s] errors are compared on this grid (and at the end)
constexpr double kOrderDt = 0.02;         // [s] coarsest step

Problem shortTautLine(const GeneralizedAlpha& scheme, double dt) {
  Problem p;
  p.name = "short taut line";
  p.environment.depth = 200.0;
  p.environment.current = {{0.0, 1.0, 0.0}, {200.0, 1.0, 0.0}};
  Material m;
  m.name = "rope";
  m.EA = 1.0e4;
  m.EI = 1.0;
  m.mass = 5.0;
  m.added_mass = 5.0;
  m.wet_weight = 10.0;
  m.diameter = 0.2;
  m.cdn = 1.2;
  m.cdt = 0.5;
  p.materials.push_back(m);
  Segment s;
  s.material = 0;
  s.length = kOrderL;
  s.spacing = 2.0;
  p.segments.push_back(s);
  p.anchor_x = 0.0;
  p.anchor_z = -100.0;
  p.top.type = TopBoundary::Type::Position;
  const double chord = 1.05 * kOrderL;  // ~5% strain
  p.top.x = 5.0;
  p.top.z = p.anchor_z + std::sqrt(chord * chord - 25.0);
  p.dynamics.scheme = scheme;
  p.dynamics.dt = dt;
  p.dynamics.duration = kOrderEnd;
  p.dynamics.tolerance = 1e-12;  // Newton error far below the time-discretization error
  p.dynamics.max_iterations = 60;
  return p;
}

/// Smooth 0 -> 1 ramp over [0, 1] with all derivatives zero at both ends, and its slope.
void smoothRamp(double q, double& r, double& dr) {
  auto psi = [](double s) { return s > 0.0 ? std::exp(-1.0 / s) : 0.0; };
  auto dpsi = [&](double s) { return s > 0.0 ? psi(s) / (s * s) : 0.0; };
  if (q <= 0.0) {
    r = dr = 0.0;
  } else if (q >= 1.0) {
    r = 1.0;
    dr = 0.0;
  } else {
    const double a = psi(q), b = psi(1.0 - q);
    r = a / (a + b);
    dr = (dpsi(q) * b + a * dpsi(1.0 - q)) / ((a + b) * (a + b));
  }
}

/// Top tension on the sample grid kOrderSample .. kOrderEnd.
std::vector<double> topTensionSeries(const GeneralizedAlpha& scheme, double dt) {
  DynamicSolver2D solver(shortTautLine(scheme, dt));
  const NodeState top0 = solver.initialStatic().nodes.back();
  const double w = kTwoPi / kOrderPeriod;
  solver.setTopInput([=](double t) {
    double r, dr;
    smoothRamp(t / kOrderRamp, r, dr);
    dr /= kOrderRamp;
    TopInput in;
    in.x = top0.x + kOrderAmplitude * r * std::sin(w * t);
    in.z = top0.z;
    in.vx = kOrderAmplitude * (dr * std::sin(w * t) + r * w * std::cos(w * t));
    in.vz = 0.0;
    return in;
  });
  std::vector<double> T;
  const int samples = static_cast<int>(std::lround(kOrderEnd / kOrderSample));
  for (int k = 1; k <= samples; ++k) {
    const StepReport rep = solver.advanceTo(k * kOrderSample);
    EXPECT_TRUE(rep.ok) << rep.message;
    EXPECT_EQ(rep.cuts, 0) << "dt = " << dt;  // the order is that of the base step only
    T.push_back(solver.snapshot().topTension());
  }
  return T;
}

struct MeasuredOrder {
  double at_end = 0.0;   ///< slope of the top tension error at t = kOrderEnd
  double max_norm = 0.0; ///< slope of the largest error over the samples
  std::vector<double> end_errors, max_errors;  ///< [N] for dt, dt/2, dt/4
};

/// Top tension with dt, dt/2, dt/4 against dt/32. The error of an oscillating response crosses
/// zero, so its value at one instant can be accidentally small; the largest error over the
/// samples is reported as well and both must show the order.
MeasuredOrder measureOrder(const GeneralizedAlpha& scheme) {
  const std::vector<double> ref = topTensionSeries(scheme, kOrderDt / 32.0);
  MeasuredOrder m;
  std::vector<double> logdt, logend, logmax;
  for (double h : {kOrderDt, kOrderDt / 2.0, kOrderDt / 4.0}) {
    const std::vector<double> T = topTensionSeries(scheme, h);
    double worst = 0.0;
    for (std::size_t k = 0; k < T.size() && k < ref.size(); ++k) worst = std::max(worst, std::abs(T[k] - ref[k]));
    const double end = std::abs(T.back() - ref.back());
    m.end_errors.push_back(end);
    m.max_errors.push_back(worst);
    logdt.push_back(std::log(h));
    logend.push_back(std::log(end));
    logmax.push_back(std::log(worst));
  }
  m.at_end = leastSquaresSlope(logdt, logend);
  m.max_norm = leastSquaresSlope(logdt, logmax);
  return m;
}

void printOrder(const char* name, const MeasuredOrder& m) {
  std::printf("%-12s order at t_end %.3f (errors %.2e %.2e %.2e N), max-norm %.3f (%.2e %.2e %.2e N)\n", name,
              m.at_end, m.end_errors[0], m.end_errors[1], m.end_errors[2], m.max_norm, m.max_errors[0],
              m.max_errors[1], m.max_errors[2]);
}

// --- Chain for adaptive time stepping ------------------------------------------------------------

/// The grounded chain, its top moved 1 m / 0.5 m over 16 s from rest, positions prescribed so
/// that every accepted step puts the top exactly on the motion; Newton allowed only 3 iterations
/// so that the 1 s base step fails and must be cut.
Problem cutChain() {
  Problem p = chainMooring(true);
  p.dynamics.dt = 1.0;
  p.dynamics.output_interval = 2.0;
  p.dynamics.duration = 32.0;
  p.dynamics.max_iterations = 3;
  TopMotion& tm = p.dynamics.top_motion;
  tm.type = TopMotion::Type::Sinusoid;
  tm.amplitude_x = 1.0;
  tm.amplitude_z = 0.5;
  tm.period = 16.0;
  tm.phase = -0.25 * kTwoPi;  // x = x0 + a (1 - cos(2 pi t / T)): starts at rest
  tm.prescribe_position = false;  // eq. 34: the top velocity
  return p;
}

}  // namespace

// --- Natural frequencies of a taut string --------------------------------------------------------

TEST(Dynamics2D, TautStringTransverseFrequencyUsesAddedMass) {
  // Across the line (eqs. 2, 4 with u = 0, Sn ~ 0): (m + ma) v_t = T phi_s, (1 + eps) phi_t = v_s,
  // a string with tension T and mass (m + ma) / (1 + eps) per stretched length L (1 + eps).
  const double T = kStringEA * kStringStrain;
  const double Ls = kStringL * (1.0 + kStringStrain);
  const double mu = (kStringMass + kStringAddedMass) / (1.0 + kStringStrain);
  const double f1 = std::sqrt(T / mu) / (2.0 * Ls);
  const double f_no_added_mass = f1 * std::sqrt((kStringMass + kStringAddedMass) / kStringMass);
  int n = 0;
  const double f = stringFrequency(1.0 / f1, true, 0.1, n);
  RecordProperty("f_theory_Hz", std::to_string(f1));
  RecordProperty("f_measured_Hz", std::to_string(f));
  std::printf("transverse:   measured %.5f Hz, theory %.5f Hz (ratio %.4f; without added mass %.5f Hz)\n", f, f1,
              f / f1, f_no_added_mass);
  EXPECT_NEAR(n, 9, 1) << "zero crossings in 9.5 periods of the expected mode";
  EXPECT_NEAR(f, f1, kFrequencyRelTol * f1);
}

TEST(Dynamics2D, TautStringLongitudinalFrequencyHasNoAddedMass) {
  // Along the line (eqs. 1, 3 with phi constant): m u_t = EA eps_s, eps_t = u_s on the unstretched
  // 0 <= s <= L, a fixed-fixed rod: f1 = sqrt(EA / m) / (2 L). For a linear law the strain does
  // not enter; added mass (normal only) must not either.
  const double f1 = std::sqrt(kStringEA / kStringMass) / (2.0 * kStringL);
  int n = 0;
  const double f = stringFrequency(1.0 / f1, false, 0.005, n);
  RecordProperty("f_theory_Hz", std::to_string(f1));
  RecordProperty("f_measured_Hz", std::to_string(f));
  std::printf("longitudinal: measured %.5f Hz, theory %.5f Hz (ratio %.4f; with added mass %.5f Hz)\n", f, f1,
              f / f1, f1 * std::sqrt(kStringMass / (kStringMass + kStringAddedMass)));
  EXPECT_NEAR(n, 9, 1) << "zero crossings in 9.5 periods of the expected mode";
  EXPECT_NEAR(f, f1, kFrequencyRelTol * f1);
}

// --- Order of accuracy in time -------------------------------------------------------------------

TEST(Dynamics2D, MeasuredOrderInTimeOnACableBoxAndBackwardDifferences) {
  const MeasuredOrder box = measureOrder(GeneralizedAlpha::preset("box"));
  const MeasuredOrder bd = measureOrder(GeneralizedAlpha::preset("backward"));
  printOrder("box", box);
  printOrder("backward", bd);
  RecordProperty("order_box", std::to_string(box.max_norm));
  RecordProperty("order_backward", std::to_string(bd.max_norm));
  // The premise: the errors are time-discretization errors, far above the Newton tolerance.
  EXPECT_GT(box.max_errors[2], 1e-6);
  EXPECT_NEAR(box.at_end, 2.0, kSecondOrderBand);
  EXPECT_NEAR(box.max_norm, 2.0, kSecondOrderBand);
  EXPECT_NEAR(bd.at_end, 1.0, kFirstOrderBand);
  EXPECT_NEAR(bd.max_norm, 1.0, kFirstOrderBand);
}

// lambda_inf = -0.5 is second order on a cable only with the mass matrix averaged by the alpha_k
// weights (see dynamics2d.cpp): with eq. 31's alpha_m weights this test measured slopes 2.43 at
// t_end and 1.61 for the largest error over the run (errors 4.99e-3, 1.57e-3, 5.37e-4 N); a state-
// dependent M evaluated at t_{i-1} + (1 - alpha_m) dt against a rate that approximates dY/dt at
// t_{i-1} + (1 - alpha_k) dt leaves an O(dt) residual. (Scalar check M(t) y' + y = 0,
// M = 2 + sin t: 0.66, 0.85, 0.93 with alpha_m weights, 2.00 with alpha_k.)
TEST(Dynamics2D, MeasuredOrderInTimeOnACableLambdaMinusHalf) {
  const MeasuredOrder half = measureOrder(GeneralizedAlpha::fromLambdaInf(-0.5));
  printOrder("lambda=-0.5", half);
  RecordProperty("order_lambda_-0.5", std::to_string(half.max_norm));
  EXPECT_GT(half.max_errors[2], 1e-6);
  EXPECT_NEAR(half.at_end, 2.0, kSecondOrderBand);
  EXPECT_NEAR(half.max_norm, 2.0, kSecondOrderBand);
}

// --- Prescribed top position ----------------------------------------------------------------------

// Driving the top by its velocity (eq. 34) integrates the position through the line's
// compatibility equations, which the box rows approximate differently from the coordinate rows
// (eq. 42): the top drifts from the commanded path by an O(h^2) rate. prescribe_position feeds
// the position error back into the velocity condition (imposing the position directly blew up
// within a second with lambda_inf = -0.5 and box: a higher-index constraint the dissipative
// schemes do not damp). The position-driven top must track the path, and better than the
// velocity-driven one.
TEST(Dynamics2D, PrescribedTopPositionTracksThePath) {
  Problem p = shortTautLine(GeneralizedAlpha::fromLambdaInf(-0.5), 0.01);
  p.dynamics.duration = 4.0;
  p.dynamics.output_interval = 0.1;
  p.dynamics.tolerance = DynamicOptions().tolerance;
  TopMotion& tm = p.dynamics.top_motion;
  tm.type = TopMotion::Type::Sinusoid;
  tm.amplitude_x = kOrderAmplitude;
  tm.period = kOrderPeriod;
  tm.phase = -0.25 * kTwoPi;
  auto trackingError = [&](const DynamicSeries& r) {
    const double x0 = r.initial_static.nodes.back().x;
    double worst = 0.0;
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      const double a = kTwoPi * r.t[k] / tm.period + tm.phase;
      worst = std::max(worst, std::abs(r.top_x[k] - (x0 + tm.amplitude_x * (std::sin(a) - std::sin(tm.phase)))));
    }
    return worst;
  };
  tm.prescribe_position = false;
  const DynamicSeries byVelocity = runDynamic(p);
  tm.prescribe_position = true;
  const DynamicSeries byPosition = runDynamic(p);
  ASSERT_TRUE(byVelocity.completed) << byVelocity.message;
  ASSERT_TRUE(byPosition.completed) << byPosition.message;
  const double ev = trackingError(byVelocity), ep = trackingError(byPosition);
  std::printf("top tracking error: velocity-driven %.3e m, position-driven %.3e m\n", ev, ep);
  EXPECT_LT(ep, ev);
  // The feedback lags by (drift rate) x (5 dt): well under 1% of the amplitude here.
  EXPECT_LT(ep, 0.01 * kOrderAmplitude);
}

// --- Adaptive time stepping (section 4.3) ----------------------------------------------------------

TEST(Dynamics2D, AdaptiveTimeSteppingCutsAndStaysOnTheOutputGrid) {
  const Problem p = cutChain();
  const DynamicSeries r = runDynamic(p);
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_GT(r.cuts, 0);
  RecordProperty("cuts", std::to_string(r.cuts));
  const double out = p.dynamics.output_interval;
  ASSERT_EQ(r.t.size(), static_cast<std::size_t>(std::lround(p.dynamics.duration / out)) + 1);
  const double x0 = r.initial_static.nodes.back().x, z0 = r.initial_static.nodes.back().z;
  const TopMotion& tm = p.dynamics.top_motion;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    EXPECT_EQ(r.t[k], static_cast<double>(k) * out) << "sample " << k;
    // The top is where the motion puts it at t_k: the sub-steps ended exactly on the sample.
    const double a = kTwoPi * r.t[k] / tm.period + tm.phase;
    EXPECT_NEAR(r.top_x[k], x0 + tm.amplitude_x * (std::sin(a) - std::sin(tm.phase)), kGridPositionTol)
        << "t = " << r.t[k];
    EXPECT_NEAR(r.top_z[k], z0 + tm.amplitude_z * (std::sin(a) - std::sin(tm.phase)), kGridPositionTol)
        << "t = " << r.t[k];
  }
  // Cutting refines: against a fine reference (dt = 0.05 s) the cut run is no worse than the
  // same base step run with the default Newton budget, which needs no cut.
  Problem ref = p, uncut = p;
  ref.dynamics.dt = 0.05;
  ref.dynamics.max_iterations = uncut.dynamics.max_iterations = DynamicOptions().max_iterations;
  const DynamicSeries f = runDynamic(ref);
  const DynamicSeries u = runDynamic(uncut);
  ASSERT_TRUE(f.completed) << f.message;
  ASSERT_TRUE(u.completed) << u.message;
  ASSERT_EQ(u.cuts, 0);
  ASSERT_EQ(f.t.size(), r.t.size());
  ASSERT_EQ(u.t.size(), r.t.size());
  const auto [lo, hi] = std::minmax_element(f.top_tension.begin(), f.top_tension.end());
  const double swing = *hi - *lo;
  ASSERT_GT(swing, 0.05 * *hi);  // the premise: the motion loads the line
  double err_cut = 0.0, err_uncut = 0.0;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    err_cut = std::max(err_cut, std::abs(r.top_tension[k] - f.top_tension[k]));
    err_uncut = std::max(err_uncut, std::abs(u.top_tension[k] - f.top_tension[k]));
  }
  RecordProperty("error_cut_N", std::to_string(err_cut));
  RecordProperty("error_uncut_N", std::to_string(err_uncut));
  std::printf("cuts %ld; top tension swing %.0f N; largest error vs dt = 0.05 s: cut run %.1f N, uncut %.1f N\n",
              r.cuts, swing, err_cut, err_uncut);
  EXPECT_LT(err_uncut, 0.1 * swing);  // dt = 1 s resolves a 16 s motion to a few percent
  EXPECT_LE(err_cut, err_uncut);
}

TEST(Dynamics2D, FailureIsReportedNotThrown) {
  Problem p = cutChain();
  p.dynamics.max_cut_levels = 0;
  p.dynamics.fallback = false;  // (the fallback step would take the step: test_dynamics2d_fallback)
  DynamicSeries r;
  ASSERT_NO_THROW(r = runDynamic(p));
  EXPECT_FALSE(r.completed);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_EQ(r.t.size(), 1u);  // only the start: the first base step (t = 1 s) failed
  // The message names the time and a node with its variable.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.message, m, std::regex(R"(t = ([0-9.eE+-]+) s)"))) << r.message;
  EXPECT_NEAR(std::stod(m[1].str()), 1.0, 1e-9) << r.message;
  EXPECT_TRUE(
      std::regex_search(r.message, std::regex(R"(node [0-9]+ \(s = [0-9.]+ m\) (eps|Sn|u|v|phi|Omega3|x|z)\b)")))
      << r.message;
  // The solver behind it is left usable at the last converged time.
  DynamicSolver2D solver(p);
  const StepReport rep = solver.advanceTo(1.0);
  EXPECT_FALSE(rep.ok);
  EXPECT_EQ(solver.time(), 0.0);
  EXPECT_FALSE(rep.message.empty());
}

// --- Jacobian of a time step --------------------------------------------------------------------

// The assembled Jacobian of a generalized-alpha step (hand-coded interval rows of
// dynamic_interval.hpp, AutoDiff junction and end rows) against central finite differences,
// mid-run on a heaved line in current without seabed contact (the contact onset is a kink that
// central differences straddle; test_dynamic_interval checks the contact terms against AutoDiff). Smooth terms agree to round-off; 1e-5 leaves room
// for the step-size truncation of the finite differences. The line is also split into two
// segments (junction rows). The matrix is assembled over NaN entries, as solveNewton reuses it
// without clearing: an entry the assembly leaves unwritten fails the check.
TEST(Dynamics2D, StepJacobianMatchesFiniteDifferences) {
  constexpr double kFdRelativeTolerance = 1e-5;
  for (bool junction : {false, true}) {
    Problem p = chainMooring(false);
    if (junction) {
      Segment upper = p.segments[0];
      p.segments[0].length = upper.length = 50.0;
      p.segments.push_back(upper);
    }
    p.dynamics.top_motion.type = TopMotion::Type::Sinusoid;
    p.dynamics.top_motion.amplitude_x = 0.5;
    p.dynamics.top_motion.amplitude_z = 0.5;
    p.dynamics.top_motion.period = 8.0;
    for (bool position : {false, true}) {
      p.dynamics.top_motion.prescribe_position = position;
      DynamicSolver2D solver(p);
      ASSERT_TRUE(solver.advanceTo(2.0).ok);
      EXPECT_LT(solver.jacobianFiniteDifferenceError(p.dynamics.dt), kFdRelativeTolerance)
          << (position ? "position-fed top" : "velocity top") << (junction ? ", two segments" : "");
    }
  }
}

TEST(Dynamics2D, SphereBodyDragIsAlongTheRelativeFlowAtAnyLineAngle) {
  // A body at a junction towed through still water at V = (1.2, -0.5) m/s, the line inclined at
  // 0.7 rad: a sphere's drag is -1/2 rho Cd A |V| V (closed form), whatever the line's angle; a
  // line-aligned body with cdn = cdt = Cd is not (its components are squared separately).
  using namespace mooring_dynamics::core::eq2dyn;
  Problem p;
  Material m;
  m.EA = 1e6;
  p.materials = {m, m};
  Body b;
  b.wet_weight = 100.0;
  b.diameter = 0.8;
  b.drag = Body::Drag::Sphere;
  b.cd = 0.7;
  p.bodies.push_back(b);
  MeshInterval iv;
  iv.h = 0.0;
  iv.bodies = {0};
  const double phi = 0.7, Vx = 1.2, Vz = -0.5;
  double Y[N] = {0.0};
  Y[PHI] = phi;
  Y[U] = Vx * std::sin(phi) + Vz * std::cos(phi);  // u along t = (sin, cos)
  Y[V] = Vx * std::cos(phi) - Vz * std::sin(phi);  // v along n = (cos, -sin)
  Water w;                                         // still water
  double R[N];
  junctionForces(p, iv, p.materials[0], p.materials[1], Y, Y, w, R);  // same node: F_b - F_a = 0
  const double q = 0.5 * p.environment.water_density * 0.7 * 0.25 * 3.14159265358979323846 * 0.8 * 0.8;
  const double speed = std::hypot(Vx, Vz);
  const double kTol = 1e-9;  // the speed floor (1e-6 m/s) changes |V| by 1e-13 relative
  EXPECT_NEAR(R[0], -q * speed * Vx, kTol);
  EXPECT_NEAR(R[1], -q * speed * Vz - b.wet_weight, kTol);

  p.bodies[0].drag = Body::Drag::LineAligned;
  p.bodies[0].cdn = p.bodies[0].cdt = 0.7;
  double Ra[N];
  junctionForces(p, iv, p.materials[0], p.materials[1], Y, Y, w, Ra);
  EXPECT_GT(std::hypot(Ra[0] - R[0], Ra[1] - R[1]), 1.0);

  // Statics (eq2d::bodyLoad): the current U along +x at any line angle gives 1/2 rho Cd A |U| U
  // along +x.
  p.bodies[0].drag = Body::Drag::Sphere;
  p.environment.current = {{0.0, 0.9, 0.0}, {100.0, 0.9, 0.0}};
  for (double ph : {0.0, 0.4, 1.2}) {
    double Pt, Pn;
    eq2d::bodyLoad(p.environment, p.bodies[0], ph, -10.0, Pt, Pn);
    const double Px = Pt * std::sin(ph) + Pn * std::cos(ph), Pz = Pt * std::cos(ph) - Pn * std::sin(ph);
    EXPECT_NEAR(Px, q * 0.9 * 0.9, kTol) << ph;
    EXPECT_NEAR(Pz, -b.wet_weight, kTol) << ph;
  }
}

TEST(Dynamics2D, HeavedLightRopeGoesSlackAndSnapsTautWithoutPushing) {
  // config/heaved_slack.yaml (docs/validation.md, "Slack lines and snap loads"): a light rope
  // without compression heaved 1.5 m every 3 s over a clump weight. In each of the first three
  // cycles its top tension reaches exactly 0 (slack, never below: the law is 0 below the slack
  // ramp) and snaps back above the static tension; the snaps' peaks are those of the same run at
  // a quarter of the time step (measured within 1.9 %: 6277, 7389, 6527 N against 6363, 7259,
  // 6431 N), so they are the physics of the snap and not of the step.
  constexpr double kPeakDtRelTol = 0.04;  // twice the measured distance: the refined run's own error
  Problem p = loadProblemFromFile("config/heaved_slack.yaml");
  p.dynamics.duration = 9.0;
  Problem fine = p;
  fine.dynamics.dt = p.dynamics.dt / 4.0;
  fine.dynamics.output_interval = p.dynamics.output_interval;
  const DynamicSeries r = runDynamic(p);
  const DynamicSeries f = runDynamic(fine);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_TRUE(f.completed) << f.message;
  const double T0 = r.top_tension.front();
  auto cycle = [](const DynamicSeries& s, int c, double& lo, double& hi) {
    lo = 1e300;
    hi = -1e300;
    for (std::size_t i = 0; i < s.t.size(); ++i)
      if (s.t[i] >= 3.0 * c && s.t[i] < 3.0 * (c + 1)) {
        lo = std::min(lo, s.top_tension[i]);
        hi = std::max(hi, s.top_tension[i]);
      }
  };
  for (int c = 0; c < 3; ++c) {
    double lo, hi, flo, fhi;
    cycle(r, c, lo, hi);
    cycle(f, c, flo, fhi);
    std::printf("heaved rope, cycle %d: top tension from %.3g N to %.1f N (static %.1f N; at dt / 4 %.1f N)\n", c, lo, hi,
                T0, fhi);
    EXPECT_EQ(lo, 0.0) << "cycle " << c;
    EXPECT_EQ(flo, 0.0) << "cycle " << c;
    EXPECT_GT(hi, T0) << "cycle " << c;
    EXPECT_NEAR(hi, fhi, kPeakDtRelTol * fhi) << "cycle " << c;
  }
}
