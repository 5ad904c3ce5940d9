// The fallback step of the 2-D dynamic solver (docs/method.md "Slack and snap: the fallback
// step"): a base step that the implicit box scheme cannot take is taken by the explicit
// lumped-mass model of the same line in its plane (lumped_line.hpp, the model of the 3-D
// solver's fallback with y = 0), and the run goes on from its end state.
//
// Back to the box unknowns (eq2dyn: eps, Sn, u, v, phi, Omega3, x, z) at the end of the step:
// the positions as they are; the inclination phi of each node from its tangent (the mean of the
// adjacent chords, t = (sin phi, cos phi)), turned by less than half a turn from the last one; the
// strain the mean of the adjacent chords' strains; the curvature from the inclinations of
// neighbouring nodes (row 5: dphi = h Omega), averaged to the nodes; the shear from the moment
// balance (row 6: Sn p^3 = -EI dOmega/ds); the velocities along t and n. The rate Yd is the change
// over the step divided by dt.
//
// Taken by the fallback: a line from its anchor to a top whose motion is prescribed (position,
// velocity, or velocity with position feedback; a surface buoy's top, which moves as prescribed in
// dynamics). Not taken (the step fails as before, with the reason added to the message): a force
// top (or a top motion given as forces), a subsurface body.
#include <cmath>
#include <cstring>
#include <sstream>

#include "dynamics2d_impl.hpp"
#include "lumped_line.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

using lumped::Line;
using lumped::NodeWater;
using lumped::Vec3;

/// The 2-D solver's side of the lumped model (lumped_line.hpp): the box rows' seabed, and the
/// ends' paths in the x-z plane.
struct Model2 {
  const DynamicSolver2D::Impl& im;
  /// The top node's offset from its path where the step starts, kept by a top prescribed by its
  /// velocity alone and shed as e^(-kappa (t - t0)) by one held by feedback (as in 3-D).
  Vec3 top_offset;
  double kappa;      ///< feedbackGain [1/s]
  double t0;         ///< the step's start [s]
  bool compression;  ///< the top interval's material carries compression
  Vec3 anchor;  ///< the anchor's position
  double seabed(const Material& m, const Vec3& x, const Vec3& v) const {
    // phi = 0: t = (0, 1), n = (1, 0), so u is the vertical velocity and v the horizontal one.
    double y[N] = {0.0};
    y[X] = x.x();
    y[Z] = x.z();
    y[U] = v.z();
    y[V] = v.x();
    return seabedReaction(im.problem.environment, m, y);
  }
  Vec3 endBodyLoad(const Body&, const Vec3&, const Vec3&) const { return Vec3::Zero(); }  // (no free end in 2-D)
  bool topHeld() const { return true; }
  bool lowHeld() const { return true; }
  Vec3 topForce(double) const { return Vec3::Zero(); }  // (the top is held)
  void top(double t, Vec3& x, Vec3& v) const {
    const TopInput in = im.top(t);
    // Held by feedback: a top interval without compression (slack, folded where the top is off)
    // goes onto the path at once, its top interval carrying nothing; one that carries compression
    // would pass the jerk on as force, and sheds the offset at the feedback's rate. A top
    // prescribed by velocity alone keeps its drift.
    const double decay = kappa > 0.0 ? (compression ? std::exp(-kappa * (t - t0)) : 0.0) : 1.0;
    x = Vec3(in.x, 0.0, in.z) + decay * top_offset;
    v = Vec3(in.vx, 0.0, in.vz) - kappa * decay * top_offset;
  }
  void low(double, Vec3& x, Vec3& v) const {
    x = anchor;
    v.setZero();
  }
};

lumped::Setup setupOf(const DynamicSolver2D::Impl& im) {
  lumped::Setup s;
  s.problem = &im.problem;
  s.mesh = &im.mesh;
  return s;
}

Vec3 nodePosition(const Eigen::VectorXd& Y, int j) { return Vec3(Y[N * j + X], 0.0, Y[N * j + Z]); }

