// System files (docs/problem_format.md, "Systems"): points and lines, with the section readers of
// single-line problem files (problem_sections.hpp).
#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/problem_io_dynamics.hpp"
#include "mooring_dynamics/core/io/rao_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "mooring_dynamics/core/model/sea_state_motion.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {
namespace {

using namespace yaml;
using namespace sections;
using problem_io_detail::readDynamics;
using problem_io_detail::readWaves;

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

/// vessel.lines: each `{name, fairlead: [x, y, z] (body frame), anchor: [x, y, z] (world),
/// segments: [...]}` becomes an anchor point `<name>/anchor`, a vessel point `<name>/fairlead`
/// and a line between them.
void readVesselLines(const YAML::Node& node, const Item& vessel_item, const Catalogue& cat, SystemProblem& sp,
                     std::map<std::string, std::size_t>& point_index, std::vector<std::string>& point_names) {
  const Item lines_item{node, vessel_item.path + ".lines", markOf(node, vessel_item.mark)};
  const std::vector<Item> items = listItems(lines_item);
  if (items.empty()) lines_item.fail("needs at least one line");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Map m(items[i], {"name", "fairlead", "anchor", "segments"});
    SystemLine l;
    l.name = m.has("name") ? readString(m.at("name")) : "line" + std::to_string(sp.lines.size());
    for (const SystemLine& other : sp.lines)
      if (other.name == l.name) m.at("name").fail("duplicate line name");
    SystemPoint anchor, fairlead;
    anchor.name = l.name + "/anchor";
    anchor.type = SystemPoint::Type::Anchor;
    readPosition(m.required("anchor"), anchor.x, anchor.y, anchor.z);
    anchor.position_given = true;
    fairlead.name = l.name + "/fairlead";
    fairlead.type = SystemPoint::Type::Vessel;
    readPosition(m.required("fairlead"), fairlead.body_offset.x(), fairlead.body_offset.y(), fairlead.body_offset.z());
    fairlead.position_given = true;
    for (const SystemPoint* pt : {&anchor, &fairlead}) {
      if (point_index.count(pt->name)) m.at("name").fail("the point " + pt->name + " exists already");
      point_index[pt->name] = sp.points.size();
      point_names.push_back(pt->name);
      sp.points.push_back(*pt);
    }
    l.from = point_index[anchor.name];
    l.to = point_index[fairlead.name];
    Problem tmp;
    readLine(m.required("segments"), tmp, cat.mat_index, cat.mat_names, cat.body_index, cat.body_names);
    l.segments = tmp.segments;
    sp.lines.push_back(l);
  }
}

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// vessel.pose: `position` [x, y, z] (world, m; default 0) and either `orientation` {x, y, z, w}
/// (a unit quaternion, body -> world) or `roll_deg`, `pitch_deg`, `yaw_deg` (default 0).
RigidPose readPose(const Item& it) {
  const Map m(it, {"position", "orientation", "roll_deg", "pitch_deg", "yaw_deg"});
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  if (m.has("position")) readPosition(m.at("position"), pos.x(), pos.y(), pos.z());
  const bool euler = m.has("roll_deg") || m.has("pitch_deg") || m.has("yaw_deg");
  if (m.has("orientation")) {
    if (euler) m.at("orientation").fail("give either orientation or roll_deg/pitch_deg/yaw_deg, not both");
    const Map q(m.at("orientation"), {"x", "y", "z", "w"});
    RigidPose p;
    p.position = pos;
    p.orientation = Eigen::Quaterniond(q.number("w"), q.number("x"), q.number("y"), q.number("z"));
    const std::string e = p.validate(it.path);
    if (!e.empty()) m.at("orientation").fail("not a unit quaternion (" + e + ")");
    p.orientation.normalize();
    return p;
  }
  return RigidPose::fromRollPitchYaw(pos, kDegToRad * m.number("roll_deg", 0.0, Range::Any),
                                     kDegToRad * m.number("pitch_deg", 0.0, Range::Any),
                                     kDegToRad * m.number("yaw_deg", 0.0, Range::Any));
}

/// The points by name, in file order.
struct PointNames {
  std::map<std::string, std::size_t> index;
  std::vector<std::string> names;
};

