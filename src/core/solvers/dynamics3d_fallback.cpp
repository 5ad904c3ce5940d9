// The fallback step of the 3-D dynamic solver (docs/method.md "Slack and snap: the fallback
// step"): a base step that the implicit box scheme cannot take, even cut to its smallest size
// (section 4.3), is taken by the explicit lumped-mass model of the same line over the same
// interval (lumped_line.hpp, shared with the 2-D solver), and the run goes on from its end state.
//
// Back to the box unknowns at the end of the step: the positions as they are; the frame of each
// node turned by the smallest rotation from its last tangent to the new one (mean of the
// adjacent chords), the strain the mean of the adjacent chords' strains, the curvature from the
// relative rotation of neighbouring frames, the shear from the moment balance, the velocities
// in the new frames. The rate Yd is the change over the step divided by dt. The next implicit
// step starts from there; while the line stays folded it fails and falls back again.
//
// Not taken by the fallback (the step then fails as before, with the reason added to the
// message): a drifting-buoy top, a top whose force is given (a force top, a force table on a
// driven top: massless in the box rows, see docs/method.md), a step in which the winch runs
// (fallbackUnavailable()). A body at a free lower end, or a subsurface body at the top, is a
// lumped mass (its mass plus added mass) at the end node with its weight and drag, as the box
// rows' end balance has them; a force table's force on the subsurface body pulls that node. A
// top on a path follows it, the anchor stays (or follows its motion); a released end is a free
// node.
#include "dynamics3d_impl.hpp"
#include "lumped_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "mooring_dynamics/core/model/quaternion.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

using lumped::kTopOffPath;

using Vec3 = Eigen::Vector3d;

using lumped::Line;
using lumped::NodeWater;

/// What the fallback does with the line's ends over a step that ends at t_new: held on their
/// paths, or free nodes (released; a subsurface body, pulled by a force table's force if any).
struct Ends {
  std::string top, low;  ///< the end conditions' names
  bool top_held, top_free, low_held, low_free;
  bool top_unloaded;  ///< a released top: free and pulled by nothing
  bool top_pulled;    ///< a free top pulled by the top input's force (TopState::force)
  bool top_force;     ///< the top input gives a force at t_new
};
Ends endsOf(const DynamicSolver3D::Impl& im, double t_new) {
  Ends e;
  e.top = im.upper->name();
  e.low = im.lower->name();
  // A surface buoy's top moves as prescribed in dynamics (its balance is the statics' alone).
  // A driven top whose force is given (DrivenTop3D's prescribed force) is neither: refused.
  const bool driven = e.top == "position top" || e.top == "force top" || e.top == "surface buoy";
  e.top_force = im.top(t_new).force;
  e.top_held = (driven && !e.top_force) || e.top == "tow point";
  e.top_unloaded = e.top == "released top";
  e.top_pulled = e.top_force && e.top == "subsurface body";
  e.top_free = e.top_unloaded || e.top == "subsurface body";
  e.low_held = e.low == "anchor" || e.low == "moving anchor";
  e.low_free = e.low == "released lower end" || e.low == "free end" || e.low == "free end with body";
  return e;
}

/// The body at a free lower end (a tow body, a weight on a hanging line), or nullptr.
const Body* endBody(const DynamicSolver3D::Impl& im) {
  if (im.problem.end_body == Problem::kNoBody || std::strcmp(im.lower->name(), "free end with body") != 0)
    return nullptr;
  return &im.problem.bodies[im.problem.end_body];
}

/// The subsurface body at the top, or nullptr.
const Body* topBody(const DynamicSolver3D::Impl& im) {
  if (std::strcmp(im.upper->name(), "subsurface body") != 0) return nullptr;
  return &im.problem.bodies[im.problem.top.body];
}

}  // namespace

std::string fallbackUnavailable(const DynamicSolver3D::Impl& im, double t_new) {
  const Ends e = endsOf(im, t_new);
  if (e.top_force && !e.top_free) return "no fallback step while the top's force is given";
  if (!(e.top_held || e.top_free)) return "no fallback step for a line whose top is a " + e.top;
  if (!(e.low_held || e.low_free)) return "no fallback step for a line whose lower end is a " + e.low;
  // The winch's rate is set only inside an implicit step: ask its program whether the length
  // moves over this one (a step past a limit is refused by the implicit step, and stays refused).
  const WinchState& w = im.winch;
  if (w.active() && w.program.lengthAt(t_new) != w.length) return "no fallback step while the winch runs";
  return "";
}

