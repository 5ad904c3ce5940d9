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

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/scalar.hpp"
#include "mooring_dynamics/core/model/table.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq2d {

constexpr int N = 6;
enum Var { EPS = 0, SN = 1, PHI = 2, OMEGA = 3, X = 4, Z = 5 };
constexpr double kPi = 3.14159265358979323846;

/// T(eps) for a material, in the scalar type (Material::tension): the law as given, through the
/// slack ramp unless the material carries compression.
template <class S>
S tension(const Material& m, const S& eps) {
  if (m.compression) {
    if (m.tension_strain.empty()) return m.EA * eps;
    return interpolateTable(m.tension_strain, eps);
  }
  const S T = m.tension_strain.empty() ? S(m.EA * eps) : interpolateTable(m.tension_strain, eps);
  return slackRamp(T, value(T), m.slackBand());
}

/// First-order expansion around the current value: f + df (x - value(x)). Lets functions
/// evaluated in double (with a known slope) enter the AD residual.
template <class S>
S linearized(double f, double df, const S& x) {
  return f + df * (x - value(x));
}

/// Width of the contact onset [m]: the rest penetration w_o / k of the line (see seabedSpring).
inline double contactOnset(const Environment& env, const Material& m) {
  return std::max(m.wet_weight, 0.0) / env.seabed.stiffness;
}

/// Seabed reaction per unit length at a node, eq. 35 without the cap [N/m] (acts along +z): the
/// spring k (z_bot(x) - z) on the penetration p, with its onset smoothed over the first
/// delta = w_o / k of penetration (k p^2 / (2 delta) below delta, k (p - delta / 2) beyond). A
/// sharp onset makes Newton cycle a touchdown node in and out of contact; the smoothed law has a
/// continuous slope and shifts a resting line by delta / 2 (a fraction of a millimetre for
/// typical k).
template <class S>
S seabedSpring(const Environment& env, const S& x, const S& z, double delta) {
  const double zb = env.seabedElevation(value(x));
  if (!(value(z) < zb)) return S(0.0) + 0.0 * z;
  const S zbS = linearized(zb, env.seabedSlope(value(x)), x);
  const S p = zbS - z;
  const double k = env.seabed.stiffness;
  if (delta > 0.0 && value(p) < delta) return k * p * p / (2.0 * delta);
  return k * (p - 0.5 * delta);
}

/// Fraction of the seabed dashpot acting at a node: ramps from 0 to 1 over the contact onset.
template <class S>
S contactFraction(const Environment& env, const S& x, const S& z, double delta) {
  const double zb = env.seabedElevation(value(x));
  if (!(value(z) < zb)) return S(0.0) + 0.0 * z;
  const S p = linearized(zb, env.seabedSlope(value(x)), x) - z;
  if (delta > 0.0 && value(p) < delta) return p / delta;
  return S(1.0) + 0.0 * z;
}

