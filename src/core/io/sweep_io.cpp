// Sweep files -> SweepSpec, cases and their problem files (see sweep_io.hpp and
// docs/design_analysis.md for the format); the manifest a sweep folder keeps: sweep_manifest.cpp. Errors name the key, the value and the constraint as
// the problem loader's do (yaml_reader.hpp).
#include "mooring_dynamics/core/io/sweep_io.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"
#include "sweep_detail.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

namespace fs = std::filesystem;
using namespace yaml;
using sweep_detail::fmt12;
using sweep_detail::readDesignCheck;

/// The keys whose values are file names (relative to the file they are written in).
const std::vector<std::string> kPathKeys = {"environment.seabed.grid_file", "environment.current.file",
                                            "vessel.motion_table", "vessel.raos.file", "vessel.low_frequency.wave_drift.file",
                                            "dynamics.gnss.track"};

/// Most cases a sweep may expand to (a typo in a range must not write millions of files).
constexpr std::size_t kMaxCases = 100000;

bool isPathKey(const std::string& key) {
  for (const auto& k : kPathKeys)
    if (k == key) return true;
  return false;
}

std::string flowText(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

bool labelChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-';
}

/// A label made from a scalar's text: characters other than letters, digits, '.', '+', '-' become '-'.
std::string labelOf(const std::string& text) {
  std::string l;
  for (char c : text) l += labelChar(c) ? c : '-';
  return l;
}

// ---------------------------------------------------------------------------------------------
// Key paths

struct Step {
  enum class Kind { Key, Index, Name };
  Kind kind = Kind::Key;
  std::string key;  ///< Key: the map key (or a list index written as `.2`); Name: the name
  std::size_t index = 0;
};

bool allDigits(const std::string& s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos; }

/// `a.b[2].c[name=x]` -> steps; throws std::invalid_argument with the constraint.
std::vector<Step> parseKeyPath(const std::string& path) {
  const std::string syntax =
      "a dotted path of keys, list items as .N, [N] or [name=NAME], e.g. environment.waves.hs or lines[name=leg_e]";
  if (path.empty()) throw std::invalid_argument("empty key; needs " + syntax);
  std::vector<Step> steps;
  std::size_t i = 0;
  while (i < path.size()) {
    std::size_t j = i;
    while (j < path.size() && path[j] != '.' && path[j] != '[') ++j;
    if (j > i) {
      Step s;
      s.key = path.substr(i, j - i);
      steps.push_back(s);
    } else if (j < path.size() && path[j] == '.') {
      throw std::invalid_argument("empty part in the key; needs " + syntax);
    }
    while (j < path.size() && path[j] == '[') {
      const std::size_t close = path.find(']', j);
      if (close == std::string::npos) throw std::invalid_argument("'[' without ']'; needs " + syntax);
      const std::string inside = path.substr(j + 1, close - j - 1);
      Step s;
      if (allDigits(inside)) {
        s.kind = Step::Kind::Index;
        s.index = std::stoul(inside);
      } else if (inside.rfind("name=", 0) == 0 && inside.size() > 5) {
        s.kind = Step::Kind::Name;
        s.key = inside.substr(5);
      } else {
        throw std::invalid_argument("'[" + inside + "]': needs [N] or [name=NAME]");
      }
      steps.push_back(s);
      j = close + 1;
    }
    if (j < path.size()) {
      if (path[j] != '.') throw std::invalid_argument("unexpected '" + std::string(1, path[j]) + "'; needs " + syntax);
      ++j;
      if (j == path.size()) throw std::invalid_argument("key ends with '.'; needs " + syntax);
    }
    i = j;
  }
  if (steps.empty() || steps.front().kind != Step::Kind::Key)
    throw std::invalid_argument("must start with a key; needs " + syntax);
  return steps;
}

std::string namesOf(const YAML::Node& seq) {
  std::vector<std::string> names;
  for (const auto& item : seq)
    if (item.IsMap() && item["name"] && item["name"].IsScalar()) names.push_back(item["name"].Scalar());
  return names.empty() ? std::string("none of its items has a name") : "names: " + joinList(names);
}

