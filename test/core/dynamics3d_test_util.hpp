// The 3-D chain mooring shared by test_dynamics3d.cpp and test_dynamics3d_events.cpp.
#pragma once

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {
namespace testing_util {

// Newton tolerance of the comparisons (sigma of eq. 39): tight, so that two solvers on the same
// discrete equations differ by less than the tests' tolerances.
constexpr double kTightTolerance = 1e-11;

/// 100 m of chain in 50 m of water, top at the surface 75 m away: about a quarter grounded;
/// current sheared from 0.5 to 0.2 m/s toward `current_dir` [rad].
inline Problem chainMooring(double current_dir = 0.0) {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 50.0;
  p.environment.seabed.stiffness = 1.0e5;
  p.environment.seabed.damping = 1.0e3;
  p.environment.current = {{0.0, 0.5, current_dir}, {50.0, 0.2, current_dir}};
  Material m;
  m.name = "chain";
  m.EA = 1.0e8;
  m.EI = 1.0;
  m.GJ = 1.0;
  m.mass = 12.0;
  m.added_mass = 2.0;
  m.wet_weight = 100.0;
  m.diameter = 0.05;
  m.cdn = 2.4;
  m.cdt = 0.4;
  p.materials.push_back(m);
  Segment s;
  s.length = 100.0;
  s.spacing = 2.5;
  p.segments.push_back(s);
  p.anchor_z = -50.0;
  p.top.type = TopBoundary::Type::Position;
  p.top.x = 75.0;
  p.top.z = 0.0;
  p.dynamics.duration = 20.0;
  p.dynamics.dt = 0.5;
  p.dynamics.top_motion.type = TopMotion::Type::Sinusoid;
  p.dynamics.top_motion.amplitude_x = 0.4;  // no slack phase: snap loads would make the runs
  p.dynamics.top_motion.amplitude_z = 0.6;  // depend on round-off through the step cuts
  p.dynamics.top_motion.period = 8.0;
  p.dynamics.record_s = {50.0};
  p.dynamics.tolerance = kTightTolerance;
  return p;
}

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics
