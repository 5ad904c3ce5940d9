// Wave-frequency hull motion from RAOs and a realized sea (sea_state_motion.hpp).
#include "mooring_dynamics/core/model/sea_state_motion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
}  // namespace

SeaStateMotion::SeaStateMotion(const WaveField& waves, const RaoTable& raos, const RigidPose& mean_pose,
                               const Eigen::Vector3d& reference_point)
    : waves_(&waves), raos_(&raos), ref_(reference_point) {
  const std::vector<WaveComponent>& comps = waves.components();
  if (raos.extend == RaoExtend::None && !comps.empty()) {  // the band outside the table, named at once
    const double lo = raos.omega().front(), hi = raos.omega().back();
    double w_min = 0.0, w_max = 0.0, e_out = 0.0, e_all = 0.0;
    std::size_t n_out = 0;
    for (const WaveComponent& c : comps) {
      e_all += 0.5 * c.amplitude * c.amplitude;
      if (c.amplitude > 0.0 && (c.omega < lo || c.omega > hi)) {
        w_min = n_out == 0 ? c.omega : std::min(w_min, c.omega);
        w_max = n_out == 0 ? c.omega : std::max(w_max, c.omega);
        e_out += 0.5 * c.amplitude * c.amplitude;
        ++n_out;
      }
    }
    if (n_out > 0) {
      std::ostringstream m;
      m << "the sea has " << n_out << " of its " << comps.size() << " components at " << w_min << " to " << w_max
        << " rad/s (" << 100.0 * e_out / e_all << " % of its energy), outside the RAO table's " << lo << " to " << hi
        << " rad/s: give the table those frequencies, narrow the sea's band (f_min_factor, f_max_factor), or say "
           "how to extend the table (raos.extend: zero or hold)";
      throw std::invalid_argument(m.str());
    }
  }
  build(mean_pose);
}

void SeaStateMotion::rebase(const RigidPose& mean_pose) { build(mean_pose); }

void SeaStateMotion::build(const RigidPose& mean_pose) {
  const WaveField& waves = *waves_;
  const RaoTable& raos = *raos_;
  mean_ = mean_pose;
  r0_ = mean_pose.orientation.normalized().toRotationMatrix();
  const double yaw0 = std::atan2(r0_(1, 0), r0_(0, 0));
  const Eigen::Vector3d ref_world = mean_pose.position + r0_ * ref_;
  const std::vector<WaveComponent>& comps = waves.components();
  terms_.clear();
  terms_.reserve(comps.size());
  for (std::size_t j = 0; j < comps.size(); ++j) {
    const WaveComponent& c = comps[j];
    const double beta_deg = (c.direction - yaw0) * kRadToDeg;
    const std::string e = raos.check(c.omega, beta_deg);
    if (!e.empty()) {
      std::ostringstream m;
      m << "wave component " << j + 1 << " of " << comps.size() << " (omega " << c.omega << " rad/s, period "
        << 2.0 * kPi / c.omega << " s, heading " << beta_deg << " deg relative to the hull): " << e;
      throw std::invalid_argument(m.str());
    }
    const std::array<std::complex<double>, RaoTable::kDofs> x = raos.at(c.omega, beta_deg);
    Term t;
    t.omega = c.omega;
    t.offset = c.k * (ref_world.x() * std::cos(c.direction) + ref_world.y() * std::sin(c.direction)) + c.phase;
    for (int d = 0; d < RaoTable::kDofs; ++d) t.ax[d] = c.amplitude * x[d];
    terms_.push_back(t);
  }
}

void SeaStateMotion::motions(double t, Dofs& x, Dofs& rate) const {
  x.fill(0.0);
  rate.fill(0.0);
  Dofs s{}, ds{};
  for (const Term& term : terms_) {
    // Re{A e^{i psi}} and its rate Re{i w A e^{i psi}}, psi = w t - offset.
    const double psi = term.omega * t - term.offset;
    const double c = std::cos(psi), sn = std::sin(psi);
    for (int d = 0; d < RaoTable::kDofs; ++d) {
      const std::complex<double>& a = term.ax[d];
      s[d] += a.real() * c - a.imag() * sn;
      ds[d] -= term.omega * (a.real() * sn + a.imag() * c);
    }
  }
  const double r = waves_->rampFactor(t), dr = waves_->rampFactorRate(t);
  for (int d = 0; d < RaoTable::kDofs; ++d) {
    x[d] = r * s[d];
    rate[d] = r * ds[d] + dr * s[d];
  }
}

PoseSample SeaStateMotion::at(double t) const {
  Dofs x, v;
  motions(t, x, v);
  const double roll = x[3], pitch = x[4], yaw = x[5];
  const RigidPose wf = RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), roll, pitch, yaw);
  const Eigen::Matrix3d r_wf = wf.orientation.toRotationMatrix();
  const Eigen::Matrix3d r = r0_ * r_wf;
  const Eigen::Vector3d shift(x[0], x[1], x[2]), shift_rate(v[0], v[1], v[2]);
  PoseSample s;
  s.t = t;
  s.has_twist = true;
  s.pose.position = mean_.position + r0_ * ref_ + r0_ * shift - r * ref_;
  s.pose.orientation = Eigen::Quaterniond(r).normalized();
  // Angular velocity in body axes of R = Rz(yaw) Ry(pitch) Rx(roll) (R_0 is constant).
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch);
  s.twist.angular = Eigen::Vector3d(v[3] - v[5] * sp, v[4] * cr + v[5] * cp * sr, -v[4] * sr + v[5] * cp * cr);
  // The origin: d/dt (R_0 shift - R r) = R_0 shift' - omega_world x (R r).
  const Eigen::Vector3d omega_world = r * s.twist.angular;
  const Eigen::Vector3d v_world = r0_ * shift_rate - omega_world.cross(r * ref_);
  s.twist.linear = r.transpose() * v_world;
  return s;
}

PoseSample SeaStateMotion::at(double t, const Eigen::Vector3d& mean_velocity, const Eigen::Vector3d& mean_omega) const {
  PoseSample s = at(t);
  const Eigen::Matrix3d r = s.pose.orientation.toRotationMatrix();
  const Eigen::Vector3d v_world =
      r * s.twist.linear + mean_velocity + mean_omega.cross(s.pose.position - mean_.position);
  const Eigen::Vector3d w_world = r * s.twist.angular + mean_omega;
  s.twist.linear = r.transpose() * v_world;
  s.twist.angular = r.transpose() * w_world;
  return s;
}

std::vector<PoseSample> SeaStateMotion::generate(double duration, double dt) const {
  if (!(dt > 0.0) || !(duration >= 0.0) || !std::isfinite(duration))
    throw std::invalid_argument("SeaStateMotion::generate: duration >= 0 and dt > 0 needed");
  const long n = static_cast<long>(std::floor(duration / dt + 1e-9));
  std::vector<PoseSample> out;
  out.reserve(static_cast<std::size_t>(n + 1));
  for (long k = 0; k <= n; ++k) out.push_back(at(static_cast<double>(k) * dt));
  return out;
}

SeaStateMotion::Dofs SeaStateMotion::variance() const {
  Dofs var{};
  for (const Term& t : terms_)
    for (int d = 0; d < RaoTable::kDofs; ++d) var[d] += 0.5 * std::norm(t.ax[d]);
  return var;
}

}  // namespace core
}  // namespace mooring_dynamics