/// The index a step selects in the sequence `seq` (where = the path so far, for messages).
std::size_t selectInSequence(const YAML::Node& seq, const Step& s, const std::string& where) {
  if (s.kind == Step::Kind::Name) {
    std::size_t found = seq.size(), count = 0;
    for (std::size_t k = 0; k < seq.size(); ++k)
      if (seq[k].IsMap() && seq[k]["name"] && seq[k]["name"].IsScalar() && seq[k]["name"].Scalar() == s.key) {
        found = k;
        ++count;
      }
    if (count == 0) throw std::invalid_argument("no item of " + where + " has name '" + s.key + "' (" + namesOf(seq) + ")");
    if (count > 1) throw std::invalid_argument(std::to_string(count) + " items of " + where + " have name '" + s.key + "'");
    return found;
  }
  const std::size_t k = s.kind == Step::Kind::Index ? s.index : std::stoul(s.key);
  if (k >= seq.size())
    throw std::invalid_argument("item " + std::to_string(k) + " of " + where + ": the list has " +
                                std::to_string(seq.size()) + " items (0 to " + std::to_string(seq.size()) + " - 1)");
  return k;
}

std::string stepText(const Step& s) {
  if (s.kind == Step::Kind::Index) return "[" + std::to_string(s.index) + "]";
  if (s.kind == Step::Kind::Name) return "[name=" + s.key + "]";
  return s.key;
}

/// Apply one edit to `root`; throws std::invalid_argument with the reason.
void applyEdit(YAML::Node root, const SweepEdit& e) {
  const std::vector<Step> steps = parseKeyPath(e.key);
  YAML::Node cur;
  cur.reset(root);
  std::string where;
  for (std::size_t k = 0; k + 1 < steps.size(); ++k) {
    const Step& s = steps[k];
    const std::string next_where = where.empty() ? stepText(s) : where + (s.kind == Step::Kind::Key ? "." : "") + stepText(s);
    YAML::Node child;
    if (cur.IsSequence()) {
      if (s.kind == Step::Kind::Key && !allDigits(s.key))
        throw std::invalid_argument(where + " is a list: address its items as .N, [N] or [name=NAME]");
      child.reset(cur[selectInSequence(cur, s, where)]);
    } else if (cur.IsMap() || cur.IsNull()) {
      if (s.kind != Step::Kind::Key) throw std::invalid_argument((where.empty() ? "the file" : where) + " is not a list");
      if (!cur[s.key] || cur[s.key].IsNull()) {
        if (e.kind == SweepEdit::Kind::Remove) throw std::invalid_argument(next_where + ": not in the base file");
        cur[s.key] = YAML::Node(YAML::NodeType::Map);  // set a key of a section the base file does not have
      }
      child.reset(cur[s.key]);
    } else {
      throw std::invalid_argument(where + " is a value (" + flowText(cur) + "), not a map or list");
    }
    cur.reset(child);
    where = next_where;
  }
  const Step& last = steps.back();
  const std::string full = e.key;
  if (cur.IsSequence()) {
    if (last.kind == Step::Kind::Key && !allDigits(last.key))
      throw std::invalid_argument(where + " is a list: address its items as .N, [N] or [name=NAME]");
    const std::size_t k = selectInSequence(cur, last, where);
    if (e.kind == SweepEdit::Kind::Set) {
      cur[k] = YAML::Load(e.value);
    } else {
      YAML::Node rest(YAML::NodeType::Sequence);
      rest.SetStyle(cur.Style());
      for (std::size_t q = 0; q < cur.size(); ++q)
        if (q != k) rest.push_back(cur[q]);
      cur = rest;  // assigns the content of the list in the tree
    }
    return;
  }
  if (!(cur.IsMap() || cur.IsNull()) || last.kind != Step::Kind::Key)
    throw std::invalid_argument((where.empty() ? "the file" : where) + " is not " +
                                (last.kind == Step::Kind::Key ? "a map" : "a list"));
  if (e.kind == SweepEdit::Kind::Set) {
    cur[last.key] = YAML::Load(e.value);
  } else {
    if (!cur.IsMap() || !cur[last.key]) throw std::invalid_argument(full + ": not in the base file");
    cur.remove(last.key);
  }
}

/// The value of `key` (a plain dotted path) in `root`, if it is a scalar.
bool scalarAt(const YAML::Node& root, const std::string& key, std::string& out) {
  YAML::Node cur;
  cur.reset(root);
  std::size_t i = 0;
  while (i <= key.size()) {
    const std::size_t j = std::min(key.find('.', i), key.size());
    if (!cur.IsMap()) return false;
    const YAML::Node child = cur[key.substr(i, j - i)];
    if (!child) return false;
    cur.reset(child);
    i = j + 1;
  }
  if (!cur.IsScalar()) return false;
  out = cur.Scalar();
  return true;
}

void setScalar(YAML::Node root, const std::string& key, const std::string& value) {
  SweepEdit e;
  e.key = key;
  e.value = flowText(YAML::Node(value));
  applyEdit(root, e);
}

// ---------------------------------------------------------------------------------------------
// Reading the sweep file

