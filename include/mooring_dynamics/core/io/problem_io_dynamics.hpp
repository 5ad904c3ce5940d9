// Internal (not part of the public API): the waves and dynamics section readers of problem
// files, split from problem_io.cpp. Errors are ProblemError, as everywhere in problem_io.
#pragma once

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/waves.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"

namespace mooring_dynamics {
namespace core {
namespace problem_io_detail {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

/// environment.waves -> WaveSpec. Keys not used by the chosen type are rejected.
WaveSpec readWaves(const yaml::Item& it);

/// The `dynamics` section (incl. top_motion) into `d`, on top of its current values.
void readDynamics(const yaml::Item& it, DynamicOptions& d, double line_length);

}  // namespace problem_io_detail
}  // namespace core
}  // namespace mooring_dynamics
