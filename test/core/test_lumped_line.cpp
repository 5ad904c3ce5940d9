// The lumped-mass line of the fallback step (src/core/solvers/lumped_line.cpp and .hpp): a hanging
// line at its closed-form static state stays there; the vectorized passes over component arrays
// give the forces and the sub-steps of a plain node-by-node loop bit for bit, whatever
// instruction set the machine picks (the runs' determinism rests on it).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "../../src/core/solvers/lumped_line.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"

using namespace mooring_dynamics::core;
using lumped::Vec3;

namespace {

/// The solver's side of the lumped model for these tests (as dynamics3d_fallback.cpp's): the
/// 3-D seabed rows, the top held on a straight path, the lower end held or free.
struct TestModel {
  const Problem* p = nullptr;
  Vec3 top0, top_velocity, anchor;
  bool low_held = true;
  double seabed(const Material& m, const Vec3& x, const Vec3& v) const {
    double y[eq3d::N] = {0.0};
    y[eq3d::X] = x.x();
    y[eq3d::Y] = x.y();
    y[eq3d::Z] = x.z();
    y[eq3d::U1] = v.x();
    y[eq3d::U2] = v.y();
    y[eq3d::U3] = v.z();
    const double Rid[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    return eq3d::seabedReaction(p->environment, m, y, Rid);
  }
  Vec3 endBodyLoad(const Body& b, const Vec3& tangent, const Vec3& r) const {
    double P[3] = {0.0, 0.0, 0.0};
    eq3d::addBodyLoad(p->environment, b, tangent.data(), r.data(), P);
    return Vec3(P[0], P[1], P[2]);
  }
  bool topHeld() const { return true; }
  bool lowHeld() const { return low_held; }
  Vec3 topForce(double) const { return Vec3::Zero(); }
  void top(double t, Vec3& x, Vec3& v) const {
    x = top0 + t * top_velocity;
    v = top_velocity;
  }
  void low(double, Vec3& x, Vec3& v) const {
    x = anchor;
    v.setZero();
  }
};

/// A chain without compression (EA 5e8 N, 100 kg/m, 850 N/m wet, drag) in 60 m of water on a
/// damped flat seabed, 40 intervals of 2 m; with `junction` interval 20 is an inline clump.
struct Case {
  Problem p;
  Mesh mesh;
  lumped::Setup setup;
  explicit Case(bool junction, bool compression) {
    p.environment.depth = 60.0;
    p.environment.water_density = 1025.0;
    p.environment.seabed.stiffness = 1e5;
    p.environment.seabed.damping = 650.0;
    Material m;
    m.EA = 5e8;
    m.mass = 100.0;
    m.added_mass = 20.0;
    m.wet_weight = 850.0;
    m.diameter = 0.1;
    m.cdn = 2.4;
    m.cdt = 1.15;
    m.EI = 1.0;
    m.compression = compression;
    p.materials.push_back(m);
    Body clump;
    clump.mass = 200.0;
    clump.added_mass = 50.0;
    clump.wet_weight = 1700.0;
    clump.diameter = 0.5;
    clump.drag = Body::Drag::Sphere;
    clump.cd = 1.0;
    p.bodies.push_back(clump);
    const int n = 41;
    for (int j = 0; j < n; ++j) mesh.nodes.push_back(MeshNode{2.0 * j, 0, 0});
    for (int j = 0; j + 1 < n; ++j) {
      MeshInterval iv;
      iv.h = 2.0;
      if (junction && j == 20) {
        iv.h = 0.0;
        iv.bodies = {0};
      }
      mesh.intervals.push_back(iv);
    }
    setup.problem = &p;
    setup.mesh = &mesh;
  }
};

/// A state of the chain lying on the seabed near the anchor (nodes 0-10), rising slack (to node
/// 25) and then taut (chords 1.5 % long) to the top, jiggled, with random velocities and water
/// (seeded).
void jiggledState(const Case& c, lumped::Line& L, std::vector<lumped::NodeWater>& water) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  lumped::lumpMasses(c.setup, L);
  const int n = L.n;
  double rise = 0.0;
  for (int j = 0; j < n; ++j) {
    const bool tied = j > 0 && !(c.mesh.intervals[static_cast<std::size_t>(j) - 1].h > 0.0);
    if (j > 10 && !tied) rise += j > 25 ? 1.6 : 1.0;
    L.x[j] = tied ? L.x[j - 1] : Vec3(1.25 * j + 0.02 * u(gen), 0.02 * u(gen), -60.0 + rise + 0.05 * u(gen));
    L.v[j] = tied ? L.v[j - 1] : Vec3(u(gen), u(gen), u(gen));
  }
  lumped::setReferenceLengths(c.setup, std::vector<Vec3>(n, Vec3(1.0, 0.0, 0.0)), L);
  water.resize(static_cast<std::size_t>(n));
  for (lumped::NodeWater& w : water) {
    w.w0 = Vec3(0.5 + 0.1 * u(gen), 0.2 * u(gen), 0.1 * u(gen));
    w.w1 = Vec3(0.6, 0.1, -0.1 * u(gen));
  }
}

/// The forces of lumped_line.hpp's file comment, node by node with Eigen's 3-vectors (the
/// reference the passes must equal bit for bit).
void referenceForces(const lumped::Setup& s, const lumped::Constants& c, const TestModel& model, const lumped::Line& L,
                     const std::vector<lumped::NodeWater>& water, double w, std::vector<Vec3>& f,
                     std::vector<double>& rate) {
  const Problem& p = *s.problem;
  const double rho = p.environment.water_density;
  const int n = L.n;
  f.assign(static_cast<std::size_t>(n), Vec3::Zero());
  rate.assign(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const lumped::Constants::Interval& ci = c.intervals[static_cast<std::size_t>(j)];
    if (!ci.m) {
      const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
      for (std::size_t b : s.mesh->intervals[static_cast<std::size_t>(j)].bodies) {
        const Body& body = p.bodies[b];
        f[j].z() -= body.wet_weight;
        const Vec3 r = wv - L.v[j];
        const double area = 0.25 * eq2d::kPi * body.diameter * body.diameter;
        f[j] += 0.5 * rho * body.isotropicCd() * area * r.norm() * r;
      }
      continue;
    }
    const Material& m = *ci.m;
    f[j].z() -= ci.half_weight;
    f[j + 1].z() -= ci.half_weight;
    const double len = L.chord_len[j];
    const double eps = len / L.ref[j] - 1.0;
    const bool has_dir = len > lumped::kShortChord * ci.h;
    const Vec3& t = has_dir ? L.chord_dir[j] : L.tangent[j];
    const double eps_rate = has_dir ? t.dot(L.v[j + 1] - L.v[j]) / L.ref[j] : 0.0;
    const double Te = ci.tension(eps);
    double T = Te + ci.damper * eps_rate;
    if (!m.compression) T = Te > 0.0 ? std::max(T, 0.0) : 0.0;
    f[j] += T * t;
    f[j + 1] -= T * t;
    const Vec3 wv = 0.5 * ((1.0 - w) * (water[j].w0 + water[j + 1].w0) + w * (water[j].w1 + water[j + 1].w1));
    const Vec3 vr = 0.5 * (L.v[j] + L.v[j + 1]) - wv;
    const double vt = vr.dot(t);
    const Vec3 vn = vr - vt * t;
    const double stretch = std::sqrt(std::max(1.0 + eps, 0.0));
    const double vnn = std::sqrt(vn.squaredNorm() + eq3d::kDragSpeedFloor * eq3d::kDragSpeedFloor);
    const Vec3 drag = ci.drag * stretch * (m.cdn * vnn * vn + eq2d::kPi * m.cdt * std::abs(vt) * vt * t);
    f[j] += 0.5 * drag;
    f[j + 1] += 0.5 * drag;
    const double r = ci.drag_rate * stretch * 2.0 * std::max(m.cdn * vnn, eq2d::kPi * m.cdt * std::abs(vt));
    rate[j] += 0.25 * r;
    rate[j + 1] += 0.25 * r;
  }
  for (int j = 0; j < n; ++j) {
    const lumped::Constants::Node& cn = c.nodes[static_cast<std::size_t>(j)];
    if (cn.m) f[j].z() += cn.length * model.seabed(*cn.m, L.x[j], L.v[j]);
  }
}

TestModel modelOf(const Case& c, const lumped::Line& L) {
  TestModel model;
  model.p = &c.p;
  model.top0 = L.x[static_cast<std::size_t>(L.n) - 1];
  model.top_velocity = Vec3(0.3, 0.0, -4.0);  // a fairlead diving at 4 m/s: the line goes slack
  model.anchor = L.x[0];
  return model;
}

}  // namespace

// Reference: the node-by-node loop above, the formulas of lumped_line.hpp's file comment.
// Tolerance: none, the same bits (the passes do the same operations in the same order; the
// machine's vector width must not change a result).
TEST(LumpedLine, PassesGiveTheForcesOfANodeByNodeLoopBitForBit) {
  for (bool junction : {false, true})
    for (bool compression : {false, true}) {
      SCOPED_TRACE(std::string(junction ? "with" : "without") + " a junction, compression " +
                   (compression ? "on" : "off"));
      const Case c(junction, compression);
      lumped::Line L;
      std::vector<lumped::NodeWater> water;
      jiggledState(c, L, water);
      const TestModel model = modelOf(c, L);
      const lumped::Constants k = lumped::Constants::of(c.setup, L.n);
      lumped::Substeps sub = lumped::Substeps::of(c.setup, k, L, water);
      const double w = 0.3;
      sub.chords();
      sub.axial(k);
      sub.intervalForces(w);
      sub.nodeSums();
      lumped::modelLoads(c.setup, k, model, water, w, sub);
      lumped::updateTangents(c.setup, L);
      std::vector<Vec3> f;
      std::vector<double> rate;
      referenceForces(c.setup, k, model, L, water, w, f, rate);
      int grounded = 0, slack = 0;
      for (int j = 0; j < L.n; ++j) {
        grounded += L.x[j].z() < -c.p.environment.depth;
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(sub.t[i][j], L.tangent[j][i]) << "node " << j;
          EXPECT_EQ(sub.f[i][j], f[j][i]) << "node " << j << " component " << i;
        }
        EXPECT_EQ(sub.dr[j], rate[j]) << "node " << j;
      }
      for (int j = 0; j + 1 < L.n; ++j) slack += c.mesh.intervals[j].h > 0.0 && lumped::chordStrain(L, j) < 0.0;
      // The state exercises what the passes select on: contact, slack chords and taut ones.
      EXPECT_GT(grounded, 3);
      EXPECT_GT(slack, 3);
      EXPECT_LT(slack, L.n - 4);
    }
}

// Reference: lumped::advance on the passes against the same sub-steps taken node by node with the
// reference forces (symplectic Euler, drag implicit, as advance's comment says). Tolerance: none.
TEST(LumpedLine, SubStepsGiveTheStateOfANodeByNodeLoopBitForBit) {
  const Case c(true, false);
  lumped::Line L;
  std::vector<lumped::NodeWater> water;
  jiggledState(c, L, water);
  const TestModel model = modelOf(c, L);
  lumped::Line R = L;
  const double dt = 0.02;
  long substeps = 0;
  std::string message;
  ASSERT_TRUE(lumped::advance(c.setup, model, water, 0.0, dt, L, substeps, message)) << message;
  ASSERT_GT(substeps, 10);
  const lumped::Constants k = lumped::Constants::of(c.setup, R.n);
  const int n = R.n, tied_node = 21;  // junction at interval 20: node 21 rides on node 20
  const double h = dt / substeps;
  for (long step = 1; step <= substeps; ++step) {
    lumped::updateTangents(c.setup, R);
    std::vector<Vec3> f;
    std::vector<double> rate;
    referenceForces(c.setup, k, model, R, water, (step - 0.5) / substeps, f, rate);
    f[tied_node - 1] += f[tied_node];
    for (int j = 0; j < n; ++j) {
      if (j == tied_node) continue;
      double ms = R.mass[j] + R.body_mass[j], ma = R.added[j], cd = rate[j];
      if (j == tied_node - 1) {
        ms += R.mass[tied_node] + R.body_mass[tied_node];
        ma += R.added[tied_node];
        cd += rate[tied_node];
      }
      const Vec3& t = R.tangent[j];
      const Vec3 ft = t.dot(f[j]) * t;
      const Vec3 a = ft / (ms + h * cd) + (f[j] - ft) / (ms + ma + h * cd);
      R.v[j] += h * a;
      R.x[j] += h * R.v[j];
    }
    R.x[tied_node] = R.x[tied_node - 1];
    R.v[tied_node] = R.v[tied_node - 1];
    model.top(step * h, R.x[n - 1], R.v[n - 1]);
    model.low(step * h, R.x[0], R.v[0]);
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(L.x[j][i], R.x[j][i]) << "node " << j;
      EXPECT_EQ(L.v[j][i], R.v[j][i]) << "node " << j;
    }
}

// Reference: a vertical line hanging from a fixed top with a weight at its free lower end is at
// rest when interval j (from the bottom) carries T_j = W + w h (j + 1/2), the weight of the body
// and of the lumped nodes below its upper node, stretched to h (1 + T_j / EA). Started there, at
// rest in still water, the line must stay: a wrong weight share, sign or axial law moves the
// nodes by T / EA h ~ millimetres in a fraction of a second (free fall: 5 m in 1 s).
// Tolerance: 1e-9 m, rounding over ~10^4 sub-steps of positions of order 10 m.
constexpr double kRestTolerance = 1e-9;

TEST(LumpedLine, HangingLineAtItsClosedFormStaticStateStaysThere) {
  Case c(false, false);
  c.p.environment.depth = 1000.0;  // no seabed contact
  Body weight;
  weight.mass = 50.0;
  weight.wet_weight = 400.0;
  weight.diameter = 0.3;
  weight.drag = Body::Drag::Sphere;
  weight.cd = 1.0;
  c.p.bodies.push_back(weight);
  c.setup.end_body = &c.p.bodies.back();
  lumped::Line L;
  lumped::lumpMasses(c.setup, L);
  const Material& m = c.p.materials[0];
  const int n = L.n;
  const double h = 2.0, w = m.wet_weight;
  L.x[0] = Vec3(5.0, -3.0, -200.0);
  for (int j = 0; j + 1 < n; ++j) {
    const double T = weight.wet_weight + w * h * (j + 0.5);
    L.x[j + 1] = L.x[j] + Vec3(0.0, 0.0, h * (1.0 + T / m.EA));
  }
  lumped::setReferenceLengths(c.setup, std::vector<Vec3>(n, Vec3(0.0, 0.0, 1.0)), L);
  const std::vector<lumped::NodeWater> still(static_cast<std::size_t>(n), lumped::NodeWater{Vec3::Zero(), Vec3::Zero()});
  TestModel model;
  model.p = &c.p;
  model.top0 = L.x[static_cast<std::size_t>(n) - 1];
  model.top_velocity = Vec3::Zero();
  model.low_held = false;
  const std::vector<Vec3> start = L.x;
  long substeps = 0;
  std::string message;
  for (int step = 0; step < 10; ++step)
    ASSERT_TRUE(lumped::advance(c.setup, model, still, 0.1 * step, 0.1, L, substeps, message)) << message;
  for (int j = 0; j < n; ++j) EXPECT_LT((L.x[j] - start[j]).norm(), kRestTolerance) << "node " << j;
  // The same line without the weight's 400 N is not at rest (its end rises by up to twice the
  // static 40 h 400 / EA = 6.4e-5 m, the axial mode's period 0.14 s): the check can fail.
  lumped::Line light = L;
  light.x = start;
  light.v.assign(static_cast<std::size_t>(n), Vec3::Zero());
  c.p.bodies.back().wet_weight = 0.0;
  double moved = 0.0;
  for (int step = 0; step < 10; ++step) {
    ASSERT_TRUE(lumped::advance(c.setup, model, still, 0.01 * step, 0.01, light, substeps, message)) << message;
    moved = std::max(moved, (light.x[0] - start[0]).norm());
  }
  EXPECT_GT(moved, 1000.0 * kRestTolerance);
}

namespace {

/// The part of a solver's state that the fallback's policy reads (lumped::staySlack,
/// countFailedTry): nodes of (x, z, eps), all of one material, on a flat seabed at -depth.
struct PolicyLine {
  struct Totals {
    long failed_tries = 0, failed_jacobians = 0, fallback_retries = 0;
  };
  Problem problem;
  Eigen::VectorXd Y;
  bool in_fallback = true;
  double fallback_skipped_time = 0.0;
  double skipped_cap = lumped::kMaxSkippedTime;
  int retry_wait = 0;
  Totals totals;
  static constexpr int kUnknowns = 3, kX = 0, kZ = 1, kEps = 2;
  PolicyLine(int nodes, bool compression) {
    problem.environment.depth = 50.0;
    Material m;
    m.compression = compression;
    problem.materials.push_back(m);
    Y = Eigen::VectorXd::Zero(kUnknowns * nodes);
    for (int j = 0; j < nodes; ++j) {
      Y[kUnknowns * j + kX] = 2.0 * j;
      Y[kUnknowns * j + kZ] = -50.01 + 0.5 * j;  // node 0 pressed 1 cm into the seabed, the others above
      Y[kUnknowns * j + kEps] = 1e-4;           // taut
    }
  }
  int nodes() const { return static_cast<int>(Y.size()) / kUnknowns; }
  const Material& mat(int) const { return problem.materials[0]; }
  bool stays() const { return lumped::staySlack(*this, kUnknowns, kEps, kX, -1, kZ); }
  /// Base steps of dt in the fallback without a try while stays(), up to `limit` [s]; the time.
  double stayFor(double dt, double limit) {
    while (stays() && fallback_skipped_time < limit) fallback_skipped_time += dt;
    return fallback_skipped_time;
  }
};

}  // namespace

// Reference: the rules of lumped_line.hpp (staySlack, countFailedTry) as docs/method.md "Slack
// and snap" states them; times are sums of base steps of 0.1 s. Tolerance: one base step.
TEST(LumpedLine, ASlackLineStaysInTheFallbackUntilItsCapOrWhileSlackInTheWater) {
  constexpr double dt = 0.1, step = dt + 1e-9;
  // No slack node, a rod's negative strain, or a line not in the fallback: no stay.
  PolicyLine taut(10, false);
  EXPECT_FALSE(taut.stays());
  PolicyLine rod(10, true);
  rod.Y[PolicyLine::kUnknowns * 3 + PolicyLine::kEps] = -1e-3;
  EXPECT_FALSE(rod.stays());
  // A free end at rest (half the slack band below zero strain) is not slack.
  taut.Y[PolicyLine::kEps] = -0.5 * kSlackStrain;
  EXPECT_FALSE(taut.stays());

  // Slack only on the seabed (node 0): the stay ends at the cap, 1 s; a failed try there doubles
  // the cap (2, 4, 8 s, no further), and a converged step (the solver resets the cap) ends it.
  PolicyLine grounded(10, false);
  grounded.Y[PolicyLine::kEps] = -1e-3;
  double cap = lumped::kMaxSkippedTime;
  for (int attempt = 0; attempt < 5; ++attempt) {
    EXPECT_NEAR(grounded.stayFor(dt, 100.0), cap, step) << "attempt " << attempt;
    lumped::countFailedTry(grounded, 40);
    cap = std::min(2.0 * cap, lumped::kLongestSkippedTime);
    EXPECT_DOUBLE_EQ(grounded.skipped_cap, cap);
    EXPECT_EQ(grounded.fallback_skipped_time, 0.0) << "the next run starts at the failed try";
  }
  EXPECT_EQ(grounded.totals.failed_tries, 5);
  EXPECT_EQ(grounded.totals.fallback_retries, 5);
  grounded.in_fallback = false;
  EXPECT_FALSE(grounded.stays());

  // Slack off the seabed (node 5, 2.5 m above it: chain folded or hanging loose in the water):
  // the stay goes on past the cap, up to kLongestSuspendedSlack, then the line is tried.
  PolicyLine loose(10, false);
  loose.Y[PolicyLine::kUnknowns * 5 + PolicyLine::kEps] = -0.05;
  EXPECT_NEAR(loose.stayFor(dt, 1000.0), lumped::kLongestSuspendedSlack, step);
  // Once that node has straightened (only the grounded slack left) the cap holds again.
  loose.Y[PolicyLine::kUnknowns * 5 + PolicyLine::kEps] = 1e-5;
  loose.Y[PolicyLine::kEps] = -1e-3;
  loose.fallback_skipped_time = 0.0;
  EXPECT_NEAR(loose.stayFor(dt, 1000.0), lumped::kMaxSkippedTime, step);
}

// Reference: lumped_line.hpp's retry rule (docs/method.md "Slack and snap"): a retry gets at most
// kRetryIterations iterations and keeps a Jacobian only at kRetryReuseRate; stricter options
// (fewer iterations, a lower rate) are left as they are. Exact: the rule is a minimum.
TEST(LumpedLine, ARetryGetsFewIterationsAndTheDefaultReuseRate) {
  NewtonOptions storm;
  storm.max_iterations = 16;
  storm.reuse_rate = 0.5;
  const NewtonOptions retry = lumped::retryNewtonOptions(storm);
  EXPECT_EQ(retry.max_iterations, lumped::kRetryIterations);
  EXPECT_EQ(retry.reuse_rate, lumped::kRetryReuseRate);
  EXPECT_EQ(retry.tolerance, storm.tolerance) << "only the two limits change";
  EXPECT_LT(lumped::kRetryIterations, storm.max_iterations);
  NewtonOptions strict;
  strict.max_iterations = 4;
  strict.reuse_rate = 0.05;
  const NewtonOptions kept = lumped::retryNewtonOptions(strict);
  EXPECT_EQ(kept.max_iterations, 4);
  EXPECT_EQ(kept.reuse_rate, 0.05);
}
