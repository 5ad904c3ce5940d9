// 2-D dynamic cable equations (paper eqs. 1-10) on one half-grid interval, split as in eq. 7 into
// the inertia part M(Y) dY/dt and the spatial part K(Y) dY/ds + F(Y), so that the
// generalized-alpha weighting (eq. 30) can be applied to each. Written once for double and for
// automatic-differentiation scalars.
//
// Unknowns per node (N = 8): Y = [eps, Sn, u, v, phi, Omega3, x, z]
//   u, v   cable velocity along the tangent t = (sin phi, cos phi) and the normal
//          n = (cos phi, -sin phi) [m/s]; the global velocity is u t + v n.
// The other unknowns are those of the static equations (equations2d.hpp).
#pragma once

#include <cmath>

#include "mooring_dynamics/core/equations/equations2d.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq2dyn {

constexpr int N = 8;
enum Var { EPS = 0, SN = 1, U = 2, V = 3, PHI = 4, OMEGA = 5, X = 6, Z = 7 };
/// Rows of an interval whose spatial part is weighted in time (eq. 30): the six paper equations.
/// Rows 6 and 7 (coordinates, eq. 42) hold at the new time level.
constexpr int kWeightedRows = 6;

/// Water velocity (current plus waves) at a node, in the problem frame [m/s], evaluated by the
/// caller in double at the node's position, with the current's vertical gradient so that the
/// Jacobian carries the depth dependence of the current profile (the waves' dependence on the
/// node position is left out of the Jacobian: a quasi-Newton term).
struct Water {
  double wx = 0.0, wz = 0.0;
  double z = 0.0;         ///< elevation the values were taken at [m]
  double dwx_dz = 0.0;    ///< vertical gradient of the current [1/s]
};

/// Horizontal water velocity at node state Y, linear in the node's elevation about w.z.
template <class S>
S waterX(const Water& w, const S* Y) {
  return w.wx + w.dwx_dz * (Y[Z] - w.z);
}

/// cos and sin of a node's inclination Y[PHI], computed once for the functions below that
/// take them (the same values, and in AutoDiff the same derivatives, as cos(Y[PHI]), sin(Y[PHI])).
template <class S>
struct Angle {
  S c, s;
};
template <class S>
Angle<S> angleOf(const S* Y) {
  using std::cos;
  using std::sin;
  return {cos(Y[PHI]), sin(Y[PHI])};
}

/// Global velocity (Vx, Vz) of a node from its local components, with a = angleOf(Y).
template <class S>
void globalVelocity(const S* Y, const Angle<S>& a, S& Vx, S& Vz) {
  Vx = Y[U] * a.s + Y[V] * a.c;
  Vz = Y[U] * a.c - Y[V] * a.s;
}
template <class S>
void globalVelocity(const S* Y, S& Vx, S& Vz) {
  globalVelocity(Y, angleOf(Y), Vx, Vz);
}

/// Internal force F = T t + Sn n (Fx, Fz) [N], with a = angleOf(Y).
template <class S>
void internalForce(const Material& m, const S* Y, const Angle<S>& a, S& Fx, S& Fz) {
  const S T = eq2d::tension(m, Y[EPS]);
  Fx = T * a.s + Y[SN] * a.c;
  Fz = T * a.c - Y[SN] * a.s;
}
template <class S>
void internalForce(const Material& m, const S* Y, S& Fx, S& Fz) {
  internalForce(m, Y, angleOf(Y), Fx, Fz);
}

/// Distributed load per unit unstretched length at a node, along t (f1) and n (f2): wet weight
/// less the seabed reaction (eqs. 35-36, no static cap), drag on the velocity relative to the
/// water (eqs. 1-2), and the seabed's axial friction on the grounded line.
template <class S>
void distributedLoad(const Environment& env, const Material& m, const S* Y, const Water& w, const S& Fbot,
                     S& f1, S& f2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S c = cos(Y[PHI]), s = sin(Y[PHI]);
  const S wx = waterX(w, Y);
  const S wt = wx * s + w.wz * c;   // water velocity along t
  const S wn = wx * c - w.wz * s;   // and along n
  const S ur = Y[U] - wt, vr = Y[V] - wn;
  const S stretch = sqrt(1.0 + Y[EPS]);
  const double rho = env.water_density;
  const S weight = m.wet_weight - Fbot;
  f1 = -weight * c - 0.5 * rho * m.diameter * eq2d::kPi * m.cdt * signedSquare(ur) * stretch;
  f2 = weight * s - 0.5 * rho * m.diameter * m.cdn * signedSquare(vr) * stretch;
  // Seabed friction along the line on the sliding velocity u (docs/method.md, "Seabed friction").
  if (m.mu_axial > 0.0 && value(Fbot) > 0.0) f1 = f1 - m.mu_axial * Fbot * eq2d::frictionRamp(Y[U]);
}

