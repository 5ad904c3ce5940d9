// Real ship tracks: GNSS fixes (latitude, longitude) and a heading, turned into the poses the
// lockstep drivers follow (problem-file section `dynamics.gnss`, docs/problem_format.md).
//
// The chain, fix by fix (GnssTrack::addFix):
//   1. checks: fix status, finite latitude in [-90, 90] and longitude in [-180, 180], horizontal
//      standard deviation within max_horizontal_sigma, stamp after the last accepted one, distance
//      from the last accepted fix within max_speed * dt + jump_tolerance; a failing fix is rejected and counted,
//      nothing else changes;
//   2. the antenna in a local east-north-up frame about the datum (GeographicLib::LocalCartesian;
//      x east, y north: REP 103's world axes), height ignored: a ship's heave is not GNSS's job;
//   3. the heading at the fix's stamp, interpolated along the shorter arc between the heading
//      samples around it (held from the last one when none is later; a gap over max_heading_gap
//      is reported);
//   4. the body origin: antenna - R(yaw) * antenna (the antenna's position in the body frame);
//   5. the track smoother (TrackSmoother) on the origin's horizontal position;
//   6. the pose: that position (placed so that the first fix lands on the problem's start when the
//      datum is the first fix), the start's elevation, the level heading yaw.
// Everything is a pure function of the samples in their order, so the node and `cable_sim
// dynamic` give the same poses for the same samples.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace core {

struct GnssOptions {
  bool enabled = false;      ///< the section is present
  std::string track;         ///< CSV of (t, latitude, longitude, heading) for cable_sim; empty in the node
  bool datum_from_first_fix = true;  ///< else datum_latitude_deg, datum_longitude_deg
  double datum_latitude_deg = 0.0, datum_longitude_deg = 0.0;
  Eigen::Vector3d antenna = Eigen::Vector3d::Zero();  ///< antenna in the body frame (x fwd, y left, z up) [m]
  /// Time constant tau of the critically damped track smoother [s]; 0 = off (the raw fixes).
  double smoothing_time = 5.0;
  double max_speed = 15.0;            ///< a fix further than max_speed * dt + jump_tolerance is rejected [m/s] (~29 kn)
  /// [m] The fixes' noise on top of max_speed: two fixes of a receiver with metres of noise
  /// differ by up to ~3 sqrt(2) sigma more than the ship moved; 20 m covers sigma = 4.7 m.
  double jump_tolerance = 20.0;
  double max_horizontal_sigma = 10.0; ///< fixes with a larger horizontal standard deviation are rejected [m]
  double max_heading_gap = 2.0;       ///< a fix further than this from any heading sample is reported [s]
  /// Empty when valid, else "dynamics.gnss.<key> = value: constraint".
  std::string validate() const;
};

/// One GNSS fix (sensor_msgs/NavSatFix's content).
struct GnssFix {
  double t = 0.0;                 ///< [s]
  double latitude_deg = 0.0;      ///< WGS84 [deg], north positive
  double longitude_deg = 0.0;     ///< [deg], east positive
  bool has_fix = true;            ///< false: status NO_FIX
  /// Largest of the east and north position variances [m^2]; NaN: unknown (accepted).
  double horizontal_variance = std::numeric_limits<double>::quiet_NaN();
};

/// REP 103 yaw [rad] (of the body x axis, counter-clockwise from east) of a compass heading
/// [deg] (clockwise from north, as ships log it).
double yawFromHeadingDeg(double heading_deg);