/// Seabed reactions at the two nodes of a half-grid interval of material m, with the static cap
/// of eq. 35 (F_bot <= w_o) applied to the interval's mean reaction: when it exceeds w_o both
/// nodal reactions are scaled down proportionally. Capping each node separately would cap the
/// box scheme's odd-even mode (nodal elevations alternating about the rest penetration along
/// grounded line) and remove the only stiffness that mode has, and Newton then diverges.
template <class S>
void seabedForces(const Environment& env, const Material& m, const S* Ya, const S* Yb, bool capped, S& Fa, S& Fb) {
  const double delta = contactOnset(env, m);
  Fa = seabedSpring(env, Ya[X], Ya[Z], delta);
  Fb = seabedSpring(env, Yb[X], Yb[Z], delta);
  const double cap = std::max(m.wet_weight, 0.0);
  const S mean = 0.5 * (Fa + Fb);
  if (capped && value(mean) > cap) {
    const double factor = cap / value(mean);
    // Value capped; slope kept from the spring (modified Newton), see the note above.
    Fa = Fa + value(Fa) * (factor - 1.0);
    Fb = Fb + value(Fb) * (factor - 1.0);
  }
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

/// Sliding speed below which dynamic seabed friction is viscous [m/s]: the Coulomb force
/// -mu F_bot v / |v| is replaced by -mu F_bot v / v_f for |v| < v_f (docs/method.md, "Seabed
/// friction"). A stick-slip model would need a state per node and an event in the Newton
/// iteration; the linear ramp keeps the rows smooth enough for Newton and differs from Coulomb
/// only while a grounded node creeps slower than 1 cm/s.
constexpr double kFrictionSpeed = 0.01;

/// The regularized sign of a sliding velocity v [m/s]: v / v_f below kFrictionSpeed, +-1 above.
template <class S>
S frictionRamp(const S& v) {
  const double a = value(v);
  if (a > kFrictionSpeed) return 0.0 * v + 1.0;
  if (a < -kFrictionSpeed) return 0.0 * v - 1.0;
  return v / kFrictionSpeed;
}
inline double frictionRampSlope(double v) { return std::abs(v) > kFrictionSpeed ? 0.0 : 1.0 / kFrictionSpeed; }

/// Tension over which the static seabed friction of a grounded line is mobilized: the friction
/// of kStaticFrictionLength of line (mu_axial w_o times this length) [m]. See staticFriction.
constexpr double kStaticFrictionLength = 1.0;

/// Static axial seabed friction per unit length along t [N/m] (docs/method.md, "Seabed
/// friction"): the line is taken as laid from the anchor and pulled toward the top, so Coulomb
/// friction -mu_axial F_bot opposes that pull along the grounded length; F_bot is the nominal
/// reaction w_o times the contact fraction (distributedLoad). It is mobilized by the
/// tension that pulls the line: a smooth step from 0 at T <= 0 to 1 at T >= T_f = mu_axial w_o
/// kStaticFrictionLength (3x^2 - 2x^3 between), so a stretch the pull never reaches stays slack
/// with no friction instead of being pushed toward the anchor.
template <class S>
S staticFriction(const Material& m, const S& eps, const S& Fbot) {
  const S T = tension(m, eps);
  const double Tf = m.mu_axial * std::max(m.wet_weight, 0.0) * kStaticFrictionLength;
  const double Tv = value(T);
  if (!(Tv > 0.0) || !(Tf > 0.0)) return 0.0 * Fbot;
  if (Tv >= Tf) return -m.mu_axial * Fbot;
  const S x = T / Tf;
  return -m.mu_axial * Fbot * x * x * (3.0 - 2.0 * x);
}

/// Distributed static load per unit unstretched length at a node, resolved on the local frame:
/// f1 along t, f2 along n (the F terms of eq. 10 for the static case). Fbot is the seabed
/// reaction acting on this stretch of line [N/m]; with mu_axial > 0 its axial friction
/// (staticFriction) is added to f1.
template <class S>
void distributedLoad(const Environment& env, const Material& m, const S* Y, const S& Fbot, S& f1, S& f2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S& eps = Y[EPS];
  const S& phi = Y[PHI];
  const S c = cos(phi), s = sin(phi);
  const S w = m.wet_weight - Fbot;  // wet weight less the seabed reaction (5.3)
  const S U = currentX(env, Y[Z]);
  const S ur = -U * s;  // tangential velocity of the cable relative to the water
  const S vr = -U * c;  // normal velocity of the cable relative to the water
  const S stretch = sqrt(1.0 + eps);
  const double rho = env.water_density;
  f1 = -w * c - 0.5 * rho * m.diameter * kPi * m.cdt * signedSquare(ur) * stretch;
  f2 = w * s - 0.5 * rho * m.diameter * m.cdn * signedSquare(vr) * stretch;
  // Static friction on the nominal reaction w_o, ramped in over the contact onset: the spring's
  // reaction would couple the friction to the grounded line's odd-even mode of the nodal
  // elevations (see seabedForces), and Newton then cycles.
  if (m.mu_axial > 0.0 && value(Fbot) > 0.0) {
    const S reaction = std::max(m.wet_weight, 0.0) * contactFraction(env, Y[X], Y[Z], contactOnset(env, m));
    f1 = f1 + staticFriction(m, eps, reaction);
  }
}

/// Regularisation of a point body's relative speed |r| = sqrt(r.r + delta^2) in its quadratic
/// sphere drag [m/s]: keeps the drag differentiable at zero relative velocity; it changes the drag
/// by less than rho Cd A delta |r| / 2, below 1e-3 N for any body here.
constexpr double kBodySpeedFloor = 1e-6;

/// Concentrated load of an inline body at a junction with inclination phi and elevation z,
/// resolved on t (Pt) and n (Pn) [N]. A sphere's drag 1/2 rho Cd A |U| U acts along the current
/// (the statics' relative flow is the current, horizontal); a line-aligned body's splits along t
/// and n.
template <class S>
void bodyLoad(const Environment& env, const Body& b, const S& phi, const S& z, S& Pt, S& Pn) {
  using std::cos;
  using std::sin;
  const S c = cos(phi), s = sin(phi);
  const S U = currentX(env, z);
  const double area = 0.25 * kPi * b.diameter * b.diameter;
  const double q = 0.5 * env.water_density * area;
  if (b.drag == Body::Drag::Sphere) {
    const S Fx = q * b.cd * signedSquare(U);  // force (Fx, -W) resolved on t = (s, c), n = (c, -s)
    Pt = -b.wet_weight * c + Fx * s;
    Pn = b.wet_weight * s + Fx * c;
    return;
  }
  const S Ut = U * s, Un = U * c;  // water velocity along t and n
  Pt = -b.wet_weight * c + q * b.cdt * signedSquare(Ut);
  Pn = b.wet_weight * s + q * b.cdn * signedSquare(Un);
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

/// Residual of a zero-length junction (segment boundary or inline body): a pin joint. The two
/// nodes coincide, the internal force jumps by the concentrated load of the bodies there
/// (global force balance, exact for any kink angle), and the moment vanishes on both sides,
/// like the moment-free ends of eq. 33. A pin lets a low-EI line kink at a point load, which the
/// half-grid rows of eq. 11 could only represent with a very fine mesh.
template <class S>
void junctionResidual(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                      const S* Ya, const S* Yb, S* R) {
  using std::cos;
  using std::sin;
  S Fxa, Fza, Fxb, Fzb;
  internalForce(ma, Ya, Fxa, Fza);
  internalForce(mb, Yb, Fxb, Fzb);
  S Px = S(0.0) + 0.0 * Ya[EPS], Pz = S(0.0) + 0.0 * Ya[EPS];
  const S phi = 0.5 * (Ya[PHI] + Yb[PHI]);
  for (std::size_t k : iv.bodies) {
    S t, n;
    bodyLoad(p.environment, p.bodies[k], phi, Ya[Z], t, n);
    Px += t * sin(phi) + n * cos(phi);  // t = (sin, cos), n = (cos, -sin)
    Pz += t * cos(phi) - n * sin(phi);
  }
  R[0] = Fxb - Fxa + Px;
  R[1] = Fzb - Fza + Pz;
  R[2] = Ya[OMEGA];
  R[3] = Yb[OMEGA];
  R[4] = Yb[X] - Ya[X];
  R[5] = Yb[Z] - Ya[Z];
}

/// Residual of the half-grid interval between nodes a and b (eqs. 11 and 42, multiplied by h):
/// six rows. `capped` applies the static seabed cap of eq. 35.
template <class S>
void intervalResidual(const Problem& p, const MeshInterval& iv, const Material& ma, const Material& mb,
                      const S* Ya, const S* Yb, S* R, bool capped) {
  using std::cos;
  using std::sin;
  const double h = iv.h;
  if (h == 0.0) {
    junctionResidual(p, iv, ma, mb, Ya, Yb, R);
    return;
  }
  const S Ta = tension(ma, Ya[EPS]), Tb = tension(mb, Yb[EPS]);
  const S pa = 1.0 + Ya[EPS], pb = 1.0 + Yb[EPS];
  const S dphi = Yb[PHI] - Ya[PHI];
  S f1a, f2a, f1b, f2b, Fa, Fb;
  seabedForces(p.environment, ma, Ya, Yb, capped, Fa, Fb);
  distributedLoad(p.environment, ma, Ya, Fa, f1a, f2a);
  distributedLoad(p.environment, mb, Yb, Fb, f1b, f2b);
  // (1) tangential force balance: dT/ds - Sn dphi/ds + f1 = 0
  R[0] = Tb - Ta - 0.5 * (Ya[SN] + Yb[SN]) * dphi + 0.5 * h * (f1a + f1b);
  // (2) normal force balance: dSn/ds + T dphi/ds + f2 = 0
  R[1] = Yb[SN] - Ya[SN] + 0.5 * (Ta + Tb) * dphi + 0.5 * h * (f2a + f2b);
  // (5) dphi/ds - Omega3 = 0
  R[2] = dphi - 0.5 * h * (Ya[OMEGA] + Yb[OMEGA]);
  // (6) EI dOmega3/ds + Sn (1 + eps)^3 = 0
  R[3] = ma.EI * (Yb[OMEGA] - Ya[OMEGA]) + 0.5 * h * (Ya[SN] * pa * pa * pa + Yb[SN] * pb * pb * pb);
  // (42) coordinate integration: dx/ds = (1 + eps) sin phi, dz/ds = (1 + eps) cos phi
  R[4] = Yb[X] - Ya[X] - 0.5 * h * (pa * sin(Ya[PHI]) + pb * sin(Yb[PHI]));
  R[5] = Yb[Z] - Ya[Z] - 0.5 * h * (pa * cos(Ya[PHI]) + pb * cos(Yb[PHI]));
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
