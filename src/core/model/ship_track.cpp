#include "mooring_dynamics/core/model/ship_track.hpp"

#include <cmath>
#include <sstream>

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
/// A heading counts as along the x axis when |sin(heading)| is below this (pi in double has
/// sin = 1.2e-16).
constexpr double kAxisSin = 1e-12;

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string bad(const std::string& key, double v, const std::string& constraint) {
  return key + " = " + fmt(v) + ": " + constraint;
}

/// Straight run of duration tau from (x, y) at heading h.
ShipPose straightPose(double x, double y, double h, double U, double tau) {
  ShipPose p;
  const double c = std::cos(h), s = std::sin(h);
  p.x = x + U * tau * c;
  p.y = y + U * tau * s;
  p.vx = U * c;
  p.vy = U * s;
  p.heading = h;
  return p;
}

/// Time tau into a turn of radius R through `angle` started at (x, y) with heading h: the arc
/// about the centre R to port (angle > 0) or starboard, written as the displacement from the
/// start so that it is exactly zero at tau = 0.
ShipPose turnPose(double x, double y, double h, double U, double R, double angle, double tau) {
  const double sigma = angle >= 0.0 ? 1.0 : -1.0;
  const double phi = h + sigma * U * tau / R;
  ShipPose p;
  p.x = x + sigma * R * (std::sin(phi) - std::sin(h));
  p.y = y + sigma * R * (std::cos(h) - std::cos(phi));
  p.vx = U * std::cos(phi);
  p.vy = U * std::sin(phi);
  p.heading = phi;
  return p;
}

}  // namespace

ShipLeg ShipLeg::straight(double duration_s) {
  ShipLeg l;
  l.type = Type::Straight;
  l.duration = duration_s;
  return l;
}

ShipLeg ShipLeg::turn(double radius_m, double angle_rad) {
  ShipLeg l;
  l.type = Type::Turn;
  l.radius = radius_m;
  l.angle = angle_rad;
  return l;
}

ShipLeg ShipLeg::headingChange(double heading_rad) {
  ShipLeg l;
  l.type = Type::Heading;
  l.heading = heading_rad;
  return l;
}

std::string ShipTrack::validate(const std::string& key) const {
  const std::string k = key + ".";
  if (!(std::isfinite(speed) && speed > 0.0)) return bad(k + "speed", speed, "must be > 0 [m/s]");
  if (!std::isfinite(heading)) return bad(k + "heading_deg", heading * kRadToDeg, "must be finite");
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const ShipLeg& l = legs[i];
    const std::string lk = k + "legs[" + std::to_string(i) + "].";
    switch (l.type) {
      case ShipLeg::Type::Straight:
        if (!(std::isfinite(l.duration) && l.duration >= 0.0))
          return bad(lk + "straight", l.duration, "must be >= 0 (a duration [s])");
        break;
      case ShipLeg::Type::Turn:
        if (!(std::isfinite(l.radius) && l.radius > 0.0)) return bad(lk + "turn.radius", l.radius, "must be > 0 [m]");
        if (!std::isfinite(l.angle)) return bad(lk + "turn.angle_deg", l.angle * kRadToDeg, "must be finite");
        break;
      case ShipLeg::Type::Heading:
        if (!std::isfinite(l.heading)) return bad(lk + "heading_deg", l.heading * kRadToDeg, "must be finite");
        break;
    }
  }
  return {};
}

double ShipTrack::legDuration(const ShipLeg& leg) const {
  switch (leg.type) {
    case ShipLeg::Type::Straight:
      return leg.duration;
    case ShipLeg::Type::Turn:
      return leg.radius * std::abs(leg.angle) / speed;
    case ShipLeg::Type::Heading:
      return 0.0;
  }
  return 0.0;
}

double ShipTrack::legsDuration() const {
  double T = 0.0;
  for (const ShipLeg& l : legs) T += legDuration(l);
  return T;
}

ShipPose ShipTrack::at(double t, double x0, double y0) const {
  double x = x0, y = y0, h = heading, start = 0.0;  // state at the start of the current leg
  if (t < 0.0) return straightPose(x, y, h, speed, t);
  for (const ShipLeg& l : legs) {
    // t >= start here: the legs before ended at or before t.
    switch (l.type) {
      case ShipLeg::Type::Heading:
        h = l.heading;
        break;
      case ShipLeg::Type::Straight: {
        if (t < start + l.duration) return straightPose(x, y, h, speed, t - start);
        const ShipPose end = straightPose(x, y, h, speed, l.duration);
        x = end.x;
        y = end.y;
        start += l.duration;
        break;
      }
      case ShipLeg::Type::Turn: {
        const double d = legDuration(l);
        if (t < start + d) return turnPose(x, y, h, speed, l.radius, l.angle, t - start);
        // The end of the arc in closed form: turned through exactly `angle`.
        const double sigma = l.angle >= 0.0 ? 1.0 : -1.0;
        x += sigma * l.radius * (std::sin(h + l.angle) - std::sin(h));
        y += sigma * l.radius * (std::cos(h) - std::cos(h + l.angle));
        h += l.angle;
        start += d;
        break;
      }
    }
  }
  return straightPose(x, y, h, speed, t - start);
}

std::string ShipTrack::leavesXAxis(const std::string& key) const {
  const std::string why = "the track leaves the line y = 0 of the 2-D solver's x-z plane (only headings of 0 or "
                          "180 deg and no turns stay on it); this ship track needs the 3-D model";
  if (std::abs(std::sin(heading)) > kAxisSin) return bad(key + ".heading_deg", heading * kRadToDeg, why);
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const ShipLeg& l = legs[i];
    const std::string lk = key + ".legs[" + std::to_string(i) + "]";
    if (l.type == ShipLeg::Type::Turn && l.angle != 0.0)
      return bad(lk + ".turn.angle_deg", l.angle * kRadToDeg, why);
    if (l.type == ShipLeg::Type::Heading && std::abs(std::sin(l.heading)) > kAxisSin)
      return bad(lk + ".heading_deg", l.heading * kRadToDeg, why);
  }
  return {};
}

}  // namespace core
}  // namespace mooring_dynamics