/// One of `choices` (the first is the default when the key is absent), as its index.
std::size_t readChoice(const Map& m, const std::string& key, const std::vector<std::string>& choices) {
  if (!m.has(key)) return 0;
  const std::string v = readString(m.at(key));
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (v == choices[i]) return i;
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  m.at(key).failQuoted("must be one of " + list);
  return 0;
}

/// The common keys of a table section (`vessel.raos`, `low_frequency.wave_drift`): `file`
/// (resolved against base_dir; returned as written), `format` (given, or from the extension: one
/// of `wamit_exts` or .csv), `ulen` (required for wamit; `csv_ulen_note` says why a CSV has none),
/// `extend` and `symmetry`.
std::string readTableSource(const Map& m, const std::string& base_dir, const std::vector<std::string>& wamit_exts,
                            const std::string& what, const std::string& csv_ulen_note, RaoSource& how) {
  const std::string rel = readString(m.required("file", what));
  how.file = relativeTo(rel, base_dir);
  bool wamit = false;
  if (m.has("format")) {
    const std::string format = readString(m.at("format"));
    if (format != "wamit" && format != "csv") m.at("format").failQuoted("must be wamit or csv");
    wamit = format == "wamit";
  } else {
    const std::string ext = std::filesystem::path(rel).extension().string();
    wamit = std::find(wamit_exts.begin(), wamit_exts.end(), ext) != wamit_exts.end();
    if (!wamit && ext != ".csv" && ext != ".CSV") {
      std::string list;
      for (const std::string& e : wamit_exts) list += e + (wamit_exts.size() == 1 ? " nor " : ", ");
      m.at("file").failQuoted(std::string(wamit_exts.size() == 1 ? "ends in neither " : "ends in none of ") + list +
                              ".csv: say which with " + m.sub("format") + ": wamit or csv");
    }
  }
  how.format = wamit ? RaoSource::Format::Wamit : RaoSource::Format::Csv;
  if (wamit) how.ulen = m.number("ulen", Range::Positive);  // required: a WAMIT run's ULEN is not in its files
  else if (m.has("ulen")) m.at("ulen").fail("only for format wamit (" + csv_ulen_note + ")");
  const std::size_t ext = readChoice(m, "extend", {"error", "zero", "hold"});
  how.extend = ext == 0 ? RaoExtend::None : ext == 1 ? RaoExtend::Zero : RaoExtend::Hold;
  how.symmetry = readChoice(m, "symmetry", {"none", "port_starboard"}) == 1 ? RaoSymmetry::PortStarboard
                                                                             : RaoSymmetry::None;
  return rel;
}

/// vessel.raos: {file, format, ulen, phase, rotation_unit, reference_point, extend, symmetry}
/// (docs/problem_format.md "vessel.raos"); the table is read here so that its errors name the key.
void readRaos(const Item& it, const std::string& base_dir, Vessel& v) {
  const Map m(it, {"file", "format", "ulen", "phase", "rotation_unit", "reference_point", "extend", "symmetry"});
  RaoSource& how = v.raos;
  const std::string rel = readTableSource(m, base_dir, {".4"}, "a WAMIT .4 file or a CSV of the hull's motion RAOs",
                                          "a CSV gives rotations per metre; see rotation_unit", how);
  how.phase_lag = readChoice(m, "phase", {"lead", "lag"}) == 1;
  if (m.has("rotation_unit") && how.format == RaoSource::Format::Wamit)
    m.at("rotation_unit").fail("only for format csv (a WAMIT .4 file gives rotations as xi ULEN / A)");
  how.rotations_in_deg = readChoice(m, "rotation_unit", {"rad", "deg"}) == 1;
  if (m.has("reference_point")) {
    double x = 0.0, y = 0.0, z = 0.0;
    readPosition(m.at("reference_point"), x, y, z);
    how.reference_point = Eigen::Vector3d(x, y, z);
  }
  try {
    v.rao_table = loadRaos(how);
  } catch (const ProblemError& e) {
    throw ProblemError(m.sub("file") + " = " + quoted(rel) + ": " + e.what() + lineSuffix(m.at("file").mark));
  }
}

