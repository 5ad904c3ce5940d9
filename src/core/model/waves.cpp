// Linear (Airy) waves: dispersion relation, PM / JONSWAP spectra, realized seas and their
// kinematics. See include/mooring_dynamics/core/model/waves.hpp and docs/problem_format.md
// (`environment.waves`).
//
// Choices (documented here once):
// * Spectra are one-sided S(f) [m^2/Hz]. Pierson-Moskowitz in the two-parameter (Hs, Tp)
//   Bretschneider/ITTC form, which integrates to Hs^2/16 over (0, inf) exactly. JONSWAP is the PM
//   shape times gamma^r, sigma = 0.07 (f <= fp) / 0.09 (f > fp), multiplied by a normalisation
//   factor computed numerically over (0, inf) (depends on gamma only), so that it too integrates to
//   Hs^2/16 for any gamma (the DNV approximation 1 - 0.287 ln(gamma) is off by 0.2% at gamma = 3.3
//   and 1.8% at gamma = 7).
// * Random seas: `components` frequencies at the midpoints of equal bins between f_min_factor*fp
//   and f_max_factor*fp, a_i = sqrt(2 S(f_i) df), then all amplitudes are scaled by one common
//   factor so that the realized variance sum(a_i^2)/2 equals Hs^2/16 exactly (the energy outside
//   the band, ~0.5% for the default [0.5, 4] fp, and the midpoint-rule error are redistributed in
//   proportion to S; the shape inside the band is unchanged). The record repeats after 1/df s.
// * Phases: phase_i = 2 pi * (mt19937 output) / 2^32, drawn in order of increasing frequency from
//   std::mt19937(seed). The mt19937 sequence is fixed by the C++ standard, so a seed gives the same
//   sea with every compiler and library (std::uniform_real_distribution would not).
// * Ramp: all amplitudes are multiplied by R(t) = 0.5 (1 - cos(pi t / ramp)) for 0 <= t < ramp
//   (R = 0 for t < 0, R = 1 afterwards). elevationRate() and acceleration() include dR/dt, so they
//   are the exact time derivatives of elevation() and velocity() at every t. (During the ramp the
//   modulated field satisfies continuity but not exactly the surface kinematic condition.)
// * Kinematics: linear theory below z = 0; for z > 0 the values at z = 0 are used, for z < -depth
//   those at z = -depth. Accelerations are local (d/dt at a fixed point; the convective term is
//   second order in the wave steepness).
#include "mooring_dynamics/core/model/waves.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "mooring_dynamics/core/model/scalar.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr int kMaxComponents = 10000;
/// Above this k*depth the hyperbolic depth factors are evaluated in exponential form
/// (cosh(20) ~ 2.4e8: well inside double range, and e^(-2 k h) < 5e-18 is negligible there).
constexpr double kDeepKh = 20.0;

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string keyOf(const std::string& key) { return "environment.waves." + key; }

/// "" if v is finite and > 0, else the message.
std::string positive(const std::string& key, double v) {
  if (!std::isfinite(v)) return keyOf(key) + " = " + fmt(v) + ": must be finite";
  if (!(v > 0.0)) return keyOf(key) + " = " + fmt(v) + ": must be > 0";
  return {};
}

/// JONSWAP peak-enhancement exponent r(x) at x = f / fp.
double jonswapR(double x) {
  const double sigma = x <= 1.0 ? 0.07 : 0.09;
  const double d = (x - 1.0) / sigma;
  return std::exp(-0.5 * d * d);
}

/// Dimensionless PM shape: S_PM(f) df = Hs^2/16 * pmShape(x) dx, x = f/fp; integrates to 1.
double pmShape(double x) {
  if (!(x > 0.0)) return 0.0;
  const double x4 = (x * x) * (x * x);
  return 5.0 / (x4 * x) * std::exp(-1.25 / x4);
}

/// 1 / integral over (0, inf) of pmShape(x) gamma^r(x) dx.
/// = 1 / (1 + integral of pmShape(x) (gamma^r(x) - 1) dx): the excess over PM is concentrated at the
/// peak (gamma^r - 1 < 1e-30 ln(gamma) beyond 12 sigma), so composite Simpson on [1 - 12*0.07,
/// 1 + 12*0.09] with 4000 intervals gives the factor to ~1e-13. Cached per thread for the last gamma.
double jonswapNormalisation(double gamma) {
  thread_local double cached_gamma = std::numeric_limits<double>::quiet_NaN();
  thread_local double cached_factor = 1.0;
  if (gamma == cached_gamma) return cached_factor;
  const double lg = std::log(gamma);
  const double a = 1.0 - 12.0 * 0.07;
  const double b = 1.0 + 12.0 * 0.09;
  const int n = 4000;  // even
  const double h = (b - a) / n;
  auto excess = [lg](double x) { return pmShape(x) * std::expm1(jonswapR(x) * lg); };
  double s = excess(a) + excess(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * excess(a + i * h);
  const double integral = 1.0 + s * h / 3.0;
  cached_gamma = gamma;
  cached_factor = 1.0 / integral;
  return cached_factor;
}

/// Depth factors ch = cosh(k(z+h))/sinh(kh), sh = sinh(k(z+h))/sinh(kh), z already in [-h, 0].
/// Wave-particle velocity below which a component is left out of the sum [m/s]: far below what
/// changes the drag of any cable.
constexpr double kNegligibleVelocity = 1e-12;

void depthFactors(double k, double z, double h, double& ch, double& sh) {
  const double kh = k * h;
  if (kh > kDeepKh) {
    // cosh(k(z+h))/sinh(kh) = (e^{kz} +- e^{-k(z+2h)}) / (1 - e^{-2kh}); every exponent <= 0.
    const double e1 = std::exp(k * z);
    const double e2 = std::exp(-k * (z + 2.0 * h));
    const double den = -std::expm1(-2.0 * kh);
    ch = (e1 + e2) / den;
    sh = (e1 - e2) / den;
  } else {
    const double s = std::sinh(kh);
    const double kzh = k * (z + h);
    ch = std::cosh(kzh) / s;
    sh = std::sinh(kzh) / s;
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// WaveSpec

std::string WaveSpec::validate() const {
  if (type == Type::None) return {};
  std::string e;
  if (type == Type::Regular) {
    if (!(e = positive("height", height)).empty()) return e;
    if (!(e = positive("period", period)).empty()) return e;
  } else {
    if (!(e = positive("hs", hs)).empty()) return e;
    if (!(e = positive("tp", tp)).empty()) return e;
    if (type == Type::Jonswap && !(std::isfinite(gamma) && gamma >= 1.0))
      return keyOf("gamma") + " = " + fmt(gamma) + ": must be >= 1 (1 = Pierson-Moskowitz)";
    if (components < 1 || components > kMaxComponents)
      return keyOf("components") + " = " + std::to_string(components) + ": must be in [1, " +
             std::to_string(kMaxComponents) + "]";
    if (!(std::isfinite(f_min_factor) && f_min_factor > 0.0 && f_min_factor < 1.0))
      return keyOf("f_min_factor") + " = " + fmt(f_min_factor) + ": must be in (0, 1)";
    if (!(std::isfinite(f_max_factor) && f_max_factor > 1.0))
      return keyOf("f_max_factor") + " = " + fmt(f_max_factor) + ": must be finite and > 1";
    if (!(spreading_s >= 0.0 && spreading_s <= 1000.0))
      return keyOf("spreading_s") + " = " + fmt(spreading_s) + ": must be in [0, 1000] (0 = long-crested)";
  }
  if (!std::isfinite(direction))
    return keyOf("direction_deg") + " = " + fmt(direction * 180.0 / kPi) + ": must be finite";
  if (!(std::isfinite(ramp) && ramp >= 0.0))
    return keyOf("ramp") + " = " + fmt(ramp) + ": must be finite and >= 0";
  return {};
}

// ---------------------------------------------------------------------------------------------
// Dispersion and spectra

double waveNumber(double omega, double depth, double gravity) {
  if (!(gravity > 0.0) || !std::isfinite(gravity))
    throw std::invalid_argument("waveNumber: gravity = " + fmt(gravity) + ": must be finite and > 0");
  if (!(depth > 0.0))
    throw std::invalid_argument("waveNumber: depth = " + fmt(depth) + ": must be > 0");
  if (!std::isfinite(omega))
    throw std::invalid_argument("waveNumber: omega = " + fmt(omega) + ": must be finite");
  omega = std::abs(omega);
  if (omega == 0.0) return 0.0;
  const double k_deep = omega * omega / gravity;
  if (std::isinf(depth)) return k_deep;
  // Dimensionless form y tanh(y) = x with y = k h, x = omega^2 h / g. Start from the explicit
  // approximation of Fenton & McKee (1990), y0 = x / tanh(x^0.75)^(2/3) (error < 1.7 %, exact in
  // both limits), then Newton: F(y) = y tanh y - x is increasing, F' = tanh y + y sech^2 y > 0.
  const double x = k_deep * depth;
  double y = x / std::pow(std::tanh(std::pow(x, 0.75)), 2.0 / 3.0);
  if (!std::isfinite(y) || !(y > 0.0)) y = std::max(x, std::sqrt(x));
  for (int it = 0; it < 100; ++it) {
    const double t = std::tanh(y);
    const double c = std::cosh(y);
    const double sech2 = std::isfinite(c) ? 1.0 / (c * c) : 0.0;
    const double f = y * t - x;
    const double fp = t + y * sech2;
    double y_new = y - f / fp;
    if (!(y_new > 0.0)) y_new = 0.5 * y;  // safeguard (not reached from the start above)
    const double dy = y_new - y;
    y = y_new;
    if (std::abs(dy) <= 4.0 * std::numeric_limits<double>::epsilon() * y) break;
  }
  return y / depth;
}

double piersonMoskowitzSpectrum(double f, double hs, double tp) {
  if (!(f > 0.0)) return 0.0;
  const double fp = 1.0 / tp;
  // S(f) = 5/16 Hs^2 fp^4 f^-5 exp(-5/4 (fp/f)^4) = Hs^2/16 * pmShape(f/fp) / fp.
  return hs * hs / 16.0 * pmShape(f / fp) / fp;
}

double jonswapSpectrum(double f, double hs, double tp, double gamma) {
  if (!(f > 0.0)) return 0.0;
  const double x = f * tp;
  return jonswapNormalisation(gamma) * piersonMoskowitzSpectrum(f, hs, tp) *
         std::pow(gamma, jonswapR(x));
}

// ---------------------------------------------------------------------------------------------
// WaveField

namespace {
/// Inverse of the cumulative cos-2s spreading function D(t) ~ cos^(2s)(t / 2) on (-pi, pi),
/// tabulated (trapezoids on 4096 intervals) and inverted by linear interpolation.
class SpreadingSampler {
 public:
  explicit SpreadingSampler(double s) {
    if (!(s > 0.0)) return;
    constexpr int kIntervals = 4096;
    theta_.resize(kIntervals + 1);
    cdf_.resize(kIntervals + 1);
    double prev = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
      theta_[i] = -kPi + kTwoPi * i / kIntervals;
      const double d = std::pow(std::cos(0.5 * theta_[i]), 2.0 * s);
      cdf_[i] = i == 0 ? 0.0 : cdf_[i - 1] + 0.5 * (prev + d) * (kTwoPi / kIntervals);
      prev = d;
    }
    for (double& c : cdf_) c /= cdf_.back();
  }
  /// The angle [rad] from the mean direction whose cumulative probability is u in [0, 1).
  double sample(double u) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    if (it == cdf_.begin()) return theta_.front();
    if (it == cdf_.end()) return theta_.back();
    const std::size_t j = static_cast<std::size_t>(it - cdf_.begin());
    const double w = (u - cdf_[j - 1]) / (cdf_[j] - cdf_[j - 1]);
    return theta_[j - 1] + w * (theta_[j] - theta_[j - 1]);
  }

 private:
  std::vector<double> theta_, cdf_;
};
}  // namespace

WaveField::WaveField(const WaveSpec& spec, double depth, double gravity) : depth_(depth), ramp_(spec.ramp) {
  const std::string e = spec.validate();
  if (!e.empty()) throw std::invalid_argument("WaveField: " + e);
  if (!(depth > 0.0) || !std::isfinite(depth))
    throw std::invalid_argument("WaveField: depth = " + fmt(depth) + ": must be finite and > 0");
  if (!(gravity > 0.0) || !std::isfinite(gravity))
    throw std::invalid_argument("WaveField: gravity = " + fmt(gravity) + ": must be finite and > 0");

  switch (spec.type) {
    case WaveSpec::Type::None:
      return;
    case WaveSpec::Type::Regular: {
      WaveComponent c;
      c.amplitude = 0.5 * spec.height;
      c.omega = kTwoPi / spec.period;
      c.k = waveNumber(c.omega, depth, gravity);
      c.direction = spec.direction;
      c.phase = 0.0;  // crest at the origin at t = 0
      components_.push_back(c);
      precompute();
      return;
    }
    case WaveSpec::Type::Jonswap:
    case WaveSpec::Type::PiersonMoskowitz:
      break;
  }

  const double fp = 1.0 / spec.tp;
  const double f0 = spec.f_min_factor * fp;
  const double f1 = spec.f_max_factor * fp;
  const int n = spec.components;
  const double df = (f1 - f0) / n;
  std::mt19937 rng(spec.seed);
  // Frequency offsets in the bins and spreading directions come from a second stream, so that the
  // phases (and the centred, long-crested sea) keep their bits.
  std::mt19937 extra(spec.seed ^ 0x9E3779B9u);
  const SpreadingSampler spread(spec.spreading_s);
  components_.reserve(static_cast<std::size_t>(n));
  double variance = 0.0;
  for (int i = 0; i < n; ++i) {
    const double place = spec.random_frequencies ? static_cast<double>(extra()) / 4294967296.0 : 0.5;
    const double f = f0 + (i + place) * df;
    const double s = spec.type == WaveSpec::Type::Jonswap ? jonswapSpectrum(f, spec.hs, spec.tp, spec.gamma)
                                                          : piersonMoskowitzSpectrum(f, spec.hs, spec.tp);
    WaveComponent c;
    c.amplitude = std::sqrt(2.0 * s * df);
    c.omega = kTwoPi * f;
    c.k = waveNumber(c.omega, depth, gravity);
    c.direction = spec.direction;
    if (spec.spreading_s > 0.0) c.direction += spread.sample(static_cast<double>(extra()) / 4294967296.0);
    c.phase = kTwoPi * (static_cast<double>(rng()) / 4294967296.0);
    variance += 0.5 * c.amplitude * c.amplitude;
    components_.push_back(c);
  }
  // Match the requested Hs exactly: sum a_i^2 / 2 = Hs^2 / 16.
  if (variance > 0.0) {
    const double scale = std::sqrt(spec.hs * spec.hs / 16.0 / variance);
    for (auto& c : components_) c.amplitude *= scale;
  }
  precompute();
}

void WaveField::precompute() {
  kin_.clear();
  kin_.reserve(components_.size());
  z_all_negligible_ = -std::numeric_limits<double>::infinity();
  bool all_deep = !components_.empty();
  double lowest_relevant = std::numeric_limits<double>::infinity();
  for (const auto& c : components_) {
    Kinematics q;
    q.aw = c.amplitude * c.omega;
    q.cd = std::cos(c.direction);
    q.sd = std::sin(c.direction);
    q.deep = c.k * depth_ > kDeepKh;
    if (q.deep) {
      q.den = -std::expm1(-2.0 * c.k * depth_);
      q.e2kh = std::exp(-2.0 * c.k * depth_);
      // aw e^{k z} < kNegligibleVelocity  <=>  z < ln(kNegligibleVelocity / aw) / k (k > 0 here).
      q.z_skip = q.aw > 0.0 ? std::log(kNegligibleVelocity / q.aw) / c.k : std::numeric_limits<double>::infinity();
      lowest_relevant = std::min(lowest_relevant, q.z_skip);
    } else {
      q.den = std::sinh(c.k * depth_);
      all_deep = false;
    }
    kin_.push_back(q);
  }
  if (all_deep) z_all_negligible_ = lowest_relevant;
}

double WaveField::rampFactor(double t) const {
  if (ramp_ <= 0.0 || t >= ramp_) return 1.0;
  if (t <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(kPi * t / ramp_));
}

namespace {
/// dR/dt of the ramp factor.
double rampRate(double ramp, double t) {
  if (ramp <= 0.0 || t >= ramp || t <= 0.0) return 0.0;
  return 0.5 * kPi / ramp * std::sin(kPi * t / ramp);
}

/// Phase of component c at (x, y, t); cd, sd: cos and sin of its direction (Kinematics).
double phaseOf(const WaveComponent& c, double cd, double sd, double x, double y, double t) {
  return c.k * (x * cd + y * sd) - c.omega * t + c.phase;
}
}  // namespace

double WaveField::elevation(double x, double y, double t) const {
  if (components_.empty()) return 0.0;
  double eta = 0.0;
  for (std::size_t i = 0; i < components_.size(); ++i) {
    const WaveComponent& c = components_[i];
    eta += c.amplitude * std::cos(phaseOf(c, kin_[i].cd, kin_[i].sd, x, y, t));
  }
  return rampFactor(t) * eta;
}

double WaveField::elevationRate(double x, double y, double t) const {
  double eta, rate;
  elevationAndRate(x, y, t, eta, rate);
  return rate;
}

double WaveField::rampFactorRate(double t) const { return rampRate(ramp_, t); }

void WaveField::elevationAndRate(double x, double y, double t, double& eta_out, double& rate_out) const {
  eta_out = rate_out = 0.0;
  if (components_.empty()) return;
  const double r = rampFactor(t);
  const double dr = rampRate(ramp_, t);
  double eta = 0.0, rate = 0.0;
  for (std::size_t i = 0; i < components_.size(); ++i) {
    const WaveComponent& c = components_[i];
    double sth, cth;
    sinCos(phaseOf(c, kin_[i].cd, kin_[i].sd, x, y, t), sth, cth);
    rate += c.amplitude * c.omega * sth;
    eta += c.amplitude * cth;  // elevation()'s sum, term for term
  }
  eta_out = r * eta;
  rate_out = r * rate + dr * eta;
}

void WaveField::velocity(double x, double y, double z, double t, double& vx, double& vy, double& vz) const {
  vx = vy = vz = 0.0;
  if (components_.empty()) return;
  const double zc = std::min(0.0, std::max(-depth_, z));
  // Every component deep and negligible at this depth (the skip test below for each of them).
  if (zc < z_all_negligible_) return;
  for (std::size_t i = 0; i < components_.size(); ++i) {
    const WaveComponent& c = components_[i];
    const Kinematics& q = kin_[i];
    double ch, sh;
    if (q.deep) {
      // In deep water the factors are about e^{kz}: skip a component whose velocity at this
      // depth is below kNegligibleVelocity (most of a deep line sees none of the short waves).
      if (zc < q.z_skip) continue;
      // depthFactors' exponential form: (e^{kz} +- e^{-k(z+2h)}) / (1 - e^{-2kh}).
      const double e1 = std::exp(c.k * zc);
      if (q.aw * e1 < kNegligibleVelocity) continue;
      const double e2 = q.e2kh / e1;
      ch = (e1 + e2) / q.den;
      sh = (e1 - e2) / q.den;
    } else if (q.den > 0.0) {
      // depthFactors with sinh(k h) from the constructor and cosh, sinh of k (z + h) from one
      // exponential (k (z + h) is in [0, 20] here; the rounding of the difference is absolute,
      // ~1e-16 of the component's velocity).
      const double e = std::exp(c.k * (zc + depth_));
      const double ei = 1.0 / e;
      ch = 0.5 * (e + ei) / q.den;
      sh = 0.5 * (e - ei) / q.den;
    } else {
      depthFactors(c.k, zc, depth_, ch, sh);
    }
    double sth, cth;
    sinCos(phaseOf(c, q.cd, q.sd, x, y, t), sth, cth);
    const double uh = q.aw * ch * cth;
    vx += uh * q.cd;
    vy += uh * q.sd;
    vz += q.aw * sh * sth;
  }
  const double r = rampFactor(t);
  vx *= r;
  vy *= r;
  vz *= r;
}

void WaveField::acceleration(double x, double y, double z, double t, double& ax, double& ay, double& az) const {
  ax = ay = az = 0.0;
  if (components_.empty()) return;
  const double zc = std::min(0.0, std::max(-depth_, z));
  const double r = rampFactor(t);
  const double dr = rampRate(ramp_, t);
  double vx = 0.0, vy = 0.0, vz = 0.0;  // un-ramped velocity, for the dR/dt term
  for (std::size_t i = 0; i < components_.size(); ++i) {
    const WaveComponent& c = components_[i];
    double ch, sh;
    depthFactors(c.k, zc, depth_, ch, sh);
    const double cd = kin_[i].cd, sd = kin_[i].sd;
    double sth, cth;
    sinCos(phaseOf(c, cd, sd, x, y, t), sth, cth);
    const double aw = c.amplitude * c.omega;
    const double ah = aw * c.omega * ch * sth;  // d/dt of a w ch cos(th), th = ... - w t
    ax += ah * cd;
    ay += ah * sd;
    az -= aw * c.omega * sh * cth;
    if (dr != 0.0) {
      const double uh = aw * ch * cth;
      vx += uh * cd;
      vy += uh * sd;
      vz += aw * sh * sth;
    }
  }
  ax = r * ax + dr * vx;
  ay = r * ay + dr * vy;
  az = r * az + dr * vz;
}

}  // namespace core
}  // namespace mooring_dynamics
