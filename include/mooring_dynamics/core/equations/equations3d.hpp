// 3-D cable equations (DESIGN.md section 3: a Kirchhoff rod without shear deformation or rotary
// inertia, N = 13 plus the three coordinates) on one half-grid interval of the box scheme, split
// as in eq. 7 into the inertia part M(Y) dY/dt and the spatial part K(Y) dY/ds + F(Y). Written
// once for double and for automatic-differentiation scalars. The static equations are the same
// rows with the time derivatives dropped (and the velocities zero).
//
// Unknowns per node (N = 16), local components refer to the cable frame (e1 tangent, e2, e3):
//   eps            strain [-]; the tension is T(eps)
//   S2, S3         shear forces along e2, e3 [N]; internal force f = (T, S2, S3)
//   u1, u2, u3     cable velocity, local [m/s]
//   O1, O2, O3     twist and curvatures Omega, local [1/m]; moments (GJ O1, EI O2, EI O3)
//   q0..q3         Euler parameters of the frame (quaternion.hpp)
//   x, y, z        position in the problem frame [m] (x east, y north, z up, z = 0 at the mean
//                  sea surface)
// The 2-D unknowns are the special case e3 = +y (a line in the x-z plane): S2 = Sn, u1 = u,
// u2 = v, O3 = Omega3 = dphi/ds, and the rows below reduce to the 2-D rows of equations2d.hpp
// and equations2d_dynamic.hpp (the row comments name the 2-D equation).
#pragma once

#include <algorithm>
#include <cmath>

#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/quaternion.hpp"
#include "mooring_dynamics/core/model/scalar.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq3d {

constexpr int N = 16;
/// Names of the unknowns, for messages ("node 12 (s = 5.5 m) Omega2").
inline const char* varName(int k) {
  static const char* const kNames[N] = {"eps", "S2", "S3", "u1", "u2", "u3", "Omega1", "Omega2",
                                        "Omega3", "q0", "q1", "q2", "q3", "x", "y", "z"};
  return kNames[k];
}
enum Var { EPS = 0, S2 = 1, S3 = 2, U1 = 3, U2 = 4, U3 = 5, O1 = 6, O2 = 7, O3 = 8,
           Q0 = 9, Q1 = 10, Q2 = 11, Q3 = 12, X = 13, Y = 14, Z = 15 };
/// Rows of an interval with an inertia part (force balance and velocity compatibility): the rows
/// weighted in time by eq. 30. The other rows (moments, frame, coordinates) have no time
/// derivative and hold at the new time level.
constexpr int kInertiaRows = 6;
/// Regularisation of the normal relative speed |v_rn| = sqrt(v2^2 + v3^2 + delta^2) in the
/// quadratic normal drag [m/s]: keeps the drag differentiable at zero relative velocity. It
/// changes the drag by less than rho d Cdn delta |v| / 2, i.e. < 1e-4 N/m for any cable here.
constexpr double kDragSpeedFloor = 1e-6;

/// Water velocity (current plus waves) at a node in the problem frame [m/s], evaluated by the
/// caller in double at the node's position, with the current's vertical gradient so that the
/// Jacobian carries the depth dependence of the current profile (the waves' dependence on the
/// node position is left out of the Jacobian, as in 2-D).
struct Water {
  double w[3] = {0.0, 0.0, 0.0};
  double z = 0.0;                 ///< elevation the values were taken at [m]
  double dw_dz[2] = {0.0, 0.0};   ///< vertical gradient of the horizontal current [1/s]
};

template <class S>
S zeroLike(const S& like) {
  return S(0.0) + 0.0 * like;
}

/// Water velocity at node state Yn (global), linear in the node's elevation about w.z.
template <class S>
void waterVelocity(const Water& w, const S* Yn, S* out) {
  out[0] = w.w[0] + w.dw_dz[0] * (Yn[Z] - w.z);
  out[1] = w.w[1] + w.dw_dz[1] * (Yn[Z] - w.z);
  out[2] = zeroLike(Yn[Z]) + w.w[2];
}

