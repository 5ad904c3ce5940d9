#include "mooring_dynamics/core/model/top_motion.hpp"

#include <cmath>
#include <sstream>
#include <vector>

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kTwoPi = 6.283185307179586;

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// Table components at time t, linear between rows and held outside; `rate` (when given) gets the
/// slope of the current interval (0 outside the table).
void sampleTable(const std::vector<TopMotion::Row>& tab, double t, double v[3], double* rate) {
  // The interval (t_i, t_i+1] that contains t: at a row time the interval ending there, whose
  // slope is the velocity a time step arriving at that row followed (a step of the solver lands
  // on row times whenever the rows share its grid).
  std::size_t i = 0;
  while (i + 1 < tab.size() && tab[i + 1].t < t) ++i;
  const TopMotion::Row& r0 = tab[i];
  v[0] = r0.x;
  v[1] = r0.y;
  v[2] = r0.z;
  if (rate) rate[0] = rate[1] = rate[2] = 0.0;
  if (t > r0.t && i + 1 < tab.size()) {
    const TopMotion::Row& r1 = tab[i + 1];
    const double span = r1.t - r0.t;
    const double w = (t - r0.t) / span;
    const double d[3] = {r1.x - r0.x, r1.y - r0.y, r1.z - r0.z};
    for (int k = 0; k < 3; ++k) {
      if (rate) rate[k] = d[k] / span;
      v[k] = w == 1.0 ? (k == 0 ? r1.x : k == 1 ? r1.y : r1.z) : v[k] + w * d[k];
    }
  }
  // Before the first row (t <= tab.front().t) and after the last the end rows are held, at rest.
}

TopState held(double x0, double y0, double z0) {
  TopState s;
  s.x = x0;
  s.y = y0;
  s.z = z0;
  return s;
}

}  // namespace

namespace {

/// Sinusoid about the static top (x0, y0, z0), at rest at t = 0 but for its velocity.
std::function<TopState(double t)> sinusoid(const TopMotion& m, double x0, double y0, double z0) {
  return [m, x0, y0, z0](double t) {
    const double w = kTwoPi / m.period, a = w * t + m.phase;
    const double s = std::sin(a) - std::sin(m.phase), c = std::cos(a);
    TopState st;
    st.x = x0 + m.amplitude_x * s;
    st.y = y0 + m.amplitude_y * s;
    st.z = z0 + m.amplitude_z * s;
    st.vx = m.amplitude_x * w * c;
    st.vy = m.amplitude_y * w * c;
    st.vz = m.amplitude_z * w * c;
    return st;
  };
}

/// The rows' positions, linear in time, the velocity the slope of the current interval.
std::function<TopState(double t)> positionTable(const std::vector<TopMotion::Row>& table) {
  return [tab = table](double t) {
    double p[3], v[3];
    sampleTable(tab, t, p, v);
    return TopState::prescribed(p, v);
  };
}

/// The rows' forces, linear in time.
std::function<TopState(double t)> forceTable(const std::vector<TopMotion::Row>& table) {
  return [tab = table](double t) {
    double f[3];
    sampleTable(tab, t, f, nullptr);
    TopState st;
    st.force = true;
    st.fx = f[0];
    st.fy = f[1];
    st.fz = f[2];
    return st;
  };
}

/// The rows' velocities, linear in time, the position their exact integral from (x0, y0, z0).
std::function<TopState(double t)> velocityTable(const std::vector<TopMotion::Row>& table, double x0, double y0, double z0) {
  return [tab = table, x0, y0, z0](double t) {
    // Position: the exact integral of the piecewise-linear velocity (trapezoids between the
    // table times, where the velocity has its kinks).
    std::vector<double> knots{0.0};
    for (const auto& r : tab)
      if (r.t > 0.0 && r.t < t) knots.push_back(r.t);
    knots.push_back(t);
    double p[3] = {x0, y0, z0};
    double v0[3], v1[3];
    for (std::size_t k = 1; k < knots.size(); ++k) {
      sampleTable(tab, knots[k - 1], v0, nullptr);
      sampleTable(tab, knots[k], v1, nullptr);
      for (int c = 0; c < 3; ++c) p[c] += 0.5 * (v0[c] + v1[c]) * (knots[k] - knots[k - 1]);
    }
    double v[3];
    sampleTable(tab, t, v, nullptr);
    return TopState::prescribed(p, v);
  };
}

/// The ship track's position and velocity, at the static top's depth.
std::function<TopState(double t)> shipTrack(const ShipTrack& track_in, double x0, double y0, double z0) {
  return [track = track_in, x0, y0, z0](double t) {
    const ShipPose p = track.at(t, x0, y0);
    TopState st;
    st.x = p.x;
    st.y = p.y;
    st.z = z0;
    st.vx = p.vx;
    st.vy = p.vy;
    st.heading = p.heading;
    return st;
  };
}

/// The static top moved with the sea surface's elevation above it.
std::function<TopState(double t)> waveFollower(double x0, double y0, double z0, const WaveField* waves) {
  return [x0, y0, z0, waves](double t) {
    TopState st = held(x0, y0, z0);
    if (waves && !waves->empty()) {
      double eta, rate;
      waves->elevationAndRate(x0, y0, t, eta, rate);
      st.z = z0 + eta;
      st.vz = rate;
    }
    return st;
  };
}

}  // namespace