/// Three numbers [a, b, c].
Eigen::Vector3d readTriple(const Item& it) {
  const std::vector<Item> v = listItems(it);
  if (v.size() != 3) it.fail("needs 3 values (surge, sway, yaw), has " + std::to_string(v.size()));
  return Eigen::Vector3d(readNumber(v[0]), readNumber(v[1]), readNumber(v[2]));
}

/// vessel.low_frequency: {mass, yaw_inertia, added_mass, damping, mean_force} (HullSlowMotion).
const std::vector<std::string> kSlowMotionKeys = {"mass", "yaw_inertia", "added_mass", "damping", "mean_force",
                                                  "wave_drift"};

void readSlowMotion(const Item& it, Vessel& v) {
  const Map m(it, kSlowMotionKeys);
  HullSlowMotionOptions& o = v.slow;
  o.mass = m.number("mass", Range::Positive);
  o.yaw_inertia = m.number("yaw_inertia", Range::Positive);
  if (m.has("added_mass")) o.added_mass = readTriple(m.at("added_mass"));
  if (m.has("damping")) o.damping = readTriple(m.at("damping"));
  if (m.has("mean_force")) o.mean_force = readTriple(m.at("mean_force"));
  const std::string e = o.validate();
  if (!e.empty()) throw ProblemError(e + lineSuffix(it.mark));
  v.low_frequency = true;
}

/// vessel.low_frequency.wave_drift: {file, format, ulen, extend, symmetry, slowly_varying}
/// (WaveDrift; docs/problem_format.md); read after the sea state, whose frequencies and headings
/// the table must cover.
void readWaveDrift(const Item& it, const std::string& base_dir, SystemProblem& sp) {
  const Map m(it, {"file", "format", "ulen", "extend", "symmetry", "slowly_varying"});
  Vessel& v = sp.vessel;
  RaoSource& how = v.drift.table;
  const std::string rel = readTableSource(m, base_dir, {".8", ".9"},
                                          "a WAMIT .8 or .9 file or a CSV of the hull's mean drift coefficients",
                                          "a CSV gives SI values", how);
  v.drift.newman = readChoice(m, "slowly_varying", {"newman", "none"}) == 0;
  try {
    v.drift_table = loadDrift(how, sp.environment.water_density * sp.environment.gravity);
  } catch (const ProblemError& e) {
    throw ProblemError(m.sub("file") + " = " + quoted(rel) + ": " + e.what() + lineSuffix(m.at("file").mark));
  }
  try {  // the table must cover the sea: say so now, not at t = 0
    const WaveField sea(sp.environment.waves, sp.environment.depth, sp.environment.gravity);
    WaveDrift(sea, v.drift_table, v.drift.newman).meanForce(v.pose.yaw());
  } catch (const std::invalid_argument& e) {
    m.at("file").fail(e.what());
  }
  v.wave_drift = true;
}

/// The vessel section: its frame, pose and motion (a table, or a sea state through RAOs); its
/// lines come after the system's own.
void readVessel(const Item& vi, const std::string& base_dir, SystemProblem& sp) {
  const Map vm(vi, {"frame", "pose", "lines", "motion_table", "sea_state", "raos", "low_frequency"});
  sp.vessel.present = true;
  if (vm.has("frame")) sp.vessel.frame = readString(vm.at("frame"));
  if (vm.has("motion_table")) {
    const std::filesystem::path f(readString(vm.at("motion_table")));
    sp.vessel.motion_table = (f.is_relative() && !base_dir.empty() ? std::filesystem::path(base_dir) / f : f).string();
  }
  if (vm.has("pose")) sp.vessel.pose = readPose(vm.at("pose"));
  if (vm.has("low_frequency")) {
    if (vm.has("motion_table"))
      vm.at("low_frequency").fail("a motion table prescribes the whole motion: give low_frequency or motion_table");
    readSlowMotion(vm.at("low_frequency"), sp.vessel);
  }
  if (vm.has("raos") && !vm.has("sea_state")) vm.at("raos").fail("RAOs without vessel.sea_state move nothing: give the sea");
  std::optional<Item> drift;
  if (vm.has("low_frequency")) {
    const Map lf(vm.at("low_frequency"), kSlowMotionKeys);
    if (lf.has("wave_drift")) drift = lf.at("wave_drift");
  }
  if (drift && !vm.has("sea_state")) drift->fail("wave drift needs the sea: give vessel.sea_state");
  if (!vm.has("sea_state")) return;
  const Item si = vm.at("sea_state");
  if (vm.has("motion_table")) si.fail("give one motion of the vessel: sea_state or motion_table, not both");
  if (sp.environment.waves.type != WaveSpec::Type::None)
    si.fail("give the sea once: vessel.sea_state also sets the waves on the lines; remove environment.waves");
  if (!vm.has("raos")) si.fail("needs vessel.raos (the hull's motion RAOs) to move the vessel");
  sp.environment.waves = readWaves(si);
  if (sp.environment.waves.type == WaveSpec::Type::None) si.fail("type none moves nothing: remove sea_state");
  sp.vessel.sea_state = true;
  readRaos(vm.at("raos"), base_dir, sp.vessel);
  try {  // the table must cover the sea (frequencies, headings): say so now, not at t = 0
    const WaveField sea(sp.environment.waves, sp.environment.depth, sp.environment.gravity);
    SeaStateMotion(sea, sp.vessel.rao_table, sp.vessel.pose, sp.vessel.raos.reference_point);
  } catch (const std::invalid_argument& e) {
    vm.at("raos").fail(e.what());
  }
  if (drift) readWaveDrift(*drift, base_dir, sp);
}

/// One entry of `points`: its type, position (a vessel point's in the body frame), buoy or body.
SystemPoint readPoint(const std::string& name, const Item& it, const SystemProblem& sp, const Catalogue& cat) {
  const Map m(it, {"type", "position", "buoy", "body"});
  SystemPoint pt;
  pt.name = name;
  const Item ti = m.required("type");
  const std::string t = readString(ti);
  if (t == "anchor") pt.type = SystemPoint::Type::Anchor;
  else if (t == "fixed") pt.type = SystemPoint::Type::Fixed;
  else if (t == "buoy") pt.type = SystemPoint::Type::Buoy;
  else if (t == "body") pt.type = SystemPoint::Type::Body;
  else if (t == "vessel") pt.type = SystemPoint::Type::Vessel;
  else throw ProblemError(ti.path + " = " + quoted(t) +
                          ": unknown point type (known: anchor, fixed, buoy, body, vessel)" + lineSuffix(ti.mark));
  if (pt.type == SystemPoint::Type::Vessel) {  // a fairlead: its place in the vessel's body frame
    if (!sp.vessel.present) ti.fail("a vessel point needs the file's `vessel:` section (frame and pose)");
    readPosition(m.required("position"), pt.body_offset.x(), pt.body_offset.y(), pt.body_offset.z());
    pt.position_given = true;
  } else if (m.has("position")) {
    readPosition(m.at("position"), pt.x, pt.y, pt.z);
    pt.position_given = true;
  } else if (!pt.free()) {
    m.required("position");  // an anchor or a fixed point needs its place
  }
  if (pt.type == SystemPoint::Type::Buoy) readBuoy(m.required("buoy"), pt.buoy);
  else if (m.has("buoy")) m.at("buoy").fail("only for type: buoy");
  if (pt.type == SystemPoint::Type::Body) pt.body = lookup(m.required("body"), cat.body_index, cat.body_names, "body");
  else if (m.has("body")) m.at("body").fail("only for type: body");
  return pt;
}

/// The `points` map, in file order.
void readPoints(const Item& pit, const Catalogue& cat, SystemProblem& sp, PointNames& pn) {
  if (!pit.node.IsMap()) pit.wrongType("a map name -> {type, position, ...}");
  for (auto kv : pit.node) {
    if (!kv.first.IsScalar()) throw ProblemError("points: names must be plain strings" + lineSuffix(kv.first.Mark()));
    const std::string name = kv.first.Scalar();
    if (pn.index.count(name) || name == "free")
      throw ProblemError("points." + name + (name == "free" ? ": \"free\" is reserved (a line's free end)"
                                                             : ": duplicate point name") +
                         lineSuffix(kv.first.Mark()));
    const Item it{kv.second, "points." + name, markOf(kv.second, kv.first.Mark())};
    const SystemPoint pt = readPoint(name, it, sp, cat);
    pn.index[name] = sp.points.size();
    pn.names.push_back(name);
    sp.points.push_back(pt);
  }
}

