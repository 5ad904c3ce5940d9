// YAML problem files -> core::Problem. The format is documented in docs/problem_format.md.
//
// Every rejected input raises ProblemError with a message of the form
//   <key path> = <value found>: <constraint> (line N)
// e.g. `line[2].material = "chian": unknown material (known: chain, vectran) (line 14)`.
// Unknown keys are errors at every level (typos must not be silently ignored).
#include "mooring_dynamics/core/problem_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

namespace mooring_dynamics {
namespace core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

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

/// Short flow-style rendering of a node for messages (scalars as written, quoted strings quoted).
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

/// A YAML value with the key path that leads to it and a position for messages.
struct Item {
  YAML::Node node;
  std::string path;
  YAML::Mark mark;  ///< position of the key (or of the list item) in the text

  [[noreturn]] void fail(const std::string& constraint) const {
    throw ProblemError(path + " = " + render(node) + ": " + constraint + lineSuffix(mark));
  }
  /// Like fail(), with the scalar shown in quotes (text that is not what the key needs).
  [[noreturn]] void failQuoted(const std::string& constraint) const {
    throw ProblemError(path + " = " + quoted(node.Scalar()) + ": " + constraint + lineSuffix(mark));
  }
  [[noreturn]] void failNoValue(const std::string& what) const {
    throw ProblemError(path + ": " + what + lineSuffix(mark));
  }
  [[noreturn]] void wrongType(const std::string& expected) const {
    if (node.IsScalar()) fail("expected " + expected + ", found " + typeName(node));
    failNoValue("expected " + expected + ", found " + typeName(node) +
                (node.IsNull() ? "" : " " + render(node)));
  }
};

YAML::Mark markOf(const YAML::Node& n, const YAML::Mark& fallback) {
  if (n.IsDefined() && !n.IsNull()) {
    const YAML::Mark m = n.Mark();
    if (!m.is_null()) return m;
  }
  return fallback;
}

// ---------------------------------------------------------------------------------------------
// Scalars

/// YAML spellings of non-finite numbers (.nan, .inf, -.inf, ...), and C spellings (nan, inf).
bool looksNonFinite(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  if (!s.empty() && s[0] == '.') s.erase(0, 1);
  return s == "nan" || s == "inf" || s == "infinity";
}

double readNumber(const Item& it) {
  if (!it.node.IsScalar() || it.node.Tag() == "!") it.wrongType("a number");
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

enum class Range { Any, Positive, NonNegative };

double checked(const Item& it, double v, Range r) {
  if (r == Range::Positive && !(v > 0.0)) it.fail("must be > 0");
  if (r == Range::NonNegative && !(v >= 0.0)) it.fail("must be >= 0");
  return v;
}

// ---------------------------------------------------------------------------------------------
// Maps and lists

/// A YAML map with a fixed set of allowed keys. Unknown and duplicate keys are rejected on
/// construction, so a typo never goes unnoticed.
class Map {
 public:
  Map(const Item& it, const std::vector<std::string>& allowed) : item_(it) {
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

  const std::string& path() const { return item_.path; }
  const Item& item() const { return item_; }
  std::string sub(const std::string& key) const {
    return item_.path.empty() ? key : item_.path + "." + key;
  }
  bool has(const std::string& key) const { return keys_.count(key) > 0; }

  /// The value under `key` (must exist: check has() first or use required()).
  Item at(const std::string& key) const {
    const YAML::Node n = item_.node[key];
    return Item{n, sub(key), markOf(n, keys_.at(key))};
  }
  Item required(const std::string& key, const std::string& hint = "") const {
    if (!has(key))
      throw ProblemError(sub(key) + ": required key missing" + (hint.empty() ? "" : " (" + hint + ")") +
                         lineSuffix(item_.mark));
    return at(key);
  }

  double number(const std::string& key, Range r = Range::Any) const {
    const Item it = required(key);
    return checked(it, readNumber(it), r);
  }
  double number(const std::string& key, double def, Range r) const {
    if (!has(key)) return def;
    const Item it = at(key);
    return checked(it, readNumber(it), r);
  }

 private:
  Item item_;
  std::map<std::string, YAML::Mark> keys_;
};

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

/// A list of [a, b] number pairs (tables). Returns the pairs; each item is checked to be a pair.
std::vector<std::pair<double, double>> readPairs(const Item& it, const std::string& pair_desc,
                                                 std::vector<Item>* items_out = nullptr) {
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

/// Optional container section given as `key:` with nothing after it counts as absent.
bool presentAndNotNull(const Map& m, const std::string& key) { return m.has(key) && !m.at(key).node.IsNull(); }

// ---------------------------------------------------------------------------------------------
// Sections

void readEnvironment(const Item& it, Environment& env) {
  const Map m(it, {"water_density", "air_density", "gravity", "depth", "seabed", "current", "wind", "waves"});
  env.water_density = m.number("water_density", env.water_density, Range::Positive);
  env.air_density = m.number("air_density", env.air_density, Range::NonNegative);
  env.gravity = m.number("gravity", env.gravity, Range::Positive);
  env.depth = m.number("depth", env.depth, Range::Positive);

  if (m.has("seabed")) {
    const Map sb(m.at("seabed"), {"stiffness", "damping", "profile", "static_cap"});
    env.seabed.stiffness = sb.number("stiffness", env.seabed.stiffness, Range::Positive);
    env.seabed.damping = sb.number("damping", env.seabed.damping, Range::NonNegative);
    if (sb.has("static_cap")) env.seabed.static_cap = readBool(sb.at("static_cap"));
    if (sb.has("profile")) {
      std::vector<Item> items;
      const Item pit = sb.at("profile");
      env.seabed.profile = readPairs(pit, "[x, depth]", &items);
      if (env.seabed.profile.size() < 2)
        pit.fail("needs at least 2 points [x, depth]; omit it for a flat seabed at environment.depth");
      for (std::size_t i = 0; i < items.size(); ++i) {
        const auto& pt = env.seabed.profile[i];
        if (!(pt.second > 0.0)) items[i].fail("depth must be > 0");
        if (i > 0 && !(pt.first > env.seabed.profile[i - 1].first))
          items[i].fail("x must increase along the profile (previous x = " +
                        formatNumber(env.seabed.profile[i - 1].first) + ")");
      }
    }
  }

  if (m.has("wind")) {
    const Map w(m.at("wind"), {"speed", "direction_deg"});
    env.wind_speed = w.number("speed", 0.0, Range::NonNegative);
    env.wind_direction = w.number("direction_deg", 0.0, Range::Any) * kDegToRad;
  }

  if (m.has("current")) {
    const Item cit = m.at("current");
    env.current.clear();
    if (cit.node.IsMap()) {
      // Uniform current shorthand: {speed, direction_deg} -> same value from the surface to the bottom.
      const Map c(cit, {"speed", "direction_deg"});
      CurrentPoint p;
      p.speed = c.number("speed", Range::NonNegative);
      p.direction = c.number("direction_deg", 0.0, Range::Any) * kDegToRad;
      double bottom = env.depth;
      for (const auto& q : env.seabed.profile) bottom = std::max(bottom, q.second);
      p.depth = 0.0;
      env.current.push_back(p);
      p.depth = bottom;
      env.current.push_back(p);
    } else if (cit.node.IsSequence()) {
      const std::vector<Item> items = listItems(cit);
      if (items.size() < 2)
        cit.fail("a current profile needs at least 2 points {depth, speed, direction_deg}; "
                 "for a uniform current write current: {speed: ..., direction_deg: ...}");
      for (std::size_t i = 0; i < items.size(); ++i) {
        const Map c(items[i], {"depth", "speed", "direction_deg"});
        CurrentPoint p;
        p.depth = c.number("depth", Range::NonNegative);
        p.speed = c.number("speed", Range::NonNegative);
        p.direction = c.number("direction_deg", 0.0, Range::Any) * kDegToRad;
        if (i > 0 && !(p.depth > env.current.back().depth))
          c.at("depth").fail("depth must increase along the profile (previous depth = " +
                             formatNumber(env.current.back().depth) + ")");
        env.current.push_back(p);
      }
    } else {
      cit.wrongType("a list of {depth, speed, direction_deg} or a map {speed, direction_deg}");
    }
  }

  if (m.has("waves")) {
    // Linear waves (core/waves.hpp). Keys not used by the chosen type are rejected.
    const Map w(m.at("waves"), {"type", "height", "period", "hs", "tp", "gamma", "components", "f_min_factor",
                                "f_max_factor", "seed", "direction_deg", "ramp"});
    const Item ti = w.required("type", "one of regular, jonswap, pierson_moskowitz");
    const std::string type = readString(ti);
    WaveSpec ws;
    if (type == "regular")
      ws.type = WaveSpec::Type::Regular;
    else if (type == "jonswap")
      ws.type = WaveSpec::Type::Jonswap;
    else if (type == "pierson_moskowitz")
      ws.type = WaveSpec::Type::PiersonMoskowitz;
    else
      throw ProblemError(ti.path + " = " + quoted(type) +
                         ": unknown wave type (known: regular, jonswap, pierson_moskowitz)" + lineSuffix(ti.mark));
    const bool regular = ws.type == WaveSpec::Type::Regular;
    for (const char* k : {"height", "period"})
      if (!regular && w.has(k)) w.at(k).fail("only used with type: regular");
    for (const char* k : {"hs", "tp", "components", "f_min_factor", "f_max_factor", "seed"})
      if (regular && w.has(k)) w.at(k).fail("only used with type: jonswap or pierson_moskowitz");
    if (ws.type != WaveSpec::Type::Jonswap && w.has("gamma")) w.at("gamma").fail("only used with type: jonswap");

    if (regular) {
      ws.height = w.number("height", Range::Positive);
      ws.period = w.number("period", Range::Positive);
    } else {
      ws.hs = w.number("hs", Range::Positive);
      ws.tp = w.number("tp", Range::Positive);
      if (w.has("gamma")) {
        const Item gi = w.at("gamma");
        ws.gamma = readNumber(gi);
        if (!(ws.gamma >= 1.0)) gi.fail("must be >= 1 (1 = Pierson-Moskowitz)");
      }
      if (w.has("components")) {
        const Item ci = w.at("components");
        const long long v = readInteger(ci);
        if (v < 1 || v > 10000) ci.fail("must be an integer in [1, 10000]");
        ws.components = static_cast<int>(v);
      }
      if (w.has("f_min_factor")) {
        const Item fi = w.at("f_min_factor");
        ws.f_min_factor = readNumber(fi);
        if (!(ws.f_min_factor > 0.0 && ws.f_min_factor < 1.0)) fi.fail("must be in (0, 1)");
      }
      if (w.has("f_max_factor")) {
        const Item fi = w.at("f_max_factor");
        ws.f_max_factor = readNumber(fi);
        if (!(ws.f_max_factor > 1.0)) fi.fail("must be > 1");
      }
      if (w.has("seed")) {
        const Item si = w.at("seed");
        const long long v = readInteger(si);
        if (v < 0 || v > 4294967295LL) si.fail("must be an integer in [0, 4294967295]");
        ws.seed = static_cast<std::uint32_t>(v);
      }
    }
    ws.direction = w.number("direction_deg", 0.0, Range::Any) * kDegToRad;
    ws.ramp = w.number("ramp", 0.0, Range::NonNegative);
    env.waves = ws;
  }
}

Material readMaterial(const Item& it, const std::string& name) {
  const Map m(it, {"EA", "tension_strain", "EI", "GJ", "mass", "added_mass", "wet_weight", "diameter",
                   "cdn", "cdt", "max_strain"});
  Material mat;
  mat.name = name;
  if (m.has("EA") && m.has("tension_strain"))
    throw ProblemError(m.sub("EA") + ": give either EA or tension_strain, not both" +
                       lineSuffix(m.at("EA").mark));
  if (m.has("tension_strain")) {
    std::vector<Item> items;
    const Item tit = m.at("tension_strain");
    mat.tension_strain = readPairs(tit, "[strain, tension]", &items);
    const auto& t = mat.tension_strain;
    if (t.size() < 2) tit.fail("needs at least 2 points [strain, tension]");
    if (t[0].first != 0.0 || t[0].second != 0.0) items[0].fail("the table must start at [0, 0]");
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (!(t[i].first > t[i - 1].first))
        items[i].fail("strain must increase along the table (previous strain = " +
                      formatNumber(t[i - 1].first) + ")");
      if (!(t[i].second > t[i - 1].second))
        items[i].fail("tension must increase along the table (previous tension = " +
                      formatNumber(t[i - 1].second) + ")");
    }
    mat.EA = 0.0;
  } else {
    const Item ea = m.required("EA", "give EA [N] or a tension_strain table");
    mat.EA = checked(ea, readNumber(ea), Range::Positive);
  }
  mat.EI = m.number("EI", Range::Positive);
  mat.GJ = m.number("GJ", 0.0, Range::NonNegative);
  mat.mass = m.number("mass", Range::NonNegative);
  mat.added_mass = m.number("added_mass", 0.0, Range::NonNegative);
  mat.wet_weight = m.number("wet_weight", Range::Any);
  mat.diameter = m.number("diameter", Range::Positive);
  mat.cdn = m.number("cdn", Range::NonNegative);
  mat.cdt = m.number("cdt", Range::NonNegative);
  mat.max_strain = m.number("max_strain", mat.max_strain, Range::Positive);
  return mat;
}

Body readBody(const Item& it, const std::string& name) {
  const Map m(it, {"mass", "added_mass", "wet_weight", "diameter", "cdn", "cdt"});
  Body b;
  b.name = name;
  b.mass = m.number("mass", Range::NonNegative);
  b.added_mass = m.number("added_mass", 0.0, Range::NonNegative);
  b.wet_weight = m.number("wet_weight", Range::Any);
  b.diameter = m.number("diameter", Range::NonNegative);
  b.cdn = m.number("cdn", Range::NonNegative);
  b.cdt = m.number("cdt", Range::NonNegative);
  return b;
}

/// Look up a name in a name->index table; unknown names list the known ones.
std::size_t lookup(const Item& it, const std::map<std::string, std::size_t>& table,
                   const std::vector<std::string>& order, const std::string& kind) {
  const std::string name = readString(it);
  const auto f = table.find(name);
  if (f != table.end()) return f->second;
  const std::string known = order.empty() ? "none defined" : "known: " + joinList(order);
  throw ProblemError(it.path + " = " + quoted(name) + ": unknown " + kind + " (" + known + ")" +
                     lineSuffix(it.mark));
}

void readTop(const Item& it, TopBoundary& top) {
  const Map m(it, {"position", "force", "buoy"});
  std::vector<std::string> given;
  for (const char* k : {"position", "force", "buoy"})
    if (m.has(k)) given.push_back(k);
  if (given.size() != 1)
    throw ProblemError("top: " +
                       (given.empty() ? std::string("no boundary condition given")
                                      : "has " + joinList(given) + " at once") +
                       "; give exactly one of position, force, buoy" + lineSuffix(it.mark));
  if (m.has("position")) {
    const Map p(m.at("position"), {"x", "z"});
    top.type = TopBoundary::Type::Position;
    top.x = p.number("x");
    top.z = p.number("z");
  } else if (m.has("force")) {
    const Map f(m.at("force"), {"x", "z"});
    top.type = TopBoundary::Type::Force;
    top.fx = f.number("x");
    top.fz = f.number("z");
  } else {
    const Map b(m.at("buoy"),
                {"shape", "diameter", "height", "mass", "added_mass", "cd", "wind_area", "wind_cd"});
    top.type = TopBoundary::Type::Buoy;
    SurfaceBuoy& buoy = top.buoy;
    buoy.shape = SurfaceBuoy::Shape::Sphere;
    if (b.has("shape")) {
      const Item s = b.at("shape");
      const std::string v = readString(s);
      if (v == "sphere")
        buoy.shape = SurfaceBuoy::Shape::Sphere;
      else if (v == "cylinder")
        buoy.shape = SurfaceBuoy::Shape::Cylinder;
      else
        throw ProblemError(s.path + " = " + quoted(v) + ": unknown shape (known: sphere, cylinder)" +
                           lineSuffix(s.mark));
    }
    buoy.diameter = b.number("diameter", Range::Positive);
    if (buoy.shape == SurfaceBuoy::Shape::Cylinder) {
      buoy.height = b.number("height", Range::Positive);
    } else {
      if (b.has("height"))
        b.at("height").fail("only used for shape: cylinder (a sphere's height is its diameter)");
      buoy.height = buoy.diameter;
    }
    buoy.mass = b.number("mass", Range::NonNegative);
    buoy.added_mass = b.number("added_mass", 0.0, Range::NonNegative);
    buoy.cd = b.number("cd", 1.0, Range::NonNegative);
    buoy.wind_area = b.number("wind_area", 0.0, Range::NonNegative);
    buoy.wind_cd = b.number("wind_cd", 1.0, Range::NonNegative);
  }
}

void readSolver(const Item& it, StaticOptions& opt) {
  const Map m(it, {"static"});
  if (!presentAndNotNull(m, "static")) return;
  const Map s(m.at("static"),
              {"tolerance", "max_iterations", "relaxation", "adaptive_relaxation", "R1", "R2", "initial_guess"});
  opt.tolerance = s.number("tolerance", opt.tolerance, Range::Positive);
  if (s.has("max_iterations")) {
    const Item mi = s.at("max_iterations");
    const long long v = readInteger(mi);
    if (v < 1 || v > 100000000) mi.fail("must be an integer in [1, 1e8]");
    opt.max_iterations = static_cast<int>(v);
  }
  if (s.has("relaxation")) {
    const Item r = s.at("relaxation");
    opt.relaxation = readNumber(r);
    if (!(opt.relaxation > 0.0 && opt.relaxation <= 1.0)) r.fail("must be in (0, 1]");
  }
  if (s.has("adaptive_relaxation")) opt.adaptive_relaxation = readBool(s.at("adaptive_relaxation"));
  if (s.has("initial_guess")) {
    const Item g = s.at("initial_guess");
    const std::string v = readString(g);
    if (v == "catenary") opt.initial_guess = StaticOptions::InitialGuess::Catenary;
    else if (v == "straight") opt.initial_guess = StaticOptions::InitialGuess::StraightLine;
    else
      throw ProblemError(g.path + " = " + quoted(v) + ": unknown initial guess (known: catenary, straight)" +
                         lineSuffix(g.mark));
  }
  opt.R2 = s.number("R2", opt.R2, Range::Any);
  opt.R1 = s.number("R1", opt.R1, Range::Any);
  if (!(opt.R2 > 1.0)) {
    if (s.has("R2")) s.at("R2").fail("must be > 1");
    throw ProblemError("solver.static.R2 = " + formatNumber(opt.R2) + ": must be > 1");
  }
  if (!(opt.R1 > opt.R2)) {
    const std::string c = "R1 must be > R2 (R1 = " + formatNumber(opt.R1) + ", R2 = " + formatNumber(opt.R2) + ")";
    if (s.has("R1")) s.at("R1").fail(c);
    s.at("R2").fail(c);
  }
}

// ---------------------------------------------------------------------------------------------
// Dynamics

struct MotionTypeName {
  const char* name;
  TopMotion::Type type;
  const char* columns;  ///< table row layout, nullptr for types without a table
};

const std::vector<MotionTypeName>& motionTypes() {
  static const std::vector<MotionTypeName> list = {
      {"hold", TopMotion::Type::Hold, nullptr},
      {"sinusoid", TopMotion::Type::Sinusoid, nullptr},
      {"position_table", TopMotion::Type::PositionTable, "[t, x, z]"},
      {"velocity_table", TopMotion::Type::VelocityTable, "[t, vx, vz]"},
      {"force_table", TopMotion::Type::ForceTable, "[t, fx, fz]"},
      {"wave_follower", TopMotion::Type::WaveFollower, nullptr},
  };
  return list;
}

void readTopMotion(const Item& it, TopMotion& tm) {
  const Map m(it, {"type", "amplitude_x", "amplitude_z", "period", "phase_deg", "table", "prescribe"});
  std::vector<std::string> names;
  for (const auto& t : motionTypes()) names.push_back(t.name);
  const Item ti = m.required("type", "one of " + joinList(names));
  const std::string type = readString(ti);
  const MotionTypeName* mt = nullptr;
  for (const auto& t : motionTypes())
    if (type == t.name) mt = &t;
  if (mt == nullptr)
    throw ProblemError(ti.path + " = " + quoted(type) + ": unknown top motion type (known: " + joinList(names) +
                       ")" + lineSuffix(ti.mark));
  tm = TopMotion{};
  tm.type = mt->type;

  const bool sinusoid = mt->type == TopMotion::Type::Sinusoid;
  for (const char* k : {"amplitude_x", "amplitude_z", "period", "phase_deg"})
    if (!sinusoid && m.has(k)) m.at(k).fail("only used with type: sinusoid");
  if (mt->columns == nullptr && m.has("table"))
    m.at("table").fail("only used with type: position_table, velocity_table or force_table");

  if (sinusoid) {
    tm.amplitude_x = m.number("amplitude_x", 0.0, Range::Any);
    tm.amplitude_z = m.number("amplitude_z", 0.0, Range::Any);
    tm.period = m.number("period", Range::Positive);
    tm.phase = m.number("phase_deg", 0.0, Range::Any) * kDegToRad;
  }

  if (mt->columns != nullptr) {
    const Item tab = m.required("table", std::string("rows ") + mt->columns);
    const std::vector<Item> rows = listItems(tab);
    if (rows.empty()) tab.fail(std::string("needs at least one row ") + mt->columns);
    for (const Item& r : rows) {
      if (!r.node.IsSequence() || r.node.size() != 3) r.wrongType(std::string("a row ") + mt->columns);
      double v[3];
      for (std::size_t j = 0; j < 3; ++j)
        v[j] = readNumber(Item{r.node[j], r.path + "[" + std::to_string(j) + "]", markOf(r.node[j], r.mark)});
      if (!tm.table.empty() && !(v[0] > tm.table.back().t))
        r.fail("t must increase down the table (previous t = " + formatNumber(tm.table.back().t) + ")");
      tm.table.push_back(TopMotion::Row{v[0], v[1], v[2]});
    }
  }

  if (m.has("prescribe")) {
    const Item pi = m.at("prescribe");
    if (mt->type == TopMotion::Type::ForceTable) pi.fail("only used for kinematic top motions (not force_table)");
    const std::string v = readString(pi);
    if (v == "velocity") tm.prescribe_position = false;
    else if (v == "position") tm.prescribe_position = true;
    else
      throw ProblemError(pi.path + " = " + quoted(v) + ": unknown (known: velocity, position)" + lineSuffix(pi.mark));
  }
}

void readDynamics(const Item& it, DynamicOptions& d, double line_length) {
  const Map m(it, {"duration", "dt", "output_interval", "snapshot_interval", "record_s", "scheme", "lambda_inf",
                   "alpha_m", "alpha_k", "gamma", "max_cut_levels", "tolerance", "max_iterations", "relaxation",
                   "adaptive_relaxation", "adaptive_mesh", "mesh_weight", "top_motion"});
  d.duration = m.number("duration", d.duration, Range::Positive);
  d.dt = m.number("dt", d.dt, Range::Positive);
  if (m.has("output_interval")) {
    const Item oi = m.at("output_interval");
    d.output_interval = checked(oi, readNumber(oi), Range::NonNegative);
    if (d.output_interval > 0.0) {
      const double ratio = d.output_interval / d.dt;
      if (std::round(ratio) < 1.0 || std::fabs(ratio - std::round(ratio)) > 1e-9 * ratio)
        oi.fail("must be a whole multiple of dt = " + formatNumber(d.dt) + " (or 0 for every step)");
    }
  }
  d.snapshot_interval = m.number("snapshot_interval", d.snapshot_interval, Range::NonNegative);
  if (m.has("record_s")) {
    d.record_s.clear();
    for (const Item& r : listItems(m.at("record_s"))) {
      const double s = checked(r, readNumber(r), Range::NonNegative);
      if (s > line_length * (1.0 + 1e-12))
        r.fail("beyond the top of the line (total unstretched length " + formatNumber(line_length) + " m)");
      d.record_s.push_back(s);
    }
  }

  // Time integrator: exactly one of scheme (Table 1 name), lambda_inf (eq. 29) or the three parameters.
  const bool explicit_params = m.has("alpha_m") || m.has("alpha_k") || m.has("gamma");
  std::vector<std::string> forms;
  for (const char* k : {"scheme", "lambda_inf"})
    if (m.has(k)) forms.push_back(k);
  if (explicit_params) forms.push_back("alpha_m/alpha_k/gamma");
  if (forms.size() > 1) {
    const std::string k = m.has("lambda_inf") ? "lambda_inf"
                          : m.has("alpha_m")  ? "alpha_m"
                          : m.has("alpha_k")  ? "alpha_k"
                                              : "gamma";
    throw ProblemError(m.path() + ": has " + joinList(forms) +
                       " at once; give exactly one of scheme, lambda_inf or {alpha_m, alpha_k, gamma}" +
                       lineSuffix(m.at(k).mark));
  }
  const std::string kSchemes = "box, trapezoidal, backward, lambda0, lambda-0.5, lambda0.75";
  if (m.has("scheme")) {
    const Item si = m.at("scheme");
    const std::string name = readString(si);
    try {
      d.scheme = GeneralizedAlpha::preset(name);
    } catch (const std::invalid_argument&) {
      throw ProblemError(si.path + " = " + quoted(name) + ": unknown scheme (known: " + kSchemes +
                         "; for another lambda_inf write lambda_inf: VALUE)" + lineSuffix(si.mark));
    }
    d.scheme_name = name;
  } else if (m.has("lambda_inf")) {
    const Item li = m.at("lambda_inf");
    const double l = readNumber(li);
    if (!(l >= -1.0 && l < 1.0)) li.fail("must be in [-1, 1)");
    d.scheme = GeneralizedAlpha::fromLambdaInf(l);
    d.scheme_name = "lambda_inf=" + formatNumber(l);
  } else if (explicit_params) {
    const char* given = m.has("alpha_m") ? "alpha_m" : m.has("alpha_k") ? "alpha_k" : "gamma";
    for (const char* k : {"alpha_m", "alpha_k", "gamma"})
      if (!m.has(k))
        throw ProblemError(m.sub(k) + ": required key missing (alpha_m, alpha_k and gamma are given together)" +
                           lineSuffix(m.at(given).mark));
    GeneralizedAlpha g;
    g.alpha_m = m.number("alpha_m");
    g.alpha_k = m.number("alpha_k");
    g.gamma = m.number("gamma");
    const std::string e = g.validate();
    if (!e.empty()) throw ProblemError(e + lineSuffix(m.at("alpha_m").mark));
    d.scheme = g;
    d.scheme_name = "alpha_m=" + formatNumber(g.alpha_m) + ", alpha_k=" + formatNumber(g.alpha_k) +
                    ", gamma=" + formatNumber(g.gamma);
  }

  // Step control and Newton iteration per step.
  if (m.has("max_cut_levels")) {
    const Item ci = m.at("max_cut_levels");
    const long long v = readInteger(ci);
    if (v < 0 || v > 8) ci.fail("must be an integer in [0, 8]");
    d.max_cut_levels = static_cast<int>(v);
  }
  d.tolerance = m.number("tolerance", d.tolerance, Range::Positive);
  if (m.has("max_iterations")) {
    const Item mi = m.at("max_iterations");
    const long long v = readInteger(mi);
    if (v < 1 || v > 100000000) mi.fail("must be an integer in [1, 1e8]");
    d.max_iterations = static_cast<int>(v);
  }
  if (m.has("relaxation")) {
    const Item r = m.at("relaxation");
    d.relaxation = readNumber(r);
    if (!(d.relaxation > 0.0 && d.relaxation <= 1.0)) r.fail("must be in (0, 1]");
  }
  if (m.has("adaptive_relaxation")) d.adaptive_relaxation = readBool(m.at("adaptive_relaxation"));
  if (m.has("adaptive_mesh")) d.adaptive_mesh = readBool(m.at("adaptive_mesh"));
  d.mesh_weight = m.number("mesh_weight", d.mesh_weight, Range::NonNegative);

  if (presentAndNotNull(m, "top_motion")) readTopMotion(m.at("top_motion"), d.top_motion);
}

void readLine(const Item& it, Problem& pb, const std::map<std::string, std::size_t>& mat_index,
              const std::vector<std::string>& mat_names,
              const std::map<std::string, std::size_t>& body_index,
              const std::vector<std::string>& body_names) {
  const std::vector<Item> items = listItems(it);
  if (items.empty()) it.fail("needs at least one segment");
  std::vector<std::size_t> pending;  // body items before the first segment: placed at its lower end
  for (const Item& item : items) {
    if (!item.node.IsMap()) item.wrongType("a map: a segment {material, length, ...} or a body {body}");
    const bool is_seg = static_cast<bool>(item.node["material"]);
    const bool is_body = static_cast<bool>(item.node["body"]);
    if (is_seg && is_body)
      throw ProblemError(item.path + ": has both \"material\" and \"body\"; an item is either a segment "
                         "{material, length, spacing, bodies} or a body between segments {body}" +
                         lineSuffix(item.mark));
    if (!is_seg && !is_body)
      throw ProblemError(item.path + ": neither \"material\" (a segment) nor \"body\" (a body between "
                         "segments) given" + lineSuffix(item.mark));
    if (is_body) {
      const Map m(item, {"body"});
      const std::size_t b = lookup(m.at("body"), body_index, body_names, "body");
      if (pb.segments.empty())
        pending.push_back(b);
      else
        pb.segments.back().bodies.push_back(BodyPlacement{b, pb.segments.back().length});
      continue;
    }
    const Map m(item, {"material", "length", "spacing", "bodies"});
    Segment seg;
    seg.material = lookup(m.at("material"), mat_index, mat_names, "material");
    seg.length = m.number("length", Range::Positive);
    seg.spacing = m.number("spacing", seg.spacing, Range::Positive);
    for (std::size_t b : pending) seg.bodies.push_back(BodyPlacement{b, 0.0});
    pending.clear();
    if (presentAndNotNull(m, "bodies")) {
      for (const Item& bi : listItems(m.at("bodies"))) {
        const Map bm(bi, {"body", "at", "every", "count"});
        const std::size_t b = lookup(bm.required("body"), body_index, body_names, "body");
        const double at = bm.number("at", Range::NonNegative);
        long long count = 1;
        if (bm.has("count")) {
          const Item ci = bm.at("count");
          count = readInteger(ci);
          if (count < 1 || count > 1000000) ci.fail("must be an integer >= 1");
        }
        double every = 0.0;
        if (count > 1) {
          every = bm.number("every", Range::Positive);
        } else if (bm.has("every")) {
          bm.at("every").fail("only used with count > 1");
        }
        const double tol = 1e-9 * std::max(1.0, seg.length);
        for (long long k = 0; k < count; ++k) {
          double s = at + static_cast<double>(k) * every;
          if (s > seg.length + tol) {
            if (k == 0) bm.at("at").fail("must be <= the segment length " + formatNumber(seg.length));
            throw ProblemError(bi.path + ": body " + std::to_string(k + 1) + " of " + std::to_string(count) +
                               " lands at " + formatNumber(s) + " m, beyond the segment length " +
                               formatNumber(seg.length) + " m" + lineSuffix(bi.mark));
          }
          s = std::min(s, seg.length);
          seg.bodies.push_back(BodyPlacement{b, s});
        }
      }
    }
    pb.segments.push_back(seg);
  }
  if (pb.segments.empty()) it.failNoValue("needs at least one segment {material, length}");
}

Problem parse(const YAML::Node& root) {
  if (!root.IsDefined() || root.IsNull())
    throw ProblemError("problem file is empty: expected a map with at least materials, line and top");
  const Item rit{root, "", markOf(root, YAML::Mark::null_mark())};
  if (!root.IsMap())
    throw ProblemError("top level: expected a map with keys materials, line, top, ..., found " + typeName(root) +
                       lineSuffix(rit.mark));
  const Map top(rit, {"name", "environment", "materials", "bodies", "line", "anchor", "top", "solver",
                      "dynamics"});
  Problem pb;
  if (top.has("name")) pb.name = readString(top.at("name"));
  if (presentAndNotNull(top, "environment")) readEnvironment(top.at("environment"), pb.environment);

  // Materials, in file order.
  std::map<std::string, std::size_t> mat_index;
  std::vector<std::string> mat_names;
  {
    const Item mit = top.required("materials");
    if (!mit.node.IsMap()) mit.wrongType("a map name -> properties");
    if (mit.node.size() == 0) mit.failNoValue("needs at least one material");
    for (auto kv : mit.node) {
      if (!kv.first.IsScalar())
        throw ProblemError("materials: names must be plain strings" + lineSuffix(kv.first.Mark()));
      const std::string name = kv.first.Scalar();
      if (mat_index.count(name))
        throw ProblemError("materials." + name + ": duplicate material name" + lineSuffix(kv.first.Mark()));
      const Item m{kv.second, "materials." + name, markOf(kv.second, kv.first.Mark())};
      mat_index[name] = pb.materials.size();
      mat_names.push_back(name);
      pb.materials.push_back(readMaterial(m, name));
    }
  }

  // Bodies (optional).
  std::map<std::string, std::size_t> body_index;
  std::vector<std::string> body_names;
  if (presentAndNotNull(top, "bodies")) {
    const Item bit = top.at("bodies");
    if (!bit.node.IsMap()) bit.wrongType("a map name -> properties");
    for (auto kv : bit.node) {
      if (!kv.first.IsScalar())
        throw ProblemError("bodies: names must be plain strings" + lineSuffix(kv.first.Mark()));
      const std::string name = kv.first.Scalar();
      if (body_index.count(name))
        throw ProblemError("bodies." + name + ": duplicate body name" + lineSuffix(kv.first.Mark()));
      const Item b{kv.second, "bodies." + name, markOf(kv.second, kv.first.Mark())};
      body_index[name] = pb.bodies.size();
      body_names.push_back(name);
      pb.bodies.push_back(readBody(b, name));
    }
  }

  readLine(top.required("line"), pb, mat_index, mat_names, body_index, body_names);

  // Anchor: x defaults to 0, z to the seabed elevation at x.
  pb.anchor_x = 0.0;
  bool anchor_z_given = false;
  if (presentAndNotNull(top, "anchor")) {
    const Map a(top.at("anchor"), {"x", "z"});
    pb.anchor_x = a.number("x", 0.0, Range::Any);
    if (a.has("z")) {
      anchor_z_given = true;
      const Item zi = a.at("z");
      pb.anchor_z = readNumber(zi);
      if (pb.anchor_z > 0.0) zi.fail("must be <= 0 (z = 0 is the mean sea surface, z up)");
      const double bottom = pb.environment.seabedElevation(pb.anchor_x);
      if (pb.anchor_z < bottom - 1e-9 * std::max(1.0, std::fabs(bottom)))
        zi.fail("below the seabed (seabed at z = " + formatNumber(bottom) + " m at x = " +
                formatNumber(pb.anchor_x) + " m)");
    }
  }
  if (!anchor_z_given) pb.anchor_z = pb.environment.seabedElevation(pb.anchor_x);

  readTop(top.required("top"), pb.top);
  if (presentAndNotNull(top, "solver")) readSolver(top.at("solver"), pb.static_options);
  if (presentAndNotNull(top, "dynamics")) readDynamics(top.at("dynamics"), pb.dynamics, pb.totalLength());

  std::string msg = pb.static_options.validate();
  if (msg.empty()) msg = pb.validate();
  if (!msg.empty()) throw ProblemError(msg);
  return pb;
}

}  // namespace

Problem loadProblemFromString(const std::string& yaml_text) {
  YAML::Node root;
  try {
    const std::vector<YAML::Node> docs = YAML::LoadAll(yaml_text);
    if (docs.size() > 1)
      throw ProblemError("the text holds " + std::to_string(docs.size()) +
                         " YAML documents (separated by ---); a problem file holds exactly one");
    if (!docs.empty()) root = docs.front();
  } catch (const YAML::Exception& e) {
    std::string msg = "YAML syntax error";
    if (!e.mark.is_null())
      msg += " at line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1);
    throw ProblemError(msg + ": " + e.msg);
  }
  try {
    return parse(root);
  } catch (const YAML::Exception& e) {  // should not happen: all access is checked above
    throw ProblemError(std::string("YAML error: ") + e.what());
  }
}

Problem loadProblemFromFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const std::error_code ec(errno, std::generic_category());
    throw ProblemError(path + ": cannot read file (" + ec.message() + ")");
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw ProblemError(path + ": read error");
  try {
    Problem pb = loadProblemFromString(ss.str());
    if (pb.name.empty()) {
      // Default name: the file name without directory and extension.
      std::string stem = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
      const auto dot = stem.find_last_of('.');
      if (dot != std::string::npos && dot > 0) stem = stem.substr(0, dot);
      pb.name = stem;
    }
    return pb;
  } catch (const ProblemError& e) {
    throw ProblemError(path + ": " + e.what());
  }
}

}  // namespace core
}  // namespace mooring_dynamics
