// System files (docs/problem_format.md, "Systems"): points and lines, with the section readers of
// single-line problem files (problem_sections.hpp).
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/problem_io_dynamics.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {
namespace {

using namespace yaml;
using namespace sections;
using problem_io_detail::readDynamics;

/// A point position: [x, y, z] or {x, y, z} [m].
void readPosition(const Item& it, double& x, double& y, double& z) {
  if (it.node.IsSequence()) {
    const std::vector<Item> v = listItems(it);
    if (v.size() != 3) it.fail("needs 3 values [x, y, z], has " + std::to_string(v.size()));
    x = readNumber(v[0]);
    y = readNumber(v[1]);
    z = readNumber(v[2]);
    return;
  }
  const Map m(it, {"x", "y", "z"});
  x = m.number("x");
  y = m.number("y", 0.0, Range::Any);
  z = m.number("z");
}

/// A system file (docs/problem_format.md, "Systems"): `points` and `lines` instead of `line`,
/// `anchor` and `top`.
SystemProblem parseSystem(const YAML::Node& root, const std::string& base_dir) {
  const Item rit{root, "", markOf(root, YAML::Mark::null_mark())};
  if (!root.IsMap()) throw ProblemError("top level: expected a map" + lineSuffix(rit.mark));
  const Map top(rit, {"name", "model", "environment", "materials", "bodies", "points", "lines", "solver",
                      "dynamics", "limits"});
  SystemProblem sp;
  if (top.has("name")) sp.name = readString(top.at("name"));
  if (top.has("model")) sp.formulation = readModel(top.at("model"));
  if (presentAndNotNull(top, "environment")) readEnvironment(top.at("environment"), sp.environment, base_dir);
  Catalogue cat;
  readCatalogue(top, sp.materials, sp.bodies, cat);
  if (presentAndNotNull(top, "solver")) readSolver(top.at("solver"), sp.static_options);

  // Points, in file order.
  std::map<std::string, std::size_t> point_index;
  std::vector<std::string> point_names;
  const Item pit = top.required("points");
  if (!pit.node.IsMap()) pit.wrongType("a map name -> {type, position, ...}");
  for (auto kv : pit.node) {
    if (!kv.first.IsScalar()) throw ProblemError("points: names must be plain strings" + lineSuffix(kv.first.Mark()));
    const std::string name = kv.first.Scalar();
    if (point_index.count(name) || name == "free")
      throw ProblemError("points." + name + (name == "free" ? ": \"free\" is reserved (a line's free end)"
                                                             : ": duplicate point name") +
                         lineSuffix(kv.first.Mark()));
    const Item it{kv.second, "points." + name, markOf(kv.second, kv.first.Mark())};
    const Map m(it, {"type", "position", "buoy", "body"});
    SystemPoint pt;
    pt.name = name;
    const Item ti = m.required("type");
    const std::string t = readString(ti);
    if (t == "anchor") pt.type = SystemPoint::Type::Anchor;
    else if (t == "fixed") pt.type = SystemPoint::Type::Fixed;
    else if (t == "buoy") pt.type = SystemPoint::Type::Buoy;
    else if (t == "body") pt.type = SystemPoint::Type::Body;
    else throw ProblemError(ti.path + " = " + quoted(t) + ": unknown point type (known: anchor, fixed, buoy, body)" +
                            lineSuffix(ti.mark));
    if (m.has("position")) {
      readPosition(m.at("position"), pt.x, pt.y, pt.z);
      pt.position_given = true;
    } else if (!pt.free()) {
      m.required("position");  // an anchor or a fixed point needs its place
    }
    if (pt.type == SystemPoint::Type::Buoy) readBuoy(m.required("buoy"), pt.buoy);
    else if (m.has("buoy")) m.at("buoy").fail("only for type: buoy");
    if (pt.type == SystemPoint::Type::Body) pt.body = lookup(m.required("body"), cat.body_index, cat.body_names, "body");
    else if (m.has("body")) m.at("body").fail("only for type: body");
    point_index[name] = sp.points.size();
    point_names.push_back(name);
    sp.points.push_back(pt);
  }

  // Lines, each from its lower end (a point or `free`) to its upper end.
  const std::vector<Item> lit = listItems(top.required("lines"));
  if (lit.empty()) top.at("lines").fail("needs at least one line");
  for (std::size_t i = 0; i < lit.size(); ++i) {
    const Map m(lit[i], {"name", "from", "to", "segments", "end_body"});
    SystemLine l;
    l.name = m.has("name") ? readString(m.at("name")) : "line" + std::to_string(i);
    for (const SystemLine& prev : sp.lines)
      if (prev.name == l.name)
        (m.has("name") ? m.at("name") : lit[i]).fail("duplicate line name (every line needs its own: it names the "
                                                     "output files and columns)");
    const Item fi = m.required("from");
    if (readString(fi) == "free") l.from = SystemLine::kFreeEnd;
    else l.from = lookup(fi, point_index, point_names, "point");
    l.to = lookup(m.required("to"), point_index, point_names, "point");
    if (m.has("end_body")) l.end_body = lookup(m.at("end_body"), cat.body_index, cat.body_names, "body");
    Problem tmp;
    readLine(m.required("segments"), tmp, cat.mat_index, cat.mat_names, cat.body_index, cat.body_names);
    l.segments = tmp.segments;
    sp.lines.push_back(l);
  }
  if (presentAndNotNull(top, "dynamics")) {
    double longest = 0.0;
    for (const SystemLine& l : sp.lines) {
      double L = 0.0;
      for (const Segment& g : l.segments) L += g.length;
      longest = std::max(longest, L);
    }
    const Item di = top.at("dynamics");
    readDynamics(di, sp.dynamics, longest);
    if (sp.dynamics.top_motion.type != TopMotion::Type::Hold)
      di.fail("top_motion: a system's free points move by themselves; there is no top motion to give");
    if (!sp.dynamics.record_s.empty()) di.fail("record_s: not used by systems (every line's top tension is written)");
  }
  if (presentAndNotNull(top, "limits")) readLimits(top.at("limits"), sp.limits);
  std::string msg = sp.static_options.validate();
  if (msg.empty()) msg = sp.validate();
  if (!msg.empty()) throw ProblemError(msg);
  return sp;
}

}  // namespace

bool isSystemText(const std::string& yaml_text) {
  try {
    const YAML::Node root = parseYaml(yaml_text);
    return root.IsMap() && root["lines"] && root["points"];
  } catch (const std::exception&) {
    return false;
  }
}

bool isSystemFile(const std::string& path) {
  try {
    return isSystemText(readFileText(path));
  } catch (const ProblemError&) {
    return false;
  }
}

SystemProblem loadSystemFromString(const std::string& yaml_text, const std::string& base_dir) {
  const YAML::Node root = parseYaml(yaml_text);
  if (!root.IsDefined() || root.IsNull()) throw ProblemError("system file is empty: expected points and lines");
  try {
    return parseSystem(root, base_dir);
  } catch (const YAML::Exception& e) {
    throw ProblemError(std::string("YAML error: ") + e.what());
  }
}

SystemProblem loadSystemFromFile(const std::string& path) {
  const std::string text = readFileText(path);
  try {
    SystemProblem sp = loadSystemFromString(text, std::filesystem::path(path).parent_path().string());
    if (sp.name.empty()) sp.name = std::filesystem::path(path).stem().string();
    return sp;
  } catch (const ProblemError& e) {
    throw ProblemError(path + ": " + e.what());
  }
}

}  // namespace core
}  // namespace mooring_dynamics
