// cable_sim sweep's folder layout and its summary (docs/design_analysis.md): what cmd_sweep.cpp
// runs into and sweep_collect.cpp reads back.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace fs = std::filesystem;

/// The sweep's folders under its output folder DIR (cmd_sweep.cpp's opening comment).
struct SweepDirs {
  fs::path root, cases, results, failed;
  explicit SweepDirs(const fs::path& r) : root(r), cases(r / "cases"), results(r / "results"), failed(r / "failed") {}
  fs::path caseFile(const std::string& name) const { return cases / (name + ".yaml"); }
};

/// `cable_sim sweep --collect DIR` (and the end of a local run): summary.csv, storms.csv,
/// status.csv, offsets.csv, utilization plots, report.md with its plots; the exit code.
int collectSweep(const fs::path& root, std::ostream& out, std::ostream& err);

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
