#include "mooring_dynamics/core/io/csv_table.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace core {

namespace {
std::string joined(const std::vector<std::string>& columns) {
  std::string s;
  for (const auto& c : columns) s += (s.empty() ? "" : ", ") + c;
  return s;
}

double cellValue(const std::string& cell, const std::string& where, const std::string& column) {
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(cell.c_str(), &end);
  const std::string rest = end ? std::string(end) : std::string();
  if (end == cell.c_str() || rest.find_first_not_of(" \t") != std::string::npos || errno == ERANGE || !std::isfinite(x))
    throw ProblemError(where + ": column " + column + " = \"" + cell + "\": not a finite number");
  return x;
}
}  // namespace

std::vector<CsvRow> parseCsvTable(const std::string& text, const std::string& source,
                                  const std::vector<std::string>& columns) {
  std::vector<CsvRow> rows;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#' || std::isalpha(static_cast<unsigned char>(line[first])))
      continue;
    CsvRow row;
    row.line = number;
    row.where = source + ":" + std::to_string(number);
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const std::size_t col = row.values.size();
      row.values.push_back(cellValue(cell, row.where, col < columns.size() ? columns[col] : "extra"));
    }
    if (row.values.size() != columns.size())
      throw ProblemError(row.where + ": " + std::to_string(row.values.size()) + " values, expected " +
                         std::to_string(columns.size()) + " (" + joined(columns) + ")");
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw ProblemError(source + ": no rows (expected " + joined(columns) + ")");
  return rows;
}

}  // namespace core
}  // namespace mooring_dynamics