/// Penetration p [m] of a node at state Yn below the seabed z_bot(x, y), linear about the node's
/// (x, y) in the seabed's gradient; false (p untouched) where the node is not below it. A flat
/// seabed (no grid, no profile: z_bot = -depth, gradient 0) takes no lookup.
template <class S>
bool seabedPenetration(const Environment& env, const S* Yn, S& p) {
  const double xv = value(Yn[X]), yv = value(Yn[Y]);
  const bool flat = env.flatSeabed();
  const double zb = flat ? -env.depth : env.seabedElevation(xv, yv);
  if (!(value(Yn[Z]) < zb)) return false;
  double gx = 0.0, gy = 0.0;
  if (!flat) env.seabedGradient(xv, yv, gx, gy);
  p = zb + gx * (Yn[X] - xv) + gy * (Yn[Y] - yv) - Yn[Z];
  return true;
}

/// Eq. 35's spring on penetration p with its onset smoothed over delta (as eq2d::seabedSpring).
template <class S>
S seabedSpringOf(const Environment& env, const S& p, double delta) {
  const double k = env.seabed.stiffness;
  if (delta > 0.0 && value(p) < delta) return k * p * p / (2.0 * delta);
  return k * (p - 0.5 * delta);
}

/// Seabed spring per unit length at a node [N/m] along +z: eq. 35 on the penetration below
/// z_bot(x, y), onset smoothed as in 2-D (eq2d::seabedSpring).
template <class S>
S seabedSpring(const Environment& env, const S* Yn, double delta) {
  S p;
  if (!seabedPenetration(env, Yn, p)) return zeroLike(Yn[Z]);
  return seabedSpringOf(env, p, delta);
}

/// Fraction of the seabed dashpot acting at a node: 0 to 1 over the contact onset.
template <class S>
S contactFraction(const Environment& env, const S* Yn, double delta) {
  S p;
  if (!seabedPenetration(env, Yn, p)) return zeroLike(Yn[Z]);
  if (delta > 0.0 && value(p) < delta) return p / delta;
  return zeroLike(Yn[Z]) + 1.0;
}

/// Seabed reaction at a node [N/m] along +z: spring (eq. 35, no static cap) minus the dashpot
/// (eq. 36) on the vertical velocity while in contact. In statics the velocity is zero.
template <class S>
S seabedReaction(const Environment& env, const Material& m, const S* Yn, const S* R) {
  const double delta = eq2d::contactOnset(env, m);
  S p;
  if (!seabedPenetration(env, Yn, p)) return zeroLike(Yn[Z]);
  const S spring = seabedSpringOf(env, p, delta);
  if (!(value(spring) > 0.0) || env.seabed.damping == 0.0) return spring;
  const S Vz = R[6] * Yn[U1] + R[7] * Yn[U2] + R[8] * Yn[U3];
  const S fraction = delta > 0.0 && value(p) < delta ? S(p / delta) : S(zeroLike(Yn[Z]) + 1.0);
  return spring - env.seabed.damping * fraction * Vz;
}

/// Adds the seabed's Coulomb friction on a grounded node to its load g (local components) [N/m]:
/// -mu_axial F_bot ramp(u1) along the tangent e1 and -mu_lateral F_bot ramp(v_l) along the
/// horizontal direction l = e1 x z across the line, v_l the node's velocity along l, ramp the
/// regularized sign of eq2d::frictionRamp. In statics the velocities are zero and so is this.
template <class S>
void addSeabedFriction(const Material& m, const S* Yn, const S* R, const S& Fbot, S* g) {
  using std::sqrt;
  if (m.mu_axial > 0.0) g[0] = g[0] - m.mu_axial * Fbot * eq2d::frictionRamp(Yn[U1]);
  if (!(m.mu_lateral > 0.0)) return;
  const S nl = sqrt(R[7] * R[7] + R[8] * R[8]);  // |e1 x z|: 0 for a vertical line
  if (!(value(nl) > 1e-9)) return;
  const S l2 = -R[8] / nl, l3 = R[7] / nl;  // l in local components (0, l2, l3)
  const S vl = Yn[U2] * l2 + Yn[U3] * l3;
  const S f = m.mu_lateral * Fbot * eq2d::frictionRamp(vl);
  g[1] = g[1] - f * l2;
  g[2] = g[2] - f * l3;
}

/// Static axial seabed friction at a grounded node along its tangent e1 [N/m]: the 2-D law
/// (eq2d::staticFriction, docs/method.md "Seabed friction") on the nominal reaction w_o ramped in
/// over the contact onset. Statics only: the line is taken as laid from the anchor and pulled
/// from the top, so the friction opposes that pull and the tension falls toward the anchor by
/// mu_axial w_o per metre of grounded line.
template <class S>
S staticSeabedFriction(const Environment& env, const Material& m, const S* Yn) {
  const S reaction = std::max(m.wet_weight, 0.0) * contactFraction(env, Yn, eq2d::contactOnset(env, m));
  if (!(value(reaction) > 0.0)) return zeroLike(Yn[EPS]);
  return eq2d::staticFriction(m, Yn[EPS], reaction);
}

/// Adds the static axial friction of an interval of length h to its axial force row R[0]
/// (intervalSpatial's row 0, the trapezoidal mean of the two nodes as the other loads). Nothing
/// is evaluated with mu_axial = 0.
template <class S>
void addStaticSeabedFriction(const Environment& env, const Material& m, double h, const S* Ya, const S* Yb, S* R) {
  if (!(m.mu_axial > 0.0)) return;
  R[0] = R[0] + 0.5 * h * (staticSeabedFriction(env, m, Ya) + staticSeabedFriction(env, m, Yb));
}

/// Distributed load per unit unstretched length at a node, local components g = (g1, g2, g3):
/// wet weight less the seabed reaction (vertical), tangential drag 1/2 rho pi d Cdt |v_rt| v_rt
/// sqrt(1 + eps) and normal drag 1/2 rho d Cdn |v_rn| v_rn sqrt(1 + eps) on the velocity relative
/// to the water (the F terms of eqs. 1-2 in 3-D).
template <class S>
void distributedLoad(const Environment& env, const Material& m, const S* Yn, const S* R, const Water& w,
                     const S& Fbot, S* g) {
  using std::sqrt;
  S wg[3], wl[3];
  waterVelocity(w, Yn, wg);
  quat::toLocal(R, wg, wl);
  const S vr1 = Yn[U1] - wl[0], vr2 = Yn[U2] - wl[1], vr3 = Yn[U3] - wl[2];
  const S stretch = sqrt(1.0 + Yn[EPS]);
  const double rho = env.water_density;
  const S vn = sqrt(vr2 * vr2 + vr3 * vr3 + kDragSpeedFloor * kDragSpeedFloor);
  const S weight = m.wet_weight - Fbot;
  const S cn = 0.5 * rho * m.diameter * m.cdn * vn * stretch;
  // R[6..8] = local components of the global +z axis.
  g[0] = -weight * R[6] - 0.5 * rho * m.diameter * eq2d::kPi * m.cdt * signedSquare(vr1) * stretch;
  g[1] = -weight * R[7] - cn * vr2;
  g[2] = -weight * R[8] - cn * vr3;
  if ((m.mu_axial > 0.0 || m.mu_lateral > 0.0) && value(Fbot) > 0.0) addSeabedFriction(m, Yn, R, Fbot, g);
}

/// Internal force F = R f in the problem frame [N] (the force the line above a section exerts
/// on the line below it).
template <class S>
void internalForce(const Material& m, const S* Yn, S* F) {
  S R[9];
  quat::matrix(Yn + Q0, R);
  const S f[3] = {eq2d::tension(m, Yn[EPS]), Yn[S2], Yn[S3]};
  quat::toGlobal(R, f, F);
}

/// Global velocity R v of a node [m/s].
template <class S>
void globalVelocity(const S* Yn, S* V) {
  S R[9];
  quat::matrix(Yn + Q0, R);
  quat::toGlobal(R, Yn + U1, V);
}

/// Local angular velocity omega = 2 vec(q* (x) q.) [rad/s] of a node with rate Ydn.
template <class S>
void angularVelocity(const S* Yn, const S* Ydn, S* omega) {
  S r[4];
  quat::relative(Yn + Q0, Ydn + Q0, r);
  omega[0] = 2.0 * r[1];
  omega[1] = 2.0 * r[2];
  omega[2] = 2.0 * r[3];
}

/// Local acceleration of a node, a = v. + omega x v [m/s^2] (local components).
template <class S>
void acceleration(const S* Yn, const S* Ydn, S* a) {
  S om[3];
  angularVelocity(Yn, Ydn, om);
  a[0] = Ydn[U1] + om[1] * Yn[U3] - om[2] * Yn[U2];
  a[1] = Ydn[U2] + om[2] * Yn[U1] - om[0] * Yn[U3];
  a[2] = Ydn[U3] + om[0] * Yn[U2] - om[1] * Yn[U1];
}

/// Inertia rows per unit length at a node, M(Y) dY/dt (rows 0-5) given the rate Ydn: mass times
/// the acceleration, added mass on the normal components only, the added-mass term of the
/// water's tangential velocity (eq. 2, read as (rho pi d^2 / 4 + m_a) w_t, as in 2-D), and the
/// time derivatives of the compatibility rows (eqs. 3-4).
template <class S>
void inertia(const Environment& env, const Material& m, const S* Yn, const S* Ydn, const S* R, const Water& w,
             S* out) {
  S a[3], om[3], wg[3];
  acceleration(Yn, Ydn, a);
  angularVelocity(Yn, Ydn, om);
  waterVelocity(w, Yn, wg);
  const S wt = R[0] * wg[0] + R[3] * wg[1] + R[6] * wg[2];  // water velocity along e1
  const double rhoA = 0.25 * env.water_density * eq2d::kPi * m.diameter * m.diameter;
  const S p = 1.0 + Yn[EPS];
  out[0] = -m.mass * a[0];                                                             // eq. 1
  out[1] = -m.mass * a[1] - m.added_mass * Ydn[U2] - (rhoA + m.added_mass) * wt * om[2];  // eq. 2
  out[2] = -m.mass * a[2] - m.added_mass * Ydn[U3] + (rhoA + m.added_mass) * wt * om[1];
  out[3] = -Ydn[EPS];                                                                  // eq. 3
  out[4] = -p * om[2];                                                                 // eq. 4
  out[5] = p * om[1];
}

/// What the rows of an interval of material `mat` take from one of its nodes: the frame R(q),
/// the tension T(eps), the stretch p = 1 + eps and the distributed load g (with the seabed's).
/// A node shared by two intervals of one material has the same terms in both (the 3-D solver
/// computes them once there, DynamicStepSystem3D::intervalRows).
template <class S>
struct NodeTerms {
  S R[9], T, p, g[3];
};
template <class S>
void nodeTerms(const Environment& env, const Material& mat, const S* Yn, const Water& w, NodeTerms<S>& n) {
  quat::matrix(Yn + Q0, n.R);
  n.T = eq2d::tension(mat, Yn[EPS]);
  n.p = 1.0 + Yn[EPS];
  distributedLoad(env, mat, Yn, n.R, w, seabedReaction(env, mat, Yn, n.R), n.g);
}

