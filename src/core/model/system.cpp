#include "mooring_dynamics/core/model/system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>


namespace mooring_dynamics {
namespace core {

namespace {

/// Points within this fraction of the water depth of the surface or the seabed count as on it.
constexpr double kGeometryTolerance = 1e-6;

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

// --- Problem -------------------------------------------------------------------------------------

Problem SystemProblem::lineProblem(std::size_t i, const std::vector<double>& xyz) const {
  const SystemLine& l = lines[i];
  Problem p;
  p.name = name.empty() ? l.name : name + " / " + l.name;
  p.formulation = formulation;
  p.environment = environment;
  p.materials = materials;
  p.bodies = bodies;
  p.segments = l.segments;
  p.static_options = static_options;
  if (l.from == SystemLine::kFreeEnd) {
    p.lower_end = Problem::LowerEnd::Free;
    p.end_body = l.end_body;
  } else {
    p.anchor_x = xyz[3 * l.from];
    p.anchor_y = xyz[3 * l.from + 1];
    p.anchor_z = xyz[3 * l.from + 2];
  }
  p.top.type = TopBoundary::Type::Position;
  p.top.x = xyz[3 * l.to];
  p.top.y = xyz[3 * l.to + 1];
  p.top.z = xyz[3 * l.to + 2];
  return p;
}

void SystemProblem::placeVessel(const RigidPose& pose) {
  vessel.pose = pose;
  for (SystemPoint& pt : points) {
    if (pt.type != SystemPoint::Type::Vessel) continue;
    const Eigen::Vector3d w = pose.apply(pt.body_offset);
    pt.x = w.x();
    pt.y = w.y();
    pt.z = w.z();
  }
}

bool SystemProblem::hasVesselPoints() const {
  for (const SystemPoint& pt : points)
    if (pt.type == SystemPoint::Type::Vessel) return true;
  return false;
}

namespace {

/// The vessel section, and the lines: unique names, known and distinct end points, segments.
/// `used` counts the lines at each point.
std::string validateLines(const SystemProblem& s, std::vector<int>& used) {
  if (s.vessel.present) {
    const std::string e = s.vessel.pose.validate("vessel.pose");
    if (!e.empty()) return e;
    if (s.vessel.frame.empty()) return "vessel.frame = \"\": needs a frame name (e.g. base_link)";
  }
  const std::size_t np = s.points.size();
  used.assign(np, 0);
  for (std::size_t i = 0; i < s.lines.size(); ++i)  // names key the output files and columns
    for (std::size_t j = 0; j < i; ++j)
      if (s.lines[j].name == s.lines[i].name)
        return "lines[" + std::to_string(i) + "].name = \"" + s.lines[i].name + "\": duplicate line name (also lines[" +
               std::to_string(j) + "]); every line needs its own name";
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const SystemLine& l = s.lines[i];
    const std::string k = "lines[" + std::to_string(i) + "] (" + l.name + ")";
    if (l.to >= np) return k + ".to: unknown point";
    if (l.from != SystemLine::kFreeEnd && l.from >= np) return k + ".from: unknown point";
    if (l.from == l.to) return k + ": from and to are the same point (" + s.points[l.to].name + ")";
    if (l.segments.empty()) return k + ".segments: at least one segment is needed";
    if (l.end_body != Problem::kNoBody && l.from != SystemLine::kFreeEnd)
      return k + ".end_body: only for a line with a free lower end (from: free)";
    ++used[l.to];
    if (l.from != SystemLine::kFreeEnd) ++used[l.from];
  }
  return {};
}

/// Every point: joined to a line, its body and vessel known, its position finite (in 2-D, y = 0).
std::string validatePoints(const SystemProblem& s, const std::vector<int>& used) {
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    const SystemPoint& pt = s.points[p];
    if (!used[p]) return "points." + pt.name + ": not joined to any line";
    if (pt.type == SystemPoint::Type::Body && pt.body >= s.bodies.size())
      return "points." + pt.name + ".body: unknown body";
    if (pt.type == SystemPoint::Type::Vessel && !s.vessel.present)
      return "points." + pt.name + ".type = vessel: the file has no `vessel:` section (its frame and pose)";
    if (pt.type == SystemPoint::Type::Vessel && !pt.body_offset.allFinite())
      return "points." + pt.name + ".position (body frame) must be finite";
    if (!std::isfinite(pt.x) || !std::isfinite(pt.y) || !std::isfinite(pt.z))
      return "points." + pt.name + ".position = (" + fmt(pt.x) + ", " + fmt(pt.y) + ", " + fmt(pt.z) +
             "): must be finite";
    if (s.formulation == Formulation::TwoD && pt.y != 0.0)
      return "points." + pt.name + ".position y = " + fmt(pt.y) +
             ": must be 0 with model: 2d (the 2-D lines lie in the plane y = 0); use model: 3d";
  }
  return {};
}

/// One connected piece holding at least one anchor or fixed point (else it floats away:
/// statically undetermined), found by a flood fill over the lines (and the vessel's hull).
std::string validateConnected(const SystemProblem& s) {
  const std::size_t np = s.points.size();
  std::vector<int> piece(np, -1);
  std::function<void(std::size_t, int)> fill = [&](std::size_t p, int id) {
    if (piece[p] >= 0) return;
    piece[p] = id;
    if (s.points[p].type == SystemPoint::Type::Vessel)  // the vessel's points are joined by its hull
      for (std::size_t q = 0; q < np; ++q)
        if (s.points[q].type == SystemPoint::Type::Vessel) fill(q, id);
    for (const SystemLine& l : s.lines) {
      if (l.from == SystemLine::kFreeEnd) continue;
      if (l.from == p) fill(l.to, id);
      if (l.to == p) fill(l.from, id);
    }
  };
  int pieces = 0;
  for (std::size_t p = 0; p < np; ++p)
    if (piece[p] < 0) fill(p, pieces++);
  if (pieces > 1) {
    std::string names;
    for (std::size_t p = 0; p < np; ++p)
      if (piece[p] != piece[0]) names += (names.empty() ? "" : ", ") + s.points[p].name;
    return "lines: the system falls apart in " + std::to_string(pieces) + " pieces; " + names +
           " are not connected to " + s.points[0].name + " (solve separate systems in separate files)";
  }
  bool support = false;
  for (const SystemPoint& pt : s.points) support = support || !pt.free();
  if (!support)
    return "points: no anchor or fixed point; a system of free buoys and bodies has no static position "
           "(a drifting system is solved as a single line with a buoy and a free end)";
  return {};
}

/// Anchors lie on the seabed or above it and under the surface; fixed points above the seabed.
std::string validateSupports(const SystemProblem& s) {
  const double tol = kGeometryTolerance * s.environment.depth;
  for (const SystemPoint& pt : s.points) {
    if (pt.free()) continue;
    const double bed = s.environment.seabedElevation(pt.x, pt.y);
    const std::string k = "points." + pt.name + ".position.z = " + fmt(pt.z);
    if (pt.type == SystemPoint::Type::Anchor && pt.z > tol)
      return k + ": an anchor above the sea surface (z = 0); anchors lie on the seabed (z = " + fmt(bed) +
             " m here, environment.depth = " + fmt(s.environment.depth) + " m)";
    if (pt.z < bed - tol)
      return k + ": below the seabed (z = " + fmt(bed) + " m here, environment.depth = " + fmt(s.environment.depth) +
             " m)";
  }
  return {};
}

/// Spacing and the size of the whole system (limits.hpp), before any line is built.
std::string validateSizes(const SystemProblem& s) {
  std::string e;
  if (!(e = s.limits.validate()).empty()) return e;
  double nodes = 0.0;
  std::string worst;
  double worst_ratio = -1.0;
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const std::string prefix = "lines[" + std::to_string(i) + "].segments";
    if (!(e = validateSpacing(s.lines[i].segments, prefix)).empty()) return e;
    nodes += estimateLineNodes(s.lines[i].segments);
    for (std::size_t j = 0; j < s.lines[i].segments.size(); ++j) {
      const Segment& g = s.lines[i].segments[j];
      if (g.length / g.spacing > worst_ratio) {
        worst_ratio = g.length / g.spacing;
        worst = prefix + "[" + std::to_string(j) + "].spacing = " + fmt(g.spacing) + " (length " + fmt(g.length) + " m)";
      }
    }
  }
  if (!(e = s.dynamics.validate()).empty()) return e;
  return checkResources(
      estimateResources(nodes, s.dynamics, s.formulation == Formulation::ThreeD, 3 * s.points.size() + s.lines.size()),
      s.limits, worst);
}

/// The single-line checks of every line at the initial positions (materials, segments, reach).
std::string validateLineProblems(const SystemProblem& s) {
  std::vector<double> xyz;
  for (const SystemPoint& pt : s.points) xyz.insert(xyz.end(), {pt.x, pt.y, pt.z});
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    Problem p = s.lineProblem(i, xyz);
    // Free points may start anywhere; only fixed ends are held to the seabed and reach checks.
    const bool free_ends = (s.lines[i].from != SystemLine::kFreeEnd && s.points[s.lines[i].from].free()) ||
                           s.points[s.lines[i].to].free();
    if (free_ends) continue;
    const std::string e = p.validate();
    if (!e.empty()) return "lines[" + std::to_string(i) + "] (" + s.lines[i].name + "): " + e;
  }
  return {};
}

}  // namespace

