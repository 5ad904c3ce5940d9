// Ship tracks for towing problems (paper section 7.1, issue 4): a tow point moving at constant
// speed along straight legs and circular turns, with impulsive heading changes (the paper's
// Case 2 "returns impulsively to 0 degrees at the end of the turn"). Positions are exact on the
// arcs (closed form, no numerical integration). Frame: x east, y north; headings counterclockwise
// from +x. The tow point's elevation is not part of the track (it stays at its start elevation).
#pragma once

#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

/// One leg of a ship track.
struct ShipLeg {
  enum class Type {
    Straight,  ///< straight ahead at the current heading for `duration`
    Turn,      ///< circular arc of `radius` turning through `angle`
    Heading    ///< impulsive change to the absolute `heading` (zero duration, the position is continuous)
  };
  Type type = Type::Straight;
  double duration = 0.0;  ///< Straight: [s], >= 0
  double radius = 0.0;    ///< Turn: [m], > 0
  double angle = 0.0;     ///< Turn: [rad] turned through; > 0 counterclockwise (to port), < 0 to starboard; may exceed 2 pi
  double heading = 0.0;   ///< Heading: the new heading [rad] counterclockwise from +x

  static ShipLeg straight(double duration_s);
  static ShipLeg turn(double radius_m, double angle_rad);
  static ShipLeg headingChange(double heading_rad);
};

/// Where the tow point is at one instant.
struct ShipPose {
  double x = 0.0, y = 0.0;    ///< [m]
  double vx = 0.0, vy = 0.0;  ///< [m/s], = speed (cos heading, sin heading)
  double heading = 0.0;       ///< [rad] counterclockwise from +x, not wrapped (a 375 deg turn from 0 ends at 375 deg)
};

/// A tow ship at constant speed: the legs in order from t = 0, then straight on at the last heading.
struct ShipTrack {
  double speed = 0.0;            ///< U [m/s], > 0
  double heading = 0.0;          ///< initial heading [rad] counterclockwise from +x
  std::vector<ShipLeg> legs;     ///< empty: straight ahead for ever

  /// Empty when valid, else "<key>.<field> = value: constraint" (angles in degrees under *_deg
  /// keys, as in the problem file), `key` the YAML path of the track.
  std::string validate(const std::string& key = "dynamics.top_motion") const;

  /// Time [s] a leg takes at this speed: its duration, R |angle| / U for a turn, 0 for a heading change.
  double legDuration(const ShipLeg& leg) const;
  /// Time [s] until the end of the last leg.
  double legsDuration() const;

  /// Pose at time t [s] of a track that starts at (x0, y0) [m] at t = 0. Right-continuous at a
  /// heading change (at its time the new heading applies). Before t = 0 the ship comes along the
  /// initial heading at the same speed.
  ShipPose at(double t, double x0, double y0) const;

  /// Empty when the track stays on the line y = y0 (no turn other than of angle 0, every heading
  /// along +x or -x to |sin| <= 1e-12), else "<key>...: <why>" naming the first key that leaves it.
  std::string leavesXAxis(const std::string& key = "dynamics.top_motion") const;
};

}  // namespace core
}  // namespace mooring_dynamics
