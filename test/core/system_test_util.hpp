// Builders of system points and one-segment lines shared by test_system.cpp and
// test_system_dynamics.cpp.
#pragma once

#include <string>

#include "mooring_dynamics/core/system.hpp"

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

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics
