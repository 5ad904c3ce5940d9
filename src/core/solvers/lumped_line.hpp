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
#include "mooring_dynamics/core/numerics/newton.hpp"

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
/// A retry keeps a Jacobian only while each update shrinks sigma to at most this fraction of the
/// one before (NewtonOptions::reuse_rate, the default), whatever dynamics.jacobian_reuse_rate
/// says: a kept Jacobian that halves the error each update needs some thirteen updates from
/// 1e-2 to the 1e-6 tolerance, more than kRetryIterations, so with the storm file's 0.5 retries
/// failed on lines a Jacobian from a fresh assembly would have brought back.
constexpr double kRetryReuseRate = 0.15;
/// The Newton options of a retry (the first implicit try after a fallback step) from those of
/// an implicit step: at most kRetryIterations iterations, a kept Jacobian held to
/// kRetryReuseRate; options already stricter stay as they are.
inline NewtonOptions retryNewtonOptions(NewtonOptions no) {
  no.max_iterations = std::min(no.max_iterations, kRetryIterations);
  no.reuse_rate = std::min(no.reuse_rate, kRetryReuseRate);
  return no;
}
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

/// The sub-steps' state and work in component arrays (advance; the passes in lumped_line.cpp):
/// each pass over the intervals or the nodes is one loop over plain arrays, which the compiler
/// vectorizes; every value is the same operations in the same order as a node-by-node loop, so
/// the results do not depend on the instruction set (no fused multiply-add). Interval j's values
/// sit at index j + 1 of the interval arrays (n + 1 long, zero at 0 and n), so that node j finds
/// its lower and upper interval at j and j + 1. Positions in the problem frame (REP 103).
struct Substeps {
  int n = 0;
  // Nodes.
  std::vector<double> x[3], v[3], f[3], t[3];  ///< position, velocity, force, unit tangent
  std::vector<double> dr;                      ///< d|drag| / d|v| [N s/m] (semi-implicit drag)
  std::vector<double> ms, ma;  ///< structural (with bodies and the tied nodes) and added mass [kg]
  std::vector<double> free;  ///< 0: tied to the node below (a junction's upper node), else 1
  /// The seabed: flat (no grid, no profile), and per node its tributary length (Constants::Node,
  /// 0 where no material acts on it), the contact onset of its material (eq2d::contactOnset)
  /// and 1 where the seabed acts on it.
  bool flat_seabed = false;
  std::vector<double> bed_length, bed_onset, bed_acts;
  // Intervals (padded): chord, its direction where it has one (else 0), axial force and drag.
  std::vector<double> len, chord_rate, dir[3], eps, Te, damper, Tt[3], hd[3], hw, q;
  std::vector<double> along[3];  ///< the axial force's direction: the chord's, or the lower node's tangent
  std::vector<double> has_dir;  ///< 1: the chord is longer than kShortChord of the interval
  // Interval constants (padded): Constants::Interval's, the reference length, the water sums.
  std::vector<double> ref, short_h, EA, band, damper_c, drag, drag_rate, cdn, pcdt, s0[3], s1[3];
  // Flags, 1 or 0 (doubles, as the values: the masks vectorize).
  std::vector<double> force;  ///< carries axial force and drag (a cable, not parted)
  std::vector<double> comp;   ///< its law holds through zero (compression)
  bool all_linear = true;
  /// The line L's state and the step's constants c and water.
  static Substeps of(const Setup& s, const Constants& c, const Line& L, const std::vector<NodeWater>& water);
  /// Chords' lengths and directions, the nodes' tangents (updateTangents).
  void chords();
  /// Each interval's strain, elastic tension (Constants::Interval::tension) and damper.
  void axial(const Constants& c);
  /// Each interval's axial force T t and half its drag, at time fraction w of the step.
  void intervalForces(double w);
  /// Each node's force: weights, axial forces and drag of its two intervals, and its drag rate.
  void nodeSums();
  /// One sub-step h of symplectic Euler on the free nodes (see advance).
  void move(double h);
  /// Adds the reaction of a flat seabed to the nodes' forces: the solver's (eq3d::seabedReaction,
  /// eq2d's in 2-D) at a node of vertical velocity v_z, the same operations where it has a
  /// gradient of 0 and a local frame of the world's.
  void flatSeabed(const Environment& env);
  /// The first node whose position or velocity is not finite, or -1.
  int firstNonFinite() const;
  Vec3 pos(int j) const { return Vec3(x[0][j], x[1][j], x[2][j]); }
  Vec3 vel(int j) const { return Vec3(v[0][j], v[1][j], v[2][j]); }
  Vec3 tangent(int j) const { return Vec3(t[0][j], t[1][j], t[2][j]); }
  void set(int j, const Vec3& xj, const Vec3& vj) {
    for (int i = 0; i < 3; ++i) {
      x[i][j] = xj[i];
      v[i][j] = vj[i];
    }
  }
  void addForce(int j, const Vec3& fj) {
    for (int i = 0; i < 3; ++i) f[i][j] += fj[i];
  }
};

