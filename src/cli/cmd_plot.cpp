// cable_sim plot: render the result files of 'cable_sim dynamic --out DIR' with gnuplot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cli_common.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {
namespace {

/// A CSV file with a header: column names and rows of numbers.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;

  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

/// Read `path`; on failure returns false with `why` set. Every named column must be present.
bool readCsv(const fs::path& path, const std::vector<std::string>& required, CsvTable& t, std::string& why) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    why = "cannot read '" + path.string() + "'";
    return false;
  }
  std::string line;
  if (!std::getline(f, line)) {
    why = "'" + path.string() + "' is empty";
    return false;
  }
  t.header = splitCsv(line);
  for (const auto& c : required)
    if (t.column(c) < 0) {
      why = "'" + path.string() + "': no column '" + c + "' in the header";
      return false;
    }
  std::size_t lineno = 1;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = splitCsv(line);
    if (cells.size() != t.header.size()) {
      why = "'" + path.string() + "' line " + std::to_string(lineno) + ": " + std::to_string(cells.size()) +
            " values, the header has " + std::to_string(t.header.size());
      return false;
    }
    std::vector<double> row;
    for (const auto& c : cells) {
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      if (c.empty() || *end != '\0') {
        why = "'" + path.string() + "' line " + std::to_string(lineno) + ": '" + c + "' is not a number";
        return false;
      }
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
  }
  if (t.rows.empty()) {
    why = "'" + path.string() + "' has no data rows";
    return false;
  }
  return true;
}

/// Value of `"key": ...` in our own dynamic_summary.json (flat, as cmd_dynamic.cpp writes it); empty
/// if absent.
std::string jsonField(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const auto p = json.find(k);
  if (p == std::string::npos) return "";
  std::size_t i = p + k.size();
  if (i < json.size() && json[i] == '"') {
    std::string v;
    for (++i; i < json.size() && json[i] != '"'; ++i) {
      if (json[i] == '\\' && i + 1 < json.size()) {
        ++i;
        v += json[i] == 'n' ? '\n' : json[i] == 't' ? '\t' : json[i];
      } else {
        v += json[i];
      }
    }
    return v;
  }
  const auto e = json.find_first_of(",}\n", i);
  return json.substr(i, e == std::string::npos ? std::string::npos : e - i);
}

/// Colours from dark blue through teal to yellow (viridis-like), f in [0, 1].
std::string rampColour(double f) {
  static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  f = std::clamp(f, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(f));
  const double w = f - i;
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(std::lround(stops[i][0] + w * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + w * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + w * (stops[i + 1][2] - stops[i][2]))));
  return buf;
}

constexpr std::size_t kMaxShapes = 8;  ///< snapshot times drawn in shapes.png

/// What `cable_sim plot` reads from a `dynamic --out` directory.
struct PlotInputs {
  CsvTable ts, snaps, stat;
  bool have_snaps = false, have_static = false;
  std::string name, scheme, dt, static_top;
  bool stopped = false;
};

