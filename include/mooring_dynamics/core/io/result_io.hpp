// Writing static results: JSON (everything) and CSV (one row per node).
#pragma once

#include <ostream>
#include <string>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// JSON document with the problem name, summary, end forces and per-node arrays.
void writeStaticJson(std::ostream& out, const Problem& problem, const StaticResult& result);

/// CSV with header `node,s,x,z,tension,shear,angle_deg,curvature,strain,segment`.
/// 3-D results add the columns y, shear_b, azimuth_deg, curvature_b and twist.
void writeStaticCsv(std::ostream& out, const StaticResult& result, Formulation model = Formulation::TwoD);

/// Short human-readable summary (a few lines) for terminals.
std::string staticSummaryText(const Problem& problem, const StaticResult& result);

/// Readable table: node, s, x, z, tension (every `stride`-th node, always the first and last).
std::string staticTableText(const StaticResult& result, std::size_t stride = 1,
                            Formulation model = Formulation::TwoD);

}  // namespace core
}  // namespace mooring_dynamics
