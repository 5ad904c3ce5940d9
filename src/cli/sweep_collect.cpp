// cable_sim sweep --collect: the summary of a sweep's folder (core/io/sweep_summary) in CSV tables
// and plots, and the report (sweep_report.hpp). Also run at the end of a local sweep (cmd_sweep.cpp).
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "cli_common.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/sweep_io.hpp"
#include "mooring_dynamics/core/io/sweep_summary.hpp"
#include "sweep_collect.hpp"
#include "sweep_report.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {

/// The vessel offset trace in the report's plot keeps every this many samples (10 s at dt 0.1 s:
/// the slow drift's periods are minutes; a 3-hour storm gives ~1000 points per seed).
constexpr std::size_t kOffsetTraceStride = 100;

std::string firstLine(const fs::path& p) {
  std::ifstream f(p);
  std::string l;
  std::getline(f, l);
  return l;
}

/// The value a storm and line stand for in the plots: the most probable maximum's utilization
/// when fitted, else the largest maximum's; tension [kN] when the line has no MBL.
double plotValue(const core::StormLineStats& s, bool utilization) {
  const double t = s.fitted ? s.mpm : s.max_of_max;
  return utilization ? (s.mbl > 0.0 ? t / s.mbl : std::numeric_limits<double>::quiet_NaN()) : t / 1000.0;
}

bool plotVariation(const core::SweepManifest& m, std::size_t v, const std::vector<core::StormLineStats>& storms,
                   const std::map<std::string, const core::SweepCase*>& storm_case, const SweepDirs& d,
                   fs::path& png, std::ostream& err) {
  const auto& var = m.variations[v];
  bool numeric = true;
  for (double x : var.numbers) numeric = numeric && std::isfinite(x);
  bool utilization = false, fitted = false;
  for (const auto& s : storms) {
    utilization = utilization || s.mbl > 0.0;
    fitted = fitted || s.fitted;
  }
  std::vector<std::string> lines;
  for (const auto& s : storms)
    if (std::find(lines.begin(), lines.end(), s.line) == lines.end()) lines.push_back(s.line);
  // y[line][value]: the largest over the storms with that value.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<double>> y(lines.size(), std::vector<double>(var.labels.size(), nan));
  for (const auto& s : storms) {
    const auto sc = storm_case.find(s.storm);
    if (sc == storm_case.end()) continue;
    const std::size_t k = sc->second->choice[v];
    const std::size_t li = static_cast<std::size_t>(std::find(lines.begin(), lines.end(), s.line) - lines.begin());
    const double val = plotValue(s, utilization);
    if (std::isfinite(val) && !(val <= y[li][k])) y[li][k] = val;
  }
  png = d.root / ("utilization_vs_" + var.name + ".png");
  std::ostringstream gp;
  gp << "# gnuplot script written by 'cable_sim sweep' (run: gnuplot " << ("utilization_vs_" + var.name + ".gp") << ")\n"
     << "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
     << "  set terminal pngcairo noenhanced size 1100,650 font \"sans,12\"\n"
     << "} else {\n"
     << "  set terminal png noenhanced size 1100,650\n"
     << "}\n"
     << "set output " << gpString(png.string()) << "\n"
     << "set grid lc rgb \"#d0d0d0\"\n"
     << "set key outside right top box\n"
     << "set datafile missing \"NaN\"\n"
     << "set title " << gpString(m.name + ": " + (utilization ? "utilization" : "top tension") + " against " + var.name +
                                 " (largest over the other variations)") << "\n"
     << "set xlabel " << gpString(var.name) << "\n"
     << "set ylabel " << gpString(std::string(utilization ? "top tension / MBL" : "top tension [kN]") +
                                  (fitted ? " (most probable maximum over the seeds)" : " (maximum)")) << "\n"
     << "set yrange [0:*]\n";
  if (!numeric) {
    gp << "set xtics (";
    for (std::size_t k = 0; k < var.labels.size(); ++k) gp << (k ? ", " : "") << gpString(var.labels[k]) << " " << k;
    gp << ")\nset xrange [-0.5:" << var.labels.size() - 0.5 << "]\n";
  }
  gp << "$data << EOD\n";
  for (std::size_t k = 0; k < var.labels.size(); ++k) {
    gp << (numeric ? csvNum(var.numbers[k]) : std::to_string(k));
    for (std::size_t li = 0; li < lines.size(); ++li) gp << " " << (std::isfinite(y[li][k]) ? csvNum(y[li][k]) : "NaN");
    gp << "\n";
  }
  gp << "EOD\nplot ";
  for (std::size_t li = 0; li < lines.size(); ++li)
    gp << (li ? ", \\\n     " : "") << "$data using 1:" << li + 2 << " with linespoints lw 2 pt 7 title " << gpString(lines[li]);
  gp << "\n";
  return runGnuplot(d.root, "utilization_vs_" + var.name, gp.str(), err);
}

/// Per storm row: an accidental (ALS) storm, one of whose labels is in the manifest's als list.
std::vector<bool> accidentalStorms(const core::SweepManifest& m, const std::vector<core::StormLineStats>& storms,
                                   const std::map<std::string, const core::SweepCase*>& storm_case) {
  std::vector<bool> als;
  for (const auto& s : storms) {
    bool a = false;
    const auto it = storm_case.find(s.storm);
    if (it != storm_case.end())
      for (std::size_t v = 0; v < m.variations.size(); ++v)
        for (const auto& label : m.als_labels) a = a || m.variations[v].labels[it->second->choice[v]] == label;
    als.push_back(a);
  }
  return als;
}

/// "design check (...): N of M pass; largest design utilization ..." for the terminal.
std::string designCheckText(const core::SweepManifest& m, const std::vector<core::StormLineStats>& storms) {
  std::size_t checked = 0, passed = 0;
  const core::StormLineStats* worst = nullptr;
  for (const auto& s : storms) {
    if (!s.checked) continue;
    ++checked;
    passed += s.design.pass ? 1 : 0;
    if (worst == nullptr || s.design.utilization > worst->design.utilization) worst = &s;
  }
  std::string t = "  design check (DNV-OS-E301 form, consequence class " + std::to_string(m.design_class) + "): ";
  if (worst == nullptr) return t + "no storm-line with a Gumbel fit and an MBL (2 seeds or more and materials.*.mbl)\n";
  t += std::to_string(passed) + " of " + std::to_string(checked) + " storm-lines pass; largest design utilization " +
       fmtNum("%.3f", worst->design.utilization) + " (" + core::toString(worst->limit_state) + ", line " + worst->line +
       " in " + worst->storm + ": T_d " + fmtNum("%.1f", worst->design.design_tension / 1000.0) + " kN against S_c " +
       fmtNum("%.1f", worst->design.strength / 1000.0) + " kN)\n";
  return t;
}

}  // namespace