/// Seabed reaction per unit length at a node: spring on the penetration (eq. 35, onset smoothed
/// as in statics) and dashpot on the vertical velocity (eq. 36) while in contact [N/m], along +z.
template <class S>
S seabedReaction(const Environment& env, const Material& m, const S* Y) {
  const double delta = eq2d::contactOnset(env, m);
  const S spring = eq2d::seabedSpring(env, Y[X], Y[Z], delta);
  if (!(value(spring) > 0.0) || env.seabed.damping == 0.0) return spring;
  S Vx, Vz;
  globalVelocity(Y, Vx, Vz);
  return spring - env.seabed.damping * eq2d::contactFraction(env, Y[X], Y[Z], delta) * Vz;
}

/// Inertia rows per unit length at a node, M(Y) dY/dt of eq. 8 (rows 0-3), given the rate Yd.
/// The water's tangential velocity enters the added-mass term of eq. 2.
template <class S>
void inertia(const Environment& env, const Material& m, const S* Y, const S* Yd, const Water& w, S* out) {
  using std::cos;
  using std::sin;
  const S c = cos(Y[PHI]), s = sin(Y[PHI]);
  const S wt = waterX(w, Y) * s + w.wz * c;
  const double rhoA = 0.25 * env.water_density * eq2d::kPi * m.diameter * m.diameter;
  out[0] = -m.mass * Yd[U] + m.mass * Y[V] * Yd[PHI];                                          // eq. 1
  out[1] = -(m.mass + m.added_mass) * Yd[V] - (m.mass * Y[U] + (rhoA + m.added_mass) * wt) * Yd[PHI];  // eq. 2
  out[2] = -Yd[EPS];                                                                           // eq. 3
  out[3] = -(1.0 + Y[EPS]) * Yd[PHI];                                                          // eq. 4
}

/// Spatial part K dY/ds + F of one interval of length h > 0, times h (eq. 11): eight rows.
template <class S>
void intervalSpatial(const Environment& env, const Material& mat, double h, const S* Ya, const S* Yb,
                     const Water& wa, const Water& wb, S* R) {
  using std::cos;
  using std::sin;
  const S Ta = eq2d::tension(mat, Ya[EPS]), Tb = eq2d::tension(mat, Yb[EPS]);
  const S pa = 1.0 + Ya[EPS], pb = 1.0 + Yb[EPS];
  const S dphi = Yb[PHI] - Ya[PHI];
  S f1a, f2a, f1b, f2b;
  distributedLoad(env, mat, Ya, wa, seabedReaction(env, mat, Ya), f1a, f2a);
  distributedLoad(env, mat, Yb, wb, seabedReaction(env, mat, Yb), f1b, f2b);
  R[0] = Tb - Ta - 0.5 * (Ya[SN] + Yb[SN]) * dphi + 0.5 * h * (f1a + f1b);   // eq. 1
  R[1] = Yb[SN] - Ya[SN] + 0.5 * (Ta + Tb) * dphi + 0.5 * h * (f2a + f2b);   // eq. 2
  R[2] = Yb[U] - Ya[U] - 0.5 * (Ya[V] + Yb[V]) * dphi;                       // eq. 3
  R[3] = Yb[V] - Ya[V] + 0.5 * (Ya[U] + Yb[U]) * dphi;                       // eq. 4
  R[4] = dphi - 0.5 * h * (Ya[OMEGA] + Yb[OMEGA]);                           // eq. 5
  R[5] = mat.EI * (Yb[OMEGA] - Ya[OMEGA]) +
         0.5 * h * (Ya[SN] * pa * pa * pa + Yb[SN] * pb * pb * pb);          // eq. 6
  R[6] = Yb[X] - Ya[X] - 0.5 * h * (pa * sin(Ya[PHI]) + pb * sin(Yb[PHI]));  // eq. 42
  R[7] = Yb[Z] - Ya[Z] - 0.5 * h * (pa * cos(Ya[PHI]) + pb * cos(Yb[PHI]));
}

/// Inertia part of one interval (times h): h/2 (M_a Yd_a + M_b Yd_b) in rows 0-3, zero below.
template <class S>
void intervalInertia(const Environment& env, const Material& mat, double h, const S* Ya, const S* Yb,
                     const S* Yda, const S* Ydb, const Water& wa, const Water& wb, S* R) {
  S ia[4], ib[4];
  inertia(env, mat, Ya, Yda, wa, ia);
  inertia(env, mat, Yb, Ydb, wb, ib);
  for (int r = 0; r < 4; ++r) R[r] = 0.5 * h * (ia[r] + ib[r]);
  for (int r = 4; r < N; ++r) R[r] = S(0.0) + 0.0 * Ya[EPS];
}

