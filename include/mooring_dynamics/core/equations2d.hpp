// 2-D static cable equations (paper eqs. 1, 2, 5, 6 without time terms) on one half-grid
// interval of the box scheme (section 3), plus the coordinate equations (42) solved inside the
// Newton system. Written once for double and for automatic-differentiation scalars.
//
// Unknowns per node (N = 6): Y = [eps, Sn, phi, Omega3, x, z]
//   eps     strain [-]
//   Sn      shear force [N]
//   phi     inclination from the vertical, positive toward +x [rad]; tangent t = (sin phi, cos phi)
//   Omega3  curvature dphi/ds [1/m]
//   x, z    position in the problem frame [m]
// The internal force at a section is F = T t + Sn n with normal n = (cos phi, -sin phi).
#pragma once

#include <cmath>

#include "mooring_dynamics/core/mesh.hpp"
#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/core/scalar.hpp"
#include "mooring_dynamics/core/table.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq2d {

constexpr int N = 6;
enum Var { EPS = 0, SN = 1, PHI = 2, OMEGA = 3, X = 4, Z = 5 };
constexpr double kPi = 3.14159265358979323846;

/// T(eps) for a material, in the scalar type.
template <class S>
S tension(const Material& m, const S& eps) {
  if (m.tension_strain.empty()) return m.EA * eps;
  return interpolateTable(m.tension_strain, eps);
}

/// First-order expansion around the current value: f + df (x - value(x)). Lets functions
/// evaluated in double (with a known slope) enter the AD residual.
template <class S>
S linearized(double f, double df, const S& x) {
  return f + df * (x - value(x));
}

/// Seabed reaction per unit length, eq. 35 with the static cap F_bot <= w_o [N/m] (acts along +z).
template <class S>
S seabedForce(const Environment& env, const Material& m, const S& x, const S& z) {
  const double zb = env.seabedElevation(value(x));
  if (!(value(z) < zb)) return S(0.0) + 0.0 * z;
  const double cap = std::max(m.wet_weight, 0.0);
  const S zbS = linearized(zb, env.seabedSlope(value(x)), x);
  const S F = env.seabed.stiffness * (zbS - z);
  if (value(F) > cap) return S(cap) + 0.0 * z;  // strict: at the cap keep the spring's slope
  return F;
}

/// Horizontal current component along +x at elevation z [m/s], in the scalar type.
template <class S>
S currentX(const Environment& env, const S& z) {
  if (env.current.empty()) return S(0.0) + 0.0 * z;
  double ux0, uy0;
  env.currentAt(value(z), ux0, uy0);
  // Slope by a central difference on the piecewise-linear profile (exact inside a table interval).
  const double dz = 1e-6;
  double uxp, uyp, uxm, uym;
  env.currentAt(value(z) + dz, uxp, uyp);
  env.currentAt(value(z) - dz, uxm, uym);
  return linearized(ux0, (uxp - uxm) / (2.0 * dz), z);
}

/// Distributed static load per unit unstretched length at a node, resolved on the local frame:
/// f1 along t, f2 along n (the F terms of eq. 10 for the static case).
template <class S>
void distributedLoad(const Environment& env, const Material& m, const S* Y, S& f1, S& f2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S& eps = Y[EPS];
  const S& phi = Y[PHI];
  const S c = cos(phi), s = sin(phi);
  const S w = m.wet_weight - seabedForce(env, m, Y[X], Y[Z]);  // wet weight less the seabed (5.3)
  const S U = currentX(env, Y[Z]);
  const S ur = -U * s;  // tangential velocity of the cable relative to the water
  const S vr = -U * c;  // normal velocity of the cable relative to the water
  const S stretch = sqrt(1.0 + eps);
  const double rho = env.water_density;
  f1 = -w * c - 0.5 * rho * m.diameter * kPi * m.cdt * signedSquare(ur) * stretch;
  f2 = w * s - 0.5 * rho * m.diameter * m.cdn * signedSquare(vr) * stretch;
}

/// Concentrated load of an inline body at a junction with inclination phi and elevation z,
/// resolved on t (Pt) and n (Pn) [N].
template <class S>
void bodyLoad(const Environment& env, const Body& b, const S& phi, const S& z, S& Pt, S& Pn) {
  using std::cos;
  using std::sin;
  const S c = cos(phi), s = sin(phi);
  const S U = currentX(env, z);
  const S Ut = U * s, Un = U * c;  // water velocity along t and n
  const double area = 0.25 * kPi * b.diameter * b.diameter;
  const double q = 0.5 * env.water_density * area;
  Pt = -b.wet_weight * c + q * b.cdt * signedSquare(Ut);
  Pn = b.wet_weight * s + q * b.cdn * signedSquare(Un);
}

