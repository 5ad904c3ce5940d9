// The design report of a sweep (`cable_sim sweep`, docs/design_analysis.md "The report"):
// DIR/report.md with the line check (or the most probable maxima without one) and the vessel's
// offsets, and its plots: DIR/exceedance_<storm>.png, the per-seed maxima of a storm's most loaded
// lines against their Gumbel fit as exceedance probabilities, and DIR/vessel_offset.png, the
// vessel's horizontal excursion in every storm (its offset envelope).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "mooring_dynamics/core/io/sweep_io.hpp"
#include "mooring_dynamics/core/io/sweep_summary.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

struct SweepReportInput {
  const core::SweepManifest* manifest = nullptr;
  const std::vector<core::CaseLineStats>* cases = nullptr;
  const std::vector<core::StormLineStats>* storms = nullptr;
  const std::vector<core::CaseVesselOffset>* offsets = nullptr;
  std::size_t done = 0, failed = 0, pending = 0;
  bool plots = true;  ///< gnuplot is there
};

/// Write report.md and the plots into `root`; the files written are appended to `written`.
/// False, with the message on err, on an I/O or gnuplot failure.
bool writeSweepReport(const fs::path& root, const SweepReportInput& in, std::vector<fs::path>& written,
                      std::ostream& err);

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
