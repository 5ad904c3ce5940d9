// Summary statistics of a sweep's cases (see sweep_summary.hpp).
#include "mooring_dynamics/core/io/sweep_summary.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A CSV file with a header row of names and rows of numbers.
struct Table {
  std::string path;
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;

  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw ProblemError(path + ": no column '" + name + "' in the header");
  }
  bool has(const std::string& name) const { return std::find(header.begin(), header.end(), name) != header.end(); }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

Table readTable(const std::string& path) {
  Table t;
  t.path = path;
  std::istringstream in(sections::readFileText(path));
  std::string line;
  if (!std::getline(in, line)) throw ProblemError(path + ": empty file");
  t.header = split(line);
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line == "\r") continue;
    const auto cells = split(line);
    if (cells.size() != t.header.size())
      throw ProblemError(path + " line " + std::to_string(lineno) + ": " + std::to_string(cells.size()) +
                         " values, the header has " + std::to_string(t.header.size()));
    std::vector<double> row;
    for (const auto& c : cells) {
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      if (c.empty() || *end != '\0')
        throw ProblemError(path + " line " + std::to_string(lineno) + ": '" + c + "' is not a number");
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
  }
  if (t.rows.empty()) throw ProblemError(path + ": no data rows");
  return t;
}

/// The smallest mbl of the materials of `segments`; 0 when one has none.
double weakestMbl(const std::vector<Segment>& segments, const std::vector<Material>& materials) {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& s : segments) {
    const double b = s.material < materials.size() ? materials[s.material].mbl : 0.0;
    if (!(b > 0.0)) return 0.0;
    m = std::min(m, b);
  }
  return std::isfinite(m) ? m : 0.0;
}

struct LineSeries {
  std::string name;
  std::size_t tension = 0;             ///< column of its top tension
  bool has_top = false;                ///< columns of its top's horizontal position
  std::size_t x = 0, y = 0;
  bool has_y = false;
  double mbl = 0.0;
};

CaseLineStats statsOf(const Table& t, const LineSeries& l, double skip_time) {
  CaseLineStats s;
  s.line = l.name;
  s.mbl = l.mbl;
  double sum = 0.0, mx = -std::numeric_limits<double>::infinity();
  std::vector<double> used;
  for (const auto& r : t.rows)
    if (r[0] >= skip_time) used.push_back(r[l.tension]);
  if (used.empty())
    throw ProblemError(t.path + ": no sample at t >= skip_time = " + std::to_string(skip_time) + " s");
  for (double v : used) {
    sum += v;
    mx = std::max(mx, v);
  }
  s.samples = used.size();
  s.mean = sum / static_cast<double>(used.size());
  double var = 0.0;
  for (double v : used) var += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(var / static_cast<double>(used.size()));
  s.max = mx;
  s.utilization = s.mbl > 0.0 ? s.max / s.mbl : kNaN;
  s.top_offset = kNaN;
  if (l.has_top) {
    const double x0 = t.rows.front()[l.x], y0 = l.has_y ? t.rows.front()[l.y] : 0.0;
    double off = 0.0;
    for (const auto& r : t.rows)
      if (r[0] >= skip_time) off = std::max(off, std::hypot(r[l.x] - x0, l.has_y ? r[l.y] - y0 : 0.0));
    s.top_offset = off;
  }
  return s;
}

std::string num(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  return std::string(buf, r.ptr);
}

/// A CSV cell: names are letters, digits and '_.+-' (case names) or line names, quoted when needed.
std::string cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::vector<CaseLineStats> caseLineStats(const std::string& problem_path, const std::string& result_dir,
                                         double skip_time, const std::string& case_name, const std::string& storm) {
  std::vector<LineSeries> lines;
  Table t;
  const fs::path dir(result_dir);
  if (isSystemFile(problem_path)) {
    const SystemProblem s = loadSystemFromFile(problem_path);
    const bool vessel = s.vessel.present && s.hasVesselPoints();
    t = readTable((dir / (vessel ? "vessel_timeseries.csv" : "system_timeseries.csv")).string());
    for (const auto& sl : s.lines) {
      LineSeries l;
      l.name = sl.name;
      l.tension = t.column(sl.name + "_top_tension");
      l.mbl = weakestMbl(sl.segments, s.materials);
      const SystemPoint& top = s.points[sl.to];
      if (!vessel && top.free()) {
        l.has_top = l.has_y = true;
        l.x = t.column(top.name + "_x");
        l.y = t.column(top.name + "_y");
      }
      lines.push_back(l);
    }
  } else {
    const Problem p = loadProblemFromFile(problem_path);
    t = readTable((dir / "timeseries.csv").string());
    LineSeries l;
    l.name = "line";  // one line: the same name in every case (the problem name may vary)
    l.tension = t.column("top_tension");
    l.mbl = weakestMbl(p.segments, p.materials);
    l.has_top = true;
    l.x = t.column("top_x");
    l.has_y = t.has("top_y");
    if (l.has_y) l.y = t.column("top_y");
    lines.push_back(l);
  }
  if (t.header.empty() || t.header[0] != "t") throw ProblemError(t.path + ": the first column is not t");
  std::vector<CaseLineStats> out;
  for (const auto& l : lines) {
    CaseLineStats s = statsOf(t, l, skip_time);
    s.case_name = case_name;
    s.storm = storm;
    out.push_back(s);
  }
  return out;
}

bool caseVesselOffset(const std::string& result_dir, double skip_time, const std::string& case_name,
                      const std::string& storm, std::size_t stride, CaseVesselOffset& out) {
  const fs::path file = fs::path(result_dir) / "vessel_timeseries.csv";
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  const Table t = readTable(file.string());
  if (!t.has("vessel_x") || !t.has("vessel_y")) return false;
  const std::size_t ix = t.column("vessel_x"), iy = t.column("vessel_y");
  out = CaseVesselOffset();
  out.case_name = case_name;
  out.storm = storm;
  const double x0 = t.rows.front()[ix], y0 = t.rows.front()[iy];
  std::size_t n = 0;
  double sum = 0.0;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const auto& r = t.rows[k];
    if (r[0] < skip_time) continue;
    const double dx = r[ix] - x0, dy = r[iy] - y0, o = std::hypot(dx, dy);
    out.max = std::max(out.max, o);
    sum += o;
    if (n % std::max<std::size_t>(stride, 1) == 0) out.trace.emplace_back(dx, dy);
    ++n;
  }
  if (n == 0) throw ProblemError(file.string() + ": no sample at t >= skip_time = " + std::to_string(skip_time) + " s");
  out.mean = sum / static_cast<double>(n);
  return true;
}

void writeCaseVesselOffsetCsv(std::ostream& out, const std::vector<CaseVesselOffset>& rows) {
  out << "case,storm,max_offset,mean_offset\n";
  for (const auto& r : rows) out << cell(r.case_name) << "," << cell(r.storm) << "," << num(r.max) << "," << num(r.mean) << "\n";
}

std::vector<StormLineStats> stormLineStats(const std::vector<CaseLineStats>& cases, GumbelMethod method) {
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::vector<const CaseLineStats*>> groups;
  for (const auto& c : cases) {
    const auto key = std::make_pair(c.storm, c.line);
    if (groups.find(key) == groups.end()) order.push_back(key);
    groups[key].push_back(&c);
  }
  std::vector<StormLineStats> out;
  for (const auto& key : order) {
    const auto& g = groups[key];
    StormLineStats s;
    s.storm = key.first;
    s.line = key.second;
    s.seeds = g.size();
    s.mbl = g.front()->mbl;
    std::vector<double> maxima;
    double mean_sum = 0.0;
    for (const auto* c : g) {
      maxima.push_back(c->max);
      mean_sum += c->mean;
      if (c->mbl != s.mbl) s.mbl = 0.0;  // different materials across seeds: no single MBL
    }
    double sum = 0.0;
    s.max_of_max = *std::max_element(maxima.begin(), maxima.end());
    for (double v : maxima) sum += v;
    s.mean_of_max = sum / static_cast<double>(maxima.size());
    double var = 0.0;
    for (double v : maxima) var += (v - s.mean_of_max) * (v - s.mean_of_max);
    s.std_of_max = maxima.size() > 1 ? std::sqrt(var / static_cast<double>(maxima.size() - 1)) : kNaN;
    s.fitted = maxima.size() >= 2;
    if (s.fitted) {
      s.fit = fitGumbel(maxima, method);
      s.mpm = mostProbableMaximum(s.fit);
    } else {
      s.mpm = kNaN;
    }
    s.mpm_utilization = s.mbl > 0.0 && s.fitted ? s.mpm / s.mbl : kNaN;
    s.mean_tension = mean_sum / static_cast<double>(g.size());
    out.push_back(s);
  }
  return out;
}

void writeCaseLineStatsCsv(std::ostream& out, const std::vector<CaseLineStats>& rows) {
  out << "case,storm,line,samples,max_tension,mean_tension,std_tension,mbl,utilization,top_offset\n";
  for (const auto& r : rows)
    out << cell(r.case_name) << "," << cell(r.storm) << "," << cell(r.line) << "," << r.samples << "," << num(r.max)
        << "," << num(r.mean) << "," << num(r.std) << "," << (r.mbl > 0.0 ? num(r.mbl) : std::string()) << ","
        << num(r.utilization) << "," << num(r.top_offset) << "\n";
}

void designCheckStorms(std::vector<StormLineStats>& rows, const std::vector<bool>& als, int consequence_class) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    StormLineStats& r = rows[i];
    r.checked = r.fitted && r.mbl > 0.0;
    if (!r.checked) continue;
    r.limit_state = i < als.size() && als[i] ? LimitState::Als : LimitState::Uls;
    r.design = designCheck(r.mean_tension, r.mpm, r.mbl, dnvFactors(consequence_class, r.limit_state));
  }
}

void writeStormLineStatsCsv(std::ostream& out, const std::vector<StormLineStats>& rows, GumbelMethod method) {
  out << "storm,line,seeds,max_of_max,mean_of_max,std_of_max,gumbel_fit,gumbel_location,gumbel_scale,mpm,mbl,"
         "mpm_utilization,mean_tension,limit_state,t_c_mean,t_c_dyn,design_tension,characteristic_strength,"
         "design_utilization,design_pass\n";
  for (const auto& r : rows) {
    out << cell(r.storm) << "," << cell(r.line) << "," << r.seeds << "," << num(r.max_of_max) << ","
        << num(r.mean_of_max) << "," << num(r.std_of_max) << "," << (r.fitted ? gumbelMethodName(method) : "") << ","
        << (r.fitted ? num(r.fit.location) : std::string()) << "," << (r.fitted ? num(r.fit.scale) : std::string())
        << "," << num(r.mpm) << "," << (r.mbl > 0.0 ? num(r.mbl) : std::string()) << "," << num(r.mpm_utilization)
        << "," << num(r.mean_tension) << ",";
    if (r.checked)
      out << toString(r.limit_state) << "," << num(r.design.t_mean) << "," << num(r.design.t_dyn) << ","
          << num(r.design.design_tension) << "," << num(r.design.strength) << "," << num(r.design.utilization) << ","
          << (r.design.pass ? "pass" : "FAIL");
    else
      out << ",,,,,,";
    out << "\n";
  }
}

}  // namespace core
}  // namespace mooring_dynamics
