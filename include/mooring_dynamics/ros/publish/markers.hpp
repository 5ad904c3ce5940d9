// rviz markers for one cable line, built from a CableState (so the static and, later, the dynamic
// output share the same drawing) and the problem's environment (seabed).
//
// Namespaces and ids (stable across updates, so each new array replaces the previous drawing):
//   cable/0       LINE_STRIP through the nodes, per-vertex colour by tension (blue = lowest,
//                 red = highest tension of this state; uniform green when all tensions are equal)
//   anchor/0      SPHERE at the first node
//   top/0         SPHERE at the last node
//   label/0       TEXT_VIEW_FACING above the top: "T top = 12.3 kN" (+ "(not converged)", "(slack)"),
//                 prefixed with MarkerOptions::label_name and raised by its label_row
//   seabed/0      CUBE: flat seabed patch at the seabed elevation (thin slab just below it), or
//                 TRIANGLE_LIST following the bottom (profile or grid, its section at the line's
//                 mid y) when the environment has one; centred on the line's mid y and wider
//                 than its y extent (a 3-D line)
//   sea_surface/0 CUBE: translucent thin slab at z = 0 (mean sea surface), likewise centred
//   bodies/k      SPHERE per inline body (floats yellow, weights dark grey), at its arclength,
//                 drawn at its diameter (at least the automatic sphere size)
//   buoy/0        CYLINDER or SPHERE: the surface buoy at the top, when the problem has one
//   scale/0       CUBE_LIST: colour bar of the tension colours, beside the drawing
//   scale/1, /2   TEXT_VIEW_FACING: its bottom and top values ("1.2 kN"); scale/3 its title
// Sizes scale with the extent of the drawing (line width ~0.5 % of it) times `scale`.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <visualization_msgs/MarkerArray.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// A point body on the line, for drawing and tf frames.
struct BodyMark {
  std::string name;       ///< body name from the problem file, suffixed _k when it appears more than once
  double s = 0.0;         ///< unstretched arclength from the anchor [m]
  double diameter = 0.0;  ///< [m]
  bool buoyant = false;   ///< wet weight < 0
};

/// Inline bodies of a problem, anchor to top, with unique names.
std::vector<BodyMark> bodyMarks(const core::Problem& problem);

/// Position [m] on the drawn line at arclength s (linear between nodes; the nearest end outside).
geometry_msgs::Point pointAtArclength(const CableState& state, double s);

struct MarkerOptions {
  double scale = 1.0;       ///< multiplies the automatic marker sizes (line width, spheres, text) [-]
  bool sea_surface = true;  ///< draw the z = 0 plane
  /// Tension colour range [N]; NaN (default): the lowest and highest tension of each state.
  double tension_min = std::nan(""), tension_max = std::nan("");
  std::vector<BodyMark> bodies;       ///< inline bodies to draw
  bool top_buoy = false;              ///< draw a surface buoy at the top
  bool buoy_cylinder = false;         ///< its shape (vertical cylinder, else sphere)
  double buoy_diameter = 0.0, buoy_height = 0.0;  ///< [m]
  /// Label "<label_name>: T top = ..." (plain "T top = ..." when empty), raised by label_row text
  /// lines above the top: lines that share a top (a system's legs at one buoy) set row 0, 1, 2...
  /// so that their labels stack instead of overlapping.
  std::string label_name;
  int label_row = 0;
};

/// Marker options for a problem: bodies and the top buoy, `scale`.
MarkerOptions markerOptionsFor(const core::Problem& problem, double scale);

/// Colour for tension t on the scale [tmin, tmax]: hue from blue (tmin) to red (tmax).
std_msgs::ColorRGBA tensionColor(double t, double tmin, double tmax);

/// Markers in state.header.frame_id with state.header.stamp. Empty array when the state has no nodes.
visualization_msgs::MarkerArray makeMarkers(const CableState& state, const core::Environment& env,
                                            const MarkerOptions& options = MarkerOptions());

}  // namespace ros_bridge
}  // namespace mooring_dynamics
