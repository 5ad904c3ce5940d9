#include "mooring_dynamics/core/solvers/towing.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "mooring_dynamics/core/equations/equations3d.hpp"

namespace mooring_dynamics {
namespace core {

Environment relativeEnvironment(const Environment& env, double vx, double vy) {
  Environment out = env;
  if (vx == 0.0 && vy == 0.0) return out;
  if (out.current.empty()) {
    CurrentPoint c;
    c.depth = 0.0;
    out.current.push_back(c);
  }
  for (CurrentPoint& c : out.current) {
    const double ux = c.speed * std::cos(c.direction) - vx;
    const double uy = c.speed * std::sin(c.direction) - vy;
    c.speed = std::hypot(ux, uy);
    c.direction = std::atan2(uy, ux);
  }
  return out;
}

namespace {

using Eigen::Vector3d;

/// Distributed load g per unit length [N/m] (problem frame) on a line at rest with tangent t in
/// water moving at w: wet weight and quadratic drag (equations3d.hpp, line velocity zero).
Vector3d lineLoad(const Environment& env, const Material& m, const Vector3d& t, const Vector3d& w) {
  const double wt = w.dot(t);
  const Vector3d wn = w - wt * t;
  const double rho = env.water_density;
  return Vector3d(0.0, 0.0, -m.wet_weight) + 0.5 * rho * m.diameter * m.cdn * wn.norm() * wn +
         0.5 * rho * eq2d::kPi * m.diameter * m.cdt * std::abs(wt) * wt * t;
}

Vector3d bodyLoad(const Environment& env, const Body& b, const Vector3d& t, const Vector3d& w) {
  double tt[3] = {t.x(), t.y(), t.z()}, ww[3] = {w.x(), w.y(), w.z()}, P[3] = {0.0, 0.0, 0.0};
  eq3d::addBodyLoad(env, b, tt, ww, P);
  return Vector3d(P[0], P[1], P[2]);
}

Vector3d waterAt(const Environment& env, double z) {
  double ux, uy;
  env.currentAt(z, ux, uy);
  return Vector3d(ux, uy, 0.0);
}

/// Tangent along the force F, or, where the force vanishes (a bare free end), the direction the
/// local load pulls the line into: t = -g(t) / |g(t)|, by a few fixed-point passes.
Vector3d tangentOf(const Vector3d& F, const Environment& env, const Material& m, const Vector3d& w,
                   const Vector3d& previous) {
  constexpr double kNoForce = 1e-9;  // [N]
  if (F.norm() > kNoForce) return F.normalized();
  Vector3d t = previous;
  for (int k = 0; k < 20; ++k) {
    const Vector3d g = lineLoad(env, m, t, w);
    if (g.norm() == 0.0) break;
    t = -g.normalized();
  }
  return t;
}

}  // namespace

namespace {

/// The towed line's shape marched up from the free end: positions r (from the end at depth
/// z_guess), tangents t and tensions T of every node.
struct TowedShape {
  std::vector<Vector3d> r, t;
  std::vector<double> T;
};

/// F_0 = -(weight + drag of the end body) (0 without one), then F_{j+1} = F_j - h g_j with the
/// wet weight and the drag of the steady current on a tangent along F (no bending); body
/// junctions add their loads.
TowedShape marchFromFreeEnd(const Problem& p, const Mesh& mesh, double z_guess) {
  using namespace eq3d;
  const Environment& env = p.environment;
  const std::size_t n = mesh.nodes.size();
  TowedShape sh{std::vector<Vector3d>(n), std::vector<Vector3d>(n), std::vector<double>(n)};
  Vector3d F(0.0, 0.0, 0.0), tan(0.0, 0.0, 1.0);
  const Material& m0 = p.materials[mesh.nodes[0].material];
  if (p.end_body != Problem::kNoBody) {
    // The body's weight and drag with the tangent along the force it needs: a few passes.
    for (int k = 0; k < 20; ++k) {
      F = -bodyLoad(env, p.bodies[p.end_body], tan, waterAt(env, z_guess));
      if (F.norm() > 0.0) tan = F.normalized();
    }
  }
  tan = tangentOf(F, env, m0, waterAt(env, z_guess), tan);
  sh.r[0] = Vector3d(0.0, 0.0, z_guess);
  sh.t[0] = tan;
  sh.T[0] = F.dot(tan);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = mesh.intervals[j];
    const Material& m = p.materials[mesh.nodes[j].material];
    const Vector3d w = waterAt(env, sh.r[j].z());
    if (iv.h > 0.0) {
      // Midpoint rule on dF/ds = -g(t(F)).
      const Vector3d Fm = F - 0.5 * iv.h * lineLoad(env, m, sh.t[j], w);
      const Vector3d tm = tangentOf(Fm, env, m, w, sh.t[j]);
      F -= iv.h * lineLoad(env, m, tm, w);
    } else {
      for (std::size_t b : iv.bodies) F -= bodyLoad(env, p.bodies[b], sh.t[j], w);
    }
    const Material& mb = p.materials[mesh.nodes[j + 1].material];
    sh.t[j + 1] = tangentOf(F, env, mb, w, sh.t[j]);
    sh.T[j + 1] = std::max(F.dot(sh.t[j + 1]), 0.0);
    const double pa = 1.0 + m.strainAt(sh.T[j]), pb = 1.0 + mb.strainAt(sh.T[j + 1]);
    sh.r[j + 1] = sh.r[j] + 0.5 * iv.h * (pa * sh.t[j] + pb * sh.t[j + 1]);
  }
  return sh;
}

}  // namespace

Eigen::VectorXd towedInitialGuess3D(const Problem& p, const Mesh& mesh) {
  using namespace eq3d;
  const std::size_t n = mesh.nodes.size();
  // Start below the tow point: the current there sets the drag of the end.
  const double z_guess = std::min(p.top.z, 0.0) - 0.5 * p.totalLength();
  const TowedShape sh = marchFromFreeEnd(p, mesh, z_guess);
  const std::vector<Vector3d>& r = sh.r;
  const std::vector<Vector3d>& t = sh.t;
  const std::vector<double>& T = sh.T;
  const Vector3d shift = Vector3d(p.top.x, p.top.y, p.top.z) - r[n - 1];

  // Frames: e1 = t; the first e3 horizontal (or y for a vertical tangent), then parallel transport.
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N * n));
  Vector3d e3 = t[0].cross(Vector3d::UnitZ());
  if (e3.norm() < 1e-6) e3 = Vector3d::UnitY();
  e3.normalize();
  Eigen::Matrix3d Rm;
  Rm.col(0) = t[0];
  Rm.col(1) = e3.cross(t[0]);
  Rm.col(2) = e3;
  Eigen::Quaterniond q(Rm);
  for (std::size_t j = 0; j < n; ++j) {
    if (j > 0) q = Eigen::Quaterniond::FromTwoVectors(t[j - 1], t[j]) * q;
    q.normalize();
    double* y = Y.data() + N * j;
    const Material& m = p.materials[mesh.nodes[j].material];
    y[EPS] = m.strainAt(T[j]);
    y[Q0] = q.w();
    y[Q1] = q.x();
    y[Q2] = q.y();
    y[Q3] = q.z();
    const Vector3d pos = r[j] + shift;
    y[X] = pos.x();
    y[eq3d::Y] = pos.y();
    y[Z] = pos.z();
  }
  return Y;
}

}  // namespace core
}  // namespace mooring_dynamics
