// Tables of numbers in CSV (motion tables, ship tracks): one row per line, cells separated by
// commas; blank lines, lines starting with '#' and a header line starting with a letter are
// skipped. Every cell must be a finite number.
#pragma once

#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

struct CsvRow {
  int line = 0;                ///< 1-based line number in the source
  std::vector<double> values;  ///< one per column
  std::string where;           ///< "source:line", for messages
};

/// Rows of exactly `columns.size()` cells. Throws ProblemError naming the source, the line, the
/// column and the cell for a malformed number, a row of another width, or when there is no row.
std::vector<CsvRow> parseCsvTable(const std::string& text, const std::string& source,
                                  const std::vector<std::string>& columns);

}  // namespace core
}  // namespace mooring_dynamics
