// Readers of motion RAO tables: WAMIT `.4` and CSV (rao_io.hpp).
#include "mooring_dynamics/core/io/rao_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <sstream>
#include <utility>

#include "mooring_dynamics/core/io/csv_table.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {
namespace {

using yaml::formatNumber;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// The values seen for one (frequency, heading), with the line each mode came from.
struct Cell {
  std::array<std::complex<double>, RaoTable::kDofs> x{};
  std::array<std::string, RaoTable::kDofs> where{};
};

/// Collects rows into a table: keyed by (omega, heading in [0, 360)).
class Collector {
 public:
  explicit Collector(std::string source) : source_(std::move(source)) {}

  void add(double omega, double heading_deg, int dof, std::complex<double> x, const std::string& where) {
    double h = std::fmod(heading_deg, 360.0);
    if (h < 0.0) h += 360.0;
    if (h >= 360.0) h = 0.0;
    Cell& c = cells_[{omega, h}];
    if (!c.where[dof].empty()) {
      // The same heading twice (0 and 360): accepted when it carries the same value.
      const double tol = 1e-6 * std::max(1.0, std::abs(x));
      if (std::abs(c.x[dof] - x) > tol)
        throw ProblemError(where + ": " + raoDofName(dof) + " at heading " + formatNumber(heading_deg) +
                           " deg, omega " + formatNumber(omega) + " rad/s is given already (" + c.where[dof] +
                           ") with another value");
      return;
    }
    c.x[dof] = x;
    c.where[dof] = where;
  }

  /// The table; a mode missing somewhere is an error when `required` names it (bit d for mode
  /// d + 1), else zero.
  RaoTable table(const RaoSource& how, unsigned required = 0x3Fu, const char* what = "motion RAO") const {
    if (cells_.empty()) throw ProblemError(source_ + ": no " + what + " rows");
    std::vector<double> omega, heading;
    for (const auto& kv : cells_) omega.push_back(kv.first.first);
    std::sort(omega.begin(), omega.end());
    omega.erase(std::unique(omega.begin(), omega.end()), omega.end());
    for (const auto& kv : cells_) heading.push_back(kv.first.second);
    std::sort(heading.begin(), heading.end());
    heading.erase(std::unique(heading.begin(), heading.end()), heading.end());
    std::array<std::vector<std::complex<double>>, RaoTable::kDofs> values;
    for (auto& v : values) v.resize(omega.size() * heading.size());
    for (std::size_t ih = 0; ih < heading.size(); ++ih) {
      for (std::size_t iw = 0; iw < omega.size(); ++iw) {
        const auto it = cells_.find({omega[iw], heading[ih]});
        for (int d = 0; d < RaoTable::kDofs; ++d) {
          const bool missing = it == cells_.end() || it->second.where[d].empty();
          if (missing && !(required & (1u << d))) continue;
          if (missing)
            throw ProblemError(source_ + ": no " + raoDofName(d) + " (mode " + std::to_string(d + 1) +
                               ") at omega " + formatNumber(omega[iw]) + " rad/s (period " +
                               formatNumber(2.0 * kPi / omega[iw]) + " s), heading " + formatNumber(heading[ih]) +
                               " deg: the table needs every mode at every frequency and heading");
          values[d][ih * omega.size() + iw] = it->second.x[d];
        }
      }
    }
    RaoTable t;
    try {
      t = RaoTable(omega, heading, values);
    } catch (const std::invalid_argument& e) {
      throw ProblemError(source_ + ": " + e.what());
    }
    t.extend = how.extend;
    t.symmetry = how.symmetry;
    return t;
  }

 private:
  std::string source_;
  std::map<std::pair<double, double>, Cell> cells_;
};

/// The whitespace-separated numbers of a row of a WAMIT output file: false for a blank or '#'
/// line; throws naming the line when it has not `n` finite numbers (`layout` names them).
bool wamitRow(const std::string& line, const std::string& where, int n, const char* layout, double* v) {
  const std::size_t first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos || line[first] == '#') return false;
  std::istringstream cells(line);
  for (int i = 0; i < n; ++i) {
    std::string cell;
    if (!(cells >> cell))
      throw ProblemError(where + ": " + std::to_string(i) + " values, expected " + std::to_string(n) + " (" + layout + ")");
    char* end = nullptr;
    v[i] = std::strtod(cell.c_str(), &end);
    if (end == cell.c_str() || *end != '\0' || !std::isfinite(v[i]))
      throw ProblemError(where + ": value " + std::to_string(i + 1) + " = \"" + cell + "\": not a finite number");
  }
  std::string extra;
  if (cells >> extra) throw ProblemError(where + ": more than " + std::to_string(n) + " values (" + layout + ")");
  return true;
}

void checkUlen(const RaoSource& how, const std::string& source, const char* why) {
  if (!(how.ulen > 0.0) || !std::isfinite(how.ulen))
    throw ProblemError(source + ": ulen = " + formatNumber(how.ulen) + ": must be finite and > 0 (the length scale ULEN of the WAMIT run: " + why + ")");
}

/// A WAMIT period [s] as omega [rad/s]: the infinite- and zero-period rows (0, -1) are an error.
double wamitOmega(double per, const std::string& where, const char* table) {
  if (!(per > 0.0))
    throw ProblemError(where + ": period = " + formatNumber(per) + ": must be > 0 (0 and -1 are WAMIT's infinite- and zero-period limits, which a " + table + " table does not use)");
  return 2.0 * kPi / per;
}

