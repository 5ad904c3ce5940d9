#include "mooring_dynamics/core/solvers/initial_guess.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "mooring_dynamics/core/equations/equations2d.hpp"

namespace mooring_dynamics {
namespace core {

double totalWetWeight(const Problem& problem, const Mesh& mesh) {
  double W = 0.0;
  for (const auto& iv : mesh.intervals) {
    W += iv.h * problem.materials[iv.material].wet_weight;
    for (std::size_t b : iv.bodies) W += problem.bodies[b].wet_weight;
  }
  return W;
}

Shot shootFromAnchor(const Problem& problem, const Mesh& mesh, double H, double V) {
  const std::size_t n = mesh.nodes.size();
  const Environment& env = problem.environment;
  Shot shot;
  shot.H = H;
  shot.V_anchor = V;
  shot.T.resize(n);
  shot.phi.resize(n);
  shot.eps.resize(n);
  shot.x.resize(n);
  shot.z.resize(n);
  const double side = H >= 0.0 ? 1.0 : -1.0;
  bool grounded = problem.anchor_z <= env.seabedElevation(problem.anchor_x) + 1e-6;
  double Vline = V;  // vertical internal force a free-hanging line would carry here
  auto setNode = [&](std::size_t j) {
    const Material& m = problem.materials[mesh.nodes[j].material];
    double Fz = Vline;
    if (grounded && Vline <= 0.0) Fz = 0.0;  // the seabed carries the weight of grounded line
    else grounded = false;
    const double T = std::hypot(H, Fz);
    shot.T[j] = T;
    shot.phi[j] = T > 0.0 ? std::atan2(H, Fz) : (grounded ? side * 0.5 * eq2d::kPi : 0.0);
    if (grounded && Fz == 0.0) shot.phi[j] = side * 0.5 * eq2d::kPi;
    shot.eps[j] = m.strainAt(T);
  };
  shot.x[0] = problem.anchor_x;
  shot.z[0] = problem.anchor_z;
  setNode(0);
  for (std::size_t j = 1; j < n; ++j) {
    const MeshInterval& iv = mesh.intervals[j - 1];
    Vline += iv.h * problem.materials[iv.material].wet_weight;
    for (std::size_t b : iv.bodies) Vline += problem.bodies[b].wet_weight;
    setNode(j);
    const double pa = 1.0 + shot.eps[j - 1], pb = 1.0 + shot.eps[j];
    shot.x[j] = shot.x[j - 1] + 0.5 * iv.h * (pa * std::sin(shot.phi[j - 1]) + pb * std::sin(shot.phi[j]));
    shot.z[j] = shot.z[j - 1] + 0.5 * iv.h * (pa * std::cos(shot.phi[j - 1]) + pb * std::cos(shot.phi[j]));
    // No line below the bottom; grounded line rests at the penetration where the foundation
    // carries its weight (eq. 35).
    const double w = problem.materials[mesh.nodes[j].material].wet_weight;
    const double rest = env.seabedElevation(shot.x[j]) - 1.5 * std::max(w, 0.0) / env.seabed.stiffness;
    if (grounded || shot.z[j] < rest) shot.z[j] = rest;
  }
  return shot;
}

namespace {

/// Damped Newton on the two anchor-force components so that the shot's top lands on (X, Z).
Shot shootToPosition(const Problem& problem, const Mesh& mesh, double X, double Z) {
  const double W = totalWetWeight(problem, mesh);
  const double L = problem.totalLength();
  const double dx = X - problem.anchor_x, dz = Z - problem.anchor_z;
  const double side = dx >= 0.0 ? 1.0 : -1.0;
  const double w = std::max(std::abs(W) / L, 1e-6);
  // Starting values (Peyrot and Goulois): a catenary of the mean weight.
  double lambda = 0.2;
  if (L * L > dx * dx + dz * dz) lambda = std::sqrt(3.0 * ((L * L - dz * dz) / std::max(dx * dx, 1e-12 * L * L) - 1.0));
  lambda = std::clamp(lambda, 1e-3, 1e3);
  double H = std::max(w * std::abs(dx) / (2.0 * lambda), 1e-6 * w * L);
  double Vtop = 0.5 * w * (dz / std::tanh(lambda) + L);
  Eigen::Vector2d u(std::log(H), (Vtop - W) / (w * L));  // unknowns: log|H|, V / (w L)
  auto evaluate = [&](const Eigen::Vector2d& v, Shot& shot) {
    shot = shootFromAnchor(problem, mesh, side * std::exp(v[0]), v[1] * w * L);
    return Eigen::Vector2d((shot.x.back() - X) / L, (shot.z.back() - Z) / L);
  };
  Shot shot, trial;
  Eigen::Vector2d f = evaluate(u, shot);
  for (int it = 0; it < 100 && f.norm() > 1e-10; ++it) {
    Eigen::Matrix2d Jf;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d up = u;
      up[k] += 1e-7 * std::max(1.0, std::abs(u[k]));
      Jf.col(k) = (evaluate(up, trial) - f) / (up[k] - u[k]);
    }
    Eigen::Vector2d step = -Jf.colPivHouseholderQr().solve(f);
    if (!step.allFinite()) break;
    step[0] = std::clamp(step[0], -2.0, 2.0);
    step[1] = std::clamp(step[1], -1.0, 1.0);
    double a = 1.0;
    bool improved = false;
    for (int ls = 0; ls < 30; ++ls, a *= 0.5) {
      const Eigen::Vector2d un = u + a * step;
      const Eigen::Vector2d fn = evaluate(un, trial);
      if (fn.norm() < f.norm()) {
        u = un;
        f = fn;
        shot = trial;
        improved = true;
        break;
      }
    }
    if (!improved) break;
  }
  shot.ok = f.norm() < 1e-6;
  return shot;
}

/// Bisection on the buoy draft d: the buoy force at d, applied at the top, must hang the line's
/// top at z = -d.
Shot shootToBuoy(const Problem& problem, const Mesh& mesh) {
  const SurfaceBuoy& b = problem.top.buoy;
  const double W = totalWetWeight(problem, mesh);
  auto shotAt = [&](double d) {
    double Fx, Fz;
    eq2d::buoyForce(problem.environment, b, -d, Fx, Fz);
    return shootFromAnchor(problem, mesh, Fx, Fz - W);
  };
  double lo = 0.0, hi = b.totalHeight();
  Shot shot = shotAt(hi);
  if (shot.z.back() + hi < 0.0) return shot;  // even fully submerged the buoy cannot lift the line
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    Shot s = shotAt(mid);
    if (s.z.back() + mid < 0.0) lo = mid; else hi = mid;
  }
  shot = shotAt(hi);
  shot.ok = true;
  return shot;
}

}  // namespace

