// Problem::validate and the options' validate(): every field of a problem checked, the first
// violation returned as "<key> = <value>: <constraint>" (field_error.hpp), "" when valid.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "mooring_dynamics/core/model/field_error.hpp"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

// The validations' messages: "key = value: constraint" (field_error.hpp).
std::string fmt(double v) { return fieldNumber(v); }
std::string check(bool ok, const std::string& key, double v, const std::string& c) { return fieldCheck(ok, key, v, c); }
bool finite(double v) { return std::isfinite(v); }

}  // namespace

std::string StaticOptions::validate() const {
  std::string e;
  if (!(e = check(finite(tolerance) && tolerance > 0.0, "solver.static.tolerance", tolerance, "must be > 0")).empty()) return e;
  if (max_iterations < 1)
    return "solver.static.max_iterations = " + std::to_string(max_iterations) + ": must be >= 1";
  if (!(e = check(finite(relaxation) && relaxation > 0.0 && relaxation <= 1.0, "solver.static.relaxation", relaxation,
                  "must be in (0, 1]")).empty()) return e;
  if (!(e = check(finite(R2) && R2 > 1.0, "solver.static.R2", R2, "must be > 1")).empty()) return e;
  if (!(e = check(finite(R1) && R1 > R2, "solver.static.R1", R1, "must be > R2 = " + fmt(R2))).empty()) return e;
  return {};
}

double Problem::totalLength() const {
  double L = 0.0;
  for (const auto& s : segments) L += s.length;
  return L;
}

namespace {

std::string validateMaterial(const Material& m) {
  const std::string k = "materials." + m.name + ".";
  std::string e;
  if (m.tension_strain.empty()) {
    if (!(e = check(finite(m.EA) && m.EA > 0.0, k + "EA", m.EA, "must be > 0")).empty()) return e;
  } else {
    if (m.tension_strain.size() < 2)
      return k + "tension_strain has " + std::to_string(m.tension_strain.size()) + " rows: needs at least 2";
    for (std::size_t i = 0; i < m.tension_strain.size(); ++i) {
      const auto& p = m.tension_strain[i];
      const std::string r = k + "tension_strain[" + std::to_string(i) + "]";
      if (!finite(p.first) || !finite(p.second)) return r + " = [" + fmt(p.first) + ", " + fmt(p.second) + "]: must be finite";
      if (i > 0 && !(p.first > m.tension_strain[i - 1].first))
        return r + " strain " + fmt(p.first) + ": strains must increase";
      if (i > 0 && !(p.second > m.tension_strain[i - 1].second))
        return r + " tension " + fmt(p.second) + ": tensions must increase";
    }
  }
  if (!(e = check(finite(m.EI) && m.EI > 0.0, k + "EI", m.EI, "must be > 0 (the formulation needs bending stiffness; use a small value for ropes and chain)")).empty()) return e;
  if (!(e = check(finite(m.GJ) && m.GJ >= 0.0, k + "GJ", m.GJ, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.mass) && m.mass >= 0.0, k + "mass", m.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.added_mass) && m.added_mass >= 0.0, k + "added_mass", m.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.wet_weight), k + "wet_weight", m.wet_weight, "must be finite")).empty()) return e;
  if (!(e = check(finite(m.diameter) && m.diameter > 0.0, k + "diameter", m.diameter, "must be > 0")).empty()) return e;
  if (!(e = check(finite(m.cdn) && m.cdn >= 0.0, k + "cdn", m.cdn, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.cdt) && m.cdt >= 0.0, k + "cdt", m.cdt, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.max_strain) && m.max_strain > 0.0, k + "max_strain", m.max_strain, "must be > 0")).empty()) return e;
  if (!(e = check(finite(m.mbl) && m.mbl >= 0.0, k + "mbl", m.mbl, "must be > 0 (or 0 when not given)")).empty()) return e;
  if (!(e = check(finite(m.mu_axial) && m.mu_axial >= 0.0, k + "mu_axial", m.mu_axial, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.mu_lateral) && m.mu_lateral >= 0.0, k + "mu_lateral", m.mu_lateral, "must be >= 0")).empty())
    return e;
  return {};
}

std::string validateBody(const Body& b) {
  const std::string k = "bodies." + b.name + ".";
  std::string e;
  if (!(e = check(finite(b.mass) && b.mass >= 0.0, k + "mass", b.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.added_mass) && b.added_mass >= 0.0, k + "added_mass", b.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wet_weight), k + "wet_weight", b.wet_weight, "must be finite")).empty()) return e;
  if (!(e = check(finite(b.diameter) && b.diameter >= 0.0, k + "diameter", b.diameter, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cd) && b.cd >= 0.0, k + "cd", b.cd, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cdn) && b.cdn >= 0.0, k + "cdn", b.cdn, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cdt) && b.cdt >= 0.0, k + "cdt", b.cdt, "must be >= 0")).empty()) return e;
  return {};
}

