// cable_sim dynamic on a real ship track (`dynamics.gnss.track`: t, latitude, longitude, heading):
// the rows go through core::GnssTrack, as the node's NavSatFix and heading messages do, and
// become the samples the lockstep runners follow (the top's position table of one line, the
// vessel's pose samples of a moored vessel).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/vessel_motion_io.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/system.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

/// One line (model: 3d, top `position`): the accepted fixes as the top's position table, time
/// from the first accepted fix, the line's top under the track's first pose. Prints the fixes'
/// verdicts to `out`. Throws ProblemError (bad file or problem) naming the key.
void gnssTopTable(core::Problem& problem, std::ostream& out);

/// A moored vessel: the accepted fixes as pose samples (time from the first accepted fix), the
/// vessel's file pose under the first one.
std::vector<core::PoseSample> gnssVesselSamples(const core::SystemProblem& s, std::ostream& out);

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