/// intervalSpatial from the two nodes' terms (nodeTerms with the interval's material).
template <class S>
void intervalSpatialOf(const Material& mat, double h, const S* Ya, const S* Yb, const NodeTerms<S>& na,
                       const NodeTerms<S>& nb, S* R) {
  const S& pa = na.p;
  const S& pb = nb.p;
  const S* const Ra = na.R;
  const S* const Rb = nb.R;
  const S* const ga = na.g;
  const S* const gb = nb.g;
  const S fa[3] = {na.T, Ya[S2], Ya[S3]}, fb[3] = {nb.T, Yb[S2], Yb[S3]};
  S Om[3], f[3], v[3];
  for (int i = 0; i < 3; ++i) {
    Om[i] = 0.5 * (Ya[O1 + i] + Yb[O1 + i]);
    f[i] = 0.5 * (fa[i] + fb[i]);
    v[i] = 0.5 * (Ya[U1 + i] + Yb[U1 + i]);
  }
  // (1-2) force balance f' + Omega x f + g = 0 (local)
  R[0] = fb[0] - fa[0] + h * (Om[1] * f[2] - Om[2] * f[1]) + 0.5 * h * (ga[0] + gb[0]);
  R[1] = fb[1] - fa[1] + h * (Om[2] * f[0] - Om[0] * f[2]) + 0.5 * h * (ga[1] + gb[1]);
  R[2] = fb[2] - fa[2] + h * (Om[0] * f[1] - Om[1] * f[0]) + 0.5 * h * (ga[2] + gb[2]);
  // (3-4) velocity compatibility v' + Omega x v = d/dt[(1 + eps) e1] (time part in inertia())
  R[3] = Yb[U1] - Ya[U1] + h * (Om[1] * v[2] - Om[2] * v[1]);
  R[4] = Yb[U2] - Ya[U2] + h * (Om[2] * v[0] - Om[0] * v[2]);
  R[5] = Yb[U3] - Ya[U3] + h * (Om[0] * v[1] - Om[1] * v[0]);
  // (6) moments M = (GJ O1, EI O2, EI O3): M' + Omega x M + (1 + eps)^3 e1 x f = 0, with the
  // paper's (1 + eps)^3 of eq. 6. Isotropic section: the twist row reduces to O1' = 0.
  R[6] = Yb[O1] - Ya[O1];
  R[7] = mat.EI * (Yb[O2] - Ya[O2]) + h * (mat.GJ - mat.EI) * Om[0] * Om[2] -
         0.5 * h * (Ya[S3] * pa * pa * pa + Yb[S3] * pb * pb * pb);
  R[8] = mat.EI * (Yb[O3] - Ya[O3]) + h * (mat.EI - mat.GJ) * Om[0] * Om[1] +
         0.5 * h * (Ya[S2] * pa * pa * pa + Yb[S2] * pb * pb * pb);
  // (5) frame kinematics q' = 1/2 q (x) (0, Omega): over the interval with the mean Omega,
  // q_b = q_a (x) exp(h Omega / 2) (the 2-D phi_b - phi_a = h (O3_a + O3_b) / 2 exactly).
  S th[3] = {h * Om[0], h * Om[1], h * Om[2]}, e[4], qe[4];
  quat::expHalf(th, e);
  quat::multiply(Ya + Q0, e, qe);
  for (int i = 0; i < 4; ++i) R[9 + i] = Yb[Q0 + i] - qe[i];
  // (42) coordinates: r' = (1 + eps) e1, e1 = first column of R(q)
  R[13] = Yb[X] - Ya[X] - 0.5 * h * (pa * Ra[0] + pb * Rb[0]);
  R[14] = Yb[Y] - Ya[Y] - 0.5 * h * (pa * Ra[3] + pb * Rb[3]);
  R[15] = Yb[Z] - Ya[Z] - 0.5 * h * (pa * Ra[6] + pb * Rb[6]);
}

/// Spatial part K dY/ds + F of one interval of length h > 0, times h (eq. 11): sixteen rows.
/// Products are taken of interval means, as the 2-D rows take (Sn_a + Sn_b)/2 (phi_b - phi_a).
template <class S>
void intervalSpatial(const Environment& env, const Material& mat, double h, const S* Ya, const S* Yb,
                     const Water& wa, const Water& wb, S* R) {
  NodeTerms<S> na, nb;
  nodeTerms(env, mat, Ya, wa, na);
  nodeTerms(env, mat, Yb, wb, nb);
  intervalSpatialOf(mat, h, Ya, Yb, na, nb, R);
}

/// Inertia part of one interval (times h) from its nodes' inertia rows ia, ib (inertia()):
/// h/2 (M_a Yd_a + M_b Yd_b) in rows 0-5.
template <class S>
void intervalInertiaOf(double h, const S* ia, const S* ib, S* R) {
  for (int r = 0; r < kInertiaRows; ++r) R[r] = 0.5 * h * (ia[r] + ib[r]);
}

