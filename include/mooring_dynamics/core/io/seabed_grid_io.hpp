// Seabed depth grid files (problem file key `environment.seabed.grid_file`): a plain-text format,
// documented in docs/problem_format.md ("Seabed grid file"):
//
//   # comments start with '#' (whole lines or after the values); blank lines are ignored
//   x0 y0 dx dy nx ny            <- header: first grid point [m], spacings [m] > 0, counts >= 2
//   d00 d10 d20 ...              <- ny rows of nx depths [m] > 0 (positive down); row k is
//   d01 d11 d21 ...                 y = y0 + k dy, column i is x = x0 + i dx
//
// Errors are ProblemError naming the file, the line, the value found and the constraint, e.g.
//   bay.grid:7: row 2 (y = 200 m), column 3 (x = 300 m): depth = nan: must be finite
#pragma once

#include <istream>
#include <string>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace core {

/// Parse a grid from `in`; `name` (usually the file path) prefixes every message and becomes
/// SeabedGrid::source. Throws ProblemError.
SeabedGrid readSeabedGrid(std::istream& in, const std::string& name);

/// Read a grid file. Throws ProblemError (also when the file cannot be opened).
SeabedGrid loadSeabedGrid(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
