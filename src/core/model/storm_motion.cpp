// Storm motion of a moored vessel: the model, its choices and frames are in
// include/mooring_dynamics/core/model/storm_motion.hpp.
#include "mooring_dynamics/core/model/storm_motion.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "mooring_dynamics/core/model/field_error.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
/// Gravity of the deep-water dispersion relation [m/s^2] (the problem files' default).
constexpr double kGravity = 9.81;
constexpr int kMinComponents = 16;
constexpr int kMaxComponents = 10000;
/// A record of more samples is refused (10^7 rows: ~1.3 GB of CSV).
constexpr double kMaxSamples = 1e7;
/// 2^32: mt19937 outputs to [0, 1).
constexpr double kTwoPow32 = 4294967296.0;

std::string key(const char* field) { return std::string("storm.") + field; }

/// "" when v is finite and > 0.
std::string positive(const char* field, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) return fieldError(key(field), v, "must be finite and > 0");
  return {};
}
/// "" when v is finite and >= 0.
std::string nonNegative(const char* field, double v) {
  if (!std::isfinite(v) || !(v >= 0.0)) return fieldError(key(field), v, "must be finite and >= 0");
  return {};
}
std::string finite(const char* field, double v) {
  if (!std::isfinite(v)) return fieldError(key(field), v, "must be finite");
  return {};
}

/// The cosine ramp r(t) and its derivative.
void rampFactor(double t, double ramp, double& r, double& dr) {
  if (t <= 0.0) {
    r = 0.0;
    dr = 0.0;
  } else if (t >= ramp) {
    r = 1.0;
    dr = 0.0;
  } else {
    const double a = kPi * t / ramp;
    r = 0.5 * (1.0 - std::cos(a));
    dr = 0.5 * kPi / ramp * std::sin(a);
  }
}

/// Integral of the JONSWAP spectrum over [f0, f0 + df] [m^2]: composite Simpson on
/// kBandIntervals intervals (at the default band and 16 components, the fewest, an interval is
/// 0.023 fp, a third of the peak's width sigma = 0.07 fp; at 200 components 0.002 fp).
constexpr int kBandIntervals = 8;
double bandEnergy(double f0, double df, const StormMotionOptions& o) {
  const double h = df / kBandIntervals;
  double s = jonswapSpectrum(f0, o.hs, o.tp, o.gamma) + jonswapSpectrum(f0 + df, o.hs, o.tp, o.gamma);
  for (int j = 1; j < kBandIntervals; ++j) s += (j % 2 ? 4.0 : 2.0) * jonswapSpectrum(f0 + j * h, o.hs, o.tp, o.gamma);
  return s * h / 3.0;
}

}  // namespace

std::string StormMotionOptions::validate() const {
  std::string e;
  if (!(e = positive("hs", hs)).empty()) return e;
  if (!(e = positive("tp", tp)).empty()) return e;
  if (!(std::isfinite(gamma) && gamma >= 1.0))
    return fieldError(key("gamma"), gamma, "must be finite and >= 1 (1 = Pierson-Moskowitz)");
  if (!(e = finite("heading_deg", heading_deg)).empty()) return e;
  if (!(e = positive("duration", duration)).empty()) return e;
  if (!(e = positive("dt", dt)).empty()) return e;
  if (dt > duration) return fieldError(key("dt"), dt, "must be <= storm.duration = " + fieldNumber(duration));
  if (duration / dt + 1.0 > kMaxSamples)
    return fieldError(key("dt"), dt, "must give at most 1e7 samples over storm.duration = " + fieldNumber(duration));
  if (components < kMinComponents || components > kMaxComponents)
    return fieldError(key("components"), components,
                      "must be in [" + std::to_string(kMinComponents) + ", " + std::to_string(kMaxComponents) + "]");
  if (!(std::isfinite(f_min_factor) && f_min_factor > 0.0 && f_min_factor < 1.0))
    return fieldError(key("f_min_factor"), f_min_factor, "must be in (0, 1)");
  if (!(std::isfinite(f_max_factor) && f_max_factor > 1.0))
    return fieldError(key("f_max_factor"), f_max_factor, "must be finite and > 1");
  if (!(e = nonNegative("heave_gain", heave_gain)).empty()) return e;
  if (!(e = nonNegative("pitch_gain", pitch_gain)).empty()) return e;
  if (!(e = nonNegative("roll_gain", roll_gain)).empty()) return e;
  if (!(e = finite("yaw_deg", yaw_deg)).empty()) return e;
  if (!(e = nonNegative("mean_offset", mean_offset)).empty()) return e;
  if (!(e = finite("mean_offset_heading_deg", mean_offset_heading_deg)).empty()) return e;
  if (!(e = nonNegative("drift_amplitude", drift_amplitude)).empty()) return e;
  if (!(e = positive("drift_period", drift_period)).empty()) return e;
  if (!std::isfinite(ramp) || !(ramp > 0.0))
    return fieldError(key("ramp"), ramp, "must be finite and > 0 (the record starts from the still pose)");
  return {};
}

StormMotion::StormMotion(const StormMotionOptions& options) : options_(options) {
  const std::string e = options.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  const double fp = 1.0 / options.tp;
  const double f_lo = options.f_min_factor * fp;
  const double df = (options.f_max_factor - options.f_min_factor) * fp / options.components;
  std::mt19937 rng(options.seed);
  components_.resize(static_cast<std::size_t>(options.components));
  for (std::size_t i = 0; i < components_.size(); ++i) {
    StormComponent& c = components_[i];
    const double offset = static_cast<double>(rng()) / kTwoPow32;  // in [0, 1)
    c.phase = 2.0 * kPi * static_cast<double>(rng()) / kTwoPow32;
    c.frequency = f_lo + (static_cast<double>(i) + offset) * df;
    c.omega = 2.0 * kPi * c.frequency;
    c.k = c.omega * c.omega / kGravity;
    c.amplitude = std::sqrt(2.0 * bandEnergy(f_lo + static_cast<double>(i) * df, df, options));
  }
}

double StormMotion::elevationVariance() const {
  double m0 = 0.0;
  for (const StormComponent& c : components_) m0 += 0.5 * c.amplitude * c.amplitude;
  return m0;
}

PoseSample StormMotion::at(double t) const {
  const StormMotionOptions& o = options_;
  const double yaw = o.yaw_deg * kDeg;
  PoseSample s;
  s.t = t;
  s.has_twist = true;
  double r = 0.0, dr = 0.0;
  rampFactor(t, o.ramp, r, dr);
  if (r == 0.0) {  // the still pose, at rest (t <= 0)
    s.pose = RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, yaw);
    return s;
  }
  // Elevation and slope along the travel direction at the world origin, with their rates.
  double eta = 0.0, eta_rate = 0.0, slope = 0.0, slope_rate = 0.0;
  for (const StormComponent& c : components_) {
    const double psi = c.phase - c.omega * t;
    const double cs = std::cos(psi), sn = std::sin(psi);
    eta += c.amplitude * cs;
    eta_rate += c.amplitude * c.omega * sn;
    slope -= c.amplitude * c.k * sn;
    slope_rate += c.amplitude * c.k * c.omega * cs;
  }
  const double rel = (o.heading_deg - o.yaw_deg) * kDeg;  // wave direction in the yawed hull's axes
  const double along = std::cos(rel), across = std::sin(rel);
  // Unramped responses and their rates.
  const double heave0 = o.heave_gain * eta, heave0_rate = o.heave_gain * eta_rate;
  const double pitch0 = -o.pitch_gain * along * slope, pitch0_rate = -o.pitch_gain * along * slope_rate;
  const double roll0 = o.roll_gain * across * slope, roll0_rate = o.roll_gain * across * slope_rate;
  const double w_drift = 2.0 * kPi / o.drift_period;
  const double off0 = o.mean_offset + o.drift_amplitude * std::sin(w_drift * t);
  const double off0_rate = o.drift_amplitude * w_drift * std::cos(w_drift * t);
  // Ramped.
  const double z = r * heave0, z_rate = dr * heave0 + r * heave0_rate;
  const double pitch = r * pitch0, pitch_rate = dr * pitch0 + r * pitch0_rate;
  const double roll = r * roll0, roll_rate = dr * roll0 + r * roll0_rate;
  const double off = r * off0, off_rate = dr * off0 + r * off0_rate;
  const double beta = o.mean_offset_heading_deg * kDeg;
  const Eigen::Vector3d dir(std::cos(beta), std::sin(beta), 0.0);
  s.pose = RigidPose::fromRollPitchYaw(Eigen::Vector3d(off * dir.x(), off * dir.y(), z), roll, pitch, yaw);
  const Eigen::Vector3d v_world(off_rate * dir.x(), off_rate * dir.y(), z_rate);
  s.twist.linear = s.pose.toBody(v_world);
  // R = Rz(yaw) Ry(pitch) Rx(roll) with yaw fixed: omega_world = Rz pitch' e_y + Rz Ry roll' e_x, so
  // omega_body = R^T omega_world = (roll', pitch' cos(roll), -pitch' sin(roll)).
  s.twist.angular = Eigen::Vector3d(roll_rate, pitch_rate * std::cos(roll), -pitch_rate * std::sin(roll));
  return s;
}

StormMotionOptions mooringStorm(double hs, double tp, double heading_deg, std::uint32_t seed, double duration) {
  StormMotionOptions o;
  o.hs = hs;
  o.tp = tp;
  o.heading_deg = heading_deg;
  o.seed = seed;
  o.duration = duration;
  o.f_max_factor = 2.0;
  o.mean_offset = 4.0;
  o.mean_offset_heading_deg = heading_deg;
  o.drift_amplitude = 3.0;
  return o;
}

std::vector<PoseSample> generateStormMotion(const StormMotionOptions& options) {
  const StormMotion motion(options);
  const long n = static_cast<long>(std::floor(options.duration / options.dt + 1e-9));
  std::vector<PoseSample> samples;
  samples.reserve(static_cast<std::size_t>(n + 1));
  for (long k = 0; k <= n; ++k) samples.push_back(motion.at(static_cast<double>(k) * options.dt));
  return samples;
}

double maxPointVerticalSpeed(const std::vector<PoseSample>& samples, const Eigen::Vector3d& r_body, double* at_time) {
  double best = 0.0, best_t = samples.empty() ? 0.0 : samples.front().t;
  const std::size_t n = samples.size();
  for (std::size_t i = 0; i < n; ++i) {
    const PoseSample& s = samples[i];
    double vz = 0.0;
    if (s.has_twist) {
      vz = motionFromBodyTwist(s.pose, s.twist).pointVelocity(r_body).z();
    } else if (n >= 2) {
      const std::size_t a = i == 0 ? 0 : i - 1;
      const std::size_t b = i + 1 == n ? n - 1 : i + 1;
      const double span = samples[b].t - samples[a].t;
      if (span > 0.0) vz = (samples[b].pose.apply(r_body).z() - samples[a].pose.apply(r_body).z()) / span;
    }
    if (std::abs(vz) > best) {
      best = std::abs(vz);
      best_t = s.t;
    }
  }
  if (at_time != nullptr) *at_time = best_t;
  return best;
}

StormMotionStats stormMotionStats(const std::vector<PoseSample>& samples, double t_from) {
  StormMotionStats st;
  std::size_t first = 0;
  while (first < samples.size() && samples[first].t < t_from) ++first;
  if (first == samples.size()) first = 0;
  double sz = 0.0, szz = 0.0, sp = 0.0, spp = 0.0, sr = 0.0, srr = 0.0;
  for (std::size_t i = first; i < samples.size(); ++i) {
    const RigidPose& p = samples[i].pose;
    const Eigen::Matrix3d R = p.orientation.normalized().toRotationMatrix();
    // R = Rz(yaw) Ry(pitch) Rx(roll): R(2,0) = -sin(pitch), R(2,1) / R(2,2) = tan(roll).
    const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
    const double roll = std::atan2(R(2, 1), R(2, 2));
    const double z = p.position.z();
    sz += z;
    szz += z * z;
    sp += pitch;
    spp += pitch * pitch;
    sr += roll;
    srr += roll * roll;
    st.max_abs_pitch = std::max(st.max_abs_pitch, std::abs(pitch));
    st.max_abs_roll = std::max(st.max_abs_roll, std::abs(roll));
    ++st.samples;
  }
  if (st.samples == 0) return st;
  const double n = static_cast<double>(st.samples);
  auto stdev = [n](double s, double ss) { return std::sqrt(std::max(0.0, ss / n - (s / n) * (s / n))); };
  st.heave_std = stdev(sz, szz);
  st.pitch_std = stdev(sp, spp);
  st.roll_std = stdev(sr, srr);
  return st;
}

}  // namespace core
}  // namespace mooring_dynamics
