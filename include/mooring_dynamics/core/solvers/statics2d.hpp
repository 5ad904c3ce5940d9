// 2-D static solver: paper eqs. (1)-(6) without time terms on the half-grid box scheme (section 3),
// Newton relaxation with adaptive relaxation (section 6), seabed as elastic foundation (5.3).
#pragma once

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// Solve the static equilibrium of `problem` with its own static options.
/// Throws std::invalid_argument when the problem is invalid (message names the field);
/// returns a result whose summary says whether the solver converged.
StaticResult solveStatic(const Problem& problem);

/// Same, with explicit options (overrides problem.static_options).
StaticResult solveStatic(const Problem& problem, const StaticOptions& options);

/// Same, on a given mesh of the problem's line (e.g. buildAdaptiveMesh, adaptive_mesh.hpp) instead
/// of buildMesh(problem); solveStatic(problem, options) is this on buildMesh(problem).
/// Also throws std::invalid_argument when the mesh does not fit the problem.
StaticResult solveStaticOnMesh(const Problem& problem, const Mesh& mesh, const StaticOptions& options);

}  // namespace core
}  // namespace mooring_dynamics