std::string validateBuoy(const SurfaceBuoy& b) {
  const std::string k = "top.buoy.";
  std::string e;
  if (!(e = check(finite(b.diameter) && b.diameter > 0.0, k + "diameter", b.diameter, "must be > 0")).empty()) return e;
  if (b.shape == SurfaceBuoy::Shape::Cylinder &&
      !(e = check(finite(b.height) && b.height > 0.0, k + "height", b.height, "must be > 0")).empty()) return e;
  if (!(e = check(finite(b.mass) && b.mass >= 0.0, k + "mass", b.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.added_mass) && b.added_mass >= 0.0, k + "added_mass", b.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cd) && b.cd >= 0.0, k + "cd", b.cd, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wind_area) && b.wind_area >= 0.0, k + "wind_area", b.wind_area, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wind_cd) && b.wind_cd >= 0.0, k + "wind_cd", b.wind_cd, "must be >= 0")).empty()) return e;
  return {};
}

}  // namespace

namespace {

/// The environment: densities, gravity, depth, seabed, current, wind and waves.
std::string validateEnvironment(const Environment& env) {
  std::string e;
  if (!(e = check(finite(env.water_density) && env.water_density > 0.0, "environment.water_density", env.water_density, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.air_density) && env.air_density >= 0.0, "environment.air_density", env.air_density, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(env.gravity) && env.gravity > 0.0, "environment.gravity", env.gravity, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.depth) && env.depth > 0.0, "environment.depth", env.depth, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.seabed.stiffness) && env.seabed.stiffness > 0.0, "environment.seabed.stiffness", env.seabed.stiffness, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.seabed.damping) && env.seabed.damping >= 0.0, "environment.seabed.damping", env.seabed.damping, "must be >= 0")).empty()) return e;
  for (std::size_t i = 0; i < env.seabed.profile.size(); ++i) {
    const auto& p = env.seabed.profile[i];
    const std::string r = "environment.seabed.profile[" + std::to_string(i) + "]";
    if (!finite(p.first) || !finite(p.second)) return r + " = [" + fmt(p.first) + ", " + fmt(p.second) + "]: must be finite";
    if (!(p.second > 0.0)) return r + " depth = " + fmt(p.second) + ": must be > 0";
    if (i > 0 && !(p.first > env.seabed.profile[i - 1].first)) return r + " x = " + fmt(p.first) + ": x must increase";
  }
  if (!env.seabed.grid.empty()) {
    if (!env.seabed.profile.empty())
      return "environment.seabed: has both a profile and a grid; give at most one of profile and grid_file";
    if (!(e = env.seabed.grid.validate()).empty()) return e;
  }
  for (std::size_t i = 0; i < env.current.size(); ++i) {
    const auto& c = env.current[i];
    const std::string r = "environment.current[" + std::to_string(i) + "]";
    if (!(e = check(finite(c.depth) && c.depth >= 0.0, r + ".depth", c.depth, "must be >= 0")).empty()) return e;
    if (i > 0 && !(c.depth > env.current[i - 1].depth)) return r + ".depth = " + fmt(c.depth) + ": depths must increase";
    if (!(e = check(finite(c.speed) && c.speed >= 0.0, r + ".speed", c.speed, "must be >= 0")).empty()) return e;
    if (!(e = check(finite(c.direction), r + ".direction_deg", c.direction, "must be finite")).empty()) return e;
  }
  if (!(e = check(finite(env.wind_speed) && env.wind_speed >= 0.0, "environment.wind.speed", env.wind_speed, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(env.wind_direction), "environment.wind.direction_deg", env.wind_direction, "must be finite")).empty()) return e;
  if (!(e = env.waves.validate()).empty()) return e;
  return {};
}

/// The line: materials, bodies and the segments from the anchor up with their bodies.
std::string validateLine(const Problem& p) {
  std::string e;
  if (p.materials.empty()) return "materials: at least one material is needed";
  for (const auto& m : p.materials)
    if (!(e = validateMaterial(m)).empty()) return e;
  for (const auto& b : p.bodies)
    if (!(e = validateBody(b)).empty()) return e;
  if (p.segments.empty()) return "line: at least one segment is needed";
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    const Segment& s = p.segments[i];
    const std::string r = "line[" + std::to_string(i) + "]";
    if (s.material >= p.materials.size()) return r + ".material index " + std::to_string(s.material) + ": unknown material";
    if (!(e = check(finite(s.length) && s.length > 0.0, r + ".length", s.length, "must be > 0")).empty()) return e;
    if (!(e = check(finite(s.spacing) && s.spacing > 0.0, r + ".spacing", s.spacing, "must be > 0")).empty()) return e;
    if (!(e = check(s.spacing <= s.length, r + ".spacing", s.spacing,
                    "must be <= the segment length " + r + ".length = " + fmt(s.length) +
                        " m (a spacing beyond the segment collapses it to one interval)")).empty()) return e;
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      const auto& bp = s.bodies[j];
      const std::string rb = r + ".bodies[" + std::to_string(j) + "]";
      if (bp.body >= p.bodies.size()) return rb + ".body index " + std::to_string(bp.body) + ": unknown body";
      if (!(e = check(finite(bp.at) && bp.at >= 0.0 && bp.at <= s.length, rb + ".at", bp.at,
                      "must be within [0, " + fmt(s.length) + "] (the segment length)")).empty()) return e;
    }
  }
  return {};
}

/// The anchor: finite, not above the surface nor below the seabed; in the plane y = 0 in 2-D.
std::string validateAnchor(const Problem& p) {
  std::string e;
  const Environment& env = p.environment;
  if (!(e = check(finite(p.anchor_x), "anchor.x", p.anchor_x, "must be finite")).empty()) return e;
  if (!(e = check(finite(p.anchor_y), "anchor.y", p.anchor_y, "must be finite")).empty()) return e;
  if (!(e = check(finite(p.anchor_z) && p.anchor_z <= 0.0, "anchor.z", p.anchor_z, "must be <= 0 (z = 0 is the sea surface)")).empty()) return e;
  if (p.formulation == Formulation::TwoD) {
    // The 2-D equations live in the vertical plane y = 0.
    constexpr const char* kPlanar = "must be 0 with model: 2d (the 2-D line lies in the plane y = 0); use model: 3d";
    if (!(e = check(p.anchor_y == 0.0, "anchor.y", p.anchor_y, kPlanar)).empty()) return e;
    if (p.top.type == TopBoundary::Type::Position && !(e = check(p.top.y == 0.0, "top.position.y", p.top.y, kPlanar)).empty()) return e;
    if (p.top.type == TopBoundary::Type::Force && !(e = check(p.top.fy == 0.0, "top.force.y", p.top.fy, kPlanar)).empty()) return e;
  }
  const double zb = env.seabedElevation(p.anchor_x, p.anchor_y);
  if (!(e = check(p.anchor_z >= zb - 1e-6 * env.depth, "anchor.z", p.anchor_z,
                  "is below the seabed elevation " + fmt(zb) + " m at anchor.x")).empty()) return e;
  return {};
}

/// A free lower end: 3-D only, with a tow point or a drifting buoy above it.
std::string validateLowerEnd(const Problem& p) {
  std::string e;
  if (p.lower_end == Problem::LowerEnd::Free) {
    if (p.formulation != Formulation::ThreeD)
      return "free_end: a free lower end (towing) needs model: 3d";
    if (p.end_body != Problem::kNoBody && p.end_body >= p.bodies.size())
      return "free_end.body index " + std::to_string(p.end_body) + ": unknown body";
    if (p.top.type != TopBoundary::Type::Position && p.top.type != TopBoundary::Type::Buoy)
      return "top: a line with a free lower end needs top.position (the tow point) or top.buoy (a drifting "
             "surface buoy); a force or body top leaves the line's position undetermined";
    if (p.top.type == TopBoundary::Type::Buoy && p.dynamics.top_motion.type != TopMotion::Type::Hold &&
        p.dynamics.top_motion.type != TopMotion::Type::ForceTable)
      return "dynamics.top_motion: a drifting buoy (top.buoy with free_end:) moves with the current and the wind; "
             "only type hold (no extra force) or force_table (an extra force on the buoy) apply";
  }
  return {};
}