std::string topOffItsPath(const DynamicSolver3D::Impl& im, const Eigen::VectorXd& Yv, double t_new) {
  // A position top that follows its path by feedback (prescribe: position, every vessel line) is
  // off when its node is away from the path; a top prescribed by velocity alone drifts from the
  // path by design (docs/method.md "Top boundary"), and is off when its node moved over the step
  // by other than the path's displacement (an implicit step after a fallback step moved such a top
  // by 3-8 cm in one 1 ms step with the top at rest, on a 1 m mesh). Only a top interval without
  // compression (chain, rope) folds: a material that carries compression has its strain, and so
  // its coordinates, set by the equations.
  const int n = im.nodes();
  if (!im.opt.fallback || std::strcmp(im.upper->name(), "position top") != 0 || im.mat(n - 1).compression ||
      !fallbackUnavailable(im, t_new).empty())
    return "";
  const TopState s = im.top(t_new);
  if (s.force) return "";
  auto node = [n](const Eigen::VectorXd& y) { return Vec3(y[N * (n - 1) + X], y[N * (n - 1) + Y], y[N * (n - 1) + Z]); };
  Vec3 expected(s.x, s.y, s.z);
  if (!im.problem.dynamics.top_motion.prescribe_position) {
    const TopState s0 = im.top(im.t);
    if (s0.force) return "";
    expected = node(im.Y) + (expected - Vec3(s0.x, s0.y, s0.z));
  }
  const double off = (node(Yv) - expected).norm();
  const double h = im.mesh.intervals.back().h;
  double limit = kTopOffPath * h;
  if (!im.problem.dynamics.top_motion.prescribe_position) limit = std::min(limit, lumped::kTopRateMismatch * (t_new - im.t));
  if (!(off > limit)) return "";
  std::ostringstream os;
  os << "the top node is " << off << " m from " << (im.problem.dynamics.top_motion.prescribe_position ? "the top's path" : "where the top's velocity takes it")
     << " (the top interval is " << h << " m)";
  return os.str();
}

