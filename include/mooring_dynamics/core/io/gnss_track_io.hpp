// Ship tracks as ships' navigation logs export them, CSV, one fix a row:
//   t, latitude, longitude, heading
// t [s] increasing; latitude, longitude [deg] (WGS84, north and east positive); heading [deg],
// the compass heading (clockwise from north). A header line and lines starting with '#' are
// skipped. `cable_sim dynamic` feeds the rows to core::GnssTrack as the node feeds NavSatFix and
// heading messages (dynamics.gnss, docs/problem_format.md).
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model/gnss.hpp"

namespace mooring_dynamics {
namespace core {

/// Throws ProblemError naming the source, the line, the column and the value for a malformed
/// number or a row of another width, and for a time that does not increase. Latitude, longitude
/// and jumps are not checked here: GnssTrack rejects and counts such fixes, as the node does.
std::vector<GnssTrackRow> parseGnssTrack(const std::string& text, const std::string& source);
std::vector<GnssTrackRow> loadGnssTrack(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