/// The steady tow velocity: only for a towed line.
std::string validateTowVelocity(const Problem& p) {
  std::string e;
  if (!(e = check(finite(p.top.tow_vx) && finite(p.top.tow_vy), "top.tow_velocity", std::hypot(p.top.tow_vx, p.top.tow_vy),
                  "must be finite")).empty()) return e;
  if ((p.top.tow_vx != 0.0 || p.top.tow_vy != 0.0) && p.lower_end != Problem::LowerEnd::Free)
    return "top.tow_velocity = (" + fmt(p.top.tow_vx) + ", " + fmt(p.top.tow_vy) +
           "): only for a line with a free lower end (free_end:); an anchored line has no steady tow";
  if ((p.top.tow_vx != 0.0 || p.top.tow_vy != 0.0) && p.top.type == TopBoundary::Type::Buoy)
    return "top.tow_velocity = (" + fmt(p.top.tow_vx) + ", " + fmt(p.top.tow_vy) +
           "): a drifting buoy is not towed; the statics find its drift velocity";
  return {};
}

/// The top boundary of its type (section 5.1).
std::string validateTop(const Problem& p) {
  std::string e;
  const Environment& env = p.environment;
  switch (p.top.type) {
    case TopBoundary::Type::Force:
      if (!(e = check(finite(p.top.fx), "top.force.x", p.top.fx, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.fz), "top.force.z", p.top.fz, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.fy), "top.force.y", p.top.fy, "must be finite")).empty()) return e;
      break;
    case TopBoundary::Type::Position: {
      if (!(e = check(finite(p.top.x), "top.position.x", p.top.x, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.z), "top.position.z", p.top.z, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.y), "top.position.y", p.top.y, "must be finite")).empty()) return e;
      // A top below the seabed has no equilibrium: the statics would iterate to their limit.
      const double ztop_bed = env.seabedElevation(p.top.x, p.top.y);
      if (p.top.z < ztop_bed - 1e-6 * env.depth)
        return "top.position.z = " + fmt(p.top.z) + ": below the seabed (z = " + fmt(ztop_bed) +
               " m under the top; environment.depth = " + fmt(env.depth) +
               " m); the top must lie above the seabed (z = 0 is the sea surface)";
      double reach = 0.0;
      for (const auto& s : p.segments) reach += s.length * (1.0 + p.materials[s.material].max_strain);
      const double dx = p.top.x - p.anchor_x, dy = p.top.y - p.anchor_y, dz = p.top.z - p.anchor_z;
      const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (!(dist < reach) && p.lower_end == Problem::LowerEnd::Anchor) {
        const std::string at = p.formulation == Formulation::TwoD
                                   ? fmt(p.top.x) + ", " + fmt(p.top.z)
                                   : fmt(p.top.x) + ", " + fmt(p.top.y) + ", " + fmt(p.top.z);
        return "top.position = (" + at + "): " + fmt(dist) +
               " m from the anchor, farther than the stretched line can reach (" + fmt(reach) +
               " m: unstretched length " + fmt(p.totalLength()) + " m at each material's max_strain)";
      }
      break;
    }
    case TopBoundary::Type::Buoy:
      if (!(e = validateBuoy(p.top.buoy)).empty()) return e;
      break;
    case TopBoundary::Type::Body:
      if (p.top.body >= p.bodies.size()) return "top.body index " + std::to_string(p.top.body) + ": unknown body";
      if (p.formulation != Formulation::ThreeD)
        return "top.body: a subsurface buoy at the top needs model: 3d";
      if (p.lower_end != Problem::LowerEnd::Anchor)
        return "top.body with free_end: a line free at both ends under a subsurface body is not supported; a drifting "
               "system takes a surface buoy at the top (top.buoy)";
      if (p.dynamics.top_motion.type != TopMotion::Type::Hold && p.dynamics.top_motion.type != TopMotion::Type::ForceTable)
        return "dynamics.top_motion: with top.body the top is free; only type hold (no extra force) or force_table "
               "(an extra force on the body) apply";
      break;
  }
  return {};
}

/// dynamics.events of a single line (the events' own fields are checked by DynamicOptions).
std::string validateEvents(const Problem& p) {
  for (std::size_t i = 0; i < p.dynamics.events.size(); ++i) {
    const LineEvent& ev = p.dynamics.events[i];
    const std::string k = "dynamics.events[" + std::to_string(i) + "]";
    if (p.formulation != Formulation::ThreeD)
      return k + ": line events run in the 3-D solver; set formulation: 3d (a planar problem gives the same results there)";
    if (!ev.line.empty()) return k + ".line = " + ev.line + ": only a system file names the line of an event";
    const std::string e = validateEventOnLine(ev, k, "the line", p.segments, p.materials,
                                              p.lower_end == Problem::LowerEnd::Free);
    if (!e.empty()) return e;
  }
  return {};
}