namespace {

/// The 3-D solver's side of the lumped model (lumped_line.hpp): the box rows' seabed and end
/// body load, and the ends' paths.
struct Model3 {
  const DynamicSolver3D::Impl& im;
  bool top_held, low_held;
  Vec3 anchor0;  ///< the anchor where the step starts (it stays there unless it moves)
  /// The top node's offset from its path where the step starts. A top prescribed by its velocity
  /// alone keeps it (it drifts from the path by design, docs/method.md "Top boundary"); a top
  /// held by position feedback sheds it as the implicit step's feedback does, e^(-kappa (t - t0))
  /// with kappa = feedbackGain: a top pulled onto its path at once would jerk the line (a rope
  /// whose top node had left its path by metres snapped to 640 kN).
  Vec3 top_offset;
  double kappa;      ///< feedbackGain [1/s]
  double t0;         ///< the step's start [s]
  bool compression;  ///< the top interval's material carries compression
  double dt;         ///< the step [s]
  bool top_pulled;   ///< a free top pulled by the top input's force
  double seabed(const Material& m, const Vec3& x, const Vec3& v) const {
    double y[N] = {0.0};
    y[X] = x.x();
    y[eq3d::Y] = x.y();
    y[Z] = x.z();
    y[U1] = v.x();
    y[U2] = v.y();
    y[U3] = v.z();
    const double Rid[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // local = global: R[6..8] picks V_z
    return seabedReaction(im.problem.environment, m, y, Rid);
  }
  Vec3 endBodyLoad(const Body& b, const Vec3& tangent, const Vec3& r) const {
    double P[3] = {0.0, 0.0, 0.0};
    eq3d::addBodyLoad(im.problem.environment, b, tangent.data(), r.data(), P);
    return Vec3(P[0], P[1], P[2]);
  }
  bool topHeld() const { return top_held; }
  bool lowHeld() const { return low_held; }
  /// The force on a free top at fraction w of the step [N] (problem frame): the top input's, as
  /// the box rows take it (DrivenTop3D's prescribed force, the subsurface body's extra force).
  Vec3 topForce(double w) const {
    if (!top_pulled) return Vec3::Zero();
    const TopState s = im.top(t0 + w * dt);
    return s.force ? Vec3(s.fx, s.fy, s.fz) : Vec3::Zero();
  }
  void top(double t, Vec3& x, Vec3& v) const {
    const TopState s = im.top(t);
    // Held by feedback: a top interval without compression (slack, folded where the top is off)
    // goes onto the path at once, its top interval carrying nothing; one that carries compression
    // would pass the jerk on as force, and sheds the offset at the feedback's rate. A top
    // prescribed by velocity alone keeps its drift.
    const double decay = kappa > 0.0 ? (compression ? std::exp(-kappa * (t - t0)) : 0.0) : 1.0;
    x = Vec3(s.x, s.y, s.z) + decay * top_offset;
    v = Vec3(s.vx, s.vy, s.vz) - kappa * decay * top_offset;
  }
  void low(double t, Vec3& x, Vec3& v) const {
    if (im.lower_path) {
      const TopState s = im.lower_path(t);
      x = Vec3(s.x, s.y, s.z);
      v = Vec3(s.vx, s.vy, s.vz);
    } else {
      x = anchor0;
      v.setZero();
    }
  }
};

lumped::Setup setupOf(const DynamicSolver3D::Impl& im) {
  lumped::Setup s;
  s.problem = &im.problem;
  s.mesh = &im.mesh;
  s.parted = im.parted;
  s.end_body = endBody(im);
  s.top_body = topBody(im);
  return s;
}

/// The line's state as lumped masses at the nodes.
void lumpLine(const DynamicSolver3D::Impl& im, Line& L) {
  lumped::lumpMasses(setupOf(im), L);
  for (int j = 0; j < L.n; ++j) {
    const double* y = im.Y.data() + N * j;
    L.x[j] = Vec3(y[X], y[eq3d::Y], y[Z]);
    double V[3];
    globalVelocity(y, V);
    L.v[j] = Vec3(V[0], V[1], V[2]);
  }
  if (im.in_fallback && im.fallback_ref.size() == L.ref.size()) {
    L.ref = im.fallback_ref;
    return;
  }
  std::vector<Vec3> tangent(static_cast<std::size_t>(L.n));
  for (int j = 0; j < L.n; ++j) {
    double R[9];
    quat::matrix(im.Y.data() + N * j + Q0, R);
    tangent[static_cast<std::size_t>(j)] = Vec3(R[0], R[3], R[6]).normalized();
  }
  lumped::setReferenceLengths(setupOf(im), tangent, L);
}

/// Smallest rotation taking unit vector a to unit vector b, as a quaternion (w, x, y, z).
void rotationBetween(const Vec3& a, const Vec3& b, double* q) {
  const double c = a.dot(b);
  if (c < -1.0 + 1e-12) {  // opposite: a half turn about any axis normal to a
    Vec3 axis = a.cross(Vec3::UnitX());
    if (axis.norm() < 1e-6) axis = a.cross(Vec3::UnitY());
    axis.normalize();
    q[0] = 0.0;
    q[1] = axis.x();
    q[2] = axis.y();
    q[3] = axis.z();
    return;
  }
  const Vec3 ax = a.cross(b);
  const double s = std::sqrt(2.0 * (1.0 + c));
  q[0] = 0.5 * s;
  q[1] = ax.x() / s;
  q[2] = ax.y() / s;
  q[3] = ax.z() / s;
}

/// The box unknowns at the lumped state (see the file comment); Y0 is the state before the step.
void toBoxState(const DynamicSolver3D::Impl& im, const Line& L, const Eigen::VectorXd& Y0, Eigen::VectorXd& Yout) {
  const int n = L.n;
  Yout = Y0;
  // Strain: the mean of the adjacent chords' strains.
  std::vector<double> eps_sum(n, 0.0), eps_cnt(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    const double e = lumped::chordStrain(L, j);
    for (int k : {j, j + 1}) {
      eps_sum[k] += e;
      eps_cnt[k] += 1.0;
    }
  }
  // A free end without a body carries no tension: its strain is the material's at zero tension
  // (with a body it carries the body's weight and drag: the chord's strain stays).
  const Ends ends = endsOf(im, im.t);
  const bool low_unloaded = ends.low_free && !endBody(im);
  for (int j = 0; j < n; ++j) {
    double* y = Yout.data() + N * j;
    const double* y0 = Y0.data() + N * j;
    if (eps_cnt[j] > 0.0) y[EPS] = eps_sum[j] / eps_cnt[j];
    if ((j == n - 1 && ends.top_unloaded) || (j == 0 && low_unloaded)) y[EPS] = im.mat(j).strainAt(0.0);
    // Frame: the last frame turned by the smallest rotation from its tangent to the new one.
    double R0[9];
    quat::matrix(y0 + Q0, R0);
    const Vec3 e1_old(R0[0], R0[3], R0[6]);
    if (L.tangent[j].squaredNorm() > 0.5) {
      double r[4], q[4];
      rotationBetween(e1_old.normalized(), L.tangent[j], r);
      quat::multiply(r, y0 + Q0, q);
      const double qn = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      for (int i = 0; i < 4; ++i) y[Q0 + i] = q[i] / qn;
    }
    y[X] = L.x[j].x();
    y[eq3d::Y] = L.x[j].y();
    y[Z] = L.x[j].z();
    double R[9];
    quat::matrix(y + Q0, R);
    const double V[3] = {L.v[j].x(), L.v[j].y(), L.v[j].z()};
    quat::toLocal(R, V, y + U1);
  }
  // Curvature and twist: the relative rotation of neighbouring frames over each interval,
  // q_b = q_a (x) exp(h Omega / 2) (the frame rows), averaged to the nodes.
  std::vector<Vec3> om_sum(n, Vec3::Zero());
  std::vector<double> om_cnt(n, 0.0);
  std::vector<Vec3> om_iv(n > 0 ? n - 1 : 0, Vec3::Zero());
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    double r[4];
    quat::relative(Yout.data() + N * j + Q0, Yout.data() + N * (j + 1) + Q0, r);
    if (r[0] < 0.0)
      for (double& c : r) c = -c;
    const double sv = std::sqrt(r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    const double angle = 2.0 * std::atan2(sv, r[0]);
    const Vec3 axis = sv > 1e-15 ? Vec3(r[1] / sv, r[2] / sv, r[3] / sv) : Vec3::Zero();
    om_iv[j] = axis * (angle / iv.h);
    for (int k : {j, j + 1}) {
      om_sum[k] += om_iv[j];
      om_cnt[k] += 1.0;
    }
  }
  for (int j = 0; j < n; ++j) {
    if (om_cnt[j] == 0.0) continue;
    double* y = Yout.data() + N * j;
    const Vec3 om = om_sum[j] / om_cnt[j];
    y[O1] = om.x();
    y[O2] = om.y();
    y[O3] = om.z();
  }
  // Shear from the moment balance (row 6 of the box scheme): S3 = EI dO2/ds / p^3,
  // S2 = -EI dO3/ds / p^3, the slope of each interval averaged to its nodes.
  std::vector<double> s2(n, 0.0), s3(n, 0.0), sc(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    const Material& m = im.problem.materials[iv.material];
    const double* ya = Yout.data() + N * j;
    const double* yb = ya + N;
    const double p3 = std::pow(std::max(1.0 + 0.5 * (ya[EPS] + yb[EPS]), 1e-3), 3);
    const double dO2 = (yb[O2] - ya[O2]) / iv.h, dO3 = (yb[O3] - ya[O3]) / iv.h;
    for (int k : {j, j + 1}) {
      s3[k] += m.EI * dO2 / p3;
      s2[k] -= m.EI * dO3 / p3;
      sc[k] += 1.0;
    }
  }
  for (int j = 0; j < n; ++j) {
    if (sc[j] == 0.0) continue;
    Yout[N * j + S2] = s2[j] / sc[j];
    Yout[N * j + S3] = s3[j] / sc[j];
  }
}

}  // namespace

bool fallbackStep(DynamicSolver3D::Impl& im, double dt, StepReport& rep) {
  const std::string why = fallbackUnavailable(im, im.t + dt);
  if (!why.empty()) {
    rep.message += "; " + why;
    return false;
  }
  const int n = im.nodes();
  const double t0 = im.t, t1 = im.t + dt;
  Line L;
  lumpLine(im, L);
  // Water at the nodes' start positions at both ends of the step.
  std::vector<NodeWater> water(static_cast<std::size_t>(n));
  for (const auto& [time, slot] : {std::make_pair(t0, &NodeWater::w0), std::make_pair(t1, &NodeWater::w1)}) {
    im.wave_cache.setTime(time);
    for (int j = 0; j < n; ++j) {
      const Water w = im.waterAt(j, L.x[j].x(), L.x[j].y(), L.x[j].z());
      water[static_cast<std::size_t>(j)].*slot = Vec3(w.w[0], w.w[1], w.w[2]);
    }
  }
  // Which ends are held: the top on its path, the anchor where it is (or on its path).
  const Ends ends = endsOf(im, t1);
  Vec3 top_offset = Vec3::Zero();
  if (ends.top_held) {
    const TopState s = im.top(t0);
    top_offset = L.x[n - 1] - Vec3(s.x, s.y, s.z);
  }
  // A winch's top holds its position by feedback once a program was set (as its rows do).
  const double kappa = im.winch.used ? 1.0 / (kPositionFeedbackSteps * im.problem.dynamics.dt) : feedbackGain(im.problem);
  const Model3 model{im,    ends.top_held, ends.low_held, L.x[0], top_offset, kappa, t0, im.mat(n - 1).compression,
                     dt, ends.top_pulled};
  long substeps = 0;
  if (!lumped::advance(setupOf(im), model, water, t0, dt, L, substeps, rep.message)) return false;
  Eigen::VectorXd Ynew;
  toBoxState(im, L, im.Y, Ynew);
  im.Yd_prev = im.Yd;
  im.Yd = (Ynew - im.Y) / dt;
  im.Y = Ynew;
  im.t = t1;
  im.last_dt = dt;
  im.waterField(im.Y, im.t, im.water);
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, im.t);
  rowsChanged(im);
  lumped::countFallbackStep(im, rep, substeps, L);
  return true;
}

bool stayInFallback(const DynamicSolver3D::Impl& im) {
  return lumped::staySlack(im, N, EPS, X, eq3d::Y, Z);
}

}  // namespace core
}  // namespace mooring_dynamics
