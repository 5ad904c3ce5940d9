// Internal (not part of the public API): the strict YAML reading layer under problem_io.cpp.
//
// Typed reads of YAML values that carry their key path and line number, so that every rejected
// input raises ProblemError with a message of the form
//   <key path> = <value found>: <constraint> (line N)
// Maps reject unknown keys (with a "did you mean" suggestion) and duplicate keys.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mooring_dynamics {
namespace core {
namespace yaml {

// ---------------------------------------------------------------------------------------------
// Message helpers

/// " (line N)" for a valid mark, "" otherwise.
std::string lineSuffix(const YAML::Mark& mark);
std::string quoted(const std::string& s);
/// "a, b, c".
std::string joinList(const std::vector<std::string>& items);
/// "a map", "a list", "an empty value", "a quoted string", "a scalar", "nothing".
std::string typeName(const YAML::Node& n);
/// Short flow-style rendering of a node for messages (scalars as written, quoted strings quoted).
std::string render(const YAML::Node& n);
/// %.10g.
std::string formatNumber(double v);
/// Case-insensitive Levenshtein distance.
std::size_t editDistance(const std::string& a, const std::string& b);

/// A YAML value with the key path that leads to it and a position for messages.
struct Item {
  YAML::Node node;
  std::string path;
  YAML::Mark mark;  ///< position of the key (or of the list item) in the text

  [[noreturn]] void fail(const std::string& constraint) const;
  /// Like fail(), with the scalar shown in quotes (text that is not what the key needs).
  [[noreturn]] void failQuoted(const std::string& constraint) const;
  [[noreturn]] void failNoValue(const std::string& what) const;
  [[noreturn]] void wrongType(const std::string& expected) const;
};

/// The node's own position if it has one, else `fallback`.
YAML::Mark markOf(const YAML::Node& n, const YAML::Mark& fallback);

// ---------------------------------------------------------------------------------------------
// Scalars

/// YAML spellings of non-finite numbers (.nan, .inf, -.inf, ...), and C spellings (nan, inf).
bool looksNonFinite(std::string s);

double readNumber(const Item& it);     ///< finite double
long long readInteger(const Item& it);
bool readBool(const Item& it);         ///< true/false, yes/no, on/off
std::string readString(const Item& it);

enum class Range { Any, Positive, NonNegative };

/// `v` if it is in range `r`, else it.fail().
double checked(const Item& it, double v, Range r);

// ---------------------------------------------------------------------------------------------
// Maps and lists

/// A YAML map with a fixed set of allowed keys. Unknown and duplicate keys are rejected on
/// construction, so a typo never goes unnoticed.
class Map {
 public:
  Map(const Item& it, const std::vector<std::string>& allowed);

  const std::string& path() const { return item_.path; }
  const Item& item() const { return item_; }
  std::string sub(const std::string& key) const {
    return item_.path.empty() ? key : item_.path + "." + key;
  }
  bool has(const std::string& key) const { return keys_.count(key) > 0; }

  /// The value under `key` (must exist: check has() first or use required()).
  Item at(const std::string& key) const;
  Item required(const std::string& key, const std::string& hint = "") const;

  double number(const std::string& key, Range r = Range::Any) const;
  double number(const std::string& key, double def, Range r) const;

 private:
  Item item_;
  std::map<std::string, YAML::Mark> keys_;
};

std::vector<Item> listItems(const Item& it);

/// A list of [a, b] number pairs (tables). Returns the pairs; each item is checked to be a pair.
std::vector<std::pair<double, double>> readPairs(const Item& it, const std::string& pair_desc,
                                                 std::vector<Item>* items_out = nullptr);

/// Optional container section given as `key:` with nothing after it counts as absent.
bool presentAndNotNull(const Map& m, const std::string& key);

}  // namespace yaml
}  // namespace core
}  // namespace mooring_dynamics
