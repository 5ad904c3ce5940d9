// The lumped-mass line of the fallback step (docs/method.md "Slack and snap: the fallback step"),
// shared by the 2-D and 3-D dynamic solvers (dynamics2d_fallback.cpp, dynamics3d_fallback.cpp).
// Private to src/core/solvers.
//
// A base step that the implicit box scheme cannot take, even cut to its smallest size (section
// 4.3), is taken by an explicit lumped-mass model of the same line over the same interval, and
// the run goes on from its end state. A line whose top goes wholly slack and is then overrun by
// its fairlead folds back on itself; the box scheme's unknowns (strain, frame and curvature at
// the nodes) cannot follow a fold within one step, and Newton fails at every step size. A
// lumped-mass line has no such limit: each node keeps its own inertia and moves freely while its
// neighbours carry no tension.
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
//  * the seabed as in the box rows (the solver's own reaction: spring with its contact onset,
//    dashpot);
//  * bending and torsion are left out (chain and rope: EI is negligible next to the axial
//    forces over a step; the fallback serves lines that fold, not rods);
//  * the ends as the solver says: held on their paths, or free nodes.
// Time integration: symplectic Euler on sub-steps of kCourant times the shortest axial wave
// crossing time of an interval (and of the seabed spring's period), so that the snap's wave is
// resolved. The water velocity is taken at the nodes' positions at the start of the step, at
// both ends of the step, linear in time between.
//
// The solver supplies a Model with its layout-dependent parts:
//   double seabed(const Material& m, const Vec3& x, const Vec3& v) const;  // reaction [N/m], +z
//   Vec3 endBodyLoad(const Body& b, const Vec3& tangent, const Vec3& r) const;  // r: water - node
//   bool topHeld() const;  void top(double t, Vec3& x, Vec3& v) const;     // the top's path
//   Vec3 topForce(double w) const;  // the force on a free top at fraction w of the step
//   bool lowHeld() const;  void low(double t, Vec3& x, Vec3& v) const;     // the lower end's
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {
namespace lumped {

using Vec3 = Eigen::Vector3d;

/// Axial damping ratio of each interval's own axial mode (the highest mode of the lumped line,
/// ~ 2 sqrt(EA/m)/h): proportional damping, so a mode of frequency w gets kAxialDampingRatio
/// w / w_max, which leaves the line's physical modes (w << w_max) all but undamped.
constexpr double kAxialDampingRatio = 0.5;
/// Sub-step as a fraction of the stability limit of symplectic Euler (2 / w_max).
constexpr double kCourant = 0.4;
/// A chord shorter than this fraction of its interval has no direction of its own [-].
constexpr double kShortChord = 1e-6;

// When the solvers go to the fallback and leave it (dynamics2d.cpp, dynamics3d.cpp):
/// A node of a material without compression whose strain is below -kSlackStrainLimit (slack:
/// chain heaped, folded or hanging loose, at zero tension) marks the line as still slack after a
/// fallback step. One slack stretch's width of the no-compression law (kSlackStrain): its tension
/// is exactly zero there, while a free end rests at half of it (Material::strainAt(0)). Any slack
/// node will do: on the spread mooring at Hs 4 (60 s, 247 implicit tries right after a fallback
/// step) 189 of the 204 tries with a node below zero strain failed, all of them below -1e-6, and
/// 38 of the 43 without one converged; with the limit at -1e-3 (folded lines only) the tries from
/// -1e-3 to 0 were 143 of the 207 failed tries of the run.
constexpr double kSlackStrainLimit = kSlackStrain;
/// For at most this long [s] of simulated time in a row base steps go to the fallback without an
/// implicit try (whatever the steps' length: in lockstep every sample ends a step): a
/// heap of chain lying on the seabed can keep a line "slack" long after the implicit step could
/// take it again. When the try at the end of such a run fails, the next run may last twice as
/// long, up to kLongestSkippedTime, until an implicit step converges: on the spread mooring at
/// Hs 4 (60 s) 64 of the 65 tries made at 1 s failed, from lines slack for many seconds (chain
/// grounded slack near the anchor or heaped at the touchdown).
constexpr double kMaxSkippedTime = 1.0;
constexpr double kLongestSkippedTime = 8.0;
/// A converged implicit step whose top node is farther than this fraction of the top interval
/// from the top's path is refused (topOffItsPath). With the top interval folded the box
/// scheme's coordinates there are all but free: on the spread mooring at Hs 6 with 17.5 m
/// intervals the top node wandered up to 13.8 m from its fairlead (median 0.35 m), and its
/// strain rang from -6 % to +0.7 % in 0.01 s steps (3.7 MN spikes with the fairlead moving at
/// 0.5 m/s). At 3.5 m intervals the top stayed within 0.15 m (4 %) through 150 s of Hs 6.
constexpr double kTopOffPath = 0.05;
/// The same for a top interval that carries compression (2-D, dynamics2d_fallback.cpp): its top
/// node lags behind a fast top by the feedback law, no fold; a whole interval off is no lag.
constexpr double kTopOffPathCompression = 1.0;
/// A top prescribed by its velocity alone is also off when its node's displacement over a step
/// differs from the prescribed one by more than this speed times the step [m/s]: such a top
/// drifts by design, but slowly (A.3: 22 mm per 8 s cycle, 3 mm/s); after a fallback step on a
/// folded line the implicit steps moved a resting top up by 3-4 mm in 1 ms steps (3-4 m/s), 16 cm
/// in all, and the snap that followed was 70 % above its closed form.
constexpr double kTopRateMismatch = 0.5;
/// Newton iterations of the first implicit step after a fallback step: a line that is taut again
/// converges in a handful (the state is the lumped line's, close to the box solution).
constexpr int kRetryIterations = 10;
/// After such a retry fails, this many base steps go to the fallback without an implicit try.
/// Retries fail in runs while a line's top is slack (the spread mooring at Hs 4, 60 s: 326 of
/// 403 retries failed, in runs of five to eight, each costing kRetryIterations iterations and a
/// Jacobian at nearly every one, several times a fallback step); trying every second step
/// halves them and returns to the implicit step at most one step later.
constexpr int kRetryWait = 1;

/// The box scheme's coordinate rows (eq. 42) put two nodes h/2 |p_a t_a + p_b t_b| apart:
/// h (1 + eps) cos(dphi / 2) where the line turns by dphi between the nodes' tangents, shorter
/// than h (1 + eps). A lumped chord measured against h would read the difference as a strain
/// deficit of dphi^2 / 8, a tension error of EA dphi^2 / 8: a wire of EA = 1e8 N at 10 kN on
/// 11.1 m intervals, turning by up to 0.29 rad over one next to its anchor, went from 4 kN at
/// the anchor to 122 kN in the first fallback step, and a run taken wholly by the fallback swung
/// between -43 and +82 kN about its static 10 kN. So the lumped chord of each interval is
/// measured against h cos(dphi / 2) (chordFactor) of the box state's tangents where a fallback
/// step follows an implicit one (setReferenceLengths), and the box strain it hands back is the
/// chord's against that length. Fallback steps in a row keep the lengths: re-derived from the
/// lumped line's own tangents at every step they would pump its transverse vibration into its
/// tension (the same wire held still swung by 3.8 kN rms instead of 33 N).
/// Where the turn is sharper than a cos(dphi / 2) of 1 - kMaxChordCorrection (0.9 rad over one
/// interval) the interval is folded or a slack bend the mesh does not resolve: it keeps h.
constexpr double kMaxChordCorrection = 0.1;

/// The line as lumped masses at the nodes (world frame, REP 103; 2-D lines in the x-z plane).
struct Line {
  int n = 0;
  /// Unstretched length each interval's chord is measured against [m] (setReferenceLengths;
  /// 0 for a junction).
  std::vector<double> ref;
  std::vector<Vec3> x, v, f;
  std::vector<double> drag_rate;  ///< d|drag| / d|v| at the node [N s/m] (semi-implicit drag)
  std::vector<double> mass;       ///< structural mass [kg]
  std::vector<double> added;      ///< added mass across the tangent [kg] (line)
  std::vector<double> body_mass;  ///< inline bodies' mass plus added mass [kg] (isotropic)
  std::vector<Vec3> tangent;      ///< unit tangent at the node (mean of the chords)
  /// Each interval's chord at the last updateTangents: its length [m] and, where it is at least
  /// kShortChord of the interval, its direction (what forces() takes at the same positions).
  std::vector<double> chord_len;
  std::vector<Vec3> chord_dir;
};

/// Water velocity at a node at the start and the end of the step [m/s].
struct NodeWater {
  Vec3 w0, w1;
};

/// What the lumped model needs of the solver's line besides the Model: its problem, mesh (h = 0
/// intervals are junctions), the parted interval (-1: none), the body at a free lower end and the
/// subsurface body at a free top.
struct Setup {
  const Problem* problem = nullptr;
  const Mesh* mesh = nullptr;
  int parted = -1;
  const Body* end_body = nullptr;
  const Body* top_body = nullptr;
};

/// What forces() takes of each interval and node that does not change over a step, worked out
/// once a step (Constants::of) with the same operations, in the same order, as at each sub-step.
struct Constants {
  struct Interval {
    const Material* m = nullptr;  ///< nullptr: a junction (h = 0)
    double h = 0.0;               ///< unstretched length [m]
    double half_weight = 0.0;     ///< 0.5 h w: the weight each node carries [N]
    bool linear = false;          ///< a linear law (EA): its slope, so its damper, is constant
    double band = 0.0;            ///< the no-compression law's slack band (Material::slackBand) [N]
    double damper = 0.0;          ///< kAxialDampingRatio sqrt(EA m) h of a linear law [N s]
    double drag = 0.0;            ///< -0.5 rho d h [kg/m]
    double drag_rate = 0.0;       ///< 0.5 rho d h [kg/m]
    /// T(eps) of the material (Material::tension, the slack band kept).
    double tension(double eps) const {
      const double T = linear ? m->EA * eps : m->rawTension(eps);
      return m->compression ? T : slackRamp(T, T, band);
    }
  };
  struct Node {
    const Material* m = nullptr;  ///< the material the seabed acts on (nullptr: none)
    double length = 0.0;          ///< tributary length [m]: half of each adjacent interval
  };
  std::vector<Interval> intervals;
  std::vector<Node> nodes;
  static Constants of(const Setup& s, int n);
};

/// Masses of the nodes of `L` (L.x, L.v are the caller's: set them after this).
void lumpMasses(const Setup& s, Line& L);
/// cos(dphi / 2) of the turn between unit tangents ta and tb, or 1 where it is below
/// 1 - kMaxChordCorrection (see there).
inline double chordFactor(const Vec3& ta, const Vec3& tb) {
  const double c = std::sqrt(std::max(0.0, 0.5 * (1.0 + ta.dot(tb))));
  return c >= 1.0 - kMaxChordCorrection ? c : 1.0;
}
/// The reference lengths L.ref at the start of a fallback step that follows an implicit one:
/// h chordFactor of the box state's tangents at the interval's nodes (`tangent`, unit vectors),
/// so that the lumped line starts with the box state's strains.
void setReferenceLengths(const Setup& s, const std::vector<Vec3>& tangent, Line& L);
/// Unit tangents at the nodes: the mean of the adjacent chords' directions (one-sided at the
/// ends and junctions); the chords' lengths and directions kept in L.chord_len, L.chord_dir.
void updateTangents(const Setup& s, Line& L);
/// The largest stable sub-step [s]: kCourant times 2 / w_max of the stiffest interval's axial
/// mode (and of each node's seabed spring).
double stableSubstep(const Setup& s, const Line& L);
/// Strain of the chord of interval j against its reference length [-].
inline double chordStrain(const Line& L, int j) {
  return (L.x[static_cast<std::size_t>(j) + 1] - L.x[static_cast<std::size_t>(j)]).norm() / L.ref[static_cast<std::size_t>(j)] - 1.0;
}

/// Forces on the lumped nodes at time fraction `w` of the step [N], with the chords of the last
/// updateTangents at the same positions and the step's constants `c`.
template <class Model>
void forces(const Setup& s, const Constants& c, const Model& model, const std::vector<NodeWater>& water, double w,
            Line& L) {
  const Problem& p = *s.problem;
  const Environment& env = p.environment;
  const double rho = env.water_density;
  const int n = L.n;
  auto sqr = [](double a) { return a * a; };
  for (int j = 0; j < n; ++j) {
    L.f[j].setZero();
    L.drag_rate[j] = 0.0;
  }
  for (int j = 0; j + 1 < n; ++j) {
    const Constants::Interval& ci = c.intervals[static_cast<std::size_t>(j)];
    if (!ci.m) {
      // Junction: the inline bodies' weight and sphere-like drag at the lower node.
      const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
      for (std::size_t b : s.mesh->intervals[static_cast<std::size_t>(j)].bodies) {
        const Body& body = p.bodies[b];
        L.f[j].z() -= body.wet_weight;
        const Vec3 r = wv - L.v[j];
        const double area = 0.25 * eq2d::kPi * sqr(body.diameter);
        L.f[j] += 0.5 * rho * body.isotropicCd() * area * r.norm() * r;
      }
      continue;
    }
    const Material& m = *ci.m;
    const double h = ci.h;
    // Weight, half to each end.
    L.f[j].z() -= ci.half_weight;
    L.f[j + 1].z() -= ci.half_weight;
    if (j == s.parted) continue;  // a parted interval carries no force between its nodes
    const double len = L.chord_len[j];
    const double eps = len / L.ref[j] - 1.0;
    const bool has_dir = len > kShortChord * h;
    const Vec3& t = has_dir ? L.chord_dir[j] : L.tangent[j];
    // Axial force with proportional damping on the strain rate; a line without compression
    // neither pushes nor pulls back through the damper below zero tension.
    const double eps_rate = has_dir ? t.dot(L.v[j + 1] - L.v[j]) / L.ref[j] : 0.0;
    const double damper =
        ci.linear ? ci.damper
                  : kAxialDampingRatio * std::sqrt(std::max(m.rawTensionSlope(std::max(eps, 0.0)), 0.0) * m.mass) * h;
    const double Te = ci.tension(eps);
    double T = Te + damper * eps_rate;
    if (!m.compression) T = Te > 0.0 ? std::max(T, 0.0) : 0.0;
    L.f[j] += T * t;
    L.f[j + 1] -= T * t;
    // Drag on the chord at its mid-point velocity relative to the water.
    const Vec3 wv = 0.5 * ((1.0 - w) * (water[j].w0 + water[j + 1].w0) + w * (water[j].w1 + water[j + 1].w1));
    const Vec3 vr = 0.5 * (L.v[j] + L.v[j + 1]) - wv;
    const double vt = vr.dot(t);
    const Vec3 vn = vr - vt * t;
    const double stretch = std::sqrt(std::max(1.0 + eps, 0.0));
    const double vnn = std::sqrt(vn.squaredNorm() + sqr(eq3d::kDragSpeedFloor));
    const Vec3 drag = ci.drag * stretch * (m.cdn * vnn * vn + eq2d::kPi * m.cdt * std::abs(vt) * vt * t);
    L.f[j] += 0.5 * drag;
    L.f[j + 1] += 0.5 * drag;
    // The drag's rate of change with the node's speed (quadratic drag: twice the force per unit
    // speed), half to each node: the update treats the drag implicitly with it.
    const double rate = ci.drag_rate * stretch * 2.0 * std::max(m.cdn * vnn, eq2d::kPi * m.cdt * std::abs(vt));
    L.drag_rate[j] += 0.25 * rate;
    L.drag_rate[j + 1] += 0.25 * rate;
  }
  // The body at a free lower end, and the subsurface body at a free top: its weight and drag
  // (as the box rows' end balance) on the velocity relative to the water at the end node, taken
  // semi-implicitly as the line's.
  for (const auto& [b, j] : {std::make_pair(s.end_body, 0), std::make_pair(s.top_body, n - 1)}) {
    if (!b) continue;
    const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
    const Vec3 r = wv - L.v[j];
    L.f[j] += model.endBodyLoad(*b, L.tangent[j], r);
    const double q = 0.5 * rho * 0.25 * eq2d::kPi * sqr(b->diameter);
    const double cd = b->drag == Body::Drag::Sphere ? b->cd : std::max(b->cdn, b->cdt);
    L.drag_rate[j] += q * cd * 2.0 * r.norm();
  }
  // A free top's given force (a force top, a force table's force on a subsurface body).
  L.f[n - 1] += model.topForce(w);
  // The seabed (eq. 35-36 with the box rows' contact onset) on each node's tributary length.
  for (int j = 0; j < n; ++j) {
    const Constants::Node& cn = c.nodes[static_cast<std::size_t>(j)];
    if (!cn.m) continue;
    const double Fbot = model.seabed(*cn.m, L.x[j], L.v[j]);
    L.f[j].z() += cn.length * Fbot;
  }
}

/// Advance `L` from t0 over dt in explicit sub-steps (see the file comment); `substeps` gets
/// their number. False, with why in `message`, when a node leaves the finite numbers.
template <class Model>
bool advance(const Setup& s, const Model& model, const std::vector<NodeWater>& water, double t0, double dt, Line& L,
             long& substeps, std::string& message) {
  const int n = L.n;
  // Tie junction nodes (h = 0) to the node below them.
  std::vector<int> tie(static_cast<std::size_t>(n), -1);
  for (int j = 0; j + 1 < n; ++j)
    if (!(s.mesh->intervals[static_cast<std::size_t>(j)].h > 0.0)) tie[static_cast<std::size_t>(j) + 1] = j;
  const bool top_held = model.topHeld(), low_held = model.lowHeld();

  const Constants c = Constants::of(s, n);
  // Each node's mass with the nodes tied to it: structural and bodies' (isotropic), added (across).
  std::vector<double> mass_s(static_cast<std::size_t>(n), 0.0), mass_a(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j) {
    if (tie[j] >= 0) continue;
    double ms = L.mass[j] + L.body_mass[j], ma = L.added[j];
    for (int i = j + 1; i < n && tie[i] == j; ++i) {
      ms += L.mass[i] + L.body_mass[i];
      ma += L.added[i];
    }
    mass_s[j] = ms;
    mass_a[j] = ma;
  }

  const double hsub = std::min(stableSubstep(s, L), dt);
  const int steps = std::max(1, static_cast<int>(std::ceil(dt / hsub - 1e-9)));
  const double h = dt / steps;
  for (int k = 1; k <= steps; ++k) {
    const double tk = t0 + k * h;
    updateTangents(s, L);
    forces(s, c, model, water, (k - 0.5) / steps, L);
    // Junctions: the tied node's force and mass go to the node below.
    for (int j = n - 1; j > 0; --j)
      if (tie[j] >= 0) {
        L.f[tie[j]] += L.f[j];
        L.f[j].setZero();
      }
    for (int j = 0; j < n; ++j) {
      if (tie[j] >= 0) continue;
      const double ms = mass_s[j], ma = mass_a[j];
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
    if (top_held) model.top(tk, L.x[n - 1], L.v[n - 1]);
    if (low_held) model.low(tk, L.x[0], L.v[0]);
    for (int j = 0; j < n; ++j)
      if (!L.x[j].allFinite() || !L.v[j].allFinite()) {
        std::ostringstream os;
        os << "fallback step from t = " << t0 << " s: node " << j << " left the finite numbers at t = " << tk << " s";
        message = os.str();
        return false;
      }
  }
  updateTangents(s, L);
  substeps = steps;
  return true;
}

/// The bookkeeping of an accepted fallback step on a solver's state `im` (DynamicSolver2D::Impl or
/// DynamicSolver3D::Impl): the step counted in the report and the totals, the line marked as in
/// the fallback with the reference lengths its next fallback step keeps.
template <class Impl, class Report>
void countFallbackStep(Impl& im, Report& rep, long substeps, const Line& L) {
  ++rep.steps;
  ++rep.fallback_steps;
  ++im.totals.steps;
  ++im.totals.fallback_steps;
  im.totals.fallback_substeps += substeps;
  im.in_fallback = true;
  im.fallback_ref = L.ref;
}

/// An implicit try that did not converge, on a solver's state `im`: counted, and after a retry
/// (the first try after a fallback step) the next kRetryWait base steps wait in the fallback.
template <class Impl>
void countFailedTry(Impl& im, long jacobians) {
  ++im.totals.failed_tries;
  im.totals.failed_jacobians += jacobians;
  if (!im.in_fallback) return;
  ++im.totals.fallback_retries;
  im.retry_wait = kRetryWait;
  // A try made because a slack line had stayed in the fallback for skipped_cap: the next run
  // without a try starts with this step's fallback step and may last twice as long.
  if (im.fallback_skipped_time >= im.skipped_cap * (1.0 - 1e-9)) {
    im.skipped_cap = std::min(2.0 * im.skipped_cap, kLongestSkippedTime);
    im.fallback_skipped_time = 0.0;
  }
}

/// Whether a base step goes to the fallback without an implicit try because a retry failed
/// kRetryWait or fewer steps ago (countFailedTry); counts the step off.
template <class Impl>
bool waitAfterFailedRetry(Impl& im) {
  if (!im.in_fallback || im.retry_wait <= 0) return false;
  --im.retry_wait;
  return true;
}

/// After a fallback step: whether the next base step goes to the fallback at once, without an
/// implicit try: the line is still slack somewhere (a node of a material without compression,
/// chain or rope, whose strain Y[n_unknowns j + eps] is below -kSlackStrainLimit: negative strain
/// is slack, not a compressed rod), for less than im.skipped_cap in a row (sums of dt; from
/// kMaxSkippedTime up to kLongestSkippedTime, see there).
template <class Impl>
bool staySlack(const Impl& im, int n_unknowns, int eps) {
  if (!im.in_fallback || im.fallback_skipped_time >= im.skipped_cap * (1.0 - 1e-9)) return false;
  for (int j = 0; j < im.nodes(); ++j)
    if (!im.mat(j).compression && im.Y[n_unknowns * j + eps] < -kSlackStrainLimit) return true;
  return false;
}

}  // namespace lumped
}  // namespace core
}  // namespace mooring_dynamics
