// The text of a problem, sweep or table file before the YAML reader builds anything from it
// (problem_sections.hpp): a file read with a size cap, the input-size limit, the guards against
// texts that make yaml-cpp loop or read several documents, one YAML document with the syntax
// error's line and column, and paths relative to the problem file's folder.
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {
namespace sections {

using namespace yaml;

/// yaml-cpp 0.7 loops without end, allocating, on a flow-entry ',' outside any flow collection
/// in some parser states (a document starting with ", x"; "- a\n, b"; found by scripts/fuzz).
/// In block context a line cannot start with ',' (an indicator, not a scalar), so such a line is
/// a syntax error: refused before yaml-cpp sees it. Flow depth is tracked outside quotes and
/// comments; the rare multi-line plain or block scalar whose next line starts with ',' is
/// refused too.
void rejectStrayFlowEntry(const std::string& text) {
  int depth = 0;
  char quote = 0;
  bool line_start = true, after_quote = false;
  int line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = true;
      if (!quote) after_quote = false;
      continue;
    }
    if (quote) {
      if (quote == '"' && c == '\\') ++i;
      else if (c == quote) quote = 0, after_quote = true;
      continue;
    }
    if ((line_start || after_quote) && (c == ' ' || c == '\t' || c == '\r')) continue;
    // `"x", y` outside a flow collection loops yaml-cpp as well (a third fuzz timeout).
    if ((line_start || after_quote) && c == ',' && depth == 0)
      throw ProblemError("YAML syntax error at line " + std::to_string(line) +
                         ": ',' outside a flow collection [...] or {...}");
    line_start = false;
    after_quote = false;
    if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n')) {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;  // comment to the end of the line
    } else if ((c == '"' || c == '\'') &&
               (i == 0 || std::string(" \t\n[{,:-?").find(text[i - 1]) != std::string::npos)) {
      quote = c;  // a quoted scalar starts after an indicator or a blank, not inside "Gobat's"
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

/// Counts the YAML documents of `text`, stopping at two: a problem file holds one. Not
/// YAML::LoadAll: in yaml-cpp 0.7 its loop over documents never ends when the parser returns a
/// null "document" without consuming a token (yaml-cpp PR 1319; the fourth fuzz timeout, a
/// quote-comma line), allocating until memory runs out. Events are ignored here: the tree is
/// built by YAML::Load, which reads the first document only.
class DocumentCounter : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  static int count(const std::string& text) {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentCounter ignore;
    int documents = 0;
    while (documents < 2 && parser.HandleNextDocument(ignore)) ++documents;
    return documents;
  }
};

/// The lines of `text` from a top-level `key:` to the next top-level key, behind as many empty
/// lines as precede it (so that the YAML reader's line numbers are the file's); "" without one.
std::string topLevelBlock(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line, block;
  int before = 0;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside) {
      if (line.compare(0, key.size() + 1, key + ":") == 0) {
        inside = true;
        block.assign(static_cast<std::size_t>(before), '\n');
        block += line + "\n";
      } else {
        ++before;
      }
      continue;
    }
    if (!line.empty() && line[0] != ' ' && line[0] != '\t' && line[0] != '#' && line[0] != '\r') break;
    block += line + "\n";
  }
  return block;
}

/// limits.max_input_mb, checked on the text before the YAML reader parses it all (its cost is
/// the text's size); the file's own `limits` section, read alone first, may raise or lower it.
void checkInputSize(const std::string& text) {
  constexpr double kBytesPerMb = 1024.0 * 1024.0;
  const double mb = static_cast<double>(text.size()) / kBytesPerMb;
  ResourceLimits lim;
  const std::string block = topLevelBlock(text, "limits");
  if (!block.empty()) {
    YAML::Node n;
    try {
      n = YAML::Load(block);
    } catch (const YAML::Exception&) {
      n = YAML::Node();  // (not a readable block by itself: the default stands)
    }
    if (n.IsMap() && n["limits"] && n["limits"].IsMap())
      readLimits(Item{n["limits"], "limits", markOf(n["limits"], YAML::Mark::null_mark())}, lim);
  }
  if (mb <= lim.max_input_mb) return;
  std::ostringstream os;
  os.precision(3);
  os << "the text is " << mb << " MB, over limits.max_input_mb = " << lim.max_input_mb
     << " MB (the YAML reader takes about a second per MB). Put a long current profile in a CSV file "
        "(environment.current: {file: ...}), or raise limits.max_input_mb in the file's limits section";
  throw ProblemError(os.str());
}

YAML::Node parseYaml(const std::string& yaml_text) {
  YAML::Node root;
  checkInputSize(yaml_text);
  rejectStrayFlowEntry(yaml_text);
  try {
    if (DocumentCounter::count(yaml_text) > 1)
      throw ProblemError("the text holds 2 YAML documents or more (separated by ---, or text that yaml-cpp "
                         "reads as a further document); a problem file holds exactly one");
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    std::string msg = "YAML syntax error";
    if (!e.mark.is_null())
      msg += " at line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1);
    throw ProblemError(msg + ": " + e.msg);
  }
  return root;
}

std::string relativeTo(const std::string& path, const std::string& base_dir) {
  const std::filesystem::path p(path);
  return path.empty() || p.is_absolute() || base_dir.empty() ? path : (std::filesystem::path(base_dir) / p).string();
}

std::string readFileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const std::error_code ec(errno, std::generic_category());
    throw ProblemError(path + ": cannot read file (" + ec.message() + ")");
  }
  // Read at most kMaxProblemFileBytes: a problem file is a few kB (a current table of a million
  // points ~40 MB); a device such as /dev/zero would otherwise fill the memory.
  constexpr std::size_t kMaxProblemFileBytes = 256u << 20;
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxProblemFileBytes)
      throw ProblemError(path + ": larger than " + std::to_string(kMaxProblemFileBytes >> 20) +
                         " MB; not a problem file");
  }
  if (in.bad()) throw ProblemError(path + ": read error");
  return text;
}

}  // namespace sections
}  // namespace core
}  // namespace mooring_dynamics