/// A local east-north-up frame tangent to the WGS84 ellipsoid at a datum (GeographicLib).
class LocalDatum {
 public:
  LocalDatum(double latitude_deg, double longitude_deg);
  ~LocalDatum();
  LocalDatum(LocalDatum&&) noexcept;
  LocalDatum& operator=(LocalDatum&&) noexcept;
  /// East, north [m] of a point on the ellipsoid (height 0).
  Eigen::Vector2d eastNorth(double latitude_deg, double longitude_deg) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Critically damped second-order low-pass on a horizontal track, x'' + 2 w x' + w^2 x = w^2 u
/// with w = 1 / tau, integrated exactly for an input linear between samples (first-order hold),
/// so that any sample spacing is stable and the result depends on the samples only.
/// Cost: a track at constant velocity V comes out 2 tau late (2 tau V behind); noise above the
/// corner frequency 1 / (2 pi tau) falls by 40 dB a decade in position, 20 dB in velocity.
class TrackSmoother {
 public:
  explicit TrackSmoother(double tau) : tau_(tau) {}
  /// Starts at input u with velocity v, in the steady state of that velocity (x = u - 2 tau v),
  /// so a track that goes on at v has no start-up transient.
  void start(double t, const Eigen::Vector2d& u, const Eigen::Vector2d& v);
  /// Advances to input u at time t (> the last time); returns the smoothed position.
  Eigen::Vector2d update(double t, const Eigen::Vector2d& u);
  const Eigen::Vector2d& position() const { return x_; }
  const Eigen::Vector2d& velocity() const { return v_; }

 private:
  double tau_;
  double t_ = 0.0;
  Eigen::Vector2d u_ = Eigen::Vector2d::Zero(), x_ = Eigen::Vector2d::Zero(), v_ = Eigen::Vector2d::Zero();
};

class GnssTrack {
 public:
  enum class Verdict { Accepted, NoFix, BadValue, Covariance, Backward, Jump, NoHeading };
  static constexpr std::size_t kVerdicts = 7;
  static const char* name(Verdict v);

  struct Result {
    Verdict verdict = Verdict::Accepted;
    std::string message;        ///< why a sample was rejected (names the field and value)
    double t = 0.0;             ///< the fix's stamp [s]
    RigidPose pose;             ///< accepted fixes: the body's pose, world frame
    double heading_gap = 0.0;   ///< [s] from the fix to the nearest heading sample used
    bool ok() const { return verdict == Verdict::Accepted; }
  };

  /// `start`: the pose the run starts from (the problem's static top as a point, or the vessel's
  /// file pose); its elevation is kept. `start_velocity`: the horizontal velocity the start's
  /// statics assume [m/s] (a tow's), the smoother's initial state.
  GnssTrack(const GnssOptions& options, const RigidPose& start, const Eigen::Vector2d& start_velocity);
  ~GnssTrack();

  /// A heading sample: yaw [rad] (REP 103). Rejected when not finite or not after the last one.
  Result addHeading(double t, double yaw);
  Result addFix(const GnssFix& fix);

  /// Samples handled so far, by verdict (index: static_cast<size_t>(Verdict)); headings included.
  const std::vector<long>& counts() const { return counts_; }
  long headingGapsReported() const { return heading_gaps_; }

 private:
  Result reject(Verdict v, double t, const std::string& message);
  bool headingAt(double t, double& yaw, double& gap) const;

  GnssOptions options_;
  RigidPose start_;
  Eigen::Vector2d start_velocity_;
  std::unique_ptr<LocalDatum> datum_;
  TrackSmoother smoother_;
  bool started_ = false;
  double last_t_ = 0.0;
  Eigen::Vector2d last_antenna_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();
  std::vector<std::pair<double, double>> headings_;  ///< (t, yaw), the last two kept
  std::vector<long> counts_ = std::vector<long>(kVerdicts, 0);
  long heading_gaps_ = 0;
};

/// One row of a ship's navigation log: t [s], latitude, longitude [deg], compass heading [deg].
struct GnssTrackRow {
  double t = 0.0, latitude_deg = 0.0, longitude_deg = 0.0, heading_deg = 0.0;
};

/// The poses of a logged track, fed row by row as the node is fed messages (the heading first,
/// then the fix of the same stamp). Rejected rows are left out and counted in `track`.
std::vector<GnssTrack::Result> followTrack(GnssTrack& track, const std::vector<GnssTrackRow>& rows);

}  // namespace core
}  // namespace mooring_dynamics
