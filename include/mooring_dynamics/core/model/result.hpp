// Results of the static solver: per-node state, end forces and a convergence summary.
#pragma once

#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

/// What a nonlinear solve did. Non-convergence is a result, not an exception.
struct SolverSummary {
  bool converged = false;
  int iterations = 0;          ///< Newton iterations taken
  double error = 0.0;          ///< final scaled update sigma (paper eq. 39) [-]
  double relaxation = 0.0;     ///< final relaxation factor mu [-]
  std::string message;         ///< human-readable outcome
};

/// Value of the solution at one node. Positions are in the problem frame (x east, z up, z = 0 at
/// the mean sea surface).
struct NodeState {
  double s = 0.0;         ///< unstretched arclength from the anchor [m]
  double x = 0.0;         ///< [m]
  double z = 0.0;         ///< [m]
  double tension = 0.0;   ///< effective tension T [N]
  double shear = 0.0;     ///< shear force Sn [N]
  double angle = 0.0;     ///< inclination phi from the vertical, positive toward +x [rad]
  double curvature = 0.0; ///< Omega3 = dphi/ds [1/m]
  double strain = 0.0;    ///< eps [-]
  int segment = 0;        ///< index of the segment the node belongs to
  // 3-D model (zero from the 2-D solver). There `angle` is the inclination of the tangent from
  // the vertical (>= 0), `shear` the shear force along e2 and `curvature` Omega3.
  double y = 0.0;         ///< [m]
  double shear_b = 0.0;   ///< shear force S3 along e3 [N]
  double curvature_b = 0.0;  ///< Omega2, curvature about e2 [1/m]
  double twist = 0.0;     ///< Omega1, twist about the tangent [1/m]
  double azimuth = 0.0;   ///< direction of the tangent's horizontal part, ccw from +x [rad]
};

struct StaticResult {
  std::vector<NodeState> nodes;  ///< anchor (first) to top (last)
  double top_force_x = 0.0;      ///< force the line's top end receives from the platform/buoy [N]
  double top_force_z = 0.0;      ///< [N]
  double top_force_y = 0.0;      ///< [N] (3-D model)
  double anchor_force_x = 0.0;   ///< force the line exerts on the anchor [N]
  double anchor_force_z = 0.0;   ///< [N]
  double anchor_force_y = 0.0;   ///< [N] (3-D model)
  double buoy_draft = 0.0;       ///< surface buoy draft [m] (buoy top boundary only)
  /// Drifting system (free_end: under top.buoy, 3-D): the steady horizontal drift velocity V_d
  /// the statics found [m/s]; positions are those at t = 0 in the frame drifting with it.
  bool drifting = false;
  double drift_vx = 0.0;
  double drift_vy = 0.0;
  SolverSummary summary;

  double topTension() const { return nodes.empty() ? 0.0 : nodes.back().tension; }
};

}  // namespace core
}  // namespace mooring_dynamics