std::function<TopState(double t)> makeTopMotion(const TopMotion& m, double x0, double y0, double z0,
                                                const WaveField* waves) {
  switch (m.type) {
    case TopMotion::Type::Hold:
      return [x0, y0, z0](double) { return held(x0, y0, z0); };
    case TopMotion::Type::Sinusoid:
      return sinusoid(m, x0, y0, z0);
    case TopMotion::Type::PositionTable:
      return positionTable(m.table);
    case TopMotion::Type::ForceTable:
      return forceTable(m.table);
    case TopMotion::Type::VelocityTable:
      return velocityTable(m.table, x0, y0, z0);
    case TopMotion::Type::ShipTrack:
      return shipTrack(m.ship_track, x0, y0, z0);
    case TopMotion::Type::WaveFollower:
      return waveFollower(x0, y0, z0, waves);
  }
  return nullptr;
}

std::string planarTopMotionError(const TopMotion& m) {
  const std::string k = "dynamics.top_motion.";
  const std::string why = ": the 2-D solver works in the x-z plane (y = 0); motion in y needs the 3-D model";
  switch (m.type) {
    case TopMotion::Type::Sinusoid:
      if (m.amplitude_y != 0.0) return k + "amplitude_y = " + fmt(m.amplitude_y) + why;
      break;
    case TopMotion::Type::PositionTable:
    case TopMotion::Type::VelocityTable:
    case TopMotion::Type::ForceTable:
      for (std::size_t i = 0; i < m.table.size(); ++i)
        if (m.table[i].y != 0.0)
          return k + "table[" + std::to_string(i) + "] y = " + fmt(m.table[i].y) + why;
      break;
    case TopMotion::Type::ShipTrack:
      return m.ship_track.leavesXAxis("dynamics.top_motion");
    case TopMotion::Type::Hold:
    case TopMotion::Type::WaveFollower:
      break;
  }
  return {};
}

std::string topMotionStartError(const TopMotion& m, double x0, double y0, double z0, double tolerance) {
  if (m.type != TopMotion::Type::PositionTable || m.table.empty()) return {};
  // The row at the start: the last at t <= 0 (rows before it only set the velocity at t = 0, as a
  // tow's run-up does), else the first.
  std::size_t i = 0;
  while (i + 1 < m.table.size() && m.table[i + 1].t <= 0.0) ++i;
  const TopMotion::Row& r = m.table[i];
  const double dx = r.x - x0, dy = r.y - y0, dz = r.z - z0;
  if (std::sqrt(dx * dx + dy * dy + dz * dz) <= tolerance) return {};
  return "dynamics.top_motion.table[" + std::to_string(i) + "] = (" + fmt(r.x) + ", " + fmt(r.y) + ", " + fmt(r.z) +
         "): must start at the static top position (" + fmt(x0) + ", " + fmt(y0) + ", " + fmt(z0) +
         ") within " + fmt(tolerance) + " m";
}

}  // namespace core
}  // namespace mooring_dynamics