/// dynamics.winch of a single line (its own fields are checked by DynamicOptions): a top the
/// winch can drive, its program against the line (validateWinchOnLine).
std::string validateWinch(const Problem& p) {
  const Winch& w = p.dynamics.winch;
  if (!w.given) return {};
  const std::string k = "dynamics.winch";
  if (!w.line.empty()) return k + ".line = " + w.line + ": only a system file names the line of a winch";
  const bool free_below = p.lower_end == Problem::LowerEnd::Free;
  const char* top_kind = p.top.type == TopBoundary::Type::Force ? "force"
                    : p.top.type == TopBoundary::Type::Body ? "body"
                    : p.top.type == TopBoundary::Type::Buoy ? "buoy"
                                                            : "position";
  if (p.top.type == TopBoundary::Type::Force || p.top.type == TopBoundary::Type::Body ||
      (p.top.type == TopBoundary::Type::Buoy && free_below))
    return k + ": top: " + top_kind + (free_below ? " over a free lower end" : "") +
           ": the winch sits at a top whose motion is prescribed (top: position, or a surface buoy over an "
           "anchor); this top's position follows from its forces";
  if (p.dynamics.top_motion.type == TopMotion::Type::ForceTable)
    return k + ": dynamics.top_motion.type = force_table: the winch sits at a top whose motion is prescribed; a "
               "force table leaves the top's position to its forces";
  return validateWinchOnSegments(w, k, p.segments, p.dynamics.duration);
}

}  // namespace

double winchBase(const std::vector<Segment>& segments) {
  double base = 0.0;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) base += segments[i].length;
  double last_body = 0.0;
  for (const BodyPlacement& b : segments.back().bodies) last_body = std::max(last_body, b.at);
  return base + last_body;
}

std::string validateWinchOnSegments(const Winch& w, const std::string& key, const std::vector<Segment>& segments,
                                    double duration) {
  double L = 0.0;
  for (const Segment& g : segments) L += g.length;
  return validateWinchOnLine(w, key, L, winchBase(segments), segments.back().spacing, duration);
}

std::string validateEventOnLine(const LineEvent& ev, const std::string& key, const std::string& line,
                                const std::vector<Segment>& segments, const std::vector<Material>& materials,
                                bool lower_end_free) {
  double length = 0.0;
  bool any_mbl = false;
  for (const Segment& g : segments) {
    length += g.length;
    any_mbl = any_mbl || materials[g.material].mbl > 0.0;
  }
  if (ev.s > length * (1.0 + 1e-12))
    return key + ".s = " + std::to_string(ev.s) + ": beyond the top of " + line + " (unstretched length " +
           std::to_string(length) + " m)";
  if (ev.at_mbl && !any_mbl) return key + ".tension = mbl: no material of " + line + " has an mbl";
  if (ev.type == LineEvent::Type::Release && ev.end == LineEvent::End::Anchor && lower_end_free)
    return key + ".end = anchor: " + line + "'s lower end is free already";
  return {};
}

std::string Problem::validate() const {
  std::string e;
  if (!(e = validateEnvironment(environment)).empty()) return e;
  if (!(e = validateLine(*this)).empty()) return e;
  if (!(e = validateAnchor(*this)).empty()) return e;
  if (!(e = validateLowerEnd(*this)).empty()) return e;
  if (!(e = validateTowVelocity(*this)).empty()) return e;
  if (!(e = validateTop(*this)).empty()) return e;
  if (!(e = static_options.validate()).empty()) return e;
  if (!(e = dynamics.validate()).empty()) return e;
  if (!(e = validateEvents(*this)).empty()) return e;
  if (!(e = validateWinch(*this)).empty()) return e;
  return validateResources();
}

std::string Problem::validateResources() const {
  std::string e;
  if (!(e = limits.validate()).empty()) return e;
  // The segment with the most intervals names the key to change.
  std::size_t worst = 0;
  for (std::size_t i = 1; i < segments.size(); ++i)
    if (segments[i].length / segments[i].spacing > segments[worst].length / segments[worst].spacing) worst = i;
  const std::string key = segments.empty() ? std::string("line")
                                           : "line[" + std::to_string(worst) + "].spacing = " +
                                                 fmt(segments[worst].spacing) + " (line[" + std::to_string(worst) +
                                                 "].length = " + fmt(segments[worst].length) + " m)";
  return checkResources(estimateResources(estimateLineNodes(segments), dynamics, formulation == Formulation::ThreeD,
                                          4 * dynamics.record_s.size()),
                        limits, key);
}

}  // namespace core
}  // namespace mooring_dynamics