/// Inertia part of one interval (times h): h/2 (M_a Yd_a + M_b Yd_b) in rows 0-5.
template <class S>
void intervalInertia(const Environment& env, const Material& mat, double h, const S* Ya, const S* Yb,
                     const S* Yda, const S* Ydb, const Water& wa, const Water& wb, S* R) {
  S Ra[9], Rb[9], ia[kInertiaRows], ib[kInertiaRows];
  quat::matrix(Ya + Q0, Ra);
  quat::matrix(Yb + Q0, Rb);
  inertia(env, mat, Ya, Yda, Ra, wa, ia);
  inertia(env, mat, Yb, Ydb, Rb, wb, ib);
  intervalInertiaOf(h, ia, ib, R);
}

/// Adds a point body's load [N] to P (problem frame): wet weight, and drag on the water velocity
/// relative to the body `r` on the projected area of the body's equivalent sphere: along r for a
/// sphere (1/2 rho Cd A |r| r, isotropic), or split along the unit tangent `t` (cdt) and across it
/// (cdn) for a line-aligned body.
template <class S>
void addBodyLoad(const Environment& env, const Body& b, const S* t, const S* r, S* P) {
  using std::sqrt;
  if (b.drag == Body::Drag::Sphere) {
    const S rm = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + eq2d::kBodySpeedFloor * eq2d::kBodySpeedFloor);
    const double q = 0.5 * env.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.cd;
    for (int i = 0; i < 3; ++i) P[i] = P[i] + q * rm * r[i];
    P[2] = P[2] - b.wet_weight;
    return;
  }
  const S rt = r[0] * t[0] + r[1] * t[1] + r[2] * t[2];
  const S rn[3] = {r[0] - rt * t[0], r[1] - rt * t[1], r[2] - rt * t[2]};
  const S rnm = sqrt(rn[0] * rn[0] + rn[1] * rn[1] + rn[2] * rn[2] + kDragSpeedFloor * kDragSpeedFloor);
  const double q = 0.5 * env.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter;
  const S dt = q * b.cdt * signedSquare(rt);
  for (int i = 0; i < 3; ++i) P[i] = P[i] + dt * t[i] + q * b.cdn * rnm * rn[i];
  P[2] = P[2] - b.wet_weight;
}

/// Water velocity relative to a node (global) [m/s].
template <class S>
void relativeWater(const S* Yn, const S* R, const Water& w, S* r) {
  S V[3], wg[3];
  quat::toGlobal(R, Yn + U1, V);
  waterVelocity(w, Yn, wg);
  for (int i = 0; i < 3; ++i) r[i] = wg[i] - V[i];
}

/// Concentrated load of the inline bodies of a junction on the line [N], problem frame: wet
/// weight and drag on the water velocity relative to the node, split along the line's tangent at
/// the junction (the bisector of the two sides' tangents, the 2-D mean angle) and across it.
template <class S>
void bodyLoads(const Problem& p, const MeshInterval& iv, const S* Ya, const S* Yb, const Water& w, S* P) {
  using std::sqrt;
  for (int i = 0; i < 3; ++i) P[i] = zeroLike(Ya[EPS]);
  if (iv.bodies.empty()) return;
  S Ra[9], Rb[9], r[3];
  quat::matrix(Ya + Q0, Ra);
  quat::matrix(Yb + Q0, Rb);
  relativeWater(Ya, Ra, w, r);
  S t[3] = {Ra[0] + Rb[0], Ra[3] + Rb[3], Ra[6] + Rb[6]};
  const S tn = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (S& c : t) c = c / tn;
  for (std::size_t k : iv.bodies) addBodyLoad(p.environment, p.bodies[k], t, r, P);
}

