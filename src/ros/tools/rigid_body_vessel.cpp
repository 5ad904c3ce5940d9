#include "mooring_dynamics/ros/tools/rigid_body_vessel.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace mooring_dynamics {
namespace ros_bridge {

namespace {
constexpr double kTwoPi = 6.283185307179586;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Roll and pitch [rad] of an orientation (R = Rz Ry Rx).
void rollPitch(const Eigen::Quaterniond& q, double& roll, double& pitch) {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  pitch = std::asin(std::max(-1.0, std::min(1.0, -R(2, 0))));
  roll = std::atan2(R(2, 1), R(2, 2));
}
}  // namespace

std::string RigidBodyVesselOptions::validate() const {
  std::ostringstream os;
  if (!(mass > 0.0)) os << "mass = " << mass << " kg: must be > 0";
  else if (!(inertia.minCoeff() > 0.0)) os << "inertia = (" << inertia.transpose() << ") kg m^2: each must be > 0";
  else if (!(added_mass.minCoeff() >= 0.0)) os << "added_mass: each must be >= 0";
  else if (!(damping.minCoeff() >= 0.0)) os << "damping: each must be >= 0";
  else if (!(waterplane_area > 0.0)) os << "waterplane_area = " << waterplane_area << " m^2: must be > 0";
  else if (!(wave_period > 0.0)) os << "wave_period = " << wave_period << " s: must be > 0";
  else if (!(ramp >= 0.0)) os << "ramp = " << ramp << " s: must be >= 0";
  return os.str();
}

RigidBodyVessel::RigidBodyVessel(const RigidBodyVesselOptions& o, const Eigen::Vector3d& position,
                                 const Eigen::Quaterniond& orientation, const Vec6& mooring0)
    : o_(o), tau0_(mooring0), p0_(position), p_(position), q_(orientation.normalized()) {
  M_.setZero();
  M_.diagonal() << o.mass, o.mass, o.mass, o.inertia;
  M_.diagonal() += o.added_mass;
}

double RigidBodyVessel::heavePeriod() const {
  return kTwoPi * std::sqrt(M_(2, 2) / (o_.water_density * o_.gravity * o_.waterplane_area));
}

double RigidBodyVessel::rollPeriod() const {
  return kTwoPi * std::sqrt(M_(3, 3) / (o_.gravity * o_.mass * o_.gm_transverse));
}

Vec6 RigidBodyVessel::acceleration(double t, const Eigen::Vector3d& p, const Eigen::Quaterniond& q, const Vec6& nu,
                                   const Vec6& mooring) const {
  const Eigen::Vector3d v = nu.head<3>(), w = nu.tail<3>();
  Vec6 tau = Vec6::Zero();
  // Rigid-body Coriolis and centripetal terms about the centre of gravity.
  tau.head<3>() -= w.cross(o_.mass * v);
  tau.tail<3>() -= w.cross(o_.inertia.cwiseProduct(w));
  tau -= o_.damping.cwiseProduct(nu);
  // Hydrostatics: heave restoring in the world frame, seen in the body frame; metacentric moments.
  const double rho_g = o_.water_density * o_.gravity;
  tau.head<3>() += q.conjugate() * Eigen::Vector3d(0.0, 0.0, -rho_g * o_.waterplane_area * (p.z() - p0_.z()));
  double roll = 0.0, pitch = 0.0;
  rollPitch(q, roll, pitch);
  tau[3] -= o_.mass * o_.gravity * o_.gm_transverse * roll;
  tau[4] -= o_.mass * o_.gravity * o_.gm_longitudinal * pitch;
  // Waves, ramped in.
  const double ramp = o_.ramp > 0.0 ? std::min(1.0, t / o_.ramp) : 1.0;
  tau += ramp * std::sin(kTwoPi * t / o_.wave_period) * o_.wave_amplitude;
  tau += mooring - tau0_;
  return M_.diagonal().cwiseInverse().cwiseProduct(tau);
}

void RigidBodyVessel::step(double dt, const Vec6& mooring) {
  // Classical RK4 on (p, q, nu); the quaternion rate is q (0, w) / 2 with w in the body frame.
  struct State {
    Eigen::Vector3d p;
    Eigen::Vector4d q;  // (x, y, z, w)
    Vec6 nu;
  };
  auto deriv = [&](double t, const State& s) {
    Eigen::Quaterniond q(s.q[3], s.q[0], s.q[1], s.q[2]);
    q.normalize();
    State d;
    d.p = q * s.nu.head<3>();
    const Eigen::Vector3d w = s.nu.tail<3>();
    const Eigen::Quaterniond qd = q * Eigen::Quaterniond(0.0, w.x(), w.y(), w.z());
    d.q = 0.5 * qd.coeffs();
    d.nu = acceleration(t, s.p, q, s.nu, mooring);
    return d;
  };
  auto add = [](const State& s, const State& d, double h) {
    return State{s.p + h * d.p, s.q + h * d.q, s.nu + h * d.nu};
  };
  const State s0{p_, q_.coeffs(), nu_};
  const State k1 = deriv(t_, s0);
  const State k2 = deriv(t_ + 0.5 * dt, add(s0, k1, 0.5 * dt));
  const State k3 = deriv(t_ + 0.5 * dt, add(s0, k2, 0.5 * dt));
  const State k4 = deriv(t_ + dt, add(s0, k3, dt));
  p_ = s0.p + dt / 6.0 * (k1.p + 2.0 * k2.p + 2.0 * k3.p + k4.p);
  const Eigen::Vector4d qc = s0.q + dt / 6.0 * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
  q_ = Eigen::Quaterniond(qc[3], qc[0], qc[1], qc[2]).normalized();
  nu_ = s0.nu + dt / 6.0 * (k1.nu + 2.0 * k2.nu + 2.0 * k3.nu + k4.nu);
  t_ += dt;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