int collectSweep(const fs::path& root, std::ostream& out, std::ostream& err) {
  const SweepDirs d(root);
  core::SweepManifest m;
  try {
    m = core::loadManifestFromFile((root / "manifest.yaml").string());
  } catch (const std::exception& e) {
    err << kProg << ": error: " << e.what() << " (is " << root.string() << " a sweep's --out folder?)\n";
    return kExitBadInput;
  }
  std::vector<core::CaseLineStats> rows;
  std::vector<core::CaseVesselOffset> offsets;
  std::vector<std::pair<std::string, std::string>> status;  // case, status/message
  std::size_t done = 0, failed = 0, pending = 0;
  std::map<std::string, const core::SweepCase*> storm_case;
  for (const auto& c : m.cases) {
    storm_case.emplace(c.storm, &c);
    std::error_code ec;
    if (fs::is_directory(d.results / c.name, ec)) {
      try {
        const auto s = core::caseLineStats(d.caseFile(c.name).string(), (d.results / c.name).string(), m.skip_time,
                                           c.name, c.storm);
        rows.insert(rows.end(), s.begin(), s.end());
        core::CaseVesselOffset o;
        if (core::caseVesselOffset((d.results / c.name).string(), m.skip_time, c.name, c.storm, kOffsetTraceStride, o))
          offsets.push_back(o);
        status.emplace_back(c.name, "done,");
        ++done;
      } catch (const std::exception& e) {
        status.emplace_back(c.name, std::string("failed,\"results unreadable: ") + e.what() + "\"");
        ++failed;
      }
    } else if (fs::is_directory(d.failed / c.name, ec)) {
      std::string why = firstLine(d.failed / c.name / "error.txt");
      std::replace(why.begin(), why.end(), '"', '\'');
      status.emplace_back(c.name, "failed,\"" + why + "\"");
      ++failed;
    } else {
      status.emplace_back(c.name, "pending,");
      ++pending;
    }
  }
  std::vector<core::StormLineStats> storms = core::stormLineStats(rows, m.gumbel);
  if (m.design_class > 0) core::designCheckStorms(storms, accidentalStorms(m, storms, storm_case), m.design_class);
  if (!writeFile(root / "summary.csv", [&](std::ostream& o) { core::writeCaseLineStatsCsv(o, rows); }, err) ||
      !writeFile(root / "storms.csv", [&](std::ostream& o) { core::writeStormLineStatsCsv(o, storms, m.gumbel); }, err) ||
      !writeFile(root / "status.csv", [&](std::ostream& o) {
        o << "case,status,message\n";
        for (const auto& s : status) o << s.first << "," << s.second << "\n";
      }, err))
    return kExitIo;
  if (!offsets.empty() &&
      !writeFile(root / "offsets.csv", [&](std::ostream& o) { core::writeCaseVesselOffsetCsv(o, offsets); }, err))
    return kExitIo;
  out << m.name << ": " << done << " of " << m.cases.size() << " cases done, " << failed << " failed, " << pending
      << " not run\n";
  out << "wrote " << (root / "summary.csv").string() << " (case and line), " << (root / "storms.csv").string()
      << " (storm and line, Gumbel " << core::gumbelMethodName(m.gumbel) << " fit over the seeds), "
      << (root / "status.csv").string() << "\n";
  // The most loaded line.
  const core::StormLineStats* worst = nullptr;
  bool util = false;
  for (const auto& s : storms) util = util || s.mbl > 0.0;
  for (const auto& s : storms) {
    const double v = plotValue(s, util);
    if (std::isfinite(v) && (worst == nullptr || v > plotValue(*worst, util))) worst = &s;
  }
  if (worst != nullptr)
    out << "  most loaded: line " << worst->line << " in " << worst->storm << ": "
        << (worst->fitted ? "most probable maximum " + fmtNum("%.1f", worst->mpm / 1000.0)
                          : "maximum " + fmtNum("%.1f", worst->max_of_max / 1000.0))
        << " kN" << (util && worst->mbl > 0.0 ? ", utilization " + fmtNum("%.3f", plotValue(*worst, true)) : std::string())
        << "\n";
  if (m.design_class > 0) out << designCheckText(m, storms);
  const bool plots = gnuplotAvailable();
  if (!storms.empty()) {
    if (!plots) {
      err << kProg << ": warning: gnuplot not found: no plots (install it with scripts/setup)\n";
    } else {
      for (std::size_t v = 0; v < m.variations.size(); ++v) {
        if (m.variations[v].seeds || m.variations[v].labels.size() < 2) continue;
        fs::path png;
        if (!plotVariation(m, v, storms, storm_case, d, png, err)) return kExitIo;
        out << "wrote " << png.string() << "\n";
      }
    }
  }
  SweepReportInput report{&m, &rows, &storms, &offsets, done, failed, pending, plots};
  std::vector<fs::path> written;
  if (!writeSweepReport(root, report, written, err)) return kExitIo;
  for (const auto& f : written) out << "wrote " << f.string() << "\n";
  if (failed > 0 || pending > 0) {
    err << kProg << ": " << failed << " case(s) failed and " << pending << " not run (see " << (root / "status.csv").string()
        << "; failed cases keep their run.log and error.txt in " << d.failed.string() << ")\n";
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
