// The end conditions (end_conditions.hpp), each checked against something independent of its own
// Jacobian: the AD Jacobian block against central finite differences of its residual, in statics
// and dynamics, 2-D and 3-D; the double residual against the AD one's values; and the physics of
// a few ends (an anchor's rows vanish at the anchor at rest, a force top's when the internal force
// is the prescribed force, a position top's at the position).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/end_conditions.hpp"

using namespace mooring_dynamics::core;

namespace {

// Central differences with a step of 1e-6 relative to the unknown are accurate to about
// step^2 |f'''| plus round-off |f| 1e-16 / step: better than 1e-5 of the row's largest
// derivative on these smooth rows (the existing static-system check uses the same bound).
constexpr double kFdRelativeTolerance = 1e-5;
constexpr double kFdStep = 1e-6;
// A residual that must vanish is a difference of two computations of the same force or position
// (F - F_prescribed): zero but for the last bits of forces of order 1e4 N.
constexpr double kZeroResidual = 1e-9;

Problem baseProblem(Formulation f) {
  Problem p;
  p.formulation = f;
  p.environment.depth = 100.0;
  p.environment.current = {{0.0, 0.6, 0.4}, {100.0, 0.2, 0.1}};
  p.environment.wind_speed = 8.0;
  p.environment.wind_direction = 0.3;
  Material wire;
  wire.name = "wire";
  wire.EA = 4.0e7;
  wire.EI = 20.0;
  wire.GJ = 15.0;
  wire.mass = 5.0;
  wire.wet_weight = 40.0;
  wire.diameter = 0.03;
  wire.cdn = 1.2;
  wire.cdt = 0.02;
  p.materials = {wire};
  Body body;
  body.name = "sphere";
  body.mass = 300.0;
  body.added_mass = 150.0;
  body.wet_weight = -2000.0;
  body.diameter = 1.2;
  body.cdn = 0.8;
  body.cdt = 0.8;
  p.bodies = {body};
  Segment s;
  s.material = 0;
  s.length = 120.0;
  s.spacing = 10.0;
  p.segments = {s};
  p.anchor_x = -3.0;
  p.anchor_y = 1.5;
  p.anchor_z = -100.0;
  p.top.x = 60.0;
  p.top.y = 10.0;
  p.top.z = -2.0;
  p.top.fx = 3000.0;
  p.top.fy = -500.0;
  p.top.fz = 8000.0;
  p.top.body = 0;
  p.top.buoy.diameter = 2.0;
  p.top.buoy.mass = 500.0;
  p.top.buoy.added_mass = 300.0;
  p.top.buoy.wind_area = 1.5;
  p.dynamics.dt = 0.1;
  return p;
}

// --- 2-D -----------------------------------------------------------------------------------------

/// A 2-D node state with every unknown non-trivial (eq2d::Var / eq2dyn::Var order).
std::vector<double> state2d(int n) {
  if (n == eq2d::N) return {2.0e-4, 150.0, 0.7, 0.01, 55.0, -1.2};
  return {2.0e-4, 150.0, 0.3, -0.2, 0.7, 0.01, 55.0, -1.2};
}

/// AD residual rows of a 2-D end at y (values and Jacobian block).
template <class AD, class F>
void rows2d(const std::vector<double>& y0, int rows, const F& residual, std::vector<double>& R,
            std::vector<std::vector<double>>& J) {
  const int n = static_cast<int>(y0.size());
  std::vector<AD> y(static_cast<std::size_t>(n)), r(static_cast<std::size_t>(kMaxEndRows));
  for (int k = 0; k < n; ++k) y[static_cast<std::size_t>(k)] = AD(y0[static_cast<std::size_t>(k)], n, k);
  residual(y.data(), r.data());
  R.assign(static_cast<std::size_t>(rows), 0.0);
  J.assign(static_cast<std::size_t>(rows), std::vector<double>(static_cast<std::size_t>(n), 0.0));
  for (int q = 0; q < rows; ++q) {
    R[static_cast<std::size_t>(q)] = r[static_cast<std::size_t>(q)].value();
    for (int k = 0; k < n; ++k)
      J[static_cast<std::size_t>(q)][static_cast<std::size_t>(k)] = r[static_cast<std::size_t>(q)].derivatives()[k];
  }
}

/// The AD Jacobian block of `residual` against central differences of its values.
template <class AD, class F>
void expectJacobianMatchesDifferences(const std::vector<double>& y0, int rows, const F& residual,
                                      const std::string& what) {
  std::vector<double> R, Rp, Rm;
  std::vector<std::vector<double>> J, unused;
  rows2d<AD>(y0, rows, residual, R, J);
  for (std::size_t k = 0; k < y0.size(); ++k) {
    const double h = kFdStep * std::max(1.0, std::abs(y0[k]));
    std::vector<double> yp = y0, ym = y0;
    yp[k] += h;
    ym[k] -= h;
    rows2d<AD>(yp, rows, residual, Rp, unused);
    rows2d<AD>(ym, rows, residual, Rm, unused);
    for (int q = 0; q < rows; ++q) {
      double row_scale = 1.0;
      for (double d : J[static_cast<std::size_t>(q)]) row_scale = std::max(row_scale, std::abs(d));
      const double fd = (Rp[static_cast<std::size_t>(q)] - Rm[static_cast<std::size_t>(q)]) / (2.0 * h);
      EXPECT_NEAR(J[static_cast<std::size_t>(q)][k], fd, kFdRelativeTolerance * row_scale)
          << what << ": row " << q << ", unknown " << k;
    }
  }
}

using AD6 = EndCondition2D::ADs;
using AD8 = EndCondition2D::ADd;

void expectEnd2DJacobians(const Problem& p, const EndCondition2D& end) {
  const std::string name = end.name();
  expectJacobianMatchesDifferences<AD6>(
      state2d(eq2d::N), end.staticRows(), [&](const AD6* y, AD6* r) { end.staticResidual(y, r); }, name + " (statics)");
  TopState velocity;
  velocity.x = 54.5;
  velocity.z = -1.0;
  velocity.vx = 0.4;
  velocity.vz = -0.3;
  TopState force = velocity;
  force.force = true;
  force.fx = 2500.0;
  force.fz = 7000.0;
  for (const TopState& in : {velocity, force})
    expectJacobianMatchesDifferences<AD8>(
        state2d(eq2dyn::N), end.dynamicRows(), [&](const AD8* y, AD8* r) { end.dynamicResidual(in, y, r); },
        name + (in.force ? " (dynamics, force input)" : " (dynamics, velocity input)"));
  (void)p;
}

TEST(EndConditions2D, FactoryPicksTheTypeOfTheProblem) {
  Problem p = baseProblem(Formulation::TwoD);
  const Material& m = p.materials[0];
  EXPECT_STREQ(makeLowerEnd2D(p)->name(), "anchor");
  const std::pair<TopBoundary::Type, const char*> cases[] = {{TopBoundary::Type::Position, "position top"},
                                                             {TopBoundary::Type::Force, "force top"},
                                                             {TopBoundary::Type::Buoy, "surface buoy"},
                                                             {TopBoundary::Type::Body, "subsurface body"}};
  for (const auto& [type, name] : cases) {
    p.top.type = type;
    const auto top = makeUpperEnd2D(p, m);
    EXPECT_STREQ(top->name(), name);
    EXPECT_EQ(top->staticRows(), 3);
    EXPECT_EQ(top->dynamicRows(), 3);
  }
  EXPECT_EQ(makeLowerEnd2D(p)->staticRows(), 3);
  EXPECT_EQ(makeLowerEnd2D(p)->dynamicRows(), 5);
  // Only a force top prescribes a force, the scale of the error measure (eq. 39).
  p.top.type = TopBoundary::Type::Force;
  EXPECT_EQ(makeUpperEnd2D(p, m)->characteristicForce(), std::hypot(p.top.fx, p.top.fz));
  p.top.type = TopBoundary::Type::Position;
  EXPECT_EQ(makeUpperEnd2D(p, m)->characteristicForce(), 0.0);
  EXPECT_EQ(makeLowerEnd2D(p)->characteristicForce(), 0.0);
}

TEST(EndConditions2D, EveryJacobianBlockMatchesCentralDifferences) {
  Problem p = baseProblem(Formulation::TwoD);
  expectEnd2DJacobians(p, *makeLowerEnd2D(p));
  for (TopBoundary::Type type : {TopBoundary::Type::Position, TopBoundary::Type::Force, TopBoundary::Type::Buoy,
                                 TopBoundary::Type::Body}) {
    p.top.type = type;
    expectEnd2DJacobians(p, *makeUpperEnd2D(p, p.materials[0]));
  }
  p.dynamics.top_motion.prescribe_position = true;  // the position-feedback form of the top's rows
  expectEnd2DJacobians(p, *makeUpperEnd2D(p, p.materials[0]));
}

TEST(EndConditions2D, AnchorRowsVanishAtTheAnchorAtRest) {
  const Problem p = baseProblem(Formulation::TwoD);
  const auto anchor = makeLowerEnd2D(p);
  AD6 ys[eq2d::N], rs[kMaxEndRows];
  const double s[eq2d::N] = {1e-4, 10.0, 0.4, 0.0, p.anchor_x, p.anchor_z};
  for (int k = 0; k < eq2d::N; ++k) ys[k] = AD6(s[k], eq2d::N, k);
  anchor->staticResidual(ys, rs);
  for (int q = 0; q < anchor->staticRows(); ++q) EXPECT_EQ(rs[q].value(), 0.0) << "static row " << q;
  AD8 yd[eq2dyn::N], rd[kMaxEndRows];
  const double d[eq2dyn::N] = {1e-4, 10.0, 0.0, 0.0, 0.4, 0.0, p.anchor_x, p.anchor_z};
  for (int k = 0; k < eq2dyn::N; ++k) yd[k] = AD8(d[k], eq2dyn::N, k);
  anchor->dynamicResidual(TopState{}, yd, rd);
  for (int q = 0; q < anchor->dynamicRows(); ++q) EXPECT_EQ(rd[q].value(), 0.0) << "dynamic row " << q;
}

TEST(EndConditions2D, ForceTopVanishesWhenTheInternalForceIsThePrescribedForce) {
  Problem p = baseProblem(Formulation::TwoD);
  const std::vector<double> y0 = state2d(eq2d::N);
  double Fx, Fz;
  eq2d::internalForce(p.materials[0], y0.data(), Fx, Fz);  // the line's pull at this state
  p.top.type = TopBoundary::Type::Force;
  p.top.fx = Fx;
  p.top.fz = Fz;
  const auto top = makeUpperEnd2D(p, p.materials[0]);
  AD6 y[eq2d::N], r[kMaxEndRows];
  for (int k = 0; k < eq2d::N; ++k) y[k] = AD6(y0[static_cast<std::size_t>(k)], eq2d::N, k);
  y[eq2d::OMEGA] = AD6(0.0, eq2d::N, eq2d::OMEGA);  // moment free
  top->staticResidual(y, r);
  for (int q = 0; q < 3; ++q) EXPECT_NEAR(r[q].value(), 0.0, kZeroResidual * std::hypot(Fx, Fz)) << "row " << q;
  // The same top driven by a force input in dynamics.
  TopState in;
  in.force = true;
  AD8 yd[eq2dyn::N], rd[kMaxEndRows];
  const std::vector<double> d = state2d(eq2dyn::N);
  for (int k = 0; k < eq2dyn::N; ++k) yd[k] = AD8(d[static_cast<std::size_t>(k)], eq2dyn::N, k);
  yd[eq2dyn::OMEGA] = AD8(0.0, eq2dyn::N, eq2dyn::OMEGA);
  eq2dyn::internalForce(p.materials[0], d.data(), in.fx, in.fz);
  top->dynamicResidual(in, yd, rd);
  for (int q = 0; q < 3; ++q) EXPECT_NEAR(rd[q].value(), 0.0, kZeroResidual * std::hypot(in.fx, in.fz)) << "row " << q;
}

// --- 3-D -----------------------------------------------------------------------------------------

using AD16 = EndCondition3D::AD;

/// A 3-D node state with every unknown non-trivial: a frame turned about all three axes (unit
/// quaternion), velocities and curvatures not zero.
std::vector<double> state3d() {
  const double q[4] = {0.9, 0.2, -0.3, 0.25};
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  return {2.0e-4, 150.0, -80.0, 0.3, -0.2, 0.15, 0.002, 0.01, -0.008,
          q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm, 55.0, 8.0, -1.2};
}

struct Context3D {
  eq3d::Water water;
  double q_ref[4] = {0.95, 0.1, -0.2, 0.2};
  std::vector<double> yp, ydp;
  TopState input;
  StaticEnd3D statics() const { return {&water, q_ref}; }
  DynamicEnd3D dynamics() const {
    DynamicEnd3D c;
    c.t = 3.0;
    c.input = &input;
    c.yp = yp.data();
    c.ydp = ydp.data();
    c.water = &water;
    c.w = {-0.5, 0.0, 1.0 / (0.75 * 0.1), (1.0 - 0.75) / 0.75};  // generalized-alpha at dt = 0.1 s
    return c;
  }
};

Context3D context3d() {
  Context3D c;
  c.water.w[0] = 0.5;
  c.water.w[1] = 0.2;
  c.water.w[2] = 0.05;
  c.water.z = -1.0;
  c.water.dw_dz[0] = 0.01;
  c.water.dw_dz[1] = -0.004;
  c.yp = state3d();
  for (std::size_t k = 0; k < c.yp.size(); ++k) c.yp[k] *= 1.0 - 1e-3 * static_cast<double>(k % 3);  // a step ago
  c.ydp.assign(c.yp.size(), 0.0);
  for (std::size_t k = 0; k < c.ydp.size(); ++k) c.ydp[k] = 0.01 * std::sin(static_cast<double>(k));
  c.input.x = 54.0;
  c.input.y = 7.5;
  c.input.z = -1.0;
  c.input.vx = 1.2;
  c.input.vy = 0.1;
  c.input.vz = -0.2;
  return c;
}

void expectEnd3DJacobians(const EndCondition3D& end, Context3D c) {
  const std::string name = end.name();
  const std::vector<double> y0 = state3d();
  const StaticEnd3D sc = c.statics();
  expectJacobianMatchesDifferences<AD16>(
      y0, end.staticRows(), [&](const AD16* y, AD16* r) { end.staticResidual(sc, y, r); }, name + " (statics)");
  for (bool force : {false, true}) {
    c.input.force = force;
    c.input.fx = force ? 2500.0 : 0.0;
    c.input.fy = force ? -300.0 : 0.0;
    c.input.fz = force ? 7000.0 : 0.0;
    const DynamicEnd3D dc = c.dynamics();
    const std::string what = name + (force ? " (dynamics, force input)" : " (dynamics, velocity input)");
    expectJacobianMatchesDifferences<AD16>(
        y0, end.dynamicRows(), [&](const AD16* y, AD16* r) { end.dynamicResidual(dc, y, r); }, what);
    // The residual alone (double) is the AD residual's value, bit for bit: the solvers use either.
    AD16 ya[eq3d::N], ra[kMaxEndRows];
    double rd[kMaxEndRows];
    for (int k = 0; k < eq3d::N; ++k) ya[k] = AD16(y0[static_cast<std::size_t>(k)], eq3d::N, k);
    end.dynamicResidual(dc, ya, ra);
    end.dynamicResidual(dc, y0.data(), rd);
    for (int q = 0; q < end.dynamicRows(); ++q) EXPECT_EQ(rd[q], ra[q].value()) << what << ": row " << q;
  }
}

std::unique_ptr<EndCondition3D> upper3d(Problem p, TopBoundary::Type type, Problem::LowerEnd lower) {
  static std::vector<Problem> keep;  // the ends refer to their problem
  p.top.type = type;
  p.lower_end = lower;
  keep.reserve(64);
  keep.push_back(p);
  return makeUpperEnd3D(keep.back(), keep.back().materials[0]);
}

TEST(EndConditions3D, FactoryPicksTheTypeOfTheProblem) {
  Problem p = baseProblem(Formulation::ThreeD);
  EXPECT_STREQ(makeLowerEnd3D(p, p.materials[0])->name(), "anchor");
  p.lower_end = Problem::LowerEnd::Free;
  EXPECT_STREQ(makeLowerEnd3D(p, p.materials[0])->name(), "free end");
  EXPECT_EQ(makeLowerEnd3D(p, p.materials[0])->dynamicRows(), 7);
  p.end_body = 0;
  EXPECT_STREQ(makeLowerEnd3D(p, p.materials[0])->name(), "free end with body");
  EXPECT_STREQ(makeMovingAnchor3D(p, [](double) { return TopState{}; })->name(), "moving anchor");
  const Problem base = baseProblem(Formulation::ThreeD);
  using T = TopBoundary::Type;
  using L = Problem::LowerEnd;
  struct Case {
    T type;
    L lower;
    const char* name;
    int dynamic_rows;
  };
  for (const Case& c : {Case{T::Position, L::Anchor, "position top", 6}, Case{T::Force, L::Anchor, "force top", 6},
                        Case{T::Buoy, L::Anchor, "surface buoy", 6}, Case{T::Body, L::Anchor, "subsurface body", 6},
                        Case{T::Position, L::Free, "tow point", 9}, Case{T::Buoy, L::Free, "drifting buoy", 9}}) {
    const auto top = upper3d(base, c.type, c.lower);
    EXPECT_STREQ(top->name(), c.name);
    EXPECT_EQ(top->staticRows(), 6) << c.name;
    EXPECT_EQ(top->dynamicRows(), c.dynamic_rows) << c.name;
    // A free lower end gives up three rows (rest) that its top takes (position or kinematics).
    const int lower_rows = c.lower == L::Free ? 7 : 10;
    EXPECT_EQ(lower_rows + top->dynamicRows(), 16) << c.name;
    const double f = c.type == T::Force ? std::sqrt(base.top.fx * base.top.fx + base.top.fy * base.top.fy +
                                                    base.top.fz * base.top.fz)
                                        : 0.0;
    EXPECT_EQ(top->characteristicForce(), f) << c.name;
  }
}

TEST(EndConditions3D, EveryJacobianBlockMatchesCentralDifferences) {
  Problem p = baseProblem(Formulation::ThreeD);
  const Context3D c = context3d();
  expectEnd3DJacobians(*makeLowerEnd3D(p, p.materials[0]), c);
  const std::function<TopState(double)> motion = [](double t) {
    TopState s;
    s.x = -3.0 + 0.1 * t;
    s.y = 1.5;
    s.z = -100.0 + 0.05 * t;
    s.vx = 0.1;
    s.vz = 0.05;
    return s;
  };
  expectEnd3DJacobians(*makeMovingAnchor3D(p, motion), c);
  Problem free = p;
  free.lower_end = Problem::LowerEnd::Free;
  free.end_body = 0;
  auto end = makeLowerEnd3D(free, free.materials[0]);
  end->setState({10.0, -20.0, 30.0});  // a previous level's spatial part
  expectEnd3DJacobians(*end, c);
  using T = TopBoundary::Type;
  using L = Problem::LowerEnd;
  for (const auto& [type, lower] : {std::pair{T::Position, L::Anchor}, std::pair{T::Force, L::Anchor},
                                    std::pair{T::Buoy, L::Anchor}, std::pair{T::Body, L::Anchor},
                                    std::pair{T::Position, L::Free}, std::pair{T::Buoy, L::Free}}) {
    auto top = upper3d(p, type, lower);
    top->setState({-5.0, 4.0, 300.0});
    expectEnd3DJacobians(*top, c);
  }
  p.dynamics.top_motion.prescribe_position = true;  // the position-feedback form of a driven top
  expectEnd3DJacobians(*upper3d(p, T::Position, L::Anchor), c);
}

TEST(EndConditions3D, AnchorRowsVanishAtTheAnchorAtRestInItsOwnFrame) {
  const Problem p = baseProblem(Formulation::ThreeD);
  const auto anchor = makeLowerEnd3D(p, p.materials[0]);
  Context3D c = context3d();
  std::vector<double> y = state3d();
  for (int k : {eq3d::U1, eq3d::U2, eq3d::U3, eq3d::O2, eq3d::O3}) y[static_cast<std::size_t>(k)] = 0.0;
  for (int i = 0; i < 4; ++i) c.q_ref[i] = y[static_cast<std::size_t>(eq3d::Q0 + i)];  // no twist from the reference
  c.yp = y;
  y[eq3d::X] = p.anchor_x;
  y[eq3d::Y] = p.anchor_y;
  y[eq3d::Z] = p.anchor_z;
  AD16 ya[eq3d::N], r[kMaxEndRows];
  for (int k = 0; k < eq3d::N; ++k) ya[k] = AD16(y[static_cast<std::size_t>(k)], eq3d::N, k);
  anchor->staticResidual(c.statics(), ya, r);
  // |q|^2 - 1 of a normalized quaternion is zero to round-off.
  for (int q = 0; q < anchor->staticRows(); ++q) EXPECT_NEAR(r[q].value(), 0.0, 1e-15) << "static row " << q;
  double rd[kMaxEndRows];
  anchor->dynamicResidual(c.dynamics(), y.data(), rd);
  for (int q = 0; q < anchor->dynamicRows(); ++q) EXPECT_NEAR(rd[q], 0.0, 1e-15) << "dynamic row " << q;
}

TEST(EndConditions3D, ForceAndPositionTopsVanishAtTheirPrescribedValues) {
  Problem p = baseProblem(Formulation::ThreeD);
  std::vector<double> y = state3d();
  for (int k : {eq3d::O1, eq3d::O2, eq3d::O3}) y[static_cast<std::size_t>(k)] = 0.0;  // moment free
  double F[3];
  eq3d::internalForce(p.materials[0], y.data(), F);
  p.top.fx = F[0];
  p.top.fy = F[1];
  p.top.fz = F[2];
  p.top.x = y[eq3d::X];
  p.top.y = y[eq3d::Y];
  p.top.z = y[eq3d::Z];
  const Context3D c = context3d();
  AD16 ya[eq3d::N], r[kMaxEndRows];
  for (int k = 0; k < eq3d::N; ++k) ya[k] = AD16(y[static_cast<std::size_t>(k)], eq3d::N, k);
  for (TopBoundary::Type type : {TopBoundary::Type::Force, TopBoundary::Type::Position}) {
    const auto top = upper3d(p, type, Problem::LowerEnd::Anchor);
    top->staticResidual(c.statics(), ya, r);
    const double scale = type == TopBoundary::Type::Force ? std::sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]) : 1.0;
    for (int q = 0; q < 6; ++q) EXPECT_NEAR(r[q].value(), 0.0, kZeroResidual * scale) << top->name() << " row " << q;
  }
}

