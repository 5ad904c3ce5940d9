#include "mooring_dynamics/core/io/gnss_track_io.hpp"

#include "mooring_dynamics/core/io/csv_table.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {

std::vector<GnssTrackRow> parseGnssTrack(const std::string& text, const std::string& source) {
  std::vector<GnssTrackRow> out;
  for (const CsvRow& r : parseCsvTable(text, source, {"t", "latitude", "longitude", "heading"})) {
    GnssTrackRow row{r.values[0], r.values[1], r.values[2], r.values[3]};
    if (!out.empty() && !(row.t > out.back().t))
      throw ProblemError(r.where + ": t = " + std::to_string(row.t) + " s must be after the previous row's " +
                         std::to_string(out.back().t) + " s");
    out.push_back(row);
  }
  return out;
}

std::vector<GnssTrackRow> loadGnssTrack(const std::string& path) {
  return parseGnssTrack(sections::readFileText(path), path);
}

}  // namespace core
}  // namespace mooring_dynamics
