#include "mooring_dynamics/core/solvers/drifting.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/solvers/initial_guess.hpp"
#include "mooring_dynamics/core/solvers/static_system.hpp"
#include "mooring_dynamics/core/solvers/towing.hpp"

namespace mooring_dynamics {
namespace core {

Environment driftEnvironment(const Environment& env, double vx, double vy) {
  Environment out = relativeEnvironment(env, vx, vy);
  const double wx = env.wind_speed * std::cos(env.wind_direction) - vx;
  const double wy = env.wind_speed * std::sin(env.wind_direction) - vy;
  out.wind_speed = std::hypot(wx, wy);
  out.wind_direction = std::atan2(wy, wx);
  return out;
}

namespace {

using namespace eq3d;

/// Vertical pull of everything below the buoy [N]: the line's and bodies' wet weight.
double hangingWeight(const Problem& p, const Mesh& mesh) {
  double W = totalWetWeight(p, mesh);
  if (p.end_body != Problem::kNoBody) W += p.bodies[p.end_body].wet_weight;
  return W;
}

/// Keel elevation of the buoy [m] that carries `pull` [N] in still water (bisection on the
/// draft); just under the top of a buoy that cannot carry it (the statics then report it).
double keelGuess(const Environment& env, const SurfaceBuoy& b, double pull) {
  const double h = b.totalHeight();
  auto excess = [&](double d) {
    return env.water_density * env.gravity * b.submergedVolume(d) - b.mass * env.gravity - pull;
  };
  if (excess(h) <= 0.0) return -0.99 * h;
  double lo = 0.0, hi = h;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) < 0.0 ? lo : hi) = mid;
  }
  return -0.5 * (lo + hi);
}

struct DriftSolver {
  const Problem& problem;
  const Mesh& mesh;
  NewtonOptions newton;
  double keel;
  double q_ref[4] = {1.0, 0.0, 0.0, 0.0};
  bool have_ref = false;
  int inner_iterations = 0;
  int solves = 0;

  /// The towed-line guess (force marched up from the free end) in the drifting frame, its top
  /// at the buoy's still-water keel.
  Eigen::VectorXd freshGuess(const Problem& solved) const {
    Problem g = solved;
    g.top.z = keel;
    return towedInitialGuess3D(g, mesh);
  }

  /// Statics at drift velocity V from Y (warm start, replaced by a fresh guess when it fails);
  /// G = the buoy's horizontal force balance F_n - B [N].
  SolverSummary solveAt(const double* V, Eigen::VectorXd& Y, double* G) {
    Problem solved = problem;
    solved.environment = driftEnvironment(problem.environment, V[0], V[1]);
    const bool warm = Y.size() == N * static_cast<Eigen::Index>(mesh.nodes.size());
    Eigen::VectorXd Y0 = warm ? Y : freshGuess(solved);
    if (!have_ref) {
      for (int i = 0; i < 4; ++i) q_ref[i] = Y0[Q0 + i];
      have_ref = true;
    }
    SolverSummary s;
    for (int attempt = 0; attempt < 2; ++attempt) {
      Y = Y0;
      StaticSystem3D system(solved, mesh, q_ref);
      s = solveNewton(system, Y, newton);
      inner_iterations += s.iterations;
      ++solves;
      if (s.converged || !warm || attempt == 1) break;
      Y0 = freshGuess(solved);
    }
    const std::size_t n = mesh.nodes.size();
    const double* yt = Y.data() + N * (n - 1);
    double F[3], B[3];
    internalForce(problem.materials[mesh.nodes.back().material], yt, F);
    buoyForce(solved.environment, problem.top.buoy, yt[Z], B);
    G[0] = F[0] - B[0];
    G[1] = F[1] - B[1];
    return s;
  }
};

std::string velocityText(const double* V) {
  std::ostringstream os;
  os.precision(6);
  os << "(" << V[0] << ", " << V[1] << ") m/s";
  return os.str();
}

}  // namespace