/// Junction (pin joint, see equations2d.hpp) between nodes a and b at the same arclength:
/// spatial part of the force balance with the bodies' weight and drag (rows 0-1), with
/// aa = angleOf(Ya), ab = angleOf(Yb).
template <class S>
void junctionForces(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                    const S* Ya, const S* Yb, const Angle<S>& aa, const Angle<S>& ab, const Water& w, S* R) {
  using std::cos;
  using std::sin;
  S Fxa, Fza, Fxb, Fzb;
  internalForce(ma, Ya, aa, Fxa, Fza);
  internalForce(mb, Yb, ab, Fxb, Fzb);
  S Px = S(0.0) + 0.0 * Ya[EPS], Pz = S(0.0) + 0.0 * Ya[EPS];
  S Vx, Vz;
  globalVelocity(Ya, aa, Vx, Vz);
  const S phi = 0.5 * (Ya[PHI] + Yb[PHI]);
  const S c = cos(phi), s = sin(phi);
  for (std::size_t k : iv.bodies) {
    const Body& b = p.bodies[k];
    // Drag on the velocity of the water relative to the body: along it (a sphere), or split along
    // and across the line (a line-aligned body).
    const S rx = waterX(w, Ya) - Vx, rz = w.wz - Vz;
    const double q = 0.5 * p.environment.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter;
    if (b.drag == Body::Drag::Sphere) {
      using std::sqrt;
      const S rm = sqrt(rx * rx + rz * rz + eq2d::kBodySpeedFloor * eq2d::kBodySpeedFloor);
      Px += q * b.cd * rm * rx;
      Pz += q * b.cd * rm * rz - b.wet_weight;
      continue;
    }
    const S rt = rx * s + rz * c, rn = rx * c - rz * s;
    const S dt = q * b.cdt * signedSquare(rt), dn = q * b.cdn * signedSquare(rn);
    Px += dt * s + dn * c;
    Pz += dt * c - dn * s - b.wet_weight;
  }
  R[0] = Fxb - Fxa + Px;
  R[1] = Fzb - Fza + Pz;
}
template <class S>
void junctionForces(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                    const S* Ya, const S* Yb, const Water& w, S* R) {
  junctionForces(p, iv, ma, mb, Ya, Yb, angleOf(Ya), angleOf(Yb), w, R);
}

/// Junction inertia (rows 0-1): minus mass times acceleration of the bodies there, with
/// aa = angleOf(Ya).
template <class S>
void junctionInertia(const Problem& p, const MeshInterval& iv, const S* Ya, const Angle<S>& aa, const S* Yda, S* R) {
  double mass = 0.0;
  for (std::size_t k : iv.bodies) mass += p.bodies[k].mass + p.bodies[k].added_mass;
  // Acceleration of node a: (du/dt - v dphi/dt) t + (dv/dt + u dphi/dt) n.
  const S& c = aa.c;
  const S& s = aa.s;
  const S at = Yda[U] - Ya[V] * Yda[PHI], an = Yda[V] + Ya[U] * Yda[PHI];
  R[0] = -mass * (at * s + an * c);
  R[1] = -mass * (at * c - an * s);
}
template <class S>
void junctionInertia(const Problem& p, const MeshInterval& iv, const S* Ya, const S* Yda, S* R) {
  junctionInertia(p, iv, Ya, angleOf(Ya), Yda, R);
}

/// Junction rows that hold at the new time level (rows 2-7): moment-free pin on both sides,
/// coincident positions, equal global velocities; aa = angleOf(Ya), ab = angleOf(Yb).
template <class S>
void junctionConstraints(const S* Ya, const S* Yb, const Angle<S>& aa, const Angle<S>& ab, S* R) {
  S Vxa, Vza, Vxb, Vzb;
  globalVelocity(Ya, aa, Vxa, Vza);
  globalVelocity(Yb, ab, Vxb, Vzb);
  R[2] = Ya[OMEGA];
  R[3] = Yb[OMEGA];
  R[4] = Vxb - Vxa;
  R[5] = Vzb - Vza;
  R[6] = Yb[X] - Ya[X];
  R[7] = Yb[Z] - Ya[Z];
}
template <class S>
void junctionConstraints(const S* Ya, const S* Yb, S* R) {
  junctionConstraints(Ya, Yb, angleOf(Ya), angleOf(Yb), R);
}

}  // namespace eq2dyn
}  // namespace core
}  // namespace mooring_dynamics
