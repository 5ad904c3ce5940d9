// gnuplot helpers shared by 'cable_sim plot' and the vessel commands.
#include <cstdlib>
#include <string>

#include "cli_common.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// A double-quoted gnuplot string (backslash escapes are processed in double quotes).
std::string gpString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
