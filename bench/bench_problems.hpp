// Problems shared by the benchmarks, built in code.
#pragma once

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace bench {

/// 250 m of 76 mm studless chain in 100 m of water, anchor on a flat seabed (k = 1e6 N/m^2), top
/// held at (200, 0), `nodes` nodes. Closed form (Irvine, frictionless seabed): H = 59.05 kN, top
/// tension 157.04 kN, about 101.5 m of chain on the bottom.
inline core::Problem chainWithSeabed(int nodes) {
  core::Problem p;
  p.name = "bench chain catenary with seabed contact";
  p.environment.depth = 100.0;
  p.environment.seabed.stiffness = 1.0e6;
  p.environment.seabed.damping = 0.0;

  core::Material chain;
  chain.name = "chain76";
  chain.EA = 5.4e8;
  chain.EI = 10.0;
  chain.GJ = 1.0;
  chain.mass = 115.0;
  chain.added_mass = 14.0;
  chain.wet_weight = 980.0;
  chain.diameter = 0.137;
  chain.cdn = 2.4;
  chain.cdt = 1.15;
  p.materials.push_back(chain);

  core::Segment seg;
  seg.material = 0;
  seg.length = 250.0;
  seg.spacing = seg.length / (nodes - 1);  // nodes - 1 intervals
  p.segments.push_back(seg);

  p.anchor_x = 0.0;
  p.anchor_z = -100.0;
  p.top.type = core::TopBoundary::Type::Position;
  p.top.x = 200.0;
  p.top.z = 0.0;
  return p;
}

}  // namespace bench
}  // namespace mooring_dynamics