std::vector<SweepEdit> readSetMap(const Item& it) {
  std::vector<SweepEdit> edits;
  if (!it.node.IsMap()) it.wrongType("a map of keys (dotted paths) to values");
  for (auto kv : it.node) {
    if (!kv.first.IsScalar()) it.fail("keys must be dotted paths");
    SweepEdit e;
    e.key = kv.first.Scalar();
    const Item vi{kv.second, it.path + "." + e.key, markOf(kv.second, kv.first.Mark())};
    try {
      parseKeyPath(e.key);
    } catch (const std::invalid_argument& ex) {
      vi.failNoValue(ex.what());
    }
    if (!kv.second.IsDefined() || kv.second.IsNull()) vi.failNoValue("needs a value");
    e.value = flowText(kv.second);
    e.path_value = isPathKey(e.key);
    edits.push_back(e);
  }
  return edits;
}

std::vector<SweepEdit> readRemove(const Item& it) {
  std::vector<Item> items;
  if (it.node.IsSequence()) items = listItems(it);
  else items.push_back(it);
  std::vector<SweepEdit> edits;
  for (const Item& ri : items) {
    SweepEdit e;
    e.kind = SweepEdit::Kind::Remove;
    e.key = readString(ri);
    try {
      parseKeyPath(e.key);
    } catch (const std::invalid_argument& ex) {
      ri.failQuoted(ex.what());
    }
    edits.push_back(e);
  }
  return edits;
}

void checkLabel(const Item& it, const std::string& label) {
  if (label.empty()) it.failQuoted("a label must not be empty");
  for (char c : label)
    if (!labelChar(c)) it.failQuoted("a label may hold letters, digits, '.', '+' and '-' only (it becomes part of the case names)");
}

std::vector<SweepValue> readKeyedValues(const Map& m, const std::string& key) {
  std::vector<SweepValue> values;
  const bool path_value = isPathKey(key);
  if (m.has("values")) {
    for (const Item& vi : listItems(m.at("values"))) {
      if (!vi.node.IsScalar()) vi.wrongType("a scalar value of " + key + " (for other values give {label, set} maps and no key)");
      SweepValue v;
      v.label = labelOf(vi.node.Scalar());
      checkLabel(vi, v.label);
      SweepEdit e;
      e.key = key;
      e.value = flowText(vi.node);
      e.path_value = path_value;
      v.edits.push_back(e);
      const std::string& s = vi.node.Scalar();
      char* end = nullptr;
      const double d = std::strtod(s.c_str(), &end);
      v.numeric = !s.empty() && *end == '\0' && std::isfinite(d) && vi.node.Tag() != "!";
      v.number = v.numeric ? d : 0.0;
      values.push_back(v);
    }
    return values;
  }
  const Map r(m.at("range"), {"from", "to", "step"});
  const double from = r.number("from"), to = r.number("to"), step = r.number("step", Range::Positive);
  if (!(to >= from)) r.at("to").fail("must be >= from (" + formatNumber(from) + ")");
  const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxCases)) r.at("step").fail("gives " + formatNumber(count) + " values; at most " + std::to_string(kMaxCases));
  for (long k = 0; k < static_cast<long>(count); ++k) {
    SweepValue v;
    v.number = from + static_cast<double>(k) * step;
    v.numeric = true;
    const std::string text = fmt12(v.number);
    v.label = labelOf(text);
    SweepEdit e;
    e.key = key;
    e.value = text;
    v.edits.push_back(e);
    values.push_back(v);
  }
  return values;
}

std::vector<SweepValue> readLabelledValues(const Map& m) {
  if (!m.has("values")) m.item().failNoValue("without `key`, give `values` as a list of {label, set, remove} maps");
  std::vector<SweepValue> values;
  for (const Item& vi : listItems(m.at("values"))) {
    const Map vm(vi, {"label", "set", "remove"});
    SweepValue v;
    const Item li = vm.required("label", "each value of a variation without `key` needs a label");
    v.label = readString(li);
    checkLabel(li, v.label);
    if (presentAndNotNull(vm, "set")) v.edits = readSetMap(vm.at("set"));
    if (presentAndNotNull(vm, "remove")) {
      const auto r = readRemove(vm.at("remove"));
      v.edits.insert(v.edits.end(), r.begin(), r.end());
    }
    if (v.edits.size() == 1 && v.edits[0].kind == SweepEdit::Kind::Set) {
      const YAML::Node n = YAML::Load(v.edits[0].value);
      char* end = nullptr;
      const std::string s = n.IsScalar() ? n.Scalar() : std::string();
      const double d = std::strtod(s.c_str(), &end);
      v.numeric = !s.empty() && *end == '\0' && std::isfinite(d);
      v.number = v.numeric ? d : 0.0;
    }
    values.push_back(v);
  }
  return values;
}