/// The `lines` list, each from its lower end (a point or `free`) to its upper end.
void readSystemLines(const std::vector<Item>& lit, const Catalogue& cat, const PointNames& pn, SystemProblem& sp) {
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
    else l.from = lookup(fi, pn.index, pn.names, "point");
    l.to = lookup(m.required("to"), pn.index, pn.names, "point");
    if (m.has("end_body")) l.end_body = lookup(m.at("end_body"), cat.body_index, cat.body_names, "body");
    Problem tmp;
    readLine(m.required("segments"), tmp, cat.mat_index, cat.mat_names, cat.body_index, cat.body_names);
    l.segments = tmp.segments;
    sp.lines.push_back(l);
  }
}

/// The `dynamics` section of a system: no top motion and no recorded nodes.
void readSystemDynamics(const Item& di, SystemProblem& sp) {
  double longest = 0.0;
  for (const SystemLine& l : sp.lines) {
    double L = 0.0;
    for (const Segment& g : l.segments) L += g.length;
    longest = std::max(longest, L);
  }
  readDynamics(di, sp.dynamics, longest);
  if (sp.dynamics.top_motion.type != TopMotion::Type::Hold)
    di.fail("top_motion: a system's free points move by themselves; there is no top motion to give");
  if (!sp.dynamics.record_s.empty()) di.fail("record_s: not used by systems (every line's top tension is written)");
}

/// A system file (docs/problem_format.md, "Systems"): `points` and `lines` instead of `line`,
/// `anchor` and `top`; and/or a `vessel:` with its lines from anchors to fairleads.
SystemProblem parseSystem(const YAML::Node& root, const std::string& base_dir) {
  const Item rit{root, "", markOf(root, YAML::Mark::null_mark())};
  if (!root.IsMap()) throw ProblemError("top level: expected a map" + lineSuffix(rit.mark));
  const Map top(rit, {"name", "model", "environment", "materials", "bodies", "points", "lines", "solver",
                      "dynamics", "vessel", "limits"});
  SystemProblem sp;
  if (top.has("name")) sp.name = readString(top.at("name"));
  if (top.has("model")) sp.formulation = readModel(top.at("model"));
  if (presentAndNotNull(top, "environment")) readEnvironment(top.at("environment"), sp.environment, base_dir);
  Catalogue cat;
  readCatalogue(top, sp.materials, sp.bodies, cat);
  if (presentAndNotNull(top, "solver")) readSolver(top.at("solver"), sp.static_options);
  const bool vessel_lines = presentAndNotNull(top, "vessel") && top.at("vessel").node.IsMap() &&
                            top.at("vessel").node["lines"];
  if (presentAndNotNull(top, "vessel")) readVessel(top.at("vessel"), base_dir, sp);
  PointNames pn;
  if (!vessel_lines || top.has("points")) readPoints(top.required("points"), cat, sp, pn);
  const std::vector<Item> lit = vessel_lines && !top.has("lines") ? std::vector<Item>{} : listItems(top.required("lines"));
  if (lit.empty() && !vessel_lines) top.at("lines").fail("needs at least one line");
  readSystemLines(lit, cat, pn, sp);
  if (vessel_lines) readVesselLines(top.at("vessel").node["lines"], top.at("vessel"), cat, sp, pn.index, pn.names);
  sp.placeVessel(sp.vessel.pose);
  if (presentAndNotNull(top, "dynamics")) {
    const Item di = top.at("dynamics");
    readSystemDynamics(di, sp);
    sp.dynamics.gnss.track = relativeTo(sp.dynamics.gnss.track, base_dir);
    if (sp.dynamics.gnss.enabled && !sp.vessel.present)
      di.fail("gnss: a ship track moves a vessel; this system has no `vessel:` section");
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
    return root.IsMap() && ((root["lines"] && root["points"]) || root["vessel"]);
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
