// One entry point per analysis that picks the equations named by the problem's `model:` key
// (Problem::formulation): the 2-D solver (statics2d.hpp, dynamics2d.hpp) or the 3-D solver
// (statics3d.hpp, dynamics3d.hpp). Front ends (cable_sim, the ROS node) call these.
#pragma once

#include <functional>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"

namespace mooring_dynamics {
namespace core {

/// Static solution with the problem's model (throws std::invalid_argument like solveStatic).
inline StaticResult solveStaticModel(const Problem& problem) {
  return problem.formulation == Formulation::ThreeD ? solveStatic3D(problem) : solveStatic(problem);
}

/// Dynamic run of problem.dynamics with the problem's model (as runDynamic). A 2-D problem with
/// a winch (dynamics.winch) runs on the 3-D equations in its x-z plane, where the winch's nodes
/// are added and taken out (docs/method.md "Winch"); the series are the same quantities.
inline DynamicSeries runDynamicModel(const Problem& problem,
                                     const std::function<void(double, double)>& progress = nullptr) {
  if (problem.formulation == Formulation::TwoD && problem.dynamics.winch.given) {
    Problem planar = problem;
    planar.formulation = Formulation::ThreeD;
    return runDynamic3D(planar, progress);
  }
  return problem.formulation == Formulation::ThreeD ? runDynamic3D(problem, progress) : runDynamic(problem, progress);
}

}  // namespace core
}  // namespace mooring_dynamics
