// Drifting systems (issue 6): a surface buoy (top.buoy) at the top of a line whose lower end is
// free (free_end:, optionally with a drogue body), moved by current and wind; 3-D model only.
// The steady drift is a static problem in the frame moving with the unknown horizontal drift
// velocity V_d, found by an outer 2-D Newton iteration on the buoy's horizontal force balance
// (the paper, section 5.1: "iteratively solves the static problem with consecutively better
// guesses").
#pragma once

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"

namespace mooring_dynamics {
namespace core {

/// True for a drifting system: a free lower end under a surface buoy.
inline bool isDrifter(const Problem& p) {
  return p.lower_end == Problem::LowerEnd::Free && p.top.type == TopBoundary::Type::Buoy;
}

/// The environment seen from a frame drifting horizontally at (vx, vy) [m/s]: the current less
/// that velocity at every depth (relativeEnvironment) and the wind less it too.
Environment driftEnvironment(const Environment& env, double vx, double vy);

/// Outer iteration of the steady drift.
struct DriftOptions {
  /// Converged when the Newton update of V_d is below this [m/s] or the buoy's horizontal force
  /// balance is within force_tolerance of the line's characteristic force.
  double velocity_tolerance = 1e-9;
  double force_tolerance = 1e-10;  ///< [-] relative to max(buoy weight + line wet weight, 1 N)
  int max_iterations = 50;
  /// One-sided finite-difference step of the 2 x 2 Jacobian dG/dV_d [m/s].
  double fd_step = 1e-5;
};

/// Steady drift of a drifter on `mesh`: for a given V_d the line hangs in the drifting frame from
/// the buoy, held horizontally at (top.x, top.y) and vertically by its draft balance, down to the
/// free end; G(V_d) = the buoy's horizontal force balance F_n - B is driven to zero by Newton with
/// a finite-difference Jacobian and backtracking. result.drift_vx / drift_vy hold V_d; the
/// summary is not converged when either the inner or the outer iteration failed.
StaticState3D solveDriftStatic3D(const Problem& problem, const Mesh& mesh, const StaticOptions& options,
                                 const DriftOptions& drift = DriftOptions{});

}  // namespace core
}  // namespace mooring_dynamics
