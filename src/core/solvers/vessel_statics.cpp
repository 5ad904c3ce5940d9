#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {

namespace {

/// The pull of line `l` (state `s`) on point `p` [N], world: -top_force at its upper end,
/// anchor_force at its lower end.
Eigen::Vector3d pullOn(const SystemLine& l, const StaticResult& s, std::size_t p) {
  if (l.to == p) return {-s.top_force_x, -s.top_force_y, -s.top_force_z};
  return {s.anchor_force_x, s.anchor_force_y, s.anchor_force_z};
}

double maxTension(const StaticResult& s) {
  double T = s.nodes.empty() ? 0.0 : s.nodes.front().tension;
  for (const NodeState& n : s.nodes) T = std::max(T, n.tension);
  return T;
}

}  // namespace

Eigen::Matrix<double, 6, 1> VesselWrench::body6() const {
  Eigen::Matrix<double, 6, 1> w;
  w << force_body, moment_body;
  return w;
}

VesselWrench vesselWrench(const SystemProblem& system, const RigidPose& pose, const std::vector<StaticResult>& lines) {
  VesselWrench w;
  for (std::size_t i = 0; i < system.lines.size() && i < lines.size(); ++i) {
    const SystemLine& l = system.lines[i];
    for (std::size_t p : {l.to, l.from}) {
      if (p == SystemLine::kFreeEnd || system.points[p].type != SystemPoint::Type::Vessel) continue;
      FairleadForce f;
      f.line = i;
      f.point = p;
      const Eigen::Vector3d arm = pose.orientation * system.points[p].body_offset;  // R r_i
      f.position = pose.position + arm;
      f.force = pullOn(l, lines[i], p);
      w.force_world += f.force;
      w.moment_world += arm.cross(f.force);
      w.fairleads.push_back(f);
    }
  }
  w.force_body = pose.toBody(w.force_world);
  w.moment_body = pose.toBody(w.moment_world);
  return w;
}

VesselStaticResult solveVesselStatic(SystemProblem system, const RigidPose& pose, const SystemSolveOptions& options) {
  const std::string e = pose.validate("vessel pose");
  if (!e.empty()) throw std::invalid_argument(e);
  RigidPose p = pose;
  p.orientation.normalize();
  system.placeVessel(p);
  VesselStaticResult r;
  r.pose = p;
  r.system = solveSystemStatic(system, options);
  r.wrench = vesselWrench(system, p, r.system.lines);
  return r;
}

const char* toString(VesselDof dof) {
  switch (dof) {
    case VesselDof::Surge: return "surge";
    case VesselDof::Sway: return "sway";
    case VesselDof::Heave: return "heave";
    case VesselDof::Roll: return "roll";
    case VesselDof::Pitch: return "pitch";
    case VesselDof::Yaw: return "yaw";
  }
  return "?";
}

bool parseVesselDof(const std::string& name, VesselDof& dof) {
  for (int k = 0; k < 6; ++k)
    if (name == toString(static_cast<VesselDof>(k))) {
      dof = static_cast<VesselDof>(k);
      return true;
    }
  return false;
}

RigidPose offsetPose(const RigidPose& pose, VesselDof dof, double amount) {
  const int k = static_cast<int>(dof);
  RigidPose p = pose;
  if (k < 3) {
    p.position += pose.orientation * (amount * Eigen::Vector3d::Unit(k));
  } else {
    p.orientation = pose.orientation * Eigen::Quaterniond(Eigen::AngleAxisd(amount, Eigen::Vector3d::Unit(k - 3)));
  }
  return p;
}

std::string StiffnessOptions::validate() const {
  std::ostringstream os;
  if (!(translation_step > 0.0) || !std::isfinite(translation_step))
    os << "translation_step = " << translation_step << " m: must be > 0 and finite";
  else if (!(rotation_step > 0.0) || !(rotation_step < 0.5))
    os << "rotation_step = " << rotation_step << " rad: must be in (0, 0.5)";
  return os.str();
}

StiffnessResult mooringStiffness(const SystemProblem& system, const RigidPose& pose, const StiffnessOptions& options) {
  const std::string e = options.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  StiffnessResult r;
  r.at = solveVesselStatic(system, pose, options.solve);
  r.converged = r.at.system.summary.converged;
  if (!r.converged) r.message = "at the pose: " + r.at.system.summary.message;
  for (int j = 0; j < 6 && r.converged; ++j) {
    const VesselDof dof = static_cast<VesselDof>(j);
    const double h = j < 3 ? options.translation_step : options.rotation_step;
    const VesselStaticResult plus = solveVesselStatic(system, offsetPose(r.at.pose, dof, h), options.solve);
    const VesselStaticResult minus = solveVesselStatic(system, offsetPose(r.at.pose, dof, -h), options.solve);
    for (const VesselStaticResult* s : {&plus, &minus})
      if (!s->system.summary.converged) {
        r.converged = false;
        r.message = std::string(toString(dof)) + (s == &plus ? " +" : " -") + std::to_string(h) + ": " +
                    s->system.summary.message;
      }
    r.K.col(j) = -(plus.wrench.body6() - minus.wrench.body6()) / (2.0 * h);
  }
  return r;
}

std::vector<OffsetPoint> offsetCurve(const SystemProblem& system, const RigidPose& pose, VesselDof dof,
                                     const std::vector<double>& offsets, const SystemSolveOptions& options) {
  std::vector<OffsetPoint> out;
  for (double a : offsets) {
    OffsetPoint o;
    o.offset = a;
    const VesselStaticResult s = solveVesselStatic(system, offsetPose(pose, dof, a), options);
    o.converged = s.system.summary.converged;
    if (!o.converged) o.message = s.system.summary.message;
    o.wrench = s.wrench.body6();
    for (std::size_t i = 0; i < s.system.lines.size(); ++i) {
      const double T = maxTension(s.system.lines[i]);
      if (i == 0 || T > o.max_tension) {
        o.max_tension = T;
        o.max_tension_line = system.lines[i].name;
      }
    }
    out.push_back(o);
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