/// Reads the run's CSV files and summary; false with the error written to `err`.
bool readPlotInputs(const fs::path& dir, PlotInputs& in, std::ostream& err) {
  std::string why;
  if (!readCsv(dir / "timeseries.csv", {"t", "top_tension"}, in.ts, why)) {
    err << kProg << ": error: " << why << " (run 'cable_sim dynamic PROBLEM.yaml --out " << dir.string()
        << "' first)\n";
    return false;
  }
  in.have_snaps = fs::exists(dir / "snapshots.csv");
  if (in.have_snaps && !readCsv(dir / "snapshots.csv", {"t", "x", "z"}, in.snaps, why)) {
    err << kProg << ": error: " << why << "\n";
    return false;
  }
  in.have_static = fs::exists(dir / "static_nodes.csv");
  if (in.have_static && !readCsv(dir / "static_nodes.csv", {"x", "z"}, in.stat, why)) {
    err << kProg << ": error: " << why << "\n";
    return false;
  }
  std::string summary;
  {
    std::ifstream f(dir / "dynamic_summary.json", std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    summary = ss.str();
  }
  in.name = jsonField(summary, "problem");
  if (in.name.empty()) in.name = fs::absolute(dir).lexically_normal().filename().string();
  in.scheme = jsonField(summary, "name");
  in.dt = jsonField(summary, "dt");
  in.stopped = jsonField(summary, "completed") == "false";
  in.static_top = jsonField(summary, "static_top_tension");
  return true;
}

/// The snapshot times to draw: up to kMaxShapes, evenly spread, first and last included.
std::vector<double> shapeTimes(const PlotInputs& in) {
  std::vector<double> times;
  if (in.have_snaps) {
    const int c = in.snaps.column("t");
    for (const auto& r : in.snaps.rows)
      if (times.empty() || r[c] != times.back()) times.push_back(r[c]);
  }
  if (times.size() <= kMaxShapes) return times;
  std::vector<double> chosen;
  for (std::size_t i = 0; i < kMaxShapes; ++i)
    chosen.push_back(times[(i * (times.size() - 1) + (kMaxShapes - 1) / 2) / (kMaxShapes - 1)]);
  return chosen;
}

/// The gnuplot commands of top_tension.png (in kN when the tension reaches 10 kN).
void tensionPlot(const PlotInputs& in, const fs::path& png, std::ostream& gp) {
  const int tcol = in.ts.column("t"), Tcol = in.ts.column("top_tension");
  double tmax = 0.0;
  for (const auto& r : in.ts.rows) tmax = std::max(tmax, std::fabs(r[Tcol]));
  const bool kilo = tmax >= 1.0e4;
  const double scale = kilo ? 1.0e-3 : 1.0;
  const std::string tunit = kilo ? "kN" : "N";
  gp << "$tension << EOD\n";
  for (const auto& r : in.ts.rows) gp << csvNum(r[tcol]) << " " << csvNum(r[Tcol] * scale) << "\n";
  gp << "EOD\n";
  std::string title = in.name + ": top tension";
  if (!in.scheme.empty()) title += " (scheme " + in.scheme + (in.dt.empty() ? "" : ", dt = " + in.dt + " s") + ")";
  gp << "set output " << gpString(png.string()) << "\n"
     << "set title " << gpString(title) << "\n"
     << "set xlabel \"time t [s]\"\n"
     << "set ylabel " << gpString("top tension [" + tunit + "]") << "\n";
  if (in.stopped)
    gp << "set label 1 \"run stopped early (did not complete)\" at graph 0.02, graph 0.95 tc rgb \"#c00000\"\n";
  gp << "plot $tension using 1:2 with lines lw 2 lc rgb \"#1f4e9c\" title \"top tension\"";
  char* end = nullptr;
  const double st = std::strtod(in.static_top.c_str(), &end);
  if (!in.static_top.empty() && *end == '\0' && std::isfinite(st))
    gp << ", " << csvNum(st * scale) << " with lines dt 2 lw 1.5 lc rgb \"#555555\" title \"static\"";
  gp << "\nunset label 1\n\n";
}

/// The gnuplot commands of shapes.png: the static shape and the line at the `chosen` times.
void shapesPlot(const PlotInputs& in, const std::vector<double>& chosen, const fs::path& png, std::ostream& gp) {
  std::vector<std::string> curves;
  if (in.have_static) {
    const int xc = in.stat.column("x"), zc = in.stat.column("z");
    gp << "$static << EOD\n";
    for (const auto& r : in.stat.rows) gp << csvNum(r[xc]) << " " << csvNum(r[zc]) << "\n";
    gp << "EOD\n";
    curves.push_back("$static using 1:2 with lines dt 2 lw 2.5 lc rgb \"#000000\" title \"static\"");
  }
  const int tc = in.snaps.column("t"), xc = in.snaps.column("x"), zc = in.snaps.column("z");
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    gp << "$shape" << k << " << EOD\n";
    for (const auto& r : in.snaps.rows)
      if (r[tc] == chosen[k]) gp << csvNum(r[xc]) << " " << csvNum(r[zc]) << "\n";
    gp << "EOD\n";
    const double f = chosen.size() > 1 ? static_cast<double>(k) / static_cast<double>(chosen.size() - 1) : 0.0;
    curves.push_back("$shape" + std::to_string(k) + " using 1:2 with lines lw 1.8 lc rgb \"" + rampColour(f) +
                     "\" title " + gpString("t = " + fmtNum("%g", chosen[k]) + " s"));
  }
  gp << "set output " << gpString(png.string()) << "\n"
     << "set title " << gpString(in.name + ": line shape" + (chosen.empty() ? " (static)" : " at snapshot times")) << "\n"
     << "set xlabel \"x [m]\"\n"
     << "set ylabel \"z [m]  (z = 0: mean sea surface)\"\n"
     << "set key outside right top box\n"
     << "set arrow 1 from graph 0, first 0 to graph 1, first 0 nohead lc rgb \"#4a90d9\" dt 3\n"
     << "plot ";
  for (std::size_t i = 0; i < curves.size(); ++i) gp << (i ? ", \\\n     " : "") << curves[i];
  gp << "\n";
}

