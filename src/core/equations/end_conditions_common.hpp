// What the 2-D and 3-D end conditions share (end_conditions2d.cpp, end_conditions3d.cpp): the
// position feedback of a driven top. Private to src/core/equations.
#pragma once

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {
namespace end_detail {

// Position feedback of a driven top (docs/method.md, "Top boundary"): the velocity of eq. 34 with
// the position error fed back over this many BASE steps (a cut step must not raise the gain, or
// an offset becomes a huge velocity).
inline constexpr double kPositionFeedbackSteps = 5.0;

/// Gain of the position feedback [1/s]: 1 / (kPositionFeedbackSteps dt) when the problem asks for
/// it (dynamics.top_motion.prescribe: position), else 0.
inline double feedbackGain(const Problem& p) {
  return p.dynamics.top_motion.prescribe_position ? 1.0 / (kPositionFeedbackSteps * p.dynamics.dt) : 0.0;
}

}  // namespace end_detail
}  // namespace core
}  // namespace mooring_dynamics
