// gnuplot helpers shared by 'cable_sim plot', the vessel commands and 'sweep'.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

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

bool runGnuplot(const fs::path& dir, const std::string& name, const std::string& script, std::ostream& err) {
  if (!gnuplotAvailable()) {
    err << kProg << ": error: gnuplot not found; install it with scripts/setup (Debian package gnuplot-nox)\n";
    return false;
  }
  const fs::path gp = dir / (name + ".gp"), log = dir / (name + ".log");
  if (!writeFile(gp, [&](std::ostream& f) { f << script; }, err)) return false;
  const std::string cmd = "gnuplot " + shellQuote(gp.string()) + " >" + shellQuote(log.string()) + " 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::ifstream f(log);
    std::ostringstream ss;
    ss << f.rdbuf();
    err << kProg << ": error: gnuplot failed on " << gp.string() << ":\n" << ss.str();
    return false;
  }
  std::error_code ec;
  fs::remove(log, ec);
  return true;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
