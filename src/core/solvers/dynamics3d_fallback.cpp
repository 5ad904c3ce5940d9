// The fallback step of the 3-D dynamic solver (docs/method.md "Slack and snap: the fallback
// step"): a base step that the implicit box scheme cannot take, even cut to its smallest size
// (section 4.3), is taken by an explicit lumped-mass model of the same line over the same
// interval, and the run goes on from its end state.
//
// Why: a line whose top goes wholly slack and is then overrun by its fairlead (the fairlead
// moving down faster than the chain sinks) folds back on itself. The box scheme's unknowns
// (strain, frame and curvature at the nodes) cannot follow a fold within one step, and Newton
// fails at every step size. A lumped-mass line has no such limit: each node keeps its own
// inertia and moves freely while its neighbours carry no tension.
//
// The model (the same physics as the box rows, lumped at the nodes):
//  * masses: the line's mass per unit length times half of each adjacent interval, its added
//    mass acting across the local tangent only; inline bodies at their junction node;
//  * axial force of each interval from its chord length, T(eps) of the material (with its
//    no-compression law where it has one), plus a proportional axial damping of ratio
//    kAxialDampingRatio of the interval's own axial mode (the box scheme's numerical dissipation
//    of the mesh mode plays that part in the implicit steps);
//  * wet weight, normal and tangential quadratic drag on the velocity relative to the water
//    (current and waves) on each interval's chord, times sqrt(1 + eps) as in the box rows;
//  * the seabed as in the box rows (spring with its contact onset, dashpot);
//  * bending and torsion are left out (chain and rope: EI is negligible next to the axial
//    forces over a step; the fallback serves lines that fold, not rods);
//  * the top follows its prescribed path, the anchor stays (or follows its motion); a released
//    end is a free node.
// Time integration: symplectic Euler on sub-steps of kCourant times the shortest axial wave
// crossing time of an interval (and of the seabed spring's period), so that the snap's wave is
// resolved. The water velocity is taken at the nodes' positions at the start of the step, at
// both ends of the step, linear in time between.
//
// Back to the box unknowns at the end of the step: the positions as they are; the frame of each
// node turned by the smallest rotation from its last tangent to the new one (mean of the
// adjacent chords), the strain the mean of the adjacent chords' strains, the curvature from the
// relative rotation of neighbouring frames, the shear from the moment balance, the velocities
// in the new frames. The rate Yd is the change over the step divided by dt. The next implicit
// step starts from there; while the line stays folded it fails and falls back again.
//
// Not taken by the fallback (the step then fails as before, with the reason added to the
// message): a force, buoy, body or drifting-buoy top, a step in which the winch runs
// (fallbackUnavailable()). A body at a free lower end is a lumped mass (its mass plus added
// mass) at node 0 with its weight and drag.
#include "dynamics3d_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "mooring_dynamics/core/model/quaternion.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

/// Axial damping ratio of each interval's own axial mode (the highest mode of the lumped line,
/// ~ 2 sqrt(EA/m)/h): proportional damping, so a mode of frequency w gets kAxialDampingRatio
/// w / w_max, which leaves the line's physical modes (w << w_max) all but undamped.
constexpr double kAxialDampingRatio = 0.5;
/// Sub-step as a fraction of the stability limit of symplectic Euler (2 / w_max).
constexpr double kCourant = 0.4;
/// A node whose strain is below -kFoldedStrain (its intervals 0.1 % shorter than unstretched:
/// chain heaped or folded, carrying no tension) marks the line as still folded after a fallback
/// step. On the spread mooring at Hs 4 (30 s, 317 implicit tries right after a fallback step)
/// 297 of the 302 tries from a folded state failed, and 11 of the 15 from an unfolded one
/// converged; the five folded ones that converged were within -1.1e-4 of zero.
constexpr double kFoldedStrain = 1e-3;
/// For at most this long [s] of simulated time in a row base steps go to the fallback without an
/// implicit try (whatever the steps' length: in lockstep every sample ends a step): a
/// heap of chain lying on the seabed can keep a line "folded" long after the implicit step could
/// take it again.
constexpr double kMaxSkippedTime = 1.0;
/// A converged implicit step whose top node is farther than this fraction of the top interval
/// from the top's path is refused (topOffItsPath). With the top interval folded the box
/// scheme's coordinates there are all but free: on the spread mooring at Hs 6 with 17.5 m
/// intervals the top node wandered up to 13.8 m from its fairlead (median 0.35 m), and its
/// strain rang from -6 % to +0.7 % in 0.01 s steps (3.7 MN spikes with the fairlead moving at
/// 0.5 m/s). At 3.5 m intervals the top stayed within 0.15 m (4 %) through 150 s of Hs 6.
constexpr double kTopOffPath = 0.05;
/// A chord shorter than this fraction of its interval has no direction of its own [-].
constexpr double kShortChord = 1e-6;

using Vec3 = Eigen::Vector3d;

struct Lumped {
  int n = 0;
  std::vector<Vec3> x, v, f;
  std::vector<double> drag_rate;  ///< d|drag| / d|v| at the node [N s/m] (semi-implicit drag)
  std::vector<double> mass;       ///< structural mass [kg]
  std::vector<double> added;      ///< added mass across the tangent [kg] (line)
  std::vector<double> body_mass;  ///< inline bodies' mass plus added mass [kg] (isotropic)
  std::vector<Vec3> tangent;      ///< unit tangent at the node (mean of the chords)
  std::vector<char> fixed;        ///< prescribed (top, anchor) or tied to the node below (junction)
};

struct Water3 {
  Vec3 w0, w1;  ///< water velocity at the start and end of the step
};

double sqr(double a) { return a * a; }

/// What the fallback does with the line's ends: held on their paths, or free (released).
struct Ends {
  std::string top, low;  ///< the end conditions' names
  bool top_held, top_free, low_held, low_free;
};
Ends endsOf(const DynamicSolver3D::Impl& im) {
  Ends e;
  e.top = im.upper->name();
  e.low = im.lower->name();
  e.top_held = e.top == "position top" || e.top == "tow point";
  e.top_free = e.top == "released top";
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

}  // namespace

std::string fallbackUnavailable(const DynamicSolver3D::Impl& im, double t_new) {
  const Ends e = endsOf(im);
  if (!(e.top_held || e.top_free)) return "no fallback step for a line whose top is a " + e.top;
  if (!(e.low_held || e.low_free)) return "no fallback step for a line whose lower end is a " + e.low;
  // The winch's rate is set only inside an implicit step: ask its program whether the length
  // moves over this one (a step past a limit is refused by the implicit step, and stays refused).
  const WinchState& w = im.winch;
  if (w.active() && w.program.lengthAt(t_new) != w.length) return "no fallback step while the winch runs";
  return "";
}

std::string topOffItsPath(const DynamicSolver3D::Impl& im, const Eigen::VectorXd& Yv, double t_new) {
  // Only a position top that follows its path by feedback (prescribe: position, every vessel
  // line) has a position to be off; a top prescribed by velocity alone drifts by design. Only a
  // top interval without compression (chain, rope) folds: a material that carries compression
  // has its strain, and so its coordinates, set by the equations.
  const int n = im.nodes();
  if (!im.opt.fallback || std::strcmp(im.upper->name(), "position top") != 0 ||
      !im.problem.dynamics.top_motion.prescribe_position || im.mat(n - 1).compression ||
      !fallbackUnavailable(im, t_new).empty())
    return "";
  const TopState s = im.top(t_new);
  if (s.force) return "";
  const double off = (Vec3(Yv[N * (n - 1) + X], Yv[N * (n - 1) + Y], Yv[N * (n - 1) + Z]) - Vec3(s.x, s.y, s.z)).norm();
  const double h = im.mesh.intervals.back().h;
  if (!(off > kTopOffPath * h)) return "";
  std::ostringstream os;
  os << "the top node is " << off << " m from the top's path (the top interval is " << h << " m)";
  return os.str();
}

namespace {

/// The line's state as lumped masses at the nodes; junction nodes (h = 0) are tied to the node
/// below them.
void lumpLine(const DynamicSolver3D::Impl& im, Lumped& L) {
  const int n = im.nodes();
  L.n = n;
  L.x.assign(n, Vec3::Zero());
  L.v.assign(n, Vec3::Zero());
  L.f.assign(n, Vec3::Zero());
  L.drag_rate.assign(n, 0.0);
  L.mass.assign(n, 0.0);
  L.added.assign(n, 0.0);
  L.body_mass.assign(n, 0.0);
  L.tangent.assign(n, Vec3::Zero());
  L.fixed.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    const double* y = im.Y.data() + N * j;
    L.x[j] = Vec3(y[X], y[eq3d::Y], y[Z]);
    double V[3];
    globalVelocity(y, V);
    L.v[j] = Vec3(V[0], V[1], V[2]);
  }
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (iv.h > 0.0) {
      const Material& m = im.problem.materials[iv.material];
      for (int k : {j, j + 1}) {
        L.mass[k] += 0.5 * iv.h * m.mass;
        L.added[k] += 0.5 * iv.h * m.added_mass;
      }
    } else {
      for (std::size_t b : iv.bodies) {
        const Body& body = im.problem.bodies[b];
        L.body_mass[j] += body.mass + body.added_mass;
      }
    }
  }
  if (const Body* b = endBody(im)) L.body_mass[0] += b->mass + b->added_mass;
}