TEST(EndConditions3D, WeightedEndsKeepTheirStateAndReportItForSaveAndRestore) {
  Problem p = baseProblem(Formulation::ThreeD);
  p.lower_end = Problem::LowerEnd::Free;
  p.end_body = 0;
  const Context3D c = context3d();
  const std::vector<double> y = state3d();
  // A free end keeps the spatial part of its body's balance (eq3d::freeEndForces) at the level.
  auto end = makeLowerEnd3D(p, p.materials[0]);
  EXPECT_TRUE(end->state().size() == 3);
  end->acceptLevel(y.data(), c.water, 1.0, nullptr);
  double expected[3];
  eq3d::freeEndForces(p, p.materials[0], y.data(), c.water, expected);
  const std::vector<double> s = end->state();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(s[static_cast<std::size_t>(i)], expected[i]);
  // A subsurface body asks the top's input for an external force at the level's time only.
  auto body = upper3d(baseProblem(Formulation::ThreeD), TopBoundary::Type::Body, Problem::LowerEnd::Anchor);
  std::vector<double> asked;
  body->acceptLevel(y.data(), c.water, 2.5, [&](double t) {
    asked.push_back(t);
    TopState in;
    in.force = true;
    in.fz = 100.0;
    return in;
  });
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0], 2.5);
  // Restoring a saved state gives the same rows as before.
  const std::vector<double> saved = body->state();
  double before[kMaxEndRows], after[kMaxEndRows];
  const DynamicEnd3D dc = c.dynamics();
  body->dynamicResidual(dc, y.data(), before);
  body->setState({0.0, 0.0, 0.0});
  body->setState(saved);
  body->dynamicResidual(dc, y.data(), after);
  for (int q = 0; q < body->dynamicRows(); ++q) EXPECT_EQ(before[q], after[q]) << "row " << q;
  // Ends without a balance in time keep nothing.
  EXPECT_TRUE(makeLowerEnd3D(baseProblem(Formulation::ThreeD), p.materials[0])->state().empty());
}

}  // namespace