/// Runs gnuplot on `script`; false, with its log written to `err`, when it fails or a PNG is
/// missing.
bool runGnuplot(const fs::path& script, const std::vector<fs::path>& pngs, std::ostream& err) {
  const fs::path log = script.parent_path() / "plot.log";
  const std::string cmd = "gnuplot " + shellQuote(script.string()) + " >" + shellQuote(log.string()) + " 2>&1";
  const int rc = std::system(cmd.c_str());
  std::string log_text;
  {
    std::ifstream f(log, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    log_text = ss.str();
  }
  bool written = rc == 0;
  for (const fs::path& png : pngs) written = written && fs::exists(png);
  if (!written) {
    err << kProg << ": error: gnuplot failed on " << script.string() << ":\n" << log_text;
    return false;
  }
  std::error_code ec;
  fs::remove(log, ec);
  return true;
}

}  // namespace

int runPlot(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (args.positionals.size() != 1)
    throw UsageError(args.positionals.empty() ? "missing DIR (the --out directory of 'dynamic')"
                                              : "expected one directory, got " +
                                                    std::to_string(args.positionals.size()) + " arguments");
  const fs::path dir(args.positionals.front());
  const std::string png_arg = args.has("out") ? args.values.at("out") : std::string();
  if (args.has("out") && png_arg.empty()) throw UsageError("option '--out' needs a directory, got ''");
  const fs::path png_dir = png_arg.empty() ? dir : fs::path(png_arg);

  PlotInputs in;
  if (!readPlotInputs(dir, in, err)) return kExitBadInput;
  if (!gnuplotAvailable()) {
    err << kProg << ": error: gnuplot not found; install it with scripts/setup (Debian package gnuplot-nox)\n";
    return kExitIo;
  }
  if (!makeOutputDir(png_dir, err)) return kExitIo;

  const std::vector<double> chosen = shapeTimes(in);
  const bool want_shapes = !chosen.empty() || in.have_static;
  const fs::path tension_png = png_dir / "top_tension.png";
  const fs::path shapes_png = png_dir / "shapes.png";
  const fs::path script = png_dir / "plot.gp";
  std::ostringstream gp;
  gp << "# gnuplot script written by 'cable_sim plot' (run: gnuplot plot.gp)\n"
     << "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
     << "  set terminal pngcairo noenhanced size 1100,650 font \"sans,12\"\n"
     << "} else {\n"
     << "  set terminal png noenhanced size 1100,650\n"
     << "}\n"
     << "set grid lc rgb \"#d0d0d0\"\n"
     << "set key top right box opaque\n\n";
  tensionPlot(in, tension_png, gp);
  if (want_shapes) shapesPlot(in, chosen, shapes_png, gp);

  if (!writeFile(script, [&](std::ostream& f) { f << gp.str(); }, err)) return kExitIo;
  std::vector<fs::path> pngs = {tension_png};
  if (want_shapes) pngs.push_back(shapes_png);
  if (!runGnuplot(script, pngs, err)) return kExitIo;
  out << "wrote " << tension_png.string();
  if (want_shapes) out << " and " << shapes_png.string();
  out << " (gnuplot script: " << script.string() << ")\n";
  if (!want_shapes)
    out << "no snapshots.csv or static_nodes.csv in " << dir.string()
        << ": shapes.png not drawn (set dynamics.snapshot_interval)\n";
  return kExitOk;
}


}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
