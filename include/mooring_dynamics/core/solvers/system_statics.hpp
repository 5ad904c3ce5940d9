// Statics of a system of lines (model/system.hpp) by partitioned Newton on the free points'
// positions; see the comment at the top of model/system.hpp for the method.
#pragma once

#include <vector>

#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace core {

/// Options of the outer (point) iteration.
struct SystemSolveOptions {
  int max_iterations = 50;
  double force_tolerance = 1e-6;  ///< stop when every point's force residual < this times the largest line tension
  double fd_step = 1e-4;          ///< finite-difference step of a point coordinate [m]
  double max_move = 0.1;          ///< largest move of a point per iteration, as a fraction of its shortest line
};

struct SystemPointResult {
  std::string name;
  double x = 0.0, y = 0.0, z = 0.0;  ///< [m]
  /// Sum of the lines' pulls on the point [N] (for a fixed point or anchor: what it must resist).
  double fx = 0.0, fy = 0.0, fz = 0.0;
  double residual = 0.0;             ///< free points: |force balance| at the solution [N]
  double buoy_draft = 0.0;           ///< Buoy: draft [m]
};

struct SystemStaticResult {
  std::vector<StaticResult> lines;   ///< per line, in SystemProblem::lines order
  std::vector<SystemPointResult> points;
  SolverSummary summary;             ///< of the outer iteration (iterations, largest residual [N], message)
};

/// Solve the statics of a system. Throws std::invalid_argument when the system is invalid.
SystemStaticResult solveSystemStatic(const SystemProblem& system, const SystemSolveOptions& options = {});

}  // namespace core
}  // namespace mooring_dynamics
