#include "mooring_dynamics/core/equations/catenary.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace mooring_dynamics {
namespace core {

double CatenarySolution::topTension() const { return std::hypot(H, V); }

void catenaryEnd(const CatenaryInput& in, double H, double V, double& X, double& Z) {
  const double L = in.L, w = in.w, EA = in.EA;
  const double Va = V - w * L;  // vertical force at the anchor
  if (in.seabed && Va < 0.0) {
    // Grounded length LB = L - V/w lies flat with tension H (frictionless seabed).
    const double Ls = V / w;  // suspended length
    X = (L - Ls) + H * L / EA + (H / w) * std::asinh(V / H);
    Z = (H / w) * (std::sqrt(1.0 + (V / H) * (V / H)) - 1.0) + V * V / (2.0 * EA * w);
    return;
  }
  X = H * L / EA + (H / w) * (std::asinh(V / H) - std::asinh(Va / H));
  Z = (V * L - 0.5 * w * L * L) / EA + (H / w) * (std::sqrt(1.0 + (V / H) * (V / H)) - std::sqrt(1.0 + (Va / H) * (Va / H)));
}

CatenarySolution solveCatenary(const CatenaryInput& in) {
  CatenarySolution sol;
  const double L = in.L, w = in.w;
  double lambda = 0.2;
  const double d2 = in.X * in.X + in.Z * in.Z;
  if (L * L > d2) lambda = std::sqrt(3.0 * ((L * L - in.Z * in.Z) / (in.X * in.X) - 1.0));
  Eigen::Vector2d u(std::max(w * in.X / (2.0 * lambda), 1e-3 * w * L), 0.5 * w * (in.Z / std::tanh(lambda) + L));
  auto f = [&](const Eigen::Vector2d& v) {
    double X, Z;
    catenaryEnd(in, v[0], v[1], X, Z);
    return Eigen::Vector2d(X - in.X, Z - in.Z);
  };
  Eigen::Vector2d r = f(u);
  for (int it = 0; it < 200 && r.norm() > 1e-12 * L; ++it) {
    Eigen::Matrix2d J;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d up = u;
      const double h = 1e-7 * std::abs(u[k]) + 1e-9;
      up[k] += h;
      J.col(k) = (f(up) - r) / h;
    }
    Eigen::Vector2d step = -J.colPivHouseholderQr().solve(r);
    double a = 1.0;
    for (int ls = 0; ls < 40; ++ls, a *= 0.5) {
      Eigen::Vector2d un = u + a * step;
      if (un[0] <= 0.0) continue;
      Eigen::Vector2d rn = f(un);
      if (rn.norm() < r.norm()) {
        u = un;
        r = rn;
        break;
      }
    }
  }
  sol.H = u[0];
  sol.V = u[1];
  sol.grounded = (in.seabed && u[1] < w * L) ? L - u[1] / w : 0.0;
  sol.Va = sol.grounded > 0.0 ? 0.0 : u[1] - w * L;
  sol.converged = r.norm() <= 1e-9 * L;
  return sol;
}

double CatenarySolution::anchorTension() const { return std::hypot(H, Va); }

}  // namespace core
}  // namespace mooring_dynamics
