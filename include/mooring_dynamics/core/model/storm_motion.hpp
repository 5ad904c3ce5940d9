// Storm motion of a moored vessel: a synthetic vessel motion table (poses and body twists, as
// core/io/vessel_motion_io.hpp reads them) for a vessel in a long-crested irregular sea, to drive
// `vessel.motion_table` of a moored vessel (`cable_sim storm-motion`, docs/design_analysis.md
// "Storm motion tables").
//
// ASSUMED response model (not an RAO model, no hydrodynamics): the hull follows the sea surface
// at its origin with fixed gains, and drifts slowly about a steady offset.
//  * Sea: JONSWAP (jonswapSpectrum, waves.hpp), long-crested, travelling toward heading_deg
//    (counterclockwise from +x east, REP 103); deep-water wavenumbers k = omega^2 / g. `components`
//    frequencies, one in each of equal bands of width df between f_min_factor fp and
//    f_max_factor fp at a random offset inside its band, with the band's energy
//    a_i^2 / 2 = integral of S over the band (Simpson), and a random phase. Offsets and phases from
//    std::mt19937(seed) (per component in order of increasing frequency: the offset, then the
//    phase, each u = output / 2^32), so one seed gives the same bits everywhere. The amplitudes
//    are not rescaled: the realized variance sum(a_i^2)/2 is the spectrum's energy inside the band,
//    short of Hs^2/16 by the energy outside it (0.5 % for [0.5, 3.5] fp at gamma 3.3), the same
//    for every seed. The random offsets keep the record from repeating after 1/df.
//  * Elevation eta(t) and slope g(t) = d(eta)/d(xi) (xi along the direction of travel) at the
//    world origin (the still position; the slow offset does not shift the phases).
//  * Heave: z = heave_gain eta.
//  * Pitch and roll: the slope resolved in the hull's yawed axes, g_x = g cos(heading - yaw) along
//    the body x axis (forward), g_y = g sin(heading - yaw) across it (to port, body +y), tilt the
//    deck with the surface: pitch = -pitch_gain g_x (REP 103 pitch is about body +y, positive bow
//    DOWN: the surface rising toward the bow lifts the bow, negative pitch), roll = +roll_gain g_y
//    (positive roll lifts the port side, where the surface is higher).
//  * Yaw: fixed at yaw_deg. Orientation R = Rz(yaw) Ry(pitch) Rx(roll) (RigidPose::fromRollPitchYaw).
//  * Horizontal: the origin at (mean_offset + drift_amplitude sin(2 pi t / drift_period)) along
//    mean_offset_heading_deg (world frame).
//  * Ramp: everything above (heave, pitch, roll, offset and drift) is multiplied by
//    r(t) = (1 - cos(pi t / ramp)) / 2 for t < ramp, 1 afterwards. r(0) = r'(0) = 0, so the sample
//    at t = 0 is the still pose exactly (position (0, 0, 0), yaw_deg) with a zero twist: the
//    moored run starts from the statics at the file's pose when `vessel.pose` is that pose
//    (VesselLockstep's start_tolerance).
// Velocities are the analytic time derivatives (including the ramp's), given as the body twist
// (REP 105: the origin's velocity and the angular velocity in body axes), so the lockstep driver
// follows the Hermite path through poses and velocities.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace core {

