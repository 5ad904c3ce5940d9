// Drifting systems (issue 6): the rows of a surface buoy at the top of a line whose lower end is
// free (free_end: with top.buoy, 3-D model). The buoy has its own force balance; with both ends
// free, the kinematics of the top node, dx_n/dt = V_n, fix where the line is. Written once for
// double and AutoDiff scalars, as equations3d.hpp.
#pragma once

#include <cmath>

#include "mooring_dynamics/core/equations/equations3d.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq3d {

/// Force (problem frame) [N] a drifting surface buoy applies to the line's top end, which hangs at
/// the buoy's keel, at the top node state Yn (dynamics):
///   horizontal: water drag 1/2 rho cd A(d) |r| r on the surface current relative to the buoy
///               (r = U(0) - V_n, horizontal), wind drag 1/2 rho_a cd_w A_w |w| w on the wind
///               relative to it (w = W - V_n);
///   vertical:   buoyancy rho g V(d) of the draft d = -z_n less the buoy's weight.
/// Waves are not in the buoy's load (no wave elevation, Froude-Krylov or radiation terms: the
/// buoy floats on the mean surface), nor is vertical drag; they still act on the line. In the
/// steady drift (V_n = V_d) it equals buoyForce in the environment relative to the drift
/// (driftEnvironment), which the statics use.
template <class S>
void driftBuoyForce(const Environment& env, const SurfaceBuoy& b, const S* Yn, S* F) {
  using std::sqrt;
  const S draft = -Yn[Z];
  const double d = value(draft);
  const S vol = eq2d::linearized(b.submergedVolume(d), b.submergedVolumeSlope(d), draft);
  const S A = eq2d::linearized(b.submergedArea(d), b.submergedAreaSlope(d), draft);
  S V[3];
  globalVelocity(Yn, V);
  double ux, uy;
  env.currentAt(0.0, ux, uy);
  const double wx = env.wind_speed * std::cos(env.wind_direction);
  const double wy = env.wind_speed * std::sin(env.wind_direction);
  const S rx = ux - V[0], ry = uy - V[1];
  const S ax = wx - V[0], ay = wy - V[1];
  const double fl = kDragSpeedFloor * kDragSpeedFloor;
  const S rs = sqrt(rx * rx + ry * ry + fl), as = sqrt(ax * ax + ay * ay + fl);
  const S water = 0.5 * env.water_density * b.cd * A * rs;
  const double wind = 0.5 * env.air_density * b.wind_cd * b.wind_area;
  F[0] = water * rx + wind * as * ax;
  F[1] = water * ry + wind * as * ay;
  F[2] = env.water_density * env.gravity * vol - b.mass * env.gravity;
}

/// Spatial part of the drifting buoy's force balance, F_n - B - extra = 0 [N] (the rows of
/// topBodyForces with the surface buoy's load); `extra` an external force on the buoy [N].
template <class S>
void driftBuoyForces(const Environment& env, const SurfaceBuoy& b, const Material& mn, const S* Yn,
                     const double* extra, S* R) {
  S F[3], B[3];
  internalForce(mn, Yn, F);
  driftBuoyForce(env, b, Yn, B);
  for (int i = 0; i < 3; ++i) R[i] = F[i] - B[i] - extra[i];
}

/// Inertia of the drifting buoy: plus (mass + added mass) times the top node's acceleration [N]
/// (the added mass taken the same in every direction).
template <class S>
void driftBuoyInertia(const SurfaceBuoy& b, const S* Yn, const S* Ydn, S* R) {
  const double mass = b.mass + b.added_mass;
  S Rm[9], a[3], ag[3];
  quat::matrix(Yn + Q0, Rm);
  acceleration(Yn, Ydn, a);
  quat::toGlobal(Rm, a, ag);
  for (int i = 0; i < 3; ++i) R[i] = mass * ag[i];
}

}  // namespace eq3d
}  // namespace core
}  // namespace mooring_dynamics