/// dynamics.events of a system: each names a line of the file.
static std::string validateSystemEvents(const SystemProblem& s) {
  for (std::size_t i = 0; i < s.dynamics.events.size(); ++i) {
    const LineEvent& ev = s.dynamics.events[i];
    const std::string k = "dynamics.events[" + std::to_string(i) + "]";
    if (ev.line.empty()) return k + ".line: required in a system file (the name of the line the event happens to)";
    const SystemLine* line = nullptr;
    for (const SystemLine& l : s.lines)
      if (l.name == ev.line) line = &l;
    if (!line) return k + ".line = " + ev.line + ": no line of that name in lines";
    const std::string e = validateEventOnLine(ev, k, "line " + ev.line, line->segments, s.materials,
                                              line->from == SystemLine::kFreeEnd);
    if (!e.empty()) return e;
  }
  return {};
}

/// dynamics.winch of a system: at the top of a line of the file (validateWinchOnLine).
static std::string validateSystemWinch(const SystemProblem& s) {
  const Winch& w = s.dynamics.winch;
  if (!w.given) return {};
  const std::string k = "dynamics.winch";
  if (w.line.empty()) return k + ".line: required in a system file (the name of the line whose top the winch is at)";
  for (const SystemLine& l : s.lines)
    if (l.name == w.line) return validateWinchOnSegments(w, k, l.segments, s.dynamics.duration);
  return k + ".line = " + w.line + ": no line of that name in lines";
}

std::string SystemProblem::validate() const {
  if (points.empty()) return "points: at least one point is needed";
  if (lines.empty()) return "lines: at least one line is needed";
  std::string e;
  std::vector<int> used;
  if (!(e = validateLines(*this, used)).empty()) return e;
  if (!(e = validatePoints(*this, used)).empty()) return e;
  if (!(e = validateConnected(*this)).empty()) return e;
  if (!(e = validateSupports(*this)).empty()) return e;
  if (!(e = validateSizes(*this)).empty()) return e;
  if (!(e = validateSystemEvents(*this)).empty()) return e;
  if (!(e = validateSystemWinch(*this)).empty()) return e;
  return validateLineProblems(*this);
}

}  // namespace core
}  // namespace mooring_dynamics