/// Free lower end (towing, paper section 5.2): the spatial part of the end body's force balance,
/// F_0 + P = 0 [N] (problem frame), F_0 the internal force at node 0 (the line's pull on the
/// body) and P the body's weight and drag (tangent e1 of node 0); F_0 = 0 without a body.
template <class S>
void freeEndForces(const Problem& p, const Material& m0, const S* Y0, const Water& w, S* R) {
  S F[3], P[3] = {zeroLike(Y0[EPS]), zeroLike(Y0[EPS]), zeroLike(Y0[EPS])};
  internalForce(m0, Y0, F);
  if (p.end_body != Problem::kNoBody) {
    S Rm[9], r[3];
    quat::matrix(Y0 + Q0, Rm);
    relativeWater(Y0, Rm, w, r);
    const S t[3] = {Rm[0], Rm[3], Rm[6]};
    addBodyLoad(p.environment, p.bodies[p.end_body], t, r, P);
  }
  for (int i = 0; i < 3; ++i) R[i] = F[i] + P[i];
}

/// Subsurface buoy at the top (TopBoundary::Body): the spatial part of its force balance,
/// F_n - P = 0 [N] (problem frame): the force it applies to the line's top end, F_n, equals its
/// wet weight (negative: net buoyancy) and drag P, tangent e1 of the top node. `extra` is an
/// external force on the body [N] (0 but for a force table).
template <class S>
void topBodyForces(const Problem& p, const Material& mn, const S* Yn, const Water& w, const double* extra, S* R) {
  S F[3], P[3] = {zeroLike(Yn[EPS]), zeroLike(Yn[EPS]), zeroLike(Yn[EPS])}, Rm[9], r[3];
  internalForce(mn, Yn, F);
  quat::matrix(Yn + Q0, Rm);
  relativeWater(Yn, Rm, w, r);
  const S t[3] = {Rm[0], Rm[3], Rm[6]};
  addBodyLoad(p.environment, p.bodies[p.top.body], t, r, P);
  for (int i = 0; i < 3; ++i) R[i] = F[i] - P[i] - extra[i];
}

/// A point body's mass and added mass times the global acceleration of the node it sits at,
/// times `sign` [N]: +1 for the top body's rows (F_n - P + M a = 0), -1 for the free end's
/// (F_0 + P - M a = 0).
template <class S>
void pointBodyInertia(double mass, double sign, const S* Yn, const S* Ydn, S* R) {
  S Rm[9], a[3], ag[3];
  quat::matrix(Yn + Q0, Rm);
  acceleration(Yn, Ydn, a);
  quat::toGlobal(Rm, a, ag);
  for (int i = 0; i < 3; ++i) R[i] = sign * mass * ag[i];
}

/// Inertia of the top body (rows of topBodyForces) [N].
template <class S>
void topBodyInertia(const Problem& p, const S* Yn, const S* Ydn, S* R) {
  pointBodyInertia(p.bodies[p.top.body].mass + p.bodies[p.top.body].added_mass, 1.0, Yn, Ydn, R);
}

/// Inertia of the end body (rows of freeEndForces) [N].
template <class S>
void freeEndInertia(const Problem& p, const S* Y0, const S* Yd0, S* R) {
  const double mass =
      p.end_body == Problem::kNoBody ? 0.0 : p.bodies[p.end_body].mass + p.bodies[p.end_body].added_mass;
  pointBodyInertia(mass, -1.0, Y0, Yd0, R);
}

/// Junction (pin joint, equations2d.hpp) between nodes a and b at the same arclength: spatial
/// part of the global force balance F_b - F_a + P = 0 (rows 0-2).
template <class S>
void junctionForces(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                    const S* Ya, const S* Yb, const Water& w, S* R) {
  S Fa[3], Fb[3], P[3];
  internalForce(ma, Ya, Fa);
  internalForce(mb, Yb, Fb);
  bodyLoads(p, iv, Ya, Yb, w, P);
  for (int i = 0; i < 3; ++i) R[i] = Fb[i] - Fa[i] + P[i];
}

/// Junction inertia (rows 0-2): minus the bodies' mass and added mass times node a's acceleration.
template <class S>
void junctionInertia(const Problem& p, const MeshInterval& iv, const S* Ya, const S* Yda, S* R) {
  double mass = 0.0;
  for (std::size_t k : iv.bodies) mass += p.bodies[k].mass + p.bodies[k].added_mass;
  S Ra[9], a[3], ag[3];
  quat::matrix(Ya + Q0, Ra);
  acceleration(Ya, Yda, a);
  quat::toGlobal(Ra, a, ag);
  for (int i = 0; i < 3; ++i) R[i] = -mass * ag[i];
}