/// The loads at time fraction `w` of the step that the component passes leave to the Model (see
/// advance): inline bodies at junctions, the bodies at free ends, a free top's force and the
/// seabed, added to the nodes' forces (and drag rates) in that order.
template <class Model>
void modelLoads(const Setup& s, const Constants& c, const Model& model, const std::vector<NodeWater>& water, double w,
                Substeps& k) {
  const Problem& p = *s.problem;
  const double rho = p.environment.water_density;
  const int n = k.n;
  auto sqr = [](double a) { return a * a; };
  // Junctions: the inline bodies' weight and sphere-like drag at the lower node.
  for (int j = 0; j + 1 < n; ++j) {
    if (c.intervals[static_cast<std::size_t>(j)].m) continue;
    const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
    for (std::size_t b : s.mesh->intervals[static_cast<std::size_t>(j)].bodies) {
      const Body& body = p.bodies[b];
      k.f[2][j] -= body.wet_weight;
      const Vec3 r = wv - k.vel(j);
      const double area = 0.25 * eq2d::kPi * sqr(body.diameter);
      k.addForce(j, 0.5 * rho * body.isotropicCd() * area * r.norm() * r);
    }
  }
  // The body at a free lower end, and the subsurface body at a free top: its weight and drag
  // (as the box rows' end balance) on the velocity relative to the water at the end node, taken
  // semi-implicitly as the line's.
  for (const auto& [b, j] : {std::make_pair(s.end_body, 0), std::make_pair(s.top_body, n - 1)}) {
    if (!b) continue;
    const Vec3 wv = (1.0 - w) * water[j].w0 + w * water[j].w1;
    const Vec3 r = wv - k.vel(j);
    k.addForce(j, model.endBodyLoad(*b, k.tangent(j), r));
    const double q = 0.5 * rho * 0.25 * eq2d::kPi * sqr(b->diameter);
    const double cd = b->drag == Body::Drag::Sphere ? b->cd : std::max(b->cdn, b->cdt);
    k.dr[j] += q * cd * 2.0 * r.norm();
  }
  // A free top's given force (a force top, a force table's force on a subsurface body).
  k.addForce(n - 1, model.topForce(w));
  // The seabed (eq. 35-36 with the box rows' contact onset) on each node's tributary length: a
  // flat one in a pass of its own (Substeps::flatSeabed), any other through the solver's rows.
  if (k.flat_seabed) {
    k.flatSeabed(p.environment);
    return;
  }
  for (int j = 0; j < n; ++j) {
    const Constants::Node& cn = c.nodes[static_cast<std::size_t>(j)];
    if (!cn.m) continue;
    const double Fbot = model.seabed(*cn.m, k.pos(j), k.vel(j));
    k.f[2][j] += cn.length * Fbot;
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
  bool tied = false;
  for (int j = 0; j + 1 < n; ++j)
    if (!(s.mesh->intervals[static_cast<std::size_t>(j)].h > 0.0)) {
      tie[static_cast<std::size_t>(j) + 1] = j;
      tied = true;
    }
  const bool top_held = model.topHeld(), low_held = model.lowHeld();

  const Constants c = Constants::of(s, n);
  Substeps k = Substeps::of(s, c, L, water);
  // Each node's mass with the nodes tied to it: structural and bodies' (isotropic), added (across).
  for (int j = 0; j < n; ++j) {
    if (tie[j] >= 0) {
      k.free[j] = 0.0;
      continue;
    }
    double ms = L.mass[j] + L.body_mass[j], ma = L.added[j];
    for (int i = j + 1; i < n && tie[i] == j; ++i) {
      ms += L.mass[i] + L.body_mass[i];
      ma += L.added[i];
    }
    k.ms[j] = ms;
    k.ma[j] = ma;
  }

  const double hsub = std::min(stableSubstep(s, L), dt);
  const int steps = std::max(1, static_cast<int>(std::ceil(dt / hsub - 1e-9)));
  const double h = dt / steps;
  for (int step = 1; step <= steps; ++step) {
    const double tk = t0 + step * h;
    const double w = (step - 0.5) / steps;
    k.chords();
    k.axial(c);
    k.intervalForces(w);
    k.nodeSums();
    modelLoads(s, c, model, water, w, k);
    if (tied) {
      // Junctions: the tied node's force and drag rate go to the node below.
      for (int j = n - 1; j > 0; --j)
        if (tie[j] >= 0)
          for (int i = 0; i < 3; ++i) {
            k.f[i][tie[j]] += k.f[i][j];
            k.f[i][j] = 0.0;
          }
      for (int j = 0; j < n; ++j)
        if (tie[j] < 0)
          for (int i = j + 1; i < n && tie[i] == j; ++i) k.dr[j] += k.dr[i];
    }
    k.move(h);
    if (tied)
      for (int j = 1; j < n; ++j)
        if (tie[j] >= 0)
          for (int i = 0; i < 3; ++i) {
            k.x[i][j] = k.x[i][tie[j]];
            k.v[i][j] = k.v[i][tie[j]];
          }
    Vec3 xe, ve;
    if (top_held) {
      model.top(tk, xe, ve);
      k.set(n - 1, xe, ve);
    }
    if (low_held) {
      model.low(tk, xe, ve);
      k.set(0, xe, ve);
    }
    const int bad = k.firstNonFinite();
    if (bad >= 0) {
      std::ostringstream os;
      os << "fallback step from t = " << t0 << " s: node " << bad << " left the finite numbers at t = " << tk << " s";
      message = os.str();
      return false;
    }
  }
  for (int j = 0; j < n; ++j) {
    L.x[j] = k.pos(j);
    L.v[j] = k.vel(j);
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

/// For at most this long [s] of simulated time in a row a line stays in the fallback past its
/// skipped_cap while a slack node of it is off the seabed (staySlack): chain folded or hanging
/// loose in the water column, which gravity straightens or lays down within seconds, and from
/// which no implicit try converged: on the spread mooring at Hs 4 (60 s) all 45 tries made at
/// the cap from such a state failed (at 9.5 Jacobians each, a tenth of the run's Jacobians),
/// most with the top interval folded to -10 % to -60 % strain. A limit, not a wait: a line that
/// stayed slack in the water this long would still be tried.
constexpr double kLongestSuspendedSlack = 60.0;

/// After a fallback step: whether the next base step goes to the fallback at once, without an
/// implicit try: the line is still slack somewhere (a node of a material without compression,
/// chain or rope, whose strain Y[n_unknowns j + eps] is below -kSlackStrainLimit: negative strain
/// is slack, not a compressed rod), for less than im.skipped_cap in a row (sums of dt; from
/// kMaxSkippedTime up to kLongestSkippedTime, see there), or for less than kLongestSuspendedSlack
/// while a slack node is off the seabed (its elevation Y[n_unknowns j + z] not below the seabed
/// under (x, y); y < 0: a 2-D line in the x-z plane).
template <class Impl>
bool staySlack(const Impl& im, int n_unknowns, int eps, int x, int y, int z) {
  if (!im.in_fallback) return false;
  const Environment& env = im.problem.environment;
  bool slack = false, suspended = false;
  for (int j = 0; j < im.nodes() && !suspended; ++j) {
    const double* Yj = im.Y.data() + static_cast<std::ptrdiff_t>(n_unknowns) * j;
    if (im.mat(j).compression || !(Yj[eps] < -kSlackStrainLimit)) continue;
    slack = true;
    suspended = !(Yj[z] < env.seabedElevation(Yj[x], y >= 0 ? Yj[y] : 0.0));
  }
  if (!slack) return false;
  if (im.fallback_skipped_time < im.skipped_cap * (1.0 - 1e-9)) return true;
  return suspended && im.fallback_skipped_time < kLongestSuspendedSlack * (1.0 - 1e-9);
}

}  // namespace lumped
}  // namespace core
}  // namespace mooring_dynamics
