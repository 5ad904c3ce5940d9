// Euler parameters (unit quaternions) for the 3-D cable frame, written once for double and for
// automatic-differentiation scalars. Convention: q = (w, x, y, z), Hamilton product, and q maps
// local (body) components to the problem frame: v_global = R(q) v_local = q (x) (0, v) (x) q*.
// The frame kinematics are those of a body frame:
//   along the line   q' = 1/2 q (x) (0, Omega)   (Omega: curvature and twist, local) [1/m]
//   in time          q. = 1/2 q (x) (0, omega)   (omega: angular velocity, local) [rad/s]
// Euler parameters have no singular orientation (unlike the 2-D angle phi or Euler angles), so a
// line may pass through the vertical in any direction.
#pragma once

#include <cmath>

#include "mooring_dynamics/core/model/scalar.hpp"

namespace mooring_dynamics {
namespace core {
namespace quat {

/// Hamilton product a (x) b.
template <class S>
void multiply(const S* a, const S* b, S* out) {
  const S w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  const S x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  const S y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  const S z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  out[0] = w;
  out[1] = x;
  out[2] = y;
  out[3] = z;
}

/// conj(a) (x) b: the rotation from frame a to frame b, in frame a's components.
template <class S>
void relative(const S* a, const S* b, S* out) {
  const S ac[4] = {a[0], -a[1], -a[2], -a[3]};
  multiply(ac, b, out);
}

/// Rotation matrix R(q) (row-major 3x3), exact for unit q. Off the unit sphere (Newton iterates)
/// it is the same polynomial, which keeps the Jacobian smooth; the norm is a separate equation.
template <class S>
void matrix(const S* q, S* R) {
  const S &w = q[0], &x = q[1], &y = q[2], &z = q[3];
  R[0] = 1.0 - 2.0 * (y * y + z * z);
  R[1] = 2.0 * (x * y - w * z);
  R[2] = 2.0 * (x * z + w * y);
  R[3] = 2.0 * (x * y + w * z);
  R[4] = 1.0 - 2.0 * (x * x + z * z);
  R[5] = 2.0 * (y * z - w * x);
  R[6] = 2.0 * (x * z - w * y);
  R[7] = 2.0 * (y * z + w * x);
  R[8] = 1.0 - 2.0 * (x * x + y * y);
}

/// out = R v (local to global).
template <class S, class T>
void toGlobal(const S* R, const T* v, S* out) {
  for (int i = 0; i < 3; ++i) out[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}

/// out = R^T v (global to local).
template <class S, class T>
void toLocal(const S* R, const T* v, S* out) {
  for (int i = 0; i < 3; ++i) out[i] = R[i] * v[0] + R[3 + i] * v[1] + R[6 + i] * v[2];
}

/// exp(theta / 2) as a quaternion: the rotation by |theta| about theta / |theta| (theta [rad],
/// local components). cos(|t|/2) and sin(|t|/2)/|t| are smooth functions of |t|^2, evaluated by
/// their series near zero so that the derivative exists at theta = 0.
template <class S>
void expHalf(const S* theta, S* out) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S t2 = theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2];
  constexpr double kSeriesBelow = 1e-6;  // |theta|^2 [rad^2]: series error < 1e-25 there
  S c, k;  // cos(|t|/2), sin(|t|/2) / |t|
  if (value(t2) < kSeriesBelow) {
    c = 1.0 - t2 / 8.0 + t2 * t2 / 384.0;
    k = 0.5 - t2 / 48.0 + t2 * t2 / 3840.0;
  } else {
    const S a = sqrt(t2);
    c = cos(0.5 * a);
    k = sin(0.5 * a) / a;
  }
  out[0] = c;
  out[1] = k * theta[0];
  out[2] = k * theta[1];
  out[3] = k * theta[2];
}

/// Rotation by angle [rad] about a unit axis (double).
inline void axisAngle(double ax, double ay, double az, double angle, double* out) {
  const double s = std::sin(0.5 * angle);
  out[0] = std::cos(0.5 * angle);
  out[1] = s * ax;
  out[2] = s * ay;
  out[3] = s * az;
}

/// The cable frame of a line in the vertical plane at azimuth psi (ccw from +x), inclined by phi
/// from the vertical toward the azimuth (the 2-D solver's angle): tangent e1 = (sin phi cos psi,
/// sin phi sin psi, cos phi), e2 the in-plane normal (the 2-D n), e3 = e1 x e2 horizontal.
/// q = qz(psi) (x) qy(phi) (x) q_base, where q_base maps (x, y, z) to (z, x, y): at phi = 0
/// e1 = z, e2 = x, e3 = y.
inline void planarFrame(double psi, double phi, double* q) {
  const double base[4] = {0.5, -0.5, -0.5, -0.5};  // -120 deg about (1, 1, 1) / sqrt(3)
  double qz[4], qy[4], t[4];
  axisAngle(0.0, 0.0, 1.0, psi, qz);
  axisAngle(0.0, 1.0, 0.0, phi, qy);
  multiply(qy, base, t);
  multiply(qz, t, q);
}

}  // namespace quat
}  // namespace core
}  // namespace mooring_dynamics
