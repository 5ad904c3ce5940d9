// Builders of system points and one-segment lines shared by test_system.cpp and
// test_system_dynamics.cpp.
#pragma once

#include <cmath>
#include <string>

#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace core {
namespace testing_util {

/// A point at (x, y, z) [m]; `guess`: the position is a first guess of a free point.
inline SystemPoint point(const std::string& name, SystemPoint::Type t, double x, double y, double z,
                         bool guess = false) {
  SystemPoint p;
  p.name = name;
  p.type = t;
  p.x = x;
  p.y = y;
  p.z = z;
  p.position_given = guess;
  return p;
}

/// A line of one segment of material 0 from point `from` to point `to`.
inline SystemLine line(const std::string& name, std::size_t from, std::size_t to, double length, double spacing) {
  SystemLine l;
  l.name = name;
  l.from = from;
  l.to = to;
  Segment s;
  s.length = length;
  s.spacing = spacing;
  l.segments = {s};
  return l;
}

/// A surface buoy (4 m x 3 m cylinder, 5000 kg) held by three 300 m chain legs (300 N/m) to
/// anchors 250 m away at 120 deg, in 100 m of water; legs meshed at `spacing` [m]. No current,
/// no seabed damping, no buoy added mass: the tests add what they need.
inline SystemProblem threeLegBuoy(double spacing) {
  SystemProblem s;
  s.name = "three-leg buoy mooring";
  s.environment.depth = 100.0;
  s.environment.seabed.stiffness = 1.0e5;
  Material c;
  c.name = "chain";
  c.EA = 5.0e8;
  c.EI = 10.0;
  c.GJ = 1.0;
  c.mass = 40.0;
  c.added_mass = 5.0;
  c.wet_weight = 300.0;
  c.diameter = 0.08;
  c.cdn = 2.4;
  c.cdt = 1.15;
  s.materials = {c};
  SystemPoint b = point("buoy", SystemPoint::Type::Buoy, 0.0, 0.0, -1.0, true);
  b.buoy.shape = SurfaceBuoy::Shape::Cylinder;
  b.buoy.diameter = 4.0;
  b.buoy.height = 3.0;
  b.buoy.mass = 5000.0;
  b.buoy.cd = 1.0;
  s.points.push_back(b);
  constexpr double kTwoPi = 6.283185307179586;
  for (int k = 0; k < 3; ++k) {
    const double a = kTwoPi * k / 3.0;
    s.points.push_back(point("anchor" + std::to_string(k), SystemPoint::Type::Anchor, 250.0 * std::cos(a),
                             250.0 * std::sin(a), -100.0));
    s.lines.push_back(line("leg" + std::to_string(k), static_cast<std::size_t>(k + 1), 0, 300.0, spacing));
  }
  return s;
}

/// Four 300 m chain legs from the corners of a 40 m x 20 m hull (fairleads 5 m below the
/// waterline) to anchors 250 m out along the diagonals, in 100 m of water: symmetric about the
/// body's x and y axes at the reference pose.
inline SystemProblem fourLegVessel(double spacing = 5.0) {
  SystemProblem s = threeLegBuoy(spacing);  // for its environment and chain
  s.name = "four-leg vessel";
  s.points.clear();
  s.lines.clear();
  s.vessel.present = true;
  const double fx[4] = {20, -20, -20, 20}, fy[4] = {10, 10, -10, -10};
  for (int k = 0; k < 4; ++k) {
    const double d = std::hypot(fx[k], fy[k]);
    const double ax = fx[k] + 250.0 * fx[k] / d, ay = fy[k] + 250.0 * fy[k] / d;
    s.points.push_back(point("a" + std::to_string(k), SystemPoint::Type::Anchor, ax, ay, -100.0));
    SystemPoint f = point("f" + std::to_string(k), SystemPoint::Type::Vessel, 0, 0, 0);
    f.body_offset = Eigen::Vector3d(fx[k], fy[k], -5.0);
    s.points.push_back(f);
    s.lines.push_back(line("leg" + std::to_string(k), 2 * k, 2 * k + 1, 300.0, spacing));
  }
  s.placeVessel(RigidPose());
  return s;
}

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics
