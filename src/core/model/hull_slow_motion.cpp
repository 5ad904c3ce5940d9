// Low-frequency surge, sway and yaw of a moored hull (hull_slow_motion.hpp).
#include "mooring_dynamics/core/model/hull_slow_motion.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {
namespace {

std::string field(const std::string& name, double v, const std::string& constraint) {
  std::ostringstream s;
  s << "vessel.low_frequency." << name << " = " << v << ": " << constraint;
  return s.str();
}

}  // namespace

std::string HullSlowMotionOptions::validate() const {
  if (!std::isfinite(mass) || !(mass > 0.0)) return field("mass", mass, "must be finite and > 0 [kg]");
  if (!std::isfinite(yaw_inertia) || !(yaw_inertia > 0.0))
    return field("yaw_inertia", yaw_inertia, "must be finite and > 0 [kg m^2]");
  const char* dofs[3] = {"surge", "sway", "yaw"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(added_mass[i]) || added_mass[i] < 0.0)
      return field(std::string("added_mass (") + dofs[i] + ")", added_mass[i], "must be finite and >= 0");
    if (!std::isfinite(damping[i]) || damping[i] < 0.0)
      return field(std::string("damping (") + dofs[i] + ")", damping[i], "must be finite and >= 0");
    if (!std::isfinite(mean_force[i])) return field("mean_force", mean_force[i], "must be finite");
  }
  return {};
}

HullSlowMotion::HullSlowMotion(const HullSlowMotionOptions& options, const RigidPose& start) : o_(options) {
  const std::string e = options.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  const Eigen::Matrix3d r = start.orientation.normalized().toRotationMatrix();
  // R = Rz(yaw) Ry(pitch) Rx(roll).
  pos_ = Eigen::Vector3d(start.position.x(), start.position.y(), std::atan2(r(1, 0), r(0, 0)));
  z_ = start.position.z();
  pitch_ = std::asin(std::max(-1.0, std::min(1.0, -r(2, 0))));
  roll_ = std::atan2(r(2, 1), r(2, 2));
}

void HullSlowMotion::step(double dt, const Eigen::Vector3d& lines_xyn) {
  const double psi = pos_.z(), c = std::cos(psi), s = std::sin(psi);
  // The mean force (world) in the slow body axes; the moment about z is the same in both.
  const Eigen::Vector3d mean_body(c * o_.mean_force.x() + s * o_.mean_force.y(),
                                  -s * o_.mean_force.x() + c * o_.mean_force.y(), o_.mean_force.z());
  const Eigen::Vector3d f = lines_xyn + mean_body;
  const double m1 = o_.mass + o_.added_mass.x(), m2 = o_.mass + o_.added_mass.y();
  const double m6 = o_.yaw_inertia + o_.added_mass.z();
  const double u = vel_.x(), v = vel_.y(), r = vel_.z();
  // Velocities: forces and the rigid-body (Coriolis) terms at the start, damping implicit.
  const double u1 = (m1 * u + dt * (f.x() + m2 * v * r)) / (m1 + dt * o_.damping.x());
  const double v1 = (m2 * v + dt * (f.y() - m1 * u * r)) / (m2 + dt * o_.damping.y());
  const double r1 = (m6 * r + dt * f.z()) / (m6 + dt * o_.damping.z());
  vel_ = Eigen::Vector3d(u1, v1, r1);
  // Positions with the new velocities, in the axes at the start of the step.
  pos_.x() += dt * (u1 * c - v1 * s);
  pos_.y() += dt * (u1 * s + v1 * c);
  pos_.z() += dt * r1;
}

RigidPose HullSlowMotion::pose() const {
  return RigidPose::fromRollPitchYaw(Eigen::Vector3d(pos_.x(), pos_.y(), z_), roll_, pitch_, pos_.z());
}

}  // namespace core
}  // namespace mooring_dynamics
