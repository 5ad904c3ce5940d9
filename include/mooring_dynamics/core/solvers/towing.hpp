// Towing (a line with a free lower end, paper sections 5.2 and 7.1): the steady-tow environment
// and the initial guess of its static solution.
#pragma once

#include <Eigen/Core>

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {

/// The environment seen from a frame moving horizontally at (vx, vy) [m/s]: the current profile
/// minus that velocity at every depth (a uniform current of -(vx, vy) when there is none). A
/// steady tow at the ship's velocity is a static problem in this frame (the paper's "ship speed").
Environment relativeEnvironment(const Environment& env, double vx, double vy);

/// Initial guess (16 unknowns per node, eq3d::Var) for the statics of a line with a free lower
/// end: the internal force is marched up from the end, F_0 = -(weight + drag of the end body)
/// (0 without one), F_{j+1} = F_j - h g_j with the wet weight and the drag of the steady current
/// on a tangent along F (no bending); body junctions add their loads. The polyline is then moved
/// so that its top lands on top.position, and the frames are parallel-transported from the end.
Eigen::VectorXd towedInitialGuess3D(const Problem& problem, const Mesh& mesh);

}  // namespace core
}  // namespace mooring_dynamics
