// The one place where core structs and ROS messages meet (no node handles, no publishing).
//
// Frames: every position and force is in the node's frame (parameter ~frame_id, REP 103: x east,
// y north, z up, z = 0 at the mean sea surface). With `model: 2d` the core works in the vertical
// x-z plane of that frame, so y is 0 on the way out and must be 0 on the way in; with `model: 3d`
// all three components are used both ways.
#pragma once

#include <string>
#include <vector>

#include <ros/time.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// End forces of a line [N] (same conventions as core::StaticResult).
struct EndForces {
  double top_x = 0.0, top_z = 0.0;        ///< force the platform applies to the line's top end [N]
  double anchor_x = 0.0, anchor_z = 0.0;  ///< force the line exerts on the anchor [N]
  double top_y = 0.0, anchor_y = 0.0;     ///< y components [N] (3-D model; 0 from the 2-D solver)
};

/// CableState from per-node values (anchor first). Shared by the static and the dynamic output
/// path: positions and forces with their y (0 from the 2-D solver), min_tension over all nodes,
/// slack when any tension <= 0.
CableState toCableState(const std::vector<core::NodeState>& nodes, const EndForces& forces, bool converged,
                        const std::string& line_name, const std::string& frame_id, const ros::Time& stamp);

/// CableState of a static result.
CableState toCableState(const core::StaticResult& result, const std::string& line_name,
                        const std::string& frame_id, const ros::Time& stamp);

/// Fill a SolveStatic response from a static result: success = summary.converged, message =
/// summary.message, iterations, end forces, positions and tensions (anchor to top).
void toResponse(const core::StaticResult& result, SolveStatic::Response& res);

/// Failed response: success = false, the message, all arrays empty.
void toFailureResponse(const std::string& message, SolveStatic::Response& res);

/// Outcome of translating a SolveStatic request.
struct TopBoundaryRequest {
  bool ok = false;
  core::TopBoundary top;   ///< valid when ok
  std::string error;       ///< when !ok: names the field, its value and the constraint
  std::string summary;     ///< when ok: short description, e.g. "top position (x, z) = (90, 0) m"
};

/// SolveStatic request -> core::TopBoundary. `problem_top` is what PROBLEM_DEFAULT returns.
/// Rejects an unknown mode, NaN/inf components (`top_position.x = nan: must be finite`) and, for
/// `model` TwoD, a non-zero y (the 2-D solver works in the x-z plane); ThreeD takes y as given.
/// Whether the line can reach a requested position is left to the core (core::Problem::validate).
TopBoundaryRequest topBoundaryFromRequest(const SolveStatic::Request& req, const core::TopBoundary& problem_top,
                                          core::Formulation model = core::Formulation::TwoD);

/// Short description of a top boundary for logs and messages: "(x, z) = ..." for TwoD,
/// "(x, y, z) = ..." for ThreeD.
std::string describeTop(const core::TopBoundary& top, core::Formulation model = core::Formulation::TwoD);

/// "%.6g" formatting that prints nan/inf as such (for messages).
std::string formatNumber(double v);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
