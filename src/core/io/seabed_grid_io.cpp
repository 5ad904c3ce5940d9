#include "mooring_dynamics/core/io/seabed_grid_io.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

namespace mooring_dynamics {
namespace core {

namespace {

constexpr long long kMaxCount = 10000000;  // grid points per direction; guards against absurd headers

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// The whitespace-separated tokens of a line with any '#' comment removed.
std::vector<std::string> tokens(const std::string& line) {
  const std::string body = line.substr(0, line.find('#'));
  std::istringstream is(body);
  std::vector<std::string> out;
  for (std::string t; is >> t;) out.push_back(t);
  return out;
}

/// A whole token as a double (locale independent); false if it is not a number.
bool parseNumber(const std::string& t, double& v) {
  const char* b = t.data();
  const char* e = b + t.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, v);
  return r.ec == std::errc() && r.ptr == e;
}

class GridReader {
 public:
  explicit GridReader(const std::string& name) : name_(name) {}

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw ProblemError(name_ + ":" + std::to_string(line) + ": " + what);
  }

  /// A finite number, or an error "<what> = <token>: <constraint>".
  double number(int line, const std::string& what, const std::string& t) const {
    double v = 0.0;
    if (!parseNumber(t, v)) fail(line, what + " = \"" + t + "\": not a number");
    if (!std::isfinite(v)) fail(line, what + " = " + t + ": must be finite");
    return v;
  }

 private:
  std::string name_;
};

}  // namespace

SeabedGrid readSeabedGrid(std::istream& in, const std::string& name) {
  const GridReader rd(name);
  SeabedGrid g;
  g.source = name;
  bool have_header = false;
  std::size_t rows = 0;
  int line_no = 0, last_line = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const std::vector<std::string> tk = tokens(line);
    if (tk.empty()) continue;
    last_line = line_no;
    if (!have_header) {
      if (tk.size() != 6)
        rd.fail(line_no, "header has " + std::to_string(tk.size()) +
                             " values: expected 6, x0 y0 dx dy nx ny");
      g.x0 = rd.number(line_no, "x0", tk[0]);
      g.y0 = rd.number(line_no, "y0", tk[1]);
      g.dx = rd.number(line_no, "dx", tk[2]);
      if (!(g.dx > 0.0)) rd.fail(line_no, "dx = " + tk[2] + ": must be > 0");
      g.dy = rd.number(line_no, "dy", tk[3]);
      if (!(g.dy > 0.0)) rd.fail(line_no, "dy = " + tk[3] + ": must be > 0");
      const char* names[2] = {"nx", "ny"};
      std::size_t* counts[2] = {&g.nx, &g.ny};
      for (int k = 0; k < 2; ++k) {
        const std::string& t = tk[4 + static_cast<std::size_t>(k)];
        const double v = rd.number(line_no, names[k], t);
        if (v != std::floor(v) || v < 2.0 || v > static_cast<double>(kMaxCount))
          rd.fail(line_no, std::string(names[k]) + " = " + t + ": must be an integer in [2, " +
                               std::to_string(kMaxCount) + "]");
        *counts[k] = static_cast<std::size_t>(v);
      }
      have_header = true;
      continue;
    }
    const std::string row = "row " + std::to_string(rows) + " (y = " +
                            fmt(g.y0 + static_cast<double>(rows) * g.dy) + " m)";
    if (rows == g.ny)
      rd.fail(line_no, "more than ny = " + std::to_string(g.ny) + " rows of depths (the header says ny = " +
                           std::to_string(g.ny) + ")");
    if (tk.size() != g.nx)
      rd.fail(line_no, row + " has " + std::to_string(tk.size()) + " depths: expected nx = " + std::to_string(g.nx));
    for (std::size_t i = 0; i < tk.size(); ++i) {
      const std::string what = row + ", column " + std::to_string(i) + " (x = " +
                               fmt(g.x0 + static_cast<double>(i) * g.dx) + " m): depth";
      const double d = rd.number(line_no, what, tk[i]);
      if (!(d > 0.0)) rd.fail(line_no, what + " = " + tk[i] + ": must be > 0 (depth below the mean surface, positive down)");
      g.depths.push_back(d);
    }
    ++rows;
  }
  if (in.bad()) throw ProblemError(name + ": read error");
  if (!have_header) throw ProblemError(name + ": no header line: expected x0 y0 dx dy nx ny, then ny rows of nx depths");
  if (rows < g.ny)
    rd.fail(last_line, "the file ends after " + std::to_string(rows) + " rows of depths: expected ny = " +
                           std::to_string(g.ny));
  return g;
}

SeabedGrid loadSeabedGrid(const std::string& path) {
  // A device or a pipe (/dev/zero, /dev/stdin) may never end: grids are files.
  std::error_code fec;
  if (std::filesystem::exists(path, fec) && !std::filesystem::is_regular_file(path, fec))
    throw ProblemError(path + ": not a regular file (a seabed grid is read from a file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const std::error_code ec(errno, std::generic_category());
    throw ProblemError(path + ": cannot read file (" + ec.message() + ")");
  }
  return readSeabedGrid(in, path);
}

}  // namespace core
}  // namespace mooring_dynamics