/// Unit tangents at the nodes: the mean of the adjacent chords' directions (one-sided at the
/// ends and junctions).
void updateTangents(const DynamicSolver3D::Impl& im, Lumped& L) {
  const int n = L.n;
  for (int j = 0; j < n; ++j) L.tangent[j].setZero();
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    const Vec3 d = L.x[j + 1] - L.x[j];
    const double len = d.norm();
    if (len < kShortChord * iv.h) continue;
    L.tangent[j] += d / len;
    L.tangent[j + 1] += d / len;
  }
  for (int j = 0; j < n; ++j) {
    const double t = L.tangent[j].norm();
    if (t > 1e-9) L.tangent[j] /= t;
  }
}

/// Forces on the lumped nodes at time fraction `w` of the step [N].
void lumpedForces(const DynamicSolver3D::Impl& im, const std::vector<Water3>& water, double w, Lumped& L) {
  const Environment& env = im.problem.environment;
  const double rho = env.water_density;
  const int n = L.n;
  for (int j = 0; j < n; ++j) {
    L.f[j].setZero();
    L.drag_rate[j] = 0.0;
  }
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0)) {
      // Junction: the inline bodies' weight and sphere-like drag at the lower node.
      const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
      for (std::size_t b : iv.bodies) {
        const Body& body = im.problem.bodies[b];
        L.f[j].z() -= body.wet_weight;
        const Vec3 r = wv - L.v[j];
        const double area = 0.25 * eq2d::kPi * sqr(body.diameter);
        L.f[j] += 0.5 * rho * body.isotropicCd() * area * r.norm() * r;
      }
      continue;
    }
    const Material& m = im.problem.materials[iv.material];
    const double h = iv.h;
    // Weight, half to each end.
    L.f[j].z() -= 0.5 * h * m.wet_weight;
    L.f[j + 1].z() -= 0.5 * h * m.wet_weight;
    if (j == im.parted) continue;  // a parted interval carries no force between its nodes
    const Vec3 d = L.x[j + 1] - L.x[j];
    const double len = d.norm();
    const double eps = len / h - 1.0;
    Vec3 t = len > kShortChord * h ? Vec3(d / len) : Vec3(L.tangent[j]);
    // Axial force with proportional damping on the strain rate; a line without compression
    // neither pushes nor pulls back through the damper below zero tension.
    const double eps_rate = len > kShortChord * h ? t.dot(L.v[j + 1] - L.v[j]) / h : 0.0;
    const double slope = std::max(m.rawTensionSlope(std::max(eps, 0.0)), 0.0);
    double T = m.tension(eps) + kAxialDampingRatio * std::sqrt(slope * m.mass) * h * eps_rate;
    if (!m.compression) T = m.tension(eps) > 0.0 ? std::max(T, 0.0) : 0.0;
    L.f[j] += T * t;
    L.f[j + 1] -= T * t;
    // Drag on the chord at its mid-point velocity relative to the water.
    const Vec3 wv = 0.5 * ((1.0 - w) * (water[j].w0 + water[j + 1].w0) + w * (water[j].w1 + water[j + 1].w1));
    const Vec3 vr = 0.5 * (L.v[j] + L.v[j + 1]) - wv;
    const double vt = vr.dot(t);
    const Vec3 vn = vr - vt * t;
    const double stretch = std::sqrt(std::max(1.0 + eps, 0.0));
    const double vnn = std::sqrt(vn.squaredNorm() + sqr(eq3d::kDragSpeedFloor));
    const Vec3 drag = -0.5 * rho * m.diameter * h * stretch *
                      (m.cdn * vnn * vn + eq2d::kPi * m.cdt * std::abs(vt) * vt * t);
    L.f[j] += 0.5 * drag;
    L.f[j + 1] += 0.5 * drag;
    // The drag's rate of change with the node's speed (quadratic drag: twice the force per unit
    // speed), half to each node: the update treats the drag implicitly with it.
    const double rate = 0.5 * rho * m.diameter * h * stretch * 2.0 *
                        std::max(m.cdn * vnn, eq2d::kPi * m.cdt * std::abs(vt));
    L.drag_rate[j] += 0.25 * rate;
    L.drag_rate[j + 1] += 0.25 * rate;
  }
  // The body at a free lower end: its weight and drag (addBodyLoad, as the box rows' end balance)
  // on the velocity relative to the water at node 0, taken semi-implicitly as the line's.
  if (const Body* b = endBody(im)) {
    const Vec3 wv = (1.0 - w) * water[0].w0 + w * water[0].w1;
    const Vec3 r = wv - L.v[0];
    double P[3] = {0.0, 0.0, 0.0};
    eq3d::addBodyLoad(env, *b, L.tangent[0].data(), r.data(), P);
    L.f[0] += Vec3(P[0], P[1], P[2]);
    const double q = 0.5 * rho * 0.25 * eq2d::kPi * sqr(b->diameter);
    const double cd = b->drag == Body::Drag::Sphere ? b->cd : std::max(b->cdn, b->cdt);
    L.drag_rate[0] += q * cd * 2.0 * r.norm();
  }
  // The seabed (eq. 35-36 with the box rows' contact onset) on each node's tributary length.
  for (int j = 0; j < n; ++j) {
    double hj = 0.0;
    const Material* m = nullptr;
    for (int k : {j - 1, j}) {
      if (k < 0 || k + 1 >= n) continue;
      const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(k)];
      if (iv.h > 0.0) {
        hj += 0.5 * iv.h;
        m = &im.problem.materials[iv.material];
      }
    }
    if (!m) continue;
    double y[N] = {0.0};
    y[X] = L.x[j].x();
    y[eq3d::Y] = L.x[j].y();
    y[Z] = L.x[j].z();
    y[U1] = L.v[j].x();
    y[U2] = L.v[j].y();
    y[U3] = L.v[j].z();
    const double Rid[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // local = global: R[6..8] picks V_z
    const double Fbot = seabedReaction(env, *m, y, Rid);
    L.f[j].z() += hj * Fbot;
  }
}

/// The largest stable sub-step [s]: kCourant times 2 / w_max of the stiffest interval's axial
/// mode (and of each node's seabed spring).
double stableSubstep(const DynamicSolver3D::Impl& im, const Lumped& L) {
  const int n = L.n;
  double wmax = 0.0;
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    const Material& m = im.problem.materials[iv.material];
    const double len = (L.x[j + 1] - L.x[j]).norm();
    const double eps = len / iv.h - 1.0;
    // Stiffness of the chord k = EA_t / h (tangent slope, at least the slope at zero strain:
    // the line may be about to snap) between two masses m h / 2.
    const double slope = std::max(m.rawTensionSlope(std::max(eps, 0.0)), m.rawTensionSlope(0.0));
    const double k = slope / iv.h;
    const double mj = std::min(L.mass[j] + L.body_mass[j], L.mass[j + 1] + L.body_mass[j + 1]);
    wmax = std::max(wmax, std::sqrt(4.0 * k / std::max(mj, 1e-12)));
    wmax = std::max(wmax, std::sqrt(im.problem.environment.seabed.stiffness * iv.h / std::max(mj, 1e-12)));
  }
  return wmax > 0.0 ? kCourant * 2.0 / wmax : 1e-3;
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
void toBoxState(const DynamicSolver3D::Impl& im, const Lumped& L, const Eigen::VectorXd& Y0, Eigen::VectorXd& Yout) {
  const int n = L.n;
  Yout = Y0;
  // Strain: the mean of the adjacent chords' strains.
  std::vector<double> eps_sum(n, 0.0), eps_cnt(n, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = im.mesh.intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == im.parted) continue;
    const double e = (L.x[j + 1] - L.x[j]).norm() / iv.h - 1.0;
    for (int k : {j, j + 1}) {
      eps_sum[k] += e;
      eps_cnt[k] += 1.0;
    }
  }
  // A free end without a body carries no tension: its strain is the material's at zero tension
  // (with a body it carries the body's weight and drag: the chord's strain stays).
  const Ends ends = endsOf(im);
  const bool low_unloaded = ends.low_free && !endBody(im);
  for (int j = 0; j < n; ++j) {
    double* y = Yout.data() + N * j;
    const double* y0 = Y0.data() + N * j;
    if (eps_cnt[j] > 0.0) y[EPS] = eps_sum[j] / eps_cnt[j];
    if ((j == n - 1 && ends.top_free) || (j == 0 && low_unloaded)) y[EPS] = im.mat(j).strainAt(0.0);
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
  Lumped L;
  lumpLine(im, L);
  // Water at the nodes' start positions at both ends of the step.
  std::vector<Water3> water(static_cast<std::size_t>(n));
  for (const auto& [time, slot] : {std::make_pair(t0, &Water3::w0), std::make_pair(t1, &Water3::w1)}) {
    im.wave_cache.setTime(time);
    for (int j = 0; j < n; ++j) {
      const Water w = im.waterAt(j, L.x[j].x(), L.x[j].y(), L.x[j].z());
      water[static_cast<std::size_t>(j)].*slot = Vec3(w.w[0], w.w[1], w.w[2]);
    }
  }
  // Which ends are held: the top on its path, the anchor where it is (or on its path).
  const Ends ends = endsOf(im);
  const bool top_held = ends.top_held, anchor_held = ends.low_held;
  const Vec3 anchor0 = L.x[0];
  const std::function<TopState(double)>* anchor_path = im.lower_path ? &im.lower_path : nullptr;
  // Tie junction nodes (h = 0) to the node below them.
  std::vector<int> tie(static_cast<std::size_t>(n), -1);
  for (int j = 0; j + 1 < n; ++j)
    if (!(im.mesh.intervals[static_cast<std::size_t>(j)].h > 0.0)) tie[static_cast<std::size_t>(j) + 1] = j;

  const double hsub = std::min(stableSubstep(im, L), dt);
  const int steps = std::max(1, static_cast<int>(std::ceil(dt / hsub - 1e-9)));
  const double h = dt / steps;
  for (int k = 1; k <= steps; ++k) {
    const double tk = t0 + k * h;
    updateTangents(im, L);
    lumpedForces(im, water, (k - 0.5) / steps, L);
    // Junctions: the tied node's force and mass go to the node below.
    for (int j = n - 1; j > 0; --j)
      if (tie[j] >= 0) {
        L.f[tie[j]] += L.f[j];
        L.f[j].setZero();
      }
    for (int j = 0; j < n; ++j) {
      if (tie[j] >= 0) continue;
      double ms = L.mass[j] + L.body_mass[j], ma = L.added[j];
      for (int i = j + 1; i < n && tie[i] == j; ++i) {
        ms += L.mass[i] + L.body_mass[i];
        ma += L.added[i];
      }
      double cd = L.drag_rate[j];
      for (int i = j + 1; i < n && tie[i] == j; ++i) cd += L.drag_rate[i];
      const Vec3& t = L.tangent[j];
      // M = ms I + ma (I - t t^T): along t ms, across ms + ma. The drag linearised about the
      // current velocity and taken at the end of the sub-step (backward Euler in the drag alone)
      // adds h cd to both: the update is stable whatever the relative speed.
      const Vec3 ft = t.dot(L.f[j]) * t;
      const Vec3 a = ft / (ms + h * cd) + (L.f[j] - ft) / (ms + ma + h * cd);
      L.v[j] += h * a;
      L.x[j] += h * L.v[j];
    }
    for (int j = 1; j < n; ++j)
      if (tie[j] >= 0) {
        L.x[j] = L.x[tie[j]];
        L.v[j] = L.v[tie[j]];
      }
    if (top_held) {
      const TopState s = im.top(tk);
      L.x[n - 1] = Vec3(s.x, s.y, s.z);
      L.v[n - 1] = Vec3(s.vx, s.vy, s.vz);
    }
    if (anchor_held) {
      if (anchor_path) {
        const TopState s = (*anchor_path)(tk);
        L.x[0] = Vec3(s.x, s.y, s.z);
        L.v[0] = Vec3(s.vx, s.vy, s.vz);
      } else {
        L.x[0] = anchor0;
        L.v[0].setZero();
      }
    }
    for (int j = 0; j < n; ++j)
      if (!L.x[j].allFinite() || !L.v[j].allFinite()) {
        std::ostringstream os;
        os << "fallback step from t = " << t0 << " s: node " << j << " left the finite numbers at t = " << tk << " s";
        rep.message = os.str();
        return false;
      }
  }
  updateTangents(im, L);
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
  ++rep.steps;
  ++rep.fallback_steps;
  ++im.totals.steps;
  ++im.totals.fallback_steps;
  im.totals.fallback_substeps += steps;
  im.in_fallback = true;
  return true;
}

bool stayInFallback(const DynamicSolver3D::Impl& im) {
  if (!im.in_fallback || im.fallback_skipped_time >= kMaxSkippedTime * (1.0 - 1e-9)) return false;  // (sums of dt)
  // Folded: a node of a material without compression (chain, rope: negative strain is slack, not
  // a compressed rod) shorter than unstretched by more than kFoldedStrain.
  for (int j = 0; j < im.nodes(); ++j)
    if (!im.mat(j).compression && im.Y[N * j + EPS] < -kFoldedStrain) return true;
  return false;
}

}  // namespace core
}  // namespace mooring_dynamics
