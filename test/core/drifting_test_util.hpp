// The drifter shared by the drifting-system tests (test_drifting.cpp, test_drifting_dynamics.cpp):
// a cylinder buoy on a 20 m tether over a drogue, built in code and as a problem file, a uniform
// current, and the drift velocity's tolerance.
#pragma once

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {
namespace testing_util {

constexpr double kPi = 3.14159265358979323846;
// Drift velocity: the outer Newton stops at an update of 1e-9 m/s or a force balance of 1e-10 of
// the force scale; 1e-7 m/s leaves room for the finite-difference Jacobian's last step.
constexpr double kDriftTol = 1e-7;  // [m/s]

/// A drifter: a 1 m cylinder buoy, a 20 m tether (2 N/m in water) and a drogue body with the same
/// drag coefficient along and across the line (cdn = cdt); the current and wind are set by the tests.
inline Problem drifter() {
  Problem p;
  p.formulation = Formulation::ThreeD;
  p.environment.depth = 1000.0;
  Material m;
  m.name = "tether";
  m.EA = 1.0e6;
  m.EI = 1.0e-2;
  m.GJ = 1.0e-2;
  m.mass = 0.3;
  m.added_mass = 0.08;
  m.wet_weight = 2.0;
  m.diameter = 0.01;
  m.cdn = 1.5;
  m.cdt = 0.01;
  p.materials.push_back(m);
  Segment s;
  s.length = 20.0;
  s.spacing = 1.0;
  p.segments.push_back(s);
  Body d;
  d.name = "drogue";
  d.mass = 50.0;
  d.added_mass = 200.0;
  d.wet_weight = 100.0;
  d.diameter = 1.0;
  d.cdn = d.cdt = 1.3;
  p.bodies.push_back(d);
  p.lower_end = Problem::LowerEnd::Free;
  p.end_body = 0;
  p.top.type = TopBoundary::Type::Buoy;
  SurfaceBuoy& b = p.top.buoy;
  b.shape = SurfaceBuoy::Shape::Cylinder;
  b.diameter = 1.0;
  b.height = 1.0;
  b.mass = 150.0;
  b.added_mass = 100.0;
  b.cd = 1.0;
  b.wind_area = 0.3;
  b.wind_cd = 1.0;
  return p;
}

inline void uniformCurrent(Problem& p, double speed, double direction) {
  CurrentPoint c;
  c.speed = speed;
  c.direction = direction;
  p.environment.current = {c};
}

/// The drifter as a problem file (model: 3d, a free end with the drogue), in a current and a wind.
inline const char* const kDrifterYaml = R"(model: 3d
environment:
  depth: 4000
  current: {speed: 0.3, direction_deg: 0}
  wind: {speed: 8, direction_deg: 90}
materials:
  tether: {EA: 1.0e6, EI: 0.01, GJ: 0.01, mass: 0.3, added_mass: 0.08, wet_weight: 2.0, diameter: 0.01, cdn: 1.5, cdt: 0.01}
bodies:
  drogue: {mass: 50, added_mass: 200, wet_weight: 100, diameter: 1.0, cdn: 1.3, cdt: 1.3}
line:
  - {material: tether, length: 20, spacing: 1}
free_end: {body: drogue}
top:
  buoy: {shape: cylinder, diameter: 1.0, height: 1.0, mass: 150, added_mass: 100, cd: 1.0, wind_area: 0.3, wind_cd: 1.0}
)";

}  // namespace testing_util
}  // namespace core
}  // namespace mooring_dynamics