/// The box unknowns at the lumped state (see the file comment); Y0 is the state before the step.
void toBoxState(const DynamicSolver2D::Impl& im, const Line& L, const Eigen::VectorXd& Y0, Eigen::VectorXd& Yout) {
  const int n = L.n;
  Yout = Y0;
  std::vector<double> eps_sum(n, 0.0), eps_cnt(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0)) continue;
    const double e = lumped::chordStrain(L, j);
    for (int k : {j, j + 1}) {
      eps_sum[k] += e;
      eps_cnt[k] += 1.0;
    }
  }
  for (int j = 0; j < n; ++j) {
    double* y = Yout.data() + N * j;
    if (eps_cnt[j] > 0.0) y[EPS] = eps_sum[j] / eps_cnt[j];
    const Vec3& t = L.tangent[j];
    if (t.squaredNorm() > 0.5) y[PHI] += std::remainder(std::atan2(t.x(), t.z()) - y[PHI], 2.0 * eq2d::kPi);
    y[X] = L.x[j].x();
    y[Z] = L.x[j].z();
    const double c = std::cos(y[PHI]), s = std::sin(y[PHI]);
    y[U] = L.v[j].x() * s + L.v[j].z() * c;
    y[V] = L.v[j].x() * c - L.v[j].z() * s;
  }
  // Curvature: row 5 (dphi = h Omega on each interval), averaged to the nodes.
  std::vector<double> om(n, 0.0), om_cnt(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0)) continue;
    const double k = (Yout[N * (j + 1) + PHI] - Yout[N * j + PHI]) / iv.h;
    for (int i : {j, j + 1}) {
      om[i] += k;
      om_cnt[i] += 1.0;
    }
  }
  for (int j = 0; j < n; ++j)
    if (om_cnt[j] > 0.0) Yout[N * j + OMEGA] = om[j] / om_cnt[j];
  // Shear: row 6 (EI dOmega + h Sn p^3 = 0 on each interval), averaged to the nodes.
  std::vector<double> sn(n, 0.0), sn_cnt(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0)) continue;
    const Material& m = im.problem.materials[iv.material];
    const double p3 = std::pow(std::max(1.0 + 0.5 * (Yout[N * j + EPS] + Yout[N * (j + 1) + EPS]), 1e-3), 3);
    const double S = -m.EI * (Yout[N * (j + 1) + OMEGA] - Yout[N * j + OMEGA]) / iv.h / p3;
    for (int i : {j, j + 1}) {
      sn[i] += S;
      sn_cnt[i] += 1.0;
    }
  }
  for (int j = 0; j < n; ++j)
    if (sn_cnt[j] > 0.0) Yout[N * j + SN] = sn[j] / sn_cnt[j];
}

}  // namespace

std::string fallbackUnavailable(const DynamicSolver2D::Impl& im) {
  // A surface buoy's top moves as prescribed in dynamics (its balance is the statics' alone).
  if (std::strcmp(im.upper->name(), "position top") != 0 && std::strcmp(im.upper->name(), "surface buoy") != 0)
    return std::string("no fallback step for a line whose top is a ") + im.upper->name();
  if (std::strcmp(im.lower->name(), "anchor") != 0)
    return std::string("no fallback step for a line whose lower end is a ") + im.lower->name();
  return "";
}

