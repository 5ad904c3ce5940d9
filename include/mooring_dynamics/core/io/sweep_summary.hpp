// The summary of a load-case sweep (docs/design_analysis.md): per case and line the statistics
// of the line's top tension from the case's series file, its utilization against the minimum
// breaking load of the line's weakest material, the largest horizontal offset of its top; over
// the random seeds of each storm, the most probable maximum from a Gumbel fit of the per-seed
// maxima (model/extremes.hpp).
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/model/design_check.hpp"
#include "mooring_dynamics/core/model/extremes.hpp"

namespace mooring_dynamics {
namespace core {

/// Statistics of one line in one case. Tensions in N, offsets in m (horizontal, world frame).
struct CaseLineStats {
  std::string case_name;
  std::string storm;
  std::string line;
  std::size_t samples = 0;  ///< samples used (after the skipped start)
  double max = 0.0, mean = 0.0, std = 0.0;  ///< top tension: largest, mean, standard deviation (population)
  double mbl = 0.0;          ///< the smallest `mbl` of the line's materials; 0 when one of them has none
  double utilization = 0.0;  ///< max / mbl; NaN without mbl
  /// Largest horizontal distance of the line's top from its position at the first sample
  /// (a single line's top, a system line's free upper point); NaN where the series has no
  /// position of it (a vessel's fairlead follows the vessel's prescribed motion; a fixed point).
  double top_offset = 0.0;
};

/// The moored vessel's horizontal offset in one case (vessel files): its body origin's distance in
/// the horizontal plane (world frame) from its position at the first sample, over the samples at
/// t >= skip_time, and a thinned trace of the offset for plots.
struct CaseVesselOffset {
  std::string case_name;
  std::string storm;
  double max = 0.0;   ///< largest horizontal offset [m]
  double mean = 0.0;  ///< mean horizontal offset [m]
  std::vector<std::pair<double, double>> trace;  ///< (dx, dy) [m], world axes, every `stride`-th sample
};

/// Statistics of one line over the seeds of one storm.
struct StormLineStats {
  std::string storm;
  std::string line;
  std::size_t seeds = 0;             ///< cases (seeds) with this line
  double max_of_max = 0.0, mean_of_max = 0.0, std_of_max = 0.0;  ///< of the per-seed maxima [N] (std: n - 1)
  bool fitted = false;               ///< a Gumbel fit was made (2 seeds or more)
  GumbelFit fit;                     ///< of the per-seed maxima [N]
  double mpm = 0.0;                  ///< most probable maximum [N]: the fit's mode; NaN when not fitted
  double mbl = 0.0;                  ///< as CaseLineStats
  double mpm_utilization = 0.0;      ///< mpm / mbl; NaN without mbl or fit
  double mean_tension = 0.0;         ///< mean over the seeds of each case's mean top tension [N]
  bool checked = false;              ///< designCheckStorms made the line check (needs mbl and a fit)
  LimitState limit_state = LimitState::Uls;
  DesignCheck design;                ///< T_c,mean = mean_tension, MPM = mpm (design_check.hpp)
};

/// The line statistics of a finished case: `problem_path` is the case's problem file (line names,
/// materials, which point tops each line), `result_dir` what `cable_sim dynamic --out` wrote there
/// (timeseries.csv, system_timeseries.csv or vessel_timeseries.csv). Samples at t < skip_time are
/// left out. Throws ProblemError naming the file on a missing or malformed file or column.
std::vector<CaseLineStats> caseLineStats(const std::string& problem_path, const std::string& result_dir,
                                         double skip_time, const std::string& case_name, const std::string& storm);

/// The vessel offset of a finished vessel case (result_dir/vessel_timeseries.csv with the columns
/// vessel_x and vessel_y); false when the case has no vessel series. Throws ProblemError naming
/// the file when it is malformed. The trace keeps every `stride`-th sample (>= 1).
bool caseVesselOffset(const std::string& result_dir, double skip_time, const std::string& case_name,
                      const std::string& storm, std::size_t stride, CaseVesselOffset& out);
/// CSV `case,storm,max_offset,mean_offset` [m].
void writeCaseVesselOffsetCsv(std::ostream& out, const std::vector<CaseVesselOffset>& rows);

/// Group by storm and line (in order of first appearance) and fit the per-seed maxima.
std::vector<StormLineStats> stormLineStats(const std::vector<CaseLineStats>& cases, GumbelMethod method);

/// The line check of every fitted storm-line with an MBL: `als[i]` true where storm i of `rows`
/// is an accidental case (a line broken); factors of DNV-OS-E301 for `consequence_class`.
void designCheckStorms(std::vector<StormLineStats>& rows, const std::vector<bool>& als, int consequence_class);

/// CSV with a header; empty cells for NaN (no mbl, no offset, no fit). 12 significant digits.
void writeCaseLineStatsCsv(std::ostream& out, const std::vector<CaseLineStats>& rows);
void writeStormLineStatsCsv(std::ostream& out, const std::vector<StormLineStats>& rows, GumbelMethod method);

}  // namespace core
}  // namespace mooring_dynamics