Shot catenaryShot(const Problem& problem, const Mesh& mesh) {
  const TopBoundary& top = problem.top;
  switch (top.type) {
    case TopBoundary::Type::Position:
      return shootToPosition(problem, mesh, top.x, top.z);
    case TopBoundary::Type::Force: {
      Shot s = shootFromAnchor(problem, mesh, top.fx, top.fz - totalWetWeight(problem, mesh));
      s.ok = true;
      return s;
    }
    case TopBoundary::Type::Buoy:
      return shootToBuoy(problem, mesh);
    case TopBoundary::Type::Body: {
      // The body's net buoyancy pulls the top up (drag left to Newton).
      const double up = problem.top.body < problem.bodies.size() ? -problem.bodies[problem.top.body].wet_weight : 0.0;
      Shot s = shootFromAnchor(problem, mesh, 0.0, up - totalWetWeight(problem, mesh));
      s.ok = true;
      return s;
    }
  }
  return {};
}

Eigen::VectorXd stateFromShot(const Mesh& mesh, const Shot& shot) {
  using namespace eq2d;
  const std::size_t n = mesh.nodes.size();
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N * n));
  for (std::size_t j = 0; j < n; ++j) {
    double* y = Y.data() + N * j;
    y[EPS] = shot.eps[j];
    y[SN] = 0.0;
    y[PHI] = shot.phi[j];
    y[X] = shot.x[j];
    y[Z] = shot.z[j];
    // Curvature from the neighbouring angles (zero at the ends, eq. 33).
    if (j > 0 && j + 1 < n) {
      const double ds = mesh.nodes[j + 1].s - mesh.nodes[j - 1].s;
      y[OMEGA] = ds > 0.0 ? (shot.phi[j + 1] - shot.phi[j - 1]) / ds : 0.0;
    }
  }
  return Y;
}

Eigen::VectorXd straightLineState(const Problem& problem, const Mesh& mesh) {
  using namespace eq2d;
  const double L = problem.totalLength();
  double dx = 0.0, dz = 0.0;
  switch (problem.top.type) {
    case TopBoundary::Type::Position:
      dx = problem.top.x - problem.anchor_x;
      dz = problem.top.z - problem.anchor_z;
      break;
    case TopBoundary::Type::Force:
      dx = problem.top.fx;
      dz = problem.top.fz;
      break;
    case TopBoundary::Type::Buoy:
      dz = -problem.anchor_z;
      dx = std::sqrt(std::max(L * L - dz * dz, 0.0));
      break;
    case TopBoundary::Type::Body:
      dz = 1.0;  // straight up
      break;
  }
  const double phi = std::atan2(dx, dz);
  const std::size_t n = mesh.nodes.size();
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N * n));
  for (std::size_t j = 0; j < n; ++j) {
    double* y = Y.data() + N * j;
    y[PHI] = phi;
    y[X] = problem.anchor_x + std::sin(phi) * mesh.nodes[j].s;
    y[Z] = problem.anchor_z + std::cos(phi) * mesh.nodes[j].s;
  }
  return Y;
}

}  // namespace core
}  // namespace mooring_dynamics