/// Junction rows that hold at the new time level (rows 3-15): torque carried through, bending
/// moment free on both sides (a pin, eq. 33), no relative twist of the frames about the tangent,
/// equal frame norms, equal global velocities, coincident positions.
template <class S>
void junctionConstraints(const Material& ma, const Material& mb, const S* Ya, const S* Yb, S* R) {
  if (ma.GJ > 0.0 && mb.GJ > 0.0)
    R[3] = (mb.GJ * Yb[O1] - ma.GJ * Ya[O1]) / std::max(ma.GJ, mb.GJ);
  else
    R[3] = Yb[O1] - Ya[O1];
  R[4] = Ya[O2];
  R[5] = Ya[O3];
  R[6] = Yb[O2];
  R[7] = Yb[O3];
  S rel[4];
  quat::relative(Ya + Q0, Yb + Q0, rel);
  R[8] = rel[1];  // twist component of the relative rotation, about e1 of side a
  R[9] = Yb[Q0] * Yb[Q0] + Yb[Q1] * Yb[Q1] + Yb[Q2] * Yb[Q2] + Yb[Q3] * Yb[Q3] -
         (Ya[Q0] * Ya[Q0] + Ya[Q1] * Ya[Q1] + Ya[Q2] * Ya[Q2] + Ya[Q3] * Ya[Q3]);
  S Va[3], Vb[3];
  globalVelocity(Ya, Va);
  globalVelocity(Yb, Vb);
  for (int i = 0; i < 3; ++i) {
    R[10 + i] = Vb[i] - Va[i];
    R[13 + i] = Yb[X + i] - Ya[X + i];
  }
}

/// Force (Fx, Fy, Fz) a surface buoy applies to the line's top end hanging at elevation z [N]:
/// net buoyancy, current drag and wind (eq2d::buoyForce with the horizontal loads in 3-D).
template <class S>
void buoyForce(const Environment& env, const SurfaceBuoy& b, const S& z, S* F) {
  const S draft = -z;
  const double d = value(draft);
  const S V = eq2d::linearized(b.submergedVolume(d), b.submergedVolumeSlope(d), draft);
  const S A = eq2d::linearized(b.submergedArea(d), b.submergedAreaSlope(d), draft);
  double ux, uy;
  env.currentAt(0.0, ux, uy);
  const double speed = std::hypot(ux, uy);
  const double wx = env.wind_speed * std::cos(env.wind_direction);
  const double wy = env.wind_speed * std::sin(env.wind_direction);
  const double wind = 0.5 * env.air_density * b.wind_cd * b.wind_area * env.wind_speed;
  F[0] = 0.5 * env.water_density * b.cd * A * ux * speed + wind * wx;
  F[1] = 0.5 * env.water_density * b.cd * A * uy * speed + wind * wy;
  F[2] = env.water_density * env.gravity * V - b.mass * env.gravity;
}

/// Twist gauge of a moment-free line: the frame at a node does not turn about its tangent
/// relative to the reference frame q_ref (the twist component of q_ref* (x) q vanishes).
template <class S>
S twistGauge(const double* q_ref, const S* Yn) {
  const S ref[4] = {zeroLike(Yn[Q0]) + q_ref[0], zeroLike(Yn[Q0]) + q_ref[1], zeroLike(Yn[Q0]) + q_ref[2],
                    zeroLike(Yn[Q0]) + q_ref[3]};
  S rel[4];
  quat::relative(ref, Yn + Q0, rel);
  return rel[1];
}

/// |q|^2 - 1 at a node.
template <class S>
S normDefect(const S* Yn) {
  return Yn[Q0] * Yn[Q0] + Yn[Q1] * Yn[Q1] + Yn[Q2] * Yn[Q2] + Yn[Q3] * Yn[Q3] - 1.0;
}

}  // namespace eq3d
}  // namespace core
}  // namespace mooring_dynamics