struct StormMotionOptions {
  double hs = 4.0;              ///< significant wave height [m], > 0
  double tp = 9.0;              ///< peak period [s], > 0
  double gamma = 3.3;           ///< JONSWAP peak enhancement [-], >= 1 (1: Pierson-Moskowitz)
  double heading_deg = 0.0;     ///< direction the waves travel toward, counterclockwise from +x (east) [deg]
  std::uint32_t seed = 1;       ///< random offsets and phases (std::mt19937)
  double duration = 600.0;      ///< [s], > 0: samples at t = 0, dt, ..., <= duration
  double dt = 0.1;              ///< sample interval [s], > 0, <= duration
  int components = 200;         ///< frequency components, in [16, 10000]
  double f_min_factor = 0.5;    ///< lowest band edge as a multiple of fp = 1/tp, in (0, 1)
  double f_max_factor = 3.5;    ///< highest band edge as a multiple of fp, > 1
  double heave_gain = 1.0;      ///< heave per metre of surface elevation at the origin [-], >= 0
  /// Pitch per radian of wave slope along the hull [-], >= 0. 0.45: a 90 m hull in head seas of
  /// Hs 4 m, Tp 9 s pitches 2.5 deg (std) (the slope's std there is 5.6 deg).
  double pitch_gain = 0.45;
  /// Roll per radian of wave slope across the hull [-], >= 0. 0.8: 4.4 deg (std) in beam seas of
  /// Hs 4 m, Tp 9 s; 2.2 deg with the waves 30 deg off the bow.
  double roll_gain = 0.8;
  double yaw_deg = 0.0;         ///< the hull's fixed heading, counterclockwise from +x [deg]
  double mean_offset = 0.0;     ///< steady horizontal offset of the origin [m], >= 0
  double mean_offset_heading_deg = 0.0;  ///< its direction in the world frame, ccw from +x [deg]
  double drift_amplitude = 0.0; ///< slow drift about the offset, along the offset's direction [m], >= 0
  double drift_period = 110.0;  ///< [s], > 0
  double ramp = 20.0;           ///< cosine ramp of all motion from t = 0 [s], > 0

  /// Empty when valid, else "storm.<field> = <value>: <constraint>" (the first bad field).
  std::string validate() const;
};

/// One realized wave component: eta = a cos(k xi - omega t + phase) (xi along the travel direction).
struct StormComponent {
  double frequency = 0.0;  ///< [Hz]
  double omega = 0.0;      ///< [rad/s]
  double k = 0.0;          ///< deep-water wavenumber omega^2 / g [rad/m]
  double amplitude = 0.0;  ///< [m]
  double phase = 0.0;      ///< [rad]
};

/// The motion as a function of time (the model in the file comment).
class StormMotion {
 public:
  /// Throws std::invalid_argument with validate()'s message for invalid options.
  explicit StormMotion(const StormMotionOptions& options);

  const StormMotionOptions& options() const { return options_; }
  const std::vector<StormComponent>& components() const { return components_; }
  /// Variance of the realized surface elevation, sum(a_i^2) / 2 [m^2].
  double elevationVariance() const;

  /// The pose (world frame) and body twist at time t [s] (has_twist true). t <= 0: the still pose.
  PoseSample at(double t) const;

 private:
  StormMotionOptions options_;
  std::vector<StormComponent> components_;
};

/// Samples at t = k dt, k = 0 .. floor(duration / dt) (times as k * dt, not accumulated). Throws
/// std::invalid_argument for invalid options.
std::vector<PoseSample> generateStormMotion(const StormMotionOptions& options);

/// The storm of a moored vessel as the tests, benchmarks and scripts/storms run it: JONSWAP Hs
/// [m], Tp [s], waves toward heading_deg, components up to 2 fp (a hull hardly heaves above), a
/// 4 m mean offset down-wave (toward heading_deg: the waves' mean drift force pushes the hull the
/// way they travel) with a 3 m slow drift along it, the given seed and duration [s]; everything
/// else as StormMotionOptions' defaults.
StormMotionOptions mooringStorm(double hs, double tp, double heading_deg, std::uint32_t seed, double duration);

/// Largest vertical (world z) speed [m/s] of the body-fixed point r_body [m] over the samples:
/// from each sample's twist (v + omega x R r), or, for a sample without a twist, from central
/// differences of the point's positions (one-sided at the ends). `at_time` (if given) receives
/// the time of that sample. 0 for no samples.
double maxPointVerticalSpeed(const std::vector<PoseSample>& samples, const Eigen::Vector3d& r_body,
                             double* at_time = nullptr);

/// Statistics of a motion record over the samples with t >= t_from (all samples if none is).
struct StormMotionStats {
  std::size_t samples = 0;
  double heave_std = 0.0;      ///< of z about its mean [m]
  double pitch_std = 0.0;      ///< [rad], pitch and roll of R = Rz(yaw) Ry(pitch) Rx(roll)
  double roll_std = 0.0;       ///< [rad]
  double max_abs_pitch = 0.0;  ///< [rad]
  double max_abs_roll = 0.0;   ///< [rad]
};
StormMotionStats stormMotionStats(const std::vector<PoseSample>& samples, double t_from = 0.0);

}  // namespace core
}  // namespace mooring_dynamics