std::string topOffItsPath(const DynamicSolver2D::Impl& im, const Eigen::VectorXd& Yv, double t_new) {
  // As in 3-D (dynamics3d_fallback.cpp): a top held on its path by feedback is off when its node
  // is away from the path, a top prescribed by velocity alone when its node moved over the step by
  // other than the path's displacement. A top interval without compression (chain, rope) folds,
  // and its top node is off at 5 % of the interval. With a material that carries compression the
  // top node follows the feedback law, whose lag behind a fast top is no fold (a 2-D chain
  // mooring's buoy towed at 5 m/s in lockstep): only a whole interval off is refused (a rope with
  // the law through zero, pushed on by its top, whose top node had left its path by metres).
  const int n = im.nodes();
  if (!im.opt.fallback || !fallbackUnavailable(im).empty()) return "";
  const bool compression = im.mat(n - 1).compression;
  if (compression && !im.problem.dynamics.top_motion.prescribe_position) return "";
  const TopInput in = im.top(t_new);
  if (in.force) return "";
  double ex = in.x, ez = in.z;
  if (!im.problem.dynamics.top_motion.prescribe_position) {
    const TopInput in0 = im.top(im.t);
    if (in0.force) return "";
    ex = im.Y[N * (n - 1) + X] + (in.x - in0.x);
    ez = im.Y[N * (n - 1) + Z] + (in.z - in0.z);
  }
  const double off = std::hypot(Yv[N * (n - 1) + X] - ex, Yv[N * (n - 1) + Z] - ez);
  const double h = im.mesh.intervals.back().h;
  double limit = (compression ? lumped::kTopOffPathCompression : lumped::kTopOffPath) * h;
  if (!im.problem.dynamics.top_motion.prescribe_position) limit = std::min(limit, lumped::kTopRateMismatch * (t_new - im.t));
  if (!(off > limit)) return "";
  std::ostringstream os;
  os << "the top node is " << off << " m from "
     << (im.problem.dynamics.top_motion.prescribe_position ? "the top's path" : "where the top's velocity takes it")
     << " (the top interval is " << h << " m)";
  return os.str();
}

bool fallbackStep(DynamicSolver2D::Impl& im, double dt, StepReport& rep) {
  const double t0 = im.t, t1 = im.t + dt;
  std::string why = fallbackUnavailable(im);
  if (why.empty() && (im.top(t0).force || im.top(t1).force)) why = "no fallback step while the top's force is given";
  if (!why.empty()) {
    rep.message += "; " + why;
    return false;
  }
  const int n = im.nodes();
  const lumped::Setup setup = setupOf(im);
  Line L;
  lumped::lumpMasses(setup, L);
  for (int j = 0; j < n; ++j) {
    const double* y = im.Y.data() + N * j;
    double Vx, Vz;
    globalVelocity(y, Vx, Vz);
    L.x[j] = nodePosition(im.Y, j);
    L.v[j] = Vec3(Vx, 0.0, Vz);
  }
  if (im.in_fallback && im.fallback_ref.size() == L.ref.size()) {
    L.ref = im.fallback_ref;
  } else {
    std::vector<Vec3> tangent(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) tangent[static_cast<std::size_t>(j)] = Vec3(std::sin(im.Y[N * j + PHI]), 0.0, std::cos(im.Y[N * j + PHI]));
    lumped::setReferenceLengths(setup, tangent, L);
  }
  // Water at the nodes' start positions at both ends of the step.
  std::vector<NodeWater> water(static_cast<std::size_t>(n));
  for (const auto& [time, slot] : {std::make_pair(t0, &NodeWater::w0), std::make_pair(t1, &NodeWater::w1)}) {
    im.wave_cache.setTime(time);
    for (int j = 0; j < n; ++j) {
      const Water w = im.waterAt(j, L.x[j].x(), L.x[j].z());
      water[static_cast<std::size_t>(j)].*slot = Vec3(w.wx, 0.0, w.wz);
    }
  }
  const TopInput in0 = im.top(t0);
  const Vec3 offset = L.x[n - 1] - Vec3(in0.x, 0.0, in0.z);
  const Model2 model{im, offset, feedbackGain(im.problem), t0, im.mat(n - 1).compression, L.x[0]};
  long substeps = 0;
  if (!lumped::advance(setup, model, water, t0, dt, L, substeps, rep.message)) return false;
  Eigen::VectorXd Ynew;
  toBoxState(im, L, im.Y, Ynew);
  im.Yd_prev = im.Yd;
  im.Yd = (Ynew - im.Y) / dt;
  im.Y = Ynew;
  im.t = t1;
  im.last_dt = dt;
  im.waterField(im.Y, im.t, im.water);
  im.spatialRows(im.Y, im.water, im.S, im.cos_phi, im.sin_phi);
  im.newton_matrix.setZero();  // a kept factorization belongs to the state before
  lumped::countFallbackStep(im, rep, substeps, L);
  return true;
}

bool stayInFallback(const DynamicSolver2D::Impl& im) {
  return lumped::staySlack(im, N, EPS, X, -1, Z);
}

}  // namespace core
}  // namespace mooring_dynamics
