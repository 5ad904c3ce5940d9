// Mean and slowly varying wave drift on a hull (wave_drift.hpp).
#include "mooring_dynamics/core/model/wave_drift.hpp"

#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
/// A change of the hull's slow yaw below which the coefficients are not interpolated again [rad]:
/// drift coefficients change over tens of degrees of heading, this is 0.06 deg.
constexpr double kYawTolerance = 1e-3;
constexpr int kModes[3] = {0, 1, 5};  // surge, sway, yaw
}  // namespace

WaveDrift::WaveDrift(const WaveField& waves, const RaoTable& coefficients, bool newman)
    : waves_(&waves), table_(&coefficients), newman_(newman) {}

void WaveDrift::coefficientsAt(double yaw) {
  if (have_yaw_ && std::abs(yaw - yaw_) < kYawTolerance) return;
  const std::vector<WaveComponent>& comps = waves_->components();
  d_.resize(comps.size());
  for (std::size_t j = 0; j < comps.size(); ++j) {
    const WaveComponent& c = comps[j];
    const double beta_deg = (c.direction - yaw) * kRadToDeg;
    const std::string e = table_->check(c.omega, beta_deg);
    if (!e.empty()) {
      std::ostringstream m;
      m << "wave drift: wave component " << j + 1 << " of " << comps.size() << " (omega " << c.omega
        << " rad/s, heading " << beta_deg << " deg relative to the hull): " << e;
      throw std::invalid_argument(m.str());
    }
    const std::array<std::complex<double>, RaoTable::kDofs> x = table_->at(c.omega, beta_deg);
    for (int k = 0; k < 3; ++k) d_[j][k] = x[kModes[k]].real();
  }
  yaw_ = yaw;
  have_yaw_ = true;
}

Eigen::Vector3d WaveDrift::meanForce(double yaw) {
  coefficientsAt(yaw);
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  const std::vector<WaveComponent>& comps = waves_->components();
  for (std::size_t j = 0; j < comps.size(); ++j) f += comps[j].amplitude * comps[j].amplitude * d_[j];
  return f;
}

Eigen::Vector3d WaveDrift::force(double t, const RigidPose& slow_pose, const Eigen::Vector3d& ref_world) {
  const double r = waves_->rampFactor(t);
  if (!newman_) return r * r * meanForce(slow_pose.yaw());
  coefficientsAt(slow_pose.yaw());
  const std::vector<WaveComponent>& comps = waves_->components();
  std::complex<double> p[3], q[3];
  for (std::size_t j = 0; j < comps.size(); ++j) {
    const WaveComponent& c = comps[j];
    const double theta =
        c.omega * t - c.k * (ref_world.x() * std::cos(c.direction) + ref_world.y() * std::sin(c.direction)) - c.phase;
    const std::complex<double> e = c.amplitude * std::polar(1.0, theta);
    for (int k = 0; k < 3; ++k) {
      const double s = std::sqrt(std::abs(d_[j][k]));
      p[k] += s * e;
      q[k] += (d_[j][k] < 0.0 ? -s : s) * e;
    }
  }
  Eigen::Vector3d f;
  for (int k = 0; k < 3; ++k) f[k] = (p[k] * std::conj(q[k])).real();
  return r * r * f;
}

}  // namespace core
}  // namespace mooring_dynamics
