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

namespace {

/// The 2 x 2 Jacobian dG/dV of the buoy's horizontal force balance by one-sided differences of
/// fd_step, each solve warm-started from Y; false when a solve does not converge.
bool driftJacobian(DriftSolver& ds, const double* V, const Eigen::VectorXd& Y, const double* G, double fd_step,
                   double (&J)[2][2]) {
  bool ok = true;
  for (int k = 0; k < 2 && ok; ++k) {
    double Vk[2] = {V[0], V[1]}, Gk[2];
    Vk[k] += fd_step;
    Eigen::VectorXd Yk = Y;
    ok = ds.solveAt(Vk, Yk, Gk).converged;
    J[0][k] = (Gk[0] - G[0]) / fd_step;
    J[1][k] = (Gk[1] - G[1]) / fd_step;
  }
  return ok;
}

/// Backtracking along the Newton update dV: halved until the force balance improves; on success
/// V, Y, G and the inner summary move to the new drift velocity.
bool backtrackDrift(DriftSolver& ds, double* dV, double* V, Eigen::VectorXd& Y, double* G, SolverSummary& inner) {
  const double g0 = std::hypot(G[0], G[1]);
  for (int h = 0; h < 20; ++h) {
    double Vn[2] = {V[0] + dV[0], V[1] + dV[1]}, Gn[2];
    Eigen::VectorXd Yk = Y;
    const SolverSummary sn = ds.solveAt(Vn, Yk, Gn);
    if (sn.converged && std::hypot(Gn[0], Gn[1]) < g0) {
      V[0] = Vn[0];
      V[1] = Vn[1];
      G[0] = Gn[0];
      G[1] = Gn[1];
      Y = Yk;
      inner = sn;
      return true;
    }
    dV[0] *= 0.5;
    dV[1] *= 0.5;
  }
  return false;
}

/// The outer iteration's state: drift velocity V [m/s], the statics Y there, the balance G [N].
struct Drift {
  double V[2] = {0.0, 0.0};
  Eigen::VectorXd Y;
  double G[2] = {0.0, 0.0};
  SolverSummary inner;  ///< the last accepted static solve
  bool converged = false;
  int outer = 0;        ///< outer iterations
  std::string why;      ///< why the outer iteration stopped early
};

/// Newton on G(V) = 0 from d's start until G is within Gtol or the update is small.
void iterateDrift(DriftSolver& ds, const DriftOptions& drift, double Gtol, Drift& d) {
  while (d.inner.converged && !d.converged && d.outer < drift.max_iterations) {
    if (std::hypot(d.G[0], d.G[1]) <= Gtol) {
      d.converged = true;
      break;
    }
    ++d.outer;
    double J[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    const bool ok = driftJacobian(ds, d.V, d.Y, d.G, drift.fd_step, J);
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (!ok || !(std::abs(det) > 0.0) || !std::isfinite(det)) {
      d.why = ok ? "the drift Jacobian dG/dV is singular (no horizontal force depends on the drift velocity)"
                 : "a static solve of the finite-difference Jacobian did not converge";
      break;
    }
    double dV[2] = {-(J[1][1] * d.G[0] - J[0][1] * d.G[1]) / det, -(-J[1][0] * d.G[0] + J[0][0] * d.G[1]) / det};
    const bool small_update = std::hypot(dV[0], dV[1]) < drift.velocity_tolerance;  // the full Newton update
    if (!backtrackDrift(ds, dV, d.V, d.Y, d.G, d.inner)) {
      d.why = "no reduction of the buoy's horizontal force balance along the Newton update of the drift velocity";
      break;
    }
    if (small_update) d.converged = true;
  }
}

/// The result at the last drift velocity, its summary saying how both iterations ended.
StaticState3D driftResult(const Problem& problem, const Mesh& mesh, const DriftSolver& ds, const DriftOptions& drift,
                          Drift& d) {
  StaticState3D out;
  out.Y = d.Y;
  out.result = staticResult3DFromState(problem, mesh, d.Y);
  out.result.drifting = true;
  out.result.drift_vx = d.V[0];
  out.result.drift_vy = d.V[1];
  out.result.summary = d.inner;
  out.result.summary.iterations = ds.inner_iterations;
  std::ostringstream msg;
  if (!d.inner.converged) {
    msg << d.inner.message << "; at drift velocity " << velocityText(d.V);
    out.result.summary.converged = false;
  } else if (!d.converged) {
    if (d.why.empty()) d.why = "not converged after " + std::to_string(drift.max_iterations) + " outer iterations";
    msg << "steady drift: " << d.why << " (drift velocity " << velocityText(d.V) << ", horizontal force balance "
        << std::hypot(d.G[0], d.G[1]) << " N)";
    out.result.summary.converged = false;
  } else {
    msg << "steady drift " << velocityText(d.V) << " after " << d.outer << " outer iterations, " << ds.solves
        << " static solves (horizontal force balance " << std::hypot(d.G[0], d.G[1]) << " N; last solve: "
        << d.inner.message << ")";
  }
  out.result.summary.message = msg.str();
  return out;
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
  Drift d;
  env.currentAt(0.0, d.V[0], d.V[1]);
  d.inner = ds.solveAt(d.V, d.Y, d.G);
  iterateDrift(ds, drift, Gtol, d);
  return driftResult(problem, mesh, ds, drift, d);
}

}  // namespace core
}  // namespace mooring_dynamics