SweepVariation readVariation(const Item& it) {
  const Map m(it, {"name", "key", "values", "range", "seeds"});
  SweepVariation var;
  const Item ni = m.required("name");
  var.name = readString(ni);
  if (var.name.empty()) ni.failQuoted("must not be empty");
  for (char c : var.name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')))
      ni.failQuoted("a variation name may hold letters and digits only (case names are <name>-<label> joined with '_')");
  if (m.has("values") == m.has("range"))
    it.failNoValue(m.has("values") ? "give `values` or `range`, not both" : "needs `values` (a list) or `range` ({from, to, step})");
  if (m.has("seeds")) var.seeds = readBool(m.at("seeds"));
  if (m.has("key")) {
    const Item ki = m.at("key");
    const std::string key = readString(ki);
    try {
      parseKeyPath(key);
    } catch (const std::invalid_argument& ex) {
      ki.failQuoted(ex.what());
    }
    var.values = readKeyedValues(m, key);
  } else {
    if (m.has("range")) m.at("range").failNoValue("a range needs `key`: the key it sets");
    var.values = readLabelledValues(m);
  }
  if (var.values.empty()) m.at("values").failNoValue("needs at least one value");
  std::set<std::string> seen;
  for (std::size_t k = 0; k < var.values.size(); ++k)
    if (!seen.insert(var.values[k].label).second)
      throw ProblemError(it.path + ": two values have the label '" + var.values[k].label +
                         "' (labels name the cases and must differ)" + lineSuffix(it.mark));
  return var;
}

std::string stemOf(const std::string& path) { return fs::path(path).stem().string(); }

}  // namespace

SweepSpec loadSweepFromString(const std::string& yaml_text, const std::string& dir) {
  const YAML::Node root = sections::parseYaml(yaml_text);
  const Item top_item{root, "", YAML::Mark::null_mark()};
  const Map top(top_item, {"name", "base", "set", "remove", "variations", "statistics"});
  SweepSpec spec;
  spec.sweep_dir = dir;
  if (top.has("name")) spec.name = readString(top.at("name"));
  const Item bi = top.required("base", "the problem, system or vessel file the cases vary (relative to the sweep file)");
  const std::string base = readString(bi);
  if (base.empty()) bi.failQuoted("needs a file name");
  spec.base_path = sections::relativeTo(base, dir);
  if (!fs::is_regular_file(spec.base_path)) bi.failQuoted("no such file (" + spec.base_path + ")");
  if (presentAndNotNull(top, "set")) spec.common = readSetMap(top.at("set"));
  if (presentAndNotNull(top, "remove")) {
    const auto r = readRemove(top.at("remove"));
    spec.common.insert(spec.common.end(), r.begin(), r.end());
  }
  if (presentAndNotNull(top, "variations")) {
    std::set<std::string> names;
    int seeds = 0;
    for (const Item& vi : listItems(top.at("variations"))) {
      spec.variations.push_back(readVariation(vi));
      if (!names.insert(spec.variations.back().name).second)
        throw ProblemError(vi.path + ".name = " + spec.variations.back().name + ": two variations have this name" +
                           lineSuffix(vi.mark));
      if (spec.variations.back().seeds && ++seeds > 1)
        throw ProblemError(vi.path + ".seeds: one variation at most may be the seeds" + lineSuffix(vi.mark));
    }
  }
  if (presentAndNotNull(top, "statistics")) {
    const Map sm(top.at("statistics"), {"gumbel_fit", "skip_time", "design_check"});
    if (sm.has("skip_time")) spec.skip_time = sm.number("skip_time", Range::NonNegative);
    if (sm.has("design_check")) readDesignCheck(sm.at("design_check"), spec);
    if (sm.has("gumbel_fit")) {
      const Item gi = sm.at("gumbel_fit");
      try {
        spec.gumbel = gumbelMethodFromName(readString(gi));
      } catch (const std::invalid_argument&) {
        gi.failQuoted("needs moments or mle");
      }
    }
  }
  for (const std::string& label : spec.als_labels) {
    bool found = false;
    for (const auto& v : spec.variations)
      for (const auto& val : v.values) found = found || val.label == label;
    if (!found)
      Map(top.at("statistics"), {"gumbel_fit", "skip_time", "design_check"})
          .at("design_check")
          .failNoValue("als: no variation has the label " + quoted(label));
  }
  double count = 1.0;
  for (const auto& v : spec.variations) count *= static_cast<double>(v.values.size());
  if (count > static_cast<double>(kMaxCases))
    top.at("variations").failNoValue("expand to " + formatNumber(count) + " cases; at most " + std::to_string(kMaxCases));
  // Check every value's edits against the base file now (each with the first value of the other
  // variations); the combinations are checked when the cases are written.
  SweepCase probe;
  probe.choice.assign(spec.variations.size(), 0);
  (void)caseProblemText(spec, probe, dir.empty() ? "." : dir);
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    for (std::size_t k = 1; k < spec.variations[v].values.size(); ++k) {
      probe.choice[v] = k;
      (void)caseProblemText(spec, probe, dir.empty() ? "." : dir);
    }
    probe.choice[v] = 0;
  }
  return spec;
}

