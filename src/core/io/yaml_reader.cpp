// The strict YAML reading layer of problem_io.cpp (see yaml_reader.hpp).
#include "mooring_dynamics/core/io/yaml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <system_error>

#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace core {
namespace yaml {

// ---------------------------------------------------------------------------------------------
// Message helpers

std::string lineSuffix(const YAML::Mark& mark) {
  if (mark.is_null() || mark.line < 0) return "";
  return " (line " + std::to_string(mark.line + 1) + ")";
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

std::string joinList(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += ", ";
    out += items[i];
  }
  return out;
}

std::string typeName(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Null: return "an empty value";
    case YAML::NodeType::Scalar: return n.Tag() == "!" ? "a quoted string" : "a scalar";
    default: return "nothing";
  }
}

std::string render(const YAML::Node& n) {
  if (!n.IsDefined()) return "(missing)";
  if (n.IsNull()) return "(empty)";
  if (n.IsScalar()) return n.Tag() == "!" ? quoted(n.Scalar()) : n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  std::string s = e.c_str();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      const std::size_t sub = prev[j - 1] + (same ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

void Item::fail(const std::string& constraint) const {
  throw ProblemError(path + " = " + render(node) + ": " + constraint + lineSuffix(mark));
}

void Item::failQuoted(const std::string& constraint) const {
  throw ProblemError(path + " = " + quoted(node.Scalar()) + ": " + constraint + lineSuffix(mark));
}

void Item::failNoValue(const std::string& what) const {
  throw ProblemError(path + ": " + what + lineSuffix(mark));
}

void Item::wrongType(const std::string& expected) const {
  if (node.IsScalar()) fail("expected " + expected + ", found " + typeName(node));
  failNoValue("expected " + expected + ", found " + typeName(node) +
              (node.IsNull() ? "" : " " + render(node)));
}

YAML::Mark markOf(const YAML::Node& n, const YAML::Mark& fallback) {
  if (n.IsDefined() && !n.IsNull()) {
    const YAML::Mark m = n.Mark();
    if (!m.is_null()) return m;
  }
  return fallback;
}

// ---------------------------------------------------------------------------------------------
// Scalars

bool looksNonFinite(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  if (!s.empty() && s[0] == '.') s.erase(0, 1);
  return s == "nan" || s == "inf" || s == "infinity";
}

/// An explicit YAML tag other than the core schema's `!!<allowed...>` makes a scalar something
/// else than what it looks like (`!!str 5` is the text "5"): refused where a value is expected.
void rejectForeignTag(const Item& it, std::initializer_list<const char*> allowed, const std::string& expected) {
  const std::string& tag = it.node.Tag();
  if (tag.empty() || tag == "?" || tag == "!") return;  // plain, or quoted (handled by the caller)
  static const std::string kCore = "tag:yaml.org,2002:";
  for (const char* a : allowed)
    if (tag == kCore + a) return;
  const std::string shown = tag.compare(0, kCore.size(), kCore) == 0 ? "!!" + tag.substr(kCore.size()) : tag;
  it.fail("expected " + expected + ", found a scalar tagged " + shown + " (write the value without a tag)");
}

double readNumber(const Item& it) {
  if (!it.node.IsScalar() || it.node.Tag() == "!") it.wrongType("a number");
  rejectForeignTag(it, {"float", "int"}, "a number");
  const std::string& s = it.node.Scalar();
  if (looksNonFinite(s)) it.fail("must be a finite number");
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  double v = 0.0;
  const auto r = std::from_chars(b, e, v);
  if (r.ec == std::errc::result_out_of_range) it.fail("number out of range (must be a finite double)");
  if (r.ec != std::errc() || r.ptr != e || b == e) it.failQuoted("expected a number");
  if (!std::isfinite(v)) it.fail("must be a finite number");
  return v;
}

long long readInteger(const Item& it) {
  if (!it.node.IsScalar() || it.node.Tag() == "!") it.wrongType("an integer");
  rejectForeignTag(it, {"int"}, "an integer");
  const std::string& s = it.node.Scalar();
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  long long v = 0;
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e || b == e) it.fail("expected an integer");
  return v;
}

bool readBool(const Item& it) {
  if (!it.node.IsScalar() || it.node.Tag() == "!") it.wrongType("true or false");
  rejectForeignTag(it, {"bool"}, "true or false");
  std::string s = it.node.Scalar();
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  it.fail("expected true or false");
}

std::string readString(const Item& it) {
  if (!it.node.IsScalar()) it.wrongType("a string");
  return it.node.Scalar();
}

double checked(const Item& it, double v, Range r) {
  if (r == Range::Positive && !(v > 0.0)) it.fail("must be > 0");
  if (r == Range::NonNegative && !(v >= 0.0)) it.fail("must be >= 0");
  return v;
}

// ---------------------------------------------------------------------------------------------
// Maps and lists

Map::Map(const Item& it, const std::vector<std::string>& allowed) : item_(it) {
  if (!it.node.IsMap()) it.wrongType("a map");
  for (auto kv : it.node) {
    const YAML::Mark km = kv.first.Mark();
    if (!kv.first.IsScalar())
      throw ProblemError(it.path + ": keys must be plain names, found " + typeName(kv.first) +
                         lineSuffix(km));
    const std::string key = kv.first.Scalar();
    const std::string p = sub(key);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string best;
      std::size_t bestd = 3;  // suggest only close matches
      for (const auto& a : allowed) {
        const std::size_t d = editDistance(key, a);
        if (d < bestd) bestd = d, best = a;
      }
      std::string msg = p + ": unknown key (";
      if (!best.empty()) msg += "did you mean \"" + best + "\"? ";
      msg += "allowed here: " + joinList(allowed) + ")";
      throw ProblemError(msg + lineSuffix(km));
    }
    if (keys_.count(key))
      throw ProblemError(p + ": duplicate key (first given" + lineSuffix(keys_[key]) + ")" +
                         lineSuffix(km));
    keys_[key] = km;
  }
}