/// Residual of the half-grid interval between nodes a and b (eqs. 11 and 42, multiplied by h so
/// that zero-length junctions are included): six rows.
template <class S>
void intervalResidual(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                      const S* Ya, const S* Yb, S* R) {
  using std::cos;
  using std::pow;
  using std::sin;
  const double h = iv.h;
  const S Ta = tension(ma, Ya[EPS]), Tb = tension(mb, Yb[EPS]);
  const S pa = 1.0 + Ya[EPS], pb = 1.0 + Yb[EPS];
  const S dphi = Yb[PHI] - Ya[PHI];
  S f1a, f2a, f1b, f2b;
  if (h > 0.0) {
    distributedLoad(p.environment, ma, Ya, f1a, f2a);
    distributedLoad(p.environment, mb, Yb, f1b, f2b);
  } else {
    f1a = f2a = f1b = f2b = S(0.0) + 0.0 * Ya[EPS];
  }
  S Pt = S(0.0) + 0.0 * Ya[EPS], Pn = S(0.0) + 0.0 * Ya[EPS];
  for (std::size_t k : iv.bodies) {
    S t, n;
    bodyLoad(p.environment, p.bodies[k], S(0.5 * (Ya[PHI] + Yb[PHI])), S(0.5 * (Ya[Z] + Yb[Z])), t, n);
    Pt += t;
    Pn += n;
  }
  // (1) tangential force balance: dT/ds - Sn dphi/ds + f1 = 0
  R[0] = Tb - Ta - 0.5 * (Ya[SN] + Yb[SN]) * dphi + 0.5 * h * (f1a + f1b) + Pt;
  // (2) normal force balance: dSn/ds + T dphi/ds + f2 = 0
  R[1] = Yb[SN] - Ya[SN] + 0.5 * (Ta + Tb) * dphi + 0.5 * h * (f2a + f2b) + Pn;
  // (5) dphi/ds - Omega3 = 0
  R[2] = dphi - 0.5 * h * (Ya[OMEGA] + Yb[OMEGA]);
  // (6) EI dOmega3/ds + Sn (1 + eps)^3 = 0, moment EI Omega3 continuous across junctions
  R[3] = mb.EI * Yb[OMEGA] - ma.EI * Ya[OMEGA] + 0.5 * h * (Ya[SN] * pa * pa * pa + Yb[SN] * pb * pb * pb);
  // (42) coordinate integration: dx/ds = (1 + eps) sin phi, dz/ds = (1 + eps) cos phi
  R[4] = Yb[X] - Ya[X] - 0.5 * h * (pa * sin(Ya[PHI]) + pb * sin(Yb[PHI]));
  R[5] = Yb[Z] - Ya[Z] - 0.5 * h * (pa * cos(Ya[PHI]) + pb * cos(Yb[PHI]));
}

/// Internal force F = T t + Sn n at a node in the problem frame: (Fx, Fz) [N].
template <class S>
void internalForce(const Material& m, const S* Y, S& Fx, S& Fz) {
  using std::cos;
  using std::sin;
  const S T = tension(m, Y[EPS]);
  const S c = cos(Y[PHI]), s = sin(Y[PHI]);
  Fx = T * s + Y[SN] * c;
  Fz = T * c - Y[SN] * s;
}

/// Force (Fx, Fz) a surface buoy applies to the line's top end when the line hangs at elevation z
/// (buoy draft = -z, the line attached at the keel) [N]: net buoyancy, current drag and wind.
template <class S>
void buoyForce(const Environment& env, const SurfaceBuoy& b, const S& z, S& Fx, S& Fz) {
  const S draft = -z;
  const double d = value(draft);
  const S V = linearized(b.submergedVolume(d), b.submergedVolumeSlope(d), draft);
  const S A = linearized(b.submergedArea(d), b.submergedAreaSlope(d), draft);
  double ux, uy;
  env.currentAt(0.0, ux, uy);
  const double wind_x = env.wind_speed * std::cos(env.wind_direction);
  Fz = env.water_density * env.gravity * V - b.mass * env.gravity;
  Fx = 0.5 * env.water_density * b.cd * A * ux * std::abs(ux) +
       0.5 * env.air_density * b.wind_cd * b.wind_area * wind_x * std::abs(wind_x);
}

}  // namespace eq2d
}  // namespace core
}  // namespace mooring_dynamics
