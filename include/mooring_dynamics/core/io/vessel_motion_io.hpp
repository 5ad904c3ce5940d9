// Vessel motion tables: the vessel's pose in time as CSV, one sample a row
//   t, x, y, z, qx, qy, qz, qw                         (pose only), or
//   t, x, y, z, qx, qy, qz, qw, vx, vy, vz, wx, wy, wz   (pose and body twist)
// t [s] increasing; x, y, z [m] of the body origin in the world frame (REP 103: x east, y north,
// z up, z = 0 at the mean surface); qx, qy, qz, qw the unit quaternion body -> world; vx, vy, vz
// [m/s] the origin's velocity and wx, wy, wz [rad/s] the angular velocity, both in the BODY frame
// (x forward, y left, z up), as nav_msgs/Odometry's twist (REP 105), so that a recorded odometry
// topic is a table as it stands. Every row has the same width. A header row starting with "t"
// and lines starting with '#' are skipped. `cable_sim dynamic` feeds the rows to VesselLockstep
// as the node feeds its pose (or odometry) messages.
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace core {

// One row of the table: PoseSample (core/model/rigid_pose.hpp, where the generators of the model
// layer, e.g. storm_motion, can use it too).

/// Parses the table; throws ProblemError naming the source, the row (1-based line number), the
/// column and the value for a malformed number, a row of another width, a time that does not
/// increase, a quaternion that is not of unit norm (kUnitQuaternionTolerance), a row of neither 8
/// nor 14 values, or a row whose width differs from the first row's.
std::vector<PoseSample> parseVesselMotionTable(const std::string& text, const std::string& source);
std::vector<PoseSample> loadVesselMotionTable(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
