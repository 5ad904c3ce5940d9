// rviz markers for one cable line, built from a CableState (so the static and, later, the dynamic
// output share the same drawing) and the problem's environment (seabed).
//
// Namespaces and ids (stable across updates, so each new array replaces the previous drawing):
//   cable/0       LINE_STRIP through the nodes, per-vertex colour by tension (blue = lowest,
//                 red = highest tension of this state; uniform green when all tensions are equal)
//   anchor/0      SPHERE at the first node
//   top/0         SPHERE at the last node
//   label/0       TEXT_VIEW_FACING above the top: "T top = 12.3 kN" (+ "(not converged)", "(slack)")
//   seabed/0      CUBE: flat seabed patch at the seabed elevation (thin slab just below it), or
//                 TRIANGLE_LIST following the bottom profile when the environment has one
//   sea_surface/0 CUBE: translucent thin slab at z = 0 (mean sea surface)
// Sizes scale with the extent of the drawing (line width ~0.5 % of it) times `scale`.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/model.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

struct MarkerOptions {
  double scale = 1.0;       ///< multiplies the automatic marker sizes (line width, spheres, text) [-]
  bool sea_surface = true;  ///< draw the z = 0 plane
};

/// Colour for tension t on the scale [tmin, tmax]: hue from blue (tmin) to red (tmax).
std_msgs::ColorRGBA tensionColor(double t, double tmin, double tmax);

/// Markers in state.header.frame_id with state.header.stamp. Empty array when the state has no nodes.
visualization_msgs::MarkerArray makeMarkers(const CableState& state, const core::Environment& env,
                                            const MarkerOptions& options = MarkerOptions());

}  // namespace ros_bridge
}  // namespace mooring_dynamics
