#include "mooring_dynamics/core/io/vessel_motion_io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {

namespace {
const char* const kColumns[14] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz"};
}  // namespace

std::vector<PoseSample> parseVesselMotionTable(const std::string& text, const std::string& source) {
  std::vector<PoseSample> rows;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#' || line[first] == 't') continue;
    const std::string where = source + ":" + std::to_string(number);
    std::vector<double> v;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const std::size_t col = v.size();
      const char* name = col < 14 ? kColumns[col] : "extra";
      char* end = nullptr;
      errno = 0;
      const double x = std::strtod(cell.c_str(), &end);
      const std::string rest = end ? std::string(end) : std::string();
      if (end == cell.c_str() || rest.find_first_not_of(" \t") != std::string::npos || errno == ERANGE ||
          !std::isfinite(x))
        throw ProblemError(where + ": column " + name + " = \"" + cell + "\": not a finite number");
      v.push_back(x);
    }
    if (v.size() != 8 && v.size() != 14)
      throw ProblemError(where + ": " + std::to_string(v.size()) +
                         " values, expected 8 (t, x, y, z, qx, qy, qz, qw) or 14 (the same, then vx, vy, vz, wx, wy, "
                         "wz: the body-frame twist)");
    if (!rows.empty() && (v.size() == 14) != rows.front().has_twist)
      throw ProblemError(where + ": " + std::to_string(v.size()) + " values, the first row " +
                         (rows.front().has_twist ? "14" : "8") + ": every row has the same columns");
    PoseSample s;
    s.t = v[0];
    s.pose.position = Eigen::Vector3d(v[1], v[2], v[3]);
    s.pose.orientation = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
    if (v.size() == 14) {
      s.has_twist = true;
      s.twist.linear = Eigen::Vector3d(v[8], v[9], v[10]);
      s.twist.angular = Eigen::Vector3d(v[11], v[12], v[13]);
    }
    const std::string bad = s.pose.validate("row");
    if (!bad.empty()) throw ProblemError(where + ": " + bad);
    s.pose.orientation.normalize();
    if (!rows.empty() && !(s.t > rows.back().t))
      throw ProblemError(where + ": t = " + std::to_string(s.t) + " s must be after the previous row's " +
                         std::to_string(rows.back().t) + " s");
    rows.push_back(s);
  }
  if (rows.empty()) throw ProblemError(source + ": no rows (expected t, x, y, z, qx, qy, qz, qw[, vx, vy, vz, wx, wy, wz])");
  return rows;
}

std::vector<PoseSample> loadVesselMotionTable(const std::string& path) {
  return parseVesselMotionTable(sections::readFileText(path), path);
}

}  // namespace core
}  // namespace mooring_dynamics