StaticState3D solveDriftStatic3D(const Problem& problem, const Mesh& mesh, const StaticOptions& options,
                                 const DriftOptions& drift) {
  const Environment& env = problem.environment;
  const double pull = hangingWeight(problem, mesh);
  DriftSolver ds{problem, mesh, newtonOptions(options), keelGuess(env, problem.top.buoy, pull)};
  const double Fscale = std::max(1.0, std::abs(pull) + problem.top.buoy.mass * env.gravity);
  const double Gtol = drift.force_tolerance * Fscale;

  // Start at the surface current: a drifter in a uniform current and no wind drifts with it.
  double V[2];
  env.currentAt(0.0, V[0], V[1]);
  Eigen::VectorXd Y, Yk;
  double G[2], Gk[2];
  SolverSummary inner = ds.solveAt(V, Y, G);
  bool converged = false;
  int outer = 0;
  std::string why;
  while (inner.converged && !converged && outer < drift.max_iterations) {
    if (std::hypot(G[0], G[1]) <= Gtol) {
      converged = true;
      break;
    }
    ++outer;
    // 2 x 2 Jacobian dG/dV by one-sided differences, warm-started from the current state.
    double J[2][2];
    bool ok = true;
    for (int k = 0; k < 2 && ok; ++k) {
      double Vk[2] = {V[0], V[1]};
      Vk[k] += drift.fd_step;
      Yk = Y;
      ok = ds.solveAt(Vk, Yk, Gk).converged;
      J[0][k] = (Gk[0] - G[0]) / drift.fd_step;
      J[1][k] = (Gk[1] - G[1]) / drift.fd_step;
    }
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (!ok || !(std::abs(det) > 0.0) || !std::isfinite(det)) {
      why = ok ? "the drift Jacobian dG/dV is singular (no horizontal force depends on the drift velocity)"
               : "a static solve of the finite-difference Jacobian did not converge";
      break;
    }
    double dV[2] = {-(J[1][1] * G[0] - J[0][1] * G[1]) / det, -(-J[1][0] * G[0] + J[0][0] * G[1]) / det};
    const bool small_update = std::hypot(dV[0], dV[1]) < drift.velocity_tolerance;  // the full Newton update
    // Backtracking: halve the update until the force balance improves.
    const double g0 = std::hypot(G[0], G[1]);
    bool accepted = false;
    for (int h = 0; h < 20 && !accepted; ++h) {
      double Vn[2] = {V[0] + dV[0], V[1] + dV[1]}, Gn[2];
      Yk = Y;
      const SolverSummary sn = ds.solveAt(Vn, Yk, Gn);
      if (sn.converged && std::hypot(Gn[0], Gn[1]) < g0) {
        V[0] = Vn[0];
        V[1] = Vn[1];
        G[0] = Gn[0];
        G[1] = Gn[1];
        Y = Yk;
        inner = sn;
        accepted = true;
      } else {
        dV[0] *= 0.5;
        dV[1] *= 0.5;
      }
    }
    if (!accepted) {
      why = "no reduction of the buoy's horizontal force balance along the Newton update of the drift velocity";
      break;
    }
    if (small_update) converged = true;
  }

  StaticState3D out;
  out.Y = Y;
  out.result = staticResult3DFromState(problem, mesh, Y);
  out.result.drifting = true;
  out.result.drift_vx = V[0];
  out.result.drift_vy = V[1];
  out.result.summary = inner;
  out.result.summary.iterations = ds.inner_iterations;
  std::ostringstream msg;
  if (!inner.converged) {
    msg << inner.message << "; at drift velocity " << velocityText(V);
    out.result.summary.converged = false;
  } else if (!converged) {
    if (why.empty()) why = "not converged after " + std::to_string(drift.max_iterations) + " outer iterations";
    msg << "steady drift: " << why << " (drift velocity " << velocityText(V) << ", horizontal force balance "
        << std::hypot(G[0], G[1]) << " N)";
    out.result.summary.converged = false;
  } else {
    msg << "steady drift " << velocityText(V) << " after " << outer << " outer iterations, " << ds.solves
        << " static solves (horizontal force balance " << std::hypot(G[0], G[1]) << " N; last solve: " << inner.message
        << ")";
  }
  out.result.summary.message = msg.str();
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
