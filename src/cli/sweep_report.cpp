// The design report of a sweep: report.md, exceedance and offset plots (sweep_report.hpp).
#include "sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace mooring_dynamics {
namespace cli {
namespace detail {
namespace {

/// Lines drawn in a storm's exceedance plot: its most loaded ones (more would hide each other).
constexpr std::size_t kExceedanceLines = 4;

std::string kN(double newtons) { return std::isfinite(newtons) ? fmtNum("%.1f", newtons / 1000.0) : "-"; }

const char* kPngHeader =
    "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
    "  set terminal pngcairo noenhanced size 1000,650 font \"sans,12\"\n"
    "} else {\n"
    "  set terminal png noenhanced size 1000,650\n"
    "}\n";

/// The storms in order of first appearance.
std::vector<std::string> stormOrder(const std::vector<core::StormLineStats>& storms) {
  std::vector<std::string> out;
  for (const auto& s : storms)
    if (std::find(out.begin(), out.end(), s.storm) == out.end()) out.push_back(s.storm);
  return out;
}

/// The per-seed maxima of each line of `storm` [N], sorted.
std::map<std::string, std::vector<double>> maximaOf(const std::vector<core::CaseLineStats>& cases, const std::string& storm) {
  std::map<std::string, std::vector<double>> m;
  for (const auto& c : cases)
    if (c.storm == storm) m[c.line].push_back(c.max);
  for (auto& kv : m) std::sort(kv.second.begin(), kv.second.end());
  return m;
}

/// exceedance_<storm>.png: the maxima at the plotting positions 1 - i / (n + 1) and the fitted
/// Gumbel exceedance 1 - exp(-exp(-(x - mu) / beta)), log scale.
bool plotExceedance(const fs::path& root, const std::string& title, const std::string& storm,
                    const std::vector<core::StormLineStats>& storms, const std::vector<core::CaseLineStats>& cases,
                    std::vector<fs::path>& written, std::ostream& err) {
  std::vector<const core::StormLineStats*> lines;
  for (const auto& s : storms)
    if (s.storm == storm && s.fitted) lines.push_back(&s);
  if (lines.empty()) return true;
  std::sort(lines.begin(), lines.end(), [](const auto* a, const auto* b) { return a->mpm > b->mpm; });
  if (lines.size() > kExceedanceLines) lines.resize(kExceedanceLines);
  const auto maxima = maximaOf(cases, storm);
  const std::string name = "exceedance_" + storm;
  const fs::path png = root / (name + ".png");
  std::ostringstream gp;
  gp << "# gnuplot script written by 'cable_sim sweep' (run: gnuplot " << name << ".gp)\n" << kPngHeader
     << "set output " << gpString(png.string()) << "\n"
     << "set grid lc rgb \"#d0d0d0\"\nset key outside right top box\nset logscale y\nset yrange [0.01:1]\n"
     << "set title " << gpString(title + ": " + storm + ", per-seed maxima and their Gumbel fit") << "\n"
     << "set xlabel \"top tension, maximum of the storm [kN]\"\n"
     << "set ylabel \"probability of exceedance\"\nset samples 400\n";
  double lo = 1e300, hi = 0.0;
  for (const auto* s : lines) {
    const auto it = maxima.find(s->line);
    if (it == maxima.end()) continue;
    lo = std::min(lo, it->second.front());
    hi = std::max(hi, it->second.back());
    lo = std::min(lo, s->fit.location - 1.5 * s->fit.scale);
    hi = std::max(hi, s->fit.location + 4.6 * s->fit.scale);  // exceedance 1 % at mu + 4.6 beta
  }
  gp << "set xrange [" << csvNum(std::max(0.0, lo / 1000.0)) << ":" << csvNum(hi / 1000.0) << "]\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto it = maxima.find(lines[i]->line);
    gp << "$d" << i << " << EOD\n";
    if (it != maxima.end())
      for (std::size_t k = 0; k < it->second.size(); ++k)
        gp << csvNum(it->second[k] / 1000.0) << " " << csvNum(1.0 - (k + 1.0) / (it->second.size() + 1.0)) << "\n";
    gp << "EOD\n";
    const double beta = std::max(lines[i]->fit.scale / 1000.0, 1e-9);
    gp << "f" << i << "(x) = 1 - exp(-exp(-(x - " << csvNum(lines[i]->fit.location / 1000.0) << ") / " << csvNum(beta)
       << "))\n";
  }
  gp << "plot ";
  for (std::size_t i = 0; i < lines.size(); ++i)
    gp << (i ? ", \\\n     " : "") << "$d" << i << " using 1:2 with points pt 7 ps 1.5 lc " << i + 1 << " title "
       << gpString(lines[i]->line + " maxima") << ", f" << i << "(x) with lines lw 2 lc " << i + 1 << " title "
       << gpString("Gumbel, MPM " + kN(lines[i]->mpm) + " kN");
  gp << "\n";
  if (!runGnuplot(root, name, gp.str(), err)) return false;
  written.push_back(png);
  return true;
}

/// vessel_offset.png: the vessel's horizontal excursion from its start in every storm (all seeds).
bool plotOffsets(const fs::path& root, const std::string& title, const std::vector<core::CaseVesselOffset>& offsets,
                 std::vector<fs::path>& written, std::ostream& err) {
  std::vector<std::string> storms;
  for (const auto& o : offsets)
    if (std::find(storms.begin(), storms.end(), o.storm) == storms.end()) storms.push_back(o.storm);
  const fs::path png = root / "vessel_offset.png";
  std::ostringstream gp;
  gp << "# gnuplot script written by 'cable_sim sweep' (run: gnuplot vessel_offset.gp)\n" << kPngHeader
     << "set output " << gpString(png.string()) << "\n"
     << "set grid lc rgb \"#d0d0d0\"\nset key outside right top box\nset size ratio -1\n"
     << "set title " << gpString(title + ": the vessel's horizontal offset from its start (every seed)") << "\n"
     << "set xlabel \"east (world x) [m]\"\nset ylabel \"north (world y) [m]\"\n";
  for (std::size_t i = 0; i < storms.size(); ++i) {
    gp << "$s" << i << " << EOD\n";
    for (const auto& o : offsets) {
      if (o.storm != storms[i]) continue;
      for (const auto& p : o.trace) gp << csvNum(p.first) << " " << csvNum(p.second) << "\n";
      gp << "\n";  // a break between seeds
    }
    gp << "EOD\n";
  }
  gp << "plot ";
  for (std::size_t i = 0; i < storms.size(); ++i)
    gp << (i ? ", \\\n     " : "") << "$s" << i << " using 1:2 with lines lw 1 lc " << i + 1 << " title " << gpString(storms[i]);
  gp << "\n";
  if (!runGnuplot(root, "vessel_offset", gp.str(), err)) return false;
  written.push_back(png);
  return true;
}

/// The line check table: per storm, its line of largest design utilization.
void checkTable(std::ostream& md, const std::vector<core::StormLineStats>& storms, int consequence_class) {
  md << "## Line check\n\n"
     << "DNV-OS-E301 form (docs/design_analysis.md \"The line check\"), consequence class " << consequence_class
     << ": design tension T_d = γ_mean T_c,mean + γ_dyn T_c,dyn against S_c = 0.95 MBL. The line of each storm with "
        "the largest design utilization; every storm and line is in `storms.csv`.\n\n"
     << "| storm | limit state | line | mean [kN] | MPM [kN] | T_d [kN] | S_c [kN] | T_d / S_c | result |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  std::size_t checked = 0, passed = 0;
  for (const std::string& storm : stormOrder(storms)) {
    const core::StormLineStats* worst = nullptr;
    for (const auto& s : storms) {
      if (s.storm != storm || !s.checked) continue;
      ++checked;
      passed += s.design.pass ? 1 : 0;
      if (worst == nullptr || s.design.utilization > worst->design.utilization) worst = &s;
    }
    if (worst == nullptr) {
      md << "| " << storm << " | | | | | | | | no fit or no MBL |\n";
      continue;
    }
    md << "| " << storm << " | " << core::toString(worst->limit_state) << " | " << worst->line << " | "
       << kN(worst->mean_tension) << " | " << kN(worst->mpm) << " | " << kN(worst->design.design_tension) << " | "
       << kN(worst->design.strength) << " | " << fmtNum("%.3f", worst->design.utilization) << " | "
       << (worst->design.pass ? "pass" : "**FAIL**") << " |\n";
  }
  md << "\n" << passed << " of " << checked << " storm-lines pass.\n\n";
}

/// Without a line check: the most probable maximum of each storm's most loaded line.
void maximaTable(std::ostream& md, const std::vector<core::StormLineStats>& storms) {
  md << "## Most loaded lines\n\n| storm | line | seeds | MPM [kN] | largest maximum [kN] | MPM / MBL |\n"
     << "|---|---|---|---|---|---|\n";
  for (const std::string& storm : stormOrder(storms)) {
    const core::StormLineStats* worst = nullptr;
    for (const auto& s : storms)
      if (s.storm == storm && (worst == nullptr || s.max_of_max > worst->max_of_max)) worst = &s;
    md << "| " << storm << " | " << worst->line << " | " << worst->seeds << " | " << kN(worst->mpm) << " | "
       << kN(worst->max_of_max) << " | "
       << (std::isfinite(worst->mpm_utilization) ? fmtNum("%.3f", worst->mpm_utilization) : "-") << " |\n";
  }
  md << "\n";
}

}  // namespace

bool writeSweepReport(const fs::path& root, const SweepReportInput& in, std::vector<fs::path>& written,
                      std::ostream& err) {
  const core::SweepManifest& m = *in.manifest;
  std::vector<fs::path> pngs;
  if (in.plots) {
    for (const std::string& storm : stormOrder(*in.storms))
      if (!plotExceedance(root, m.name, storm, *in.storms, *in.cases, pngs, err)) return false;
    if (!in.offsets->empty() && !plotOffsets(root, m.name, *in.offsets, pngs, err)) return false;
  }
  std::ostringstream md;
  md << "# " << m.name << "\n\n"
     << in.done << " of " << m.cases.size() << " cases done, " << in.failed << " failed, " << in.pending
     << " not run (`status.csv`). Statistics of the top tension after t = " << csvNum(m.skip_time)
     << " s; most probable maxima (MPM) from a Gumbel " << core::gumbelMethodName(m.gumbel)
     << " fit of the per-seed maxima of each storm.\n\n";
  if (!in.storms->empty()) {
    if (m.design_class > 0) checkTable(md, *in.storms, m.design_class);
    else maximaTable(md, *in.storms);
  }
  if (!in.offsets->empty()) {
    md << "## Vessel offset\n\nThe body origin's horizontal distance from its start (world frame), over the seeds.\n\n"
       << "| storm | largest [m] | mean [m] |\n|---|---|---|\n";
    std::vector<std::string> storms;
    for (const auto& o : *in.offsets)
      if (std::find(storms.begin(), storms.end(), o.storm) == storms.end()) storms.push_back(o.storm);
    for (const auto& storm : storms) {
      double mx = 0.0, mean = 0.0;
      std::size_t n = 0;
      for (const auto& o : *in.offsets)
        if (o.storm == storm) {
          mx = std::max(mx, o.max);
          mean += o.mean;
          ++n;
        }
      md << "| " << storm << " | " << fmtNum("%.2f", mx) << " | " << fmtNum("%.2f", mean / static_cast<double>(n)) << " |\n";
    }
    md << "\n";
  }
  if (!pngs.empty()) {
    md << "## Plots\n\n";
    for (const auto& p : pngs) md << "![" << p.stem().string() << "](" << p.filename().string() << ")\n\n";
  }
  const fs::path report = root / "report.md";
  if (!writeFile(report, [&](std::ostream& o) { o << md.str(); }, err)) return false;
  written.push_back(report);
  written.insert(written.end(), pngs.begin(), pngs.end());
  return true;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