/// A WAMIT mode number 1-6 as a 0-based dof.
int wamitMode(double mode, const std::string& where) {
  if (mode != std::floor(mode) || mode < 1.0 || mode > 6.0)
    throw ProblemError(where + ": mode = " + formatNumber(mode) + ": must be 1-6 (this reader takes one rigid body; its modes 1-6)");
  return static_cast<int>(mode) - 1;
}

/// The modes a drift table must give: surge, sway and yaw.
constexpr unsigned kDriftModes = (1u << 0) | (1u << 1) | (1u << 5);

std::complex<double> withConvention(std::complex<double> x, const RaoSource& how) {
  return how.phase_lag ? std::conj(x) : x;
}

}  // namespace

RaoTable parseWamitRaos(const std::string& text, const std::string& source, const RaoSource& how) {
  checkUlen(how, source, "rotations are given as xi ULEN / A");
  Collector col(source);
  std::istringstream in(text);
  std::string line;
  int number = 0;
  double v[7];
  while (std::getline(in, line)) {
    ++number;
    const std::string where = source + ":" + std::to_string(number);
    if (!wamitRow(line, where, 7, "PER BETA I |X| phase Re(X) Im(X) of a WAMIT .4 file", v)) continue;
    const double omega = wamitOmega(v[0], where, "motion RAO");
    const int dof = wamitMode(v[2], where);
    std::complex<double> x(v[5], v[6]);
    if (dof >= 3) x /= how.ulen;  // xi L / A -> rad per m of wave amplitude
    col.add(omega, v[1], dof, withConvention(x, how), where);
  }
  return col.table(how);
}

RaoTable parseWamitDrift(const std::string& text, const std::string& source, const RaoSource& how, double rho_g) {
  checkUlen(how, source, "forces are given as F / (rho g A^2 ULEN), moments / (rho g A^2 ULEN^2)");
  Collector col(source);
  std::istringstream in(text);
  std::string line;
  int number = 0;
  double v[8];
  while (std::getline(in, line)) {
    ++number;
    const std::string where = source + ":" + std::to_string(number);
    if (!wamitRow(line, where, 8, "PER BETA1 BETA2 I |F| phase Re(F) Im(F) of a WAMIT .8 or .9 file", v)) continue;
    const double omega = wamitOmega(v[0], where, "drift");
    const int dof = wamitMode(v[3], where);
    if (v[1] != v[2]) continue;  // a bidirectional (cross-heading) term: the mean drift uses BETA1 = BETA2
    const double scale = rho_g * (dof >= 3 ? how.ulen * how.ulen : how.ulen);
    col.add(omega, v[1], dof, std::complex<double>(v[6] * scale, 0.0), where);
  }
  return col.table(how, kDriftModes, "mean drift");
}

RaoTable parseCsvRaos(const std::string& text, const std::string& source, const RaoSource& how) {
  Collector col(source);
  for (const CsvRow& r : parseCsvTable(text, source, {"omega", "heading_deg", "dof", "amplitude", "phase_deg"})) {
    const double omega = r.values[0], mode = r.values[2], amp = r.values[3];
    if (!(omega > 0.0)) throw ProblemError(r.where + ": omega = " + formatNumber(omega) + ": must be > 0 [rad/s]");
    if (mode != std::floor(mode) || mode < 1.0 || mode > 6.0)
      throw ProblemError(r.where + ": dof = " + formatNumber(mode) + ": must be 1-6 (surge, sway, heave, roll, pitch, yaw)");
    if (!(amp >= 0.0)) throw ProblemError(r.where + ": amplitude = " + formatNumber(amp) + ": must be >= 0");
    const int dof = static_cast<int>(mode) - 1;
    const double scale = dof >= 3 && how.rotations_in_deg ? kDeg : 1.0;
    const std::complex<double> x = std::polar(amp * scale, r.values[4] * kDeg);
    col.add(omega, r.values[1], dof, withConvention(x, how), r.where);
  }
  return col.table(how);
}

RaoTable parseCsvDrift(const std::string& text, const std::string& source, const RaoSource& how) {
  Collector col(source);
  for (const CsvRow& r : parseCsvTable(text, source, {"omega", "heading_deg", "surge", "sway", "yaw"})) {
    const double omega = r.values[0];
    if (!(omega > 0.0)) throw ProblemError(r.where + ": omega = " + formatNumber(omega) + ": must be > 0 [rad/s]");
    col.add(omega, r.values[1], 0, r.values[2], r.where);
    col.add(omega, r.values[1], 1, r.values[3], r.where);
    col.add(omega, r.values[1], 5, r.values[4], r.where);
  }
  return col.table(how, kDriftModes, "mean drift");
}

RaoTable loadDrift(const RaoSource& how, double rho_g) {
  const std::string text = sections::readFileText(how.file);
  return how.format == RaoSource::Format::Wamit ? parseWamitDrift(text, how.file, how, rho_g)
                                                : parseCsvDrift(text, how.file, how);
}

RaoTable loadRaos(const RaoSource& how) {
  const std::string text = sections::readFileText(how.file);
  return how.format == RaoSource::Format::Wamit ? parseWamitRaos(text, how.file, how)
                                                : parseCsvRaos(text, how.file, how);
}

}  // namespace core
}  // namespace mooring_dynamics