Item Map::at(const std::string& key) const {
  const YAML::Node n = item_.node[key];
  return Item{n, sub(key), markOf(n, keys_.at(key))};
}
Item Map::required(const std::string& key, const std::string& hint) const {
  if (!has(key))
    throw ProblemError(sub(key) + ": required key missing" + (hint.empty() ? "" : " (" + hint + ")") +
                       lineSuffix(item_.mark));
  return at(key);
}

double Map::number(const std::string& key, Range r) const {
  const Item it = required(key);
  return checked(it, readNumber(it), r);
}
double Map::number(const std::string& key, double def, Range r) const {
  if (!has(key)) return def;
  const Item it = at(key);
  return checked(it, readNumber(it), r);
}

std::vector<Item> listItems(const Item& it) {
  if (!it.node.IsSequence()) it.wrongType("a list");
  std::vector<Item> out;
  std::size_t i = 0;
  for (auto n : it.node) {
    out.push_back(Item{n, it.path + "[" + std::to_string(i) + "]", markOf(n, it.mark)});
    ++i;
  }
  return out;
}

std::vector<std::pair<double, double>> readPairs(const Item& it, const std::string& pair_desc,
                                                 std::vector<Item>* items_out) {
  std::vector<std::pair<double, double>> out;
  const std::vector<Item> items = listItems(it);
  for (const Item& p : items) {
    if (!p.node.IsSequence() || p.node.size() != 2) p.wrongType("a pair " + pair_desc);
    const Item a{p.node[0], p.path + "[0]", markOf(p.node[0], p.mark)};
    const Item b{p.node[1], p.path + "[1]", markOf(p.node[1], p.mark)};
    out.emplace_back(readNumber(a), readNumber(b));
  }
  if (items_out) *items_out = items;
  return out;
}

bool presentAndNotNull(const Map& m, const std::string& key) { return m.has(key) && !m.at(key).node.IsNull(); }

}  // namespace yaml
}  // namespace core
}  // namespace mooring_dynamics
