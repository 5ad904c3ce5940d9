// Kinematics or force of a line's top end in 3-D, from the problem file's dynamics.top_motion,
// for the dynamic solvers (the 2-D solver takes its x-z projection). Frame: x east, y north,
// z up, z = 0 the mean sea surface. All quantities SI.
#pragma once

#include <functional>
#include <string>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

/// The top end at one instant, in the problem frame.
struct TopState {
  bool force = false;                 ///< true: (fx, fy, fz) is applied; false: position and velocity prescribed
  double x = 0, y = 0, z = 0;         ///< position [m]
  double vx = 0, vy = 0, vz = 0;      ///< velocity [m/s], the exact time derivative of the position
  double fx = 0, fy = 0, fz = 0;      ///< [N] force applied to the line's top end
  double heading = 0;                 ///< [rad] ship heading ccw from +x (ship tracks), else 0

  /// A prescribed position p and velocity v (3 values each).
  static TopState prescribed(const double* p, const double* v) {
    TopState s;
    s.x = p[0];
    s.y = p[1];
    s.z = p[2];
    s.vx = v[0];
    s.vy = v[1];
    s.vz = v[2];
    return s;
  }
};

/// The top state as a function of time t [s] >= 0 for motion `m` started at the static top
/// (x0, y0, z0) [m]:
///   hold            (x0, y0, z0), at rest;
///   sinusoid        x = x0 + a_x (sin(2 pi t / T + phase) - sin(phase)), likewise y and z;
///   position_table  the rows' absolute positions, linear in time, velocity the slope of the
///                   current interval (the row values held before the first and after the last row);
///   velocity_table  the rows' velocities, linear in time, position their exact integral from
///                   (x0, y0, z0) at t = 0;
///   force_table     force = true, (fx, fy, fz) from the rows, linear in time; position unused;
///   wave_follower   (x0, y0, z0 + eta(x0, y0, t)), velocity (0, 0, d eta / dt); held when
///                   `waves` is null or empty;
///   ship_track      ShipTrack::at(t, x0, y0) at the constant elevation z0, with its heading.
/// The function holds a copy of `m` and the pointer `waves`, which must outlive it.
std::function<TopState(double t)> makeTopMotion(const TopMotion& m, double x0, double y0, double z0,
                                                const WaveField* waves);

/// Empty when the top motion stays in the vertical plane y = 0 (what the 2-D solver can follow),
/// else "dynamics.top_motion.<key> = value: ... needs the 3-D model". A ship track stays in it
/// only without turns and with headings of 0 or 180 deg (ShipTrack::leavesXAxis).
std::string planarTopMotionError(const TopMotion& m);

/// Empty unless `m` is a position table whose first row is farther than `tolerance` [m] from the
/// static top (x0, y0, z0) [m]; then "dynamics.top_motion.table[0] = (...): must start at ...".
std::string topMotionStartError(const TopMotion& m, double x0, double y0, double z0, double tolerance);

}  // namespace core
}  // namespace mooring_dynamics
