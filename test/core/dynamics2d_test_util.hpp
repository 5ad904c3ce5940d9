// The 2-D chain mooring in a current shared by test_dynamics2d.cpp and test_dynamics2d_start.cpp.
#pragma once

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {
namespace testing_util {

// 100 m of chain, 41 nodes, anchored at 50 m depth. Grounded: top at the surface 75 m away,
// about a quarter of the chain on the seabed. Suspended: the seabed lowered to 500 m and the top
// brought in to 60 m, the whole chain hangs free.
inline Problem chainMooring2D(bool grounded) {
  Problem p;
  p.name = grounded ? "grounded chain" : "suspended chain";
  p.environment.depth = grounded ? 50.0 : 500.0;
  p.environment.seabed.stiffness = 1.0e5;
  p.environment.seabed.damping = 1.0e3;
  p.environment.current = {{0.0, 0.5, 0.0}, {50.0, 0.2, 0.0}};
  Material m;
  m.name = "chain";
  m.EA = 1.0e8;
  m.EI = 1.0;
  m.mass = 12.0;
  m.added_mass = 2.0;
  m.wet_weight = 100.0;
  m.diameter = 0.05;
  m.cdn = 2.4;
  m.cdt = 0.4;
  p.materials.push_back(m);
  Segment s;
  s.material = 0;
  s.length = 100.0;
  s.spacing = 2.5;
  p.segments.push_back(s);
  p.anchor_x = 0.0;
  p.anchor_z = -50.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = grounded ? 75.0 : 60.0;
  p.top.z = 0.0;
  return p;
}

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics
