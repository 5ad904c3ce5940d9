// Linear (Airy) waves: regular waves and random seas from JONSWAP / Pierson-Moskowitz spectra,
// with water-particle velocities for the drag terms and the surface elevation for wave-following
// buoys. Finite-depth dispersion. Frame: x east, y north, z up, z = 0 mean sea surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

/// One linear wave component: eta = a cos(k (x cos(theta) + y sin(theta)) - omega t + phase).
struct WaveComponent {
  double amplitude = 0.0;  ///< a [m]
  double omega = 0.0;      ///< angular frequency [rad/s]
  double k = 0.0;          ///< wavenumber from the finite-depth dispersion relation [rad/m]
  double direction = 0.0;  ///< direction of travel, counterclockwise from +x [rad]
  double phase = 0.0;      ///< [rad]
};

/// What the user asks for (problem file `environment.waves`).
struct WaveSpec {
  enum class Type { None, Regular, Jonswap, PiersonMoskowitz };
  Type type = Type::None;
  double height = 0.0;      ///< Regular: wave height H = 2a [m]
  double period = 0.0;      ///< Regular: period [s]
  double hs = 0.0;          ///< random: significant wave height [m]
  double tp = 0.0;          ///< random: peak period [s]
  double gamma = 3.3;       ///< JONSWAP peak enhancement [-]
  int components = 200;     ///< random: number of frequency components
  double f_min_factor = 0.5;  ///< random: lowest frequency as a multiple of the peak frequency
  double f_max_factor = 4.0;  ///< random: highest frequency as a multiple of the peak frequency
  std::uint32_t seed = 1;   ///< random phases (std::mt19937)
  double direction = 0.0;   ///< direction of travel, counterclockwise from +x [rad]
  double ramp = 0.0;        ///< duration of a smooth start-up ramp on the amplitudes [s]
  /// random: each component's frequency at a random place in its bin (not the centre), so that
  /// the record does not repeat after 1 / df (3-hour storms with a few hundred components).
  bool random_frequencies = false;
  /// random: cos-2s directional spreading, D(t) ~ cos^(2s)((t - direction) / 2); 0 = long-crested.
  /// Each component gets one direction drawn from D (single-direction-per-frequency method).
  double spreading_s = 0.0;

  /// Empty when valid, else "environment.waves.<key> = value: constraint".
  std::string validate() const;
};

/// A realized sea: a sum of components. Kinematics below the mean surface follow linear theory;
/// above it (under a crest) the values at z = 0 are used (constant extrapolation).
class WaveField {
 public:
  WaveField() = default;
  /// Build the components of `spec` for water depth `depth` [m] and gravity g [m/s^2].
  WaveField(const WaveSpec& spec, double depth, double gravity);

  bool empty() const { return components_.empty(); }
  const std::vector<WaveComponent>& components() const { return components_; }

  /// Surface elevation eta(x, y, t) [m].
  double elevation(double x, double y, double t) const;
  /// Time derivative of the elevation [m/s].
  double elevationRate(double x, double y, double t) const;
  /// elevation() and elevationRate() in one pass (one sine and cosine per component), the same
  /// values to the bit.
  void elevationAndRate(double x, double y, double t, double& eta, double& rate) const;
  /// Water-particle velocity (vx, vy, vz) [m/s] at (x, y, z) and time t.
  void velocity(double x, double y, double z, double t, double& vx, double& vy, double& vz) const;
  /// Water-particle acceleration [m/s^2].
  void acceleration(double x, double y, double z, double t, double& ax, double& ay, double& az) const;
  /// The start-up ramp on every amplitude, r(t) = (1 - cos(pi t / ramp)) / 2 for 0 < t < ramp (0
  /// before, 1 after and with no ramp), and its time derivative [1/s].
  double rampFactor(double t) const;
  double rampFactorRate(double t) const;

 private:
  friend class WaveVelocityCache;
  /// Per-component constants of velocity(), computed once in the constructor (the velocity is
  /// evaluated at every node in every Newton iteration of the dynamic solver).
  struct Kinematics {
    double aw = 0.0;        ///< amplitude * omega [m/s]
    double cd = 1.0, sd = 0.0;  ///< cos and sin of the direction
    bool deep = false;      ///< k * depth above the deep-water threshold (exponential form)
    double den = 1.0;       ///< deep: 1 - e^{-2 k h}; otherwise sinh(k h)
    double e2kh = 0.0;      ///< deep: e^{-2 k h}
    double z_skip = 0.0;    ///< deep: below this elevation the component's velocity is negligible
  };
  void precompute();
  std::vector<WaveComponent> components_;
  std::vector<Kinematics> kin_;
  double z_all_negligible_ = 0.0;  ///< below this elevation every component is negligible
  double depth_ = 100.0;
  double ramp_ = 0.0;
};


/// Wavenumber k [rad/m] solving omega^2 = g k tanh(k h) (Newton iteration; deep-water start).
double waveNumber(double omega, double depth, double gravity);

/// One-sided spectral densities S(f) [m^2/Hz] at frequency f [Hz].
double piersonMoskowitzSpectrum(double f, double hs, double tp);
double jonswapSpectrum(double f, double hs, double tp, double gamma);


}  // namespace core
}  // namespace mooring_dynamics
