// Initial guess for the static Newton iteration: a generalized elastic catenary found by
// shooting from the anchor. The line carries the anchor force (H, V) plus the weight of
// everything below; a grounded stretch (anchor on the seabed, vertical force still negative)
// lies flat. Drag and bending are ignored: Newton adds them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {

struct Shot {
  std::vector<double> T, phi, eps, x, z;  ///< per node
  bool ok = false;  ///< the (H, V) pair converged to the boundary condition
  double H = 0.0, V_anchor = 0.0;
};

/// Integrate from the anchor with horizontal force H and anchor vertical force V (the internal
/// force's components at the anchor; V < 0 grounds line on the seabed).
Shot shootFromAnchor(const Problem& problem, const Mesh& mesh, double H, double V);

/// Shot satisfying the problem's top boundary condition (position, force or buoy).
Shot catenaryShot(const Problem& problem, const Mesh& mesh);

/// Newton start vector Y (N = 6 per node) from a shot.
Eigen::VectorXd stateFromShot(const Mesh& mesh, const Shot& shot);

/// Newton start vector for a straight line from the anchor toward the top: to the top position;
/// along the top force; or to the surface point one line length away for a buoy. Unstrained,
/// no shear, no curvature.
Eigen::VectorXd straightLineState(const Problem& problem, const Mesh& mesh);

/// Total wet weight of the line and its bodies [N].
double totalWetWeight(const Problem& problem, const Mesh& mesh);

}  // namespace core
}  // namespace mooring_dynamics