SweepSpec loadSweepFromFile(const std::string& path) {
  const std::string text = sections::readFileText(path);
  try {
    SweepSpec s = loadSweepFromString(text, fs::path(path).parent_path().string());
    if (s.name.empty()) s.name = stemOf(path);
    return s;
  } catch (const ProblemError& e) {
    throw ProblemError(path + ": " + e.what());
  }
}

std::vector<SweepCase> expandSweep(const SweepSpec& spec) {
  std::vector<SweepCase> cases;
  const std::size_t nv = spec.variations.size();
  std::vector<std::size_t> choice(nv, 0);
  while (true) {
    SweepCase c;
    c.choice = choice;
    for (std::size_t v = 0; v < nv; ++v) {
      const std::string part = spec.variations[v].name + "-" + spec.variations[v].values[choice[v]].label;
      c.name += (c.name.empty() ? "" : "_") + part;
      if (!spec.variations[v].seeds) c.storm += (c.storm.empty() ? "" : "_") + part;
    }
    if (c.name.empty()) c.name = "base";
    if (c.storm.empty()) c.storm = "all";
    cases.push_back(c);
    std::size_t v = nv;
    while (v > 0) {
      --v;
      if (++choice[v] < spec.variations[v].values.size()) break;
      choice[v] = 0;
      if (v == 0) return cases;
    }
    if (nv == 0) return cases;
  }
}

std::string caseProblemText(const SweepSpec& spec, const SweepCase& c, const std::string& case_dir) {
  const YAML::Node root = sections::parseYaml(sections::readFileText(spec.base_path));
  if (!root.IsMap()) throw ProblemError(spec.base_path + ": not a problem file (a YAML map)");
  const std::string base_dir = fs::path(spec.base_path).parent_path().string();
  // Files named by the base are relative to it; make them absolute before editing.
  for (const auto& k : kPathKeys) {
    std::string v;
    if (scalarAt(root, k, v) && !v.empty()) setScalar(root, k, fs::absolute(sections::relativeTo(v, base_dir)).lexically_normal().string());
  }
  auto apply = [&](const SweepEdit& e, const std::string& context) {
    try {
      applyEdit(root, e);
    } catch (const std::invalid_argument& ex) {
      throw ProblemError(context + (e.kind == SweepEdit::Kind::Set ? ": set " : ": remove ") + e.key + ": " + ex.what() +
                         " (in the base file " + spec.base_path + ")");
    } catch (const YAML::Exception& ex) {
      throw ProblemError(context + ": " + e.key + ": " + ex.what());
    }
    if (e.kind != SweepEdit::Kind::Set) return;
    // A file named by the sweep, as the value itself or inside a section it sets
    // (`vessel.raos: {file: ...}`): relative to the sweep file.
    for (const auto& k : kPathKeys) {
      if (k != e.key && k.rfind(e.key + ".", 0) != 0) continue;
      std::string v;
      if (scalarAt(root, k, v) && !v.empty())
        setScalar(root, k, fs::absolute(sections::relativeTo(v, spec.sweep_dir)).lexically_normal().string());
    }
  };
  for (const SweepEdit& e : spec.common) apply(e, "set/remove (every case)");
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    const SweepVariation& var = spec.variations[v];
    const SweepValue& val = var.values[c.choice[v]];
    for (const SweepEdit& e : val.edits) apply(e, "variation '" + var.name + "', value '" + val.label + "'");
  }
  // The files it names, relative to where the case file is written.
  const fs::path cdir = fs::absolute(case_dir).lexically_normal();
  for (const auto& k : kPathKeys) {
    std::string v;
    if (scalarAt(root, k, v) && !v.empty()) setScalar(root, k, fs::path(v).lexically_relative(cdir).string());
  }
  YAML::Emitter e;
  e << root;
  return std::string(e.c_str()) + "\n";
}

}  // namespace core
}  // namespace mooring_dynamics
