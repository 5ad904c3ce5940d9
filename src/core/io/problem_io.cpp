// YAML problem files -> core::Problem. The format is documented in docs/problem_format.md.
//
// Every rejected input raises ProblemError with a message of the form
//   <key path> = <value found>: <constraint> (line N)
// e.g. `line[2].material = "chian": unknown material (known: chain, vectran) (line 14)`.
// Unknown keys are errors at every level (typos must not be silently ignored).
#include "mooring_dynamics/core/io/problem_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/csv_table.hpp"
#include "mooring_dynamics/core/io/problem_io_dynamics.hpp"
#include "mooring_dynamics/core/io/seabed_grid_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"

namespace mooring_dynamics {
namespace core {
namespace sections {

using namespace yaml;
using problem_io_detail::kDegToRad;
using problem_io_detail::readDynamics;
using problem_io_detail::readWaves;

// ---------------------------------------------------------------------------------------------
// Sections

/// `environment.seabed.grid_file`: the path relative to `base_dir` (the problem file's directory;
/// empty = the current directory) unless absolute; errors of the grid file name both files.
SeabedGrid readGridFile(const Item& it, const std::string& base_dir) {
  const std::string rel = readString(it);
  if (rel.empty()) it.failQuoted("must name a grid file");
  namespace fs = std::filesystem;
  const fs::path p(rel);
  const std::string path = p.is_absolute() || base_dir.empty() ? rel : (fs::path(base_dir) / p).string();
  try {
    return loadSeabedGrid(path);
  } catch (const ProblemError& e) {
    throw ProblemError(it.path + " = " + quoted(rel) + ": " + e.what() + lineSuffix(it.mark));
  }
}

namespace {

/// environment.seabed: foundation stiffness and damping, the static cap, a depth profile in x or
/// a depth grid file.
void readSeabed(const Item& it, Seabed& seabed, const std::string& base_dir) {
  const Map sb(it, {"stiffness", "damping", "profile", "grid_file", "static_cap"});
  seabed.stiffness = sb.number("stiffness", seabed.stiffness, Range::Positive);
  seabed.damping = sb.number("damping", seabed.damping, Range::NonNegative);
  if (sb.has("static_cap")) seabed.static_cap = readBool(sb.at("static_cap"));
  if (sb.has("profile")) {
    std::vector<Item> items;
    const Item pit = sb.at("profile");
    seabed.profile = readPairs(pit, "[x, depth]", &items);
    if (seabed.profile.size() < 2)
      pit.fail("needs at least 2 points [x, depth]; omit it for a flat seabed at environment.depth");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const auto& pt = seabed.profile[i];
      if (!(pt.second > 0.0)) items[i].fail("depth must be > 0");
      if (i > 0 && !(pt.first > seabed.profile[i - 1].first))
        items[i].fail("x must increase along the profile (previous x = " +
                      formatNumber(seabed.profile[i - 1].first) + ")");
    }
  }
  if (sb.has("grid_file")) {
    const Item gi = sb.at("grid_file");
    if (sb.has("profile"))
      throw ProblemError(sb.path() + ": has both profile and grid_file; give at most one (a grid also covers "
                         "a depth varying in x only)" + lineSuffix(gi.mark));
    seabed.grid = readGridFile(gi, base_dir);
  }
}

/// environment.current.file: a profile in CSV, one point a row: depth [m], speed [m/s],
/// direction_deg [deg] (a header row and '#' comments skipped), depth >= 0 and increasing.
/// Read without the YAML reader, for profiles of many points (ResourceLimits::max_input_mb).
std::vector<CurrentPoint> readCurrentFile(const Item& fi, const std::string& base_dir) {
  const std::string rel = readString(fi);
  if (rel.empty()) fi.failQuoted("must name a CSV file of depth, speed, direction_deg");
  const std::string path = relativeTo(rel, base_dir);
  std::vector<CurrentPoint> out;
  try {
    const std::vector<CsvRow> rows = parseCsvTable(readFileText(path), path, {"depth", "speed", "direction_deg"});
    if (rows.size() < 2) throw ProblemError(path + ": a current profile needs at least 2 rows (depth, speed, direction_deg)");
    out.reserve(rows.size());
    for (const CsvRow& r : rows) {
      CurrentPoint p;
      p.depth = r.values[0];
      p.speed = r.values[1];
      p.direction = r.values[2] * kDegToRad;
      if (!(p.depth >= 0.0)) throw ProblemError(r.where + ": depth = " + formatNumber(p.depth) + ": must be >= 0");
      if (!(p.speed >= 0.0)) throw ProblemError(r.where + ": speed = " + formatNumber(p.speed) + ": must be >= 0");
      if (!out.empty() && !(p.depth > out.back().depth))
        throw ProblemError(r.where + ": depth = " + formatNumber(p.depth) +
                           ": must increase along the profile (previous depth = " + formatNumber(out.back().depth) + ")");
      out.push_back(p);
    }
  } catch (const ProblemError& e) {
    throw ProblemError(fi.path + " = " + quoted(rel) + ": " + e.what() + lineSuffix(fi.mark));
  }
  return out;
}

/// environment.current: a uniform {speed, direction_deg} down to the deepest seabed, a profile
/// of {depth, speed, direction_deg}, or {file: CSV} (readCurrentFile).
void readCurrent(const Item& cit, Environment& env, const std::string& base_dir) {
  env.current.clear();
  if (cit.node.IsMap() && cit.node["file"]) {
    env.current = readCurrentFile(Map(cit, {"file"}).at("file"), base_dir);
  } else if (cit.node.IsMap()) {
    // Uniform current shorthand: {speed, direction_deg} -> same value from the surface to the bottom.
    const Map c(cit, {"speed", "direction_deg"});
    CurrentPoint p;
    p.speed = c.number("speed", Range::NonNegative);
    p.direction = c.number("direction_deg", 0.0, Range::Any) * kDegToRad;
    double bottom = env.depth;
    for (const auto& q : env.seabed.profile) bottom = std::max(bottom, q.second);
    for (double d : env.seabed.grid.depths) bottom = std::max(bottom, d);
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

}  // namespace

void readEnvironment(const Item& it, Environment& env, const std::string& base_dir) {
  const Map m(it, {"water_density", "air_density", "gravity", "depth", "seabed", "current", "wind", "waves"});
  env.water_density = m.number("water_density", env.water_density, Range::Positive);
  env.air_density = m.number("air_density", env.air_density, Range::NonNegative);
  env.gravity = m.number("gravity", env.gravity, Range::Positive);
  env.depth = m.number("depth", env.depth, Range::Positive);
  if (m.has("seabed")) readSeabed(m.at("seabed"), env.seabed, base_dir);
  if (m.has("wind")) {
    const Map w(m.at("wind"), {"speed", "direction_deg"});
    env.wind_speed = w.number("speed", 0.0, Range::NonNegative);
    env.wind_direction = w.number("direction_deg", 0.0, Range::Any) * kDegToRad;
  }
  if (m.has("current")) readCurrent(m.at("current"), env, base_dir);
  if (m.has("waves")) env.waves = readWaves(m.at("waves"));
}

Material readMaterial(const Item& it, const std::string& name) {
  const Map m(it, {"EA", "tension_strain", "EI", "GJ", "mass", "added_mass", "wet_weight", "diameter",
                   "cdn", "cdt", "max_strain", "mbl", "type", "compression", "mu_axial", "mu_lateral"});
  Material mat;
  mat.name = name;
  if (m.has("type")) {
    const Item ti = m.at("type");
    mat.kind = readString(ti);
    const auto& kinds = materialKinds();
    if (std::find(kinds.begin(), kinds.end(), mat.kind) == kinds.end()) {
      std::string list;
      for (const auto& k : kinds) list += (list.empty() ? "" : ", ") + k;
      ti.fail("must be one of " + list);
    }
    mat.compression = materialCarriesCompression(mat.kind);
  }
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
  mat.mbl = m.number("mbl", 0.0, Range::Positive);
  if (m.has("compression")) mat.compression = readBool(m.at("compression"));
  mat.mu_axial = m.number("mu_axial", 0.0, Range::NonNegative);
  mat.mu_lateral = m.number("mu_lateral", 0.0, Range::NonNegative);
  return mat;
}

Body readBody(const Item& it, const std::string& name) {
  const Map m(it, {"mass", "added_mass", "wet_weight", "diameter", "cd", "cdn", "cdt"});
  Body b;
  b.name = name;
  b.mass = m.number("mass", Range::NonNegative);
  b.added_mass = m.number("added_mass", 0.0, Range::NonNegative);
  b.wet_weight = m.number("wet_weight", Range::Any);
  b.diameter = m.number("diameter", Range::NonNegative);
  // A sphere (`cd`) or a body aligned with the line (`cdn` and `cdt`): one form, not both.
  const bool sphere = m.has("cd");
  if (sphere && (m.has("cdn") || m.has("cdt")))
    throw ProblemError(m.sub(m.has("cdn") ? "cdn" : "cdt") + ": give cd (a sphere: drag along the relative flow) "
                       "or cdn and cdt (a body aligned with the line), not both" +
                       lineSuffix(m.at("cd").mark));
  if (sphere) {
    b.drag = Body::Drag::Sphere;
    b.cd = m.number("cd", Range::NonNegative);
  } else {
    b.drag = Body::Drag::LineAligned;
    b.cdn = m.number("cdn", Range::NonNegative);
    b.cdt = m.number("cdt", Range::NonNegative);
  }
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

/// A surface buoy's keys (top.buoy, or a system point of type buoy).
void readBuoy(const Item& it, SurfaceBuoy& buoy) {
  const Map b(it, {"shape", "diameter", "height", "mass", "added_mass", "cd", "wind_area", "wind_cd"});
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

void readTop(const Item& it, TopBoundary& top, const std::map<std::string, std::size_t>& body_index,
             const std::vector<std::string>& body_names) {
  const Map m(it, {"position", "force", "buoy", "body", "tow_velocity"});
  std::vector<std::string> given;
  for (const char* k : {"position", "force", "buoy", "body"})
    if (m.has(k)) given.push_back(k);
  if (m.has("tow_velocity") && !m.has("position"))
    m.at("tow_velocity").fail("only with top.position (the tow point of a line with a free lower end)");
  if (given.size() != 1)
    throw ProblemError("top: " +
                       (given.empty() ? std::string("no boundary condition given")
                                      : "has " + joinList(given) + " at once") +
                       "; give exactly one of position, force, buoy, body" + lineSuffix(it.mark));
  if (m.has("body")) {
    // A subsurface buoy: the named body, held up by nothing but the line (3-D model).
    top.type = TopBoundary::Type::Body;
    top.body = lookup(m.at("body"), body_index, body_names, "body");
  } else if (m.has("position")) {
    const Map p(m.at("position"), {"x", "y", "z"});
    top.type = TopBoundary::Type::Position;
    top.x = p.number("x");
    top.y = p.number("y", 0.0, Range::Any);
    top.z = p.number("z");
    if (m.has("tow_velocity")) {
      const Map v(m.at("tow_velocity"), {"x", "y"});
      top.tow_vx = v.number("x", 0.0, Range::Any);
      top.tow_vy = v.number("y", 0.0, Range::Any);
    }
  } else if (m.has("force")) {
    const Map f(m.at("force"), {"x", "y", "z"});
    top.type = TopBoundary::Type::Force;
    top.fx = f.number("x");
    top.fy = f.number("y", 0.0, Range::Any);
    top.fz = f.number("z");
  } else {
    top.type = TopBoundary::Type::Buoy;
    readBuoy(m.at("buoy"), top.buoy);
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
    // Default spacing: 1 m, or the whole segment when it is shorter (the same single interval).
    seg.spacing = m.number("spacing", std::min(seg.spacing, seg.length), Range::Positive);
    if (seg.spacing > seg.length)
      m.at("spacing").fail("must be <= the segment length " + m.sub("length") + " = " + formatNumber(seg.length) +
                           " m (a spacing beyond the segment collapses it to one interval)");
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

/// `materials` (required) and `bodies` (optional) of a problem or system file.
void readCatalogue(const Map& top, std::vector<Material>& materials, std::vector<Body>& bodies, Catalogue& cat) {
  {
    const Item mit = top.required("materials");
    if (!mit.node.IsMap()) mit.wrongType("a map name -> properties");
    if (mit.node.size() == 0) mit.failNoValue("needs at least one material");
    for (auto kv : mit.node) {
      if (!kv.first.IsScalar())
        throw ProblemError("materials: names must be plain strings" + lineSuffix(kv.first.Mark()));
      const std::string name = kv.first.Scalar();
      if (cat.mat_index.count(name))
        throw ProblemError("materials." + name + ": duplicate material name" + lineSuffix(kv.first.Mark()));
      const Item m{kv.second, "materials." + name, markOf(kv.second, kv.first.Mark())};
      cat.mat_index[name] = materials.size();
      cat.mat_names.push_back(name);
      materials.push_back(readMaterial(m, name));
    }
  }

  if (presentAndNotNull(top, "bodies")) {
    const Item bit = top.at("bodies");
    if (!bit.node.IsMap()) bit.wrongType("a map name -> properties");
    for (auto kv : bit.node) {
      if (!kv.first.IsScalar())
        throw ProblemError("bodies: names must be plain strings" + lineSuffix(kv.first.Mark()));
      const std::string name = kv.first.Scalar();
      if (cat.body_index.count(name))
        throw ProblemError("bodies." + name + ": duplicate body name" + lineSuffix(kv.first.Mark()));
      const Item b{kv.second, "bodies." + name, markOf(kv.second, kv.first.Mark())};
      cat.body_index[name] = bodies.size();
      cat.body_names.push_back(name);
      bodies.push_back(readBody(b, name));
    }
  }
}

void readLimits(const Item& it, ResourceLimits& lim) {
  const Map m(it, {"max_nodes", "max_steps", "max_memory_mb", "max_input_mb"});
  lim.max_nodes = m.number("max_nodes", lim.max_nodes, Range::Positive);
  lim.max_steps = m.number("max_steps", lim.max_steps, Range::Positive);
  lim.max_memory_mb = m.number("max_memory_mb", lim.max_memory_mb, Range::Positive);
  lim.max_input_mb = m.number("max_input_mb", lim.max_input_mb, Range::Positive);
  const std::string e = lim.validate();
  if (!e.empty()) throw ProblemError(e + lineSuffix(it.mark));
}

/// `model: 2d | 3d`.
Formulation readModel(const Item& mi) {
  const std::string v = readString(mi);
  if (v == "2d") return Formulation::TwoD;
  if (v == "3d") return Formulation::ThreeD;
  throw ProblemError("model = " + quoted(v) + ": unknown model (known: 2d, 3d)" + lineSuffix(mi.mark));
}

Problem parse(const YAML::Node& root, const std::string& base_dir) {
  if (!root.IsDefined() || root.IsNull())
    throw ProblemError("problem file is empty: expected a map with at least materials, line and top");
  const Item rit{root, "", markOf(root, YAML::Mark::null_mark())};
  if (!root.IsMap())
    throw ProblemError("top level: expected a map with keys materials, line, top, ..., found " + typeName(root) +
                       lineSuffix(rit.mark));
  const Map top(rit, {"name", "model", "environment", "materials", "bodies", "line", "anchor", "free_end", "top",
                      "solver", "dynamics", "limits"});
  Problem pb;
  if (top.has("name")) pb.name = readString(top.at("name"));
  if (top.has("model")) pb.formulation = readModel(top.at("model"));
  if (presentAndNotNull(top, "environment")) readEnvironment(top.at("environment"), pb.environment, base_dir);

  Catalogue cat;
  readCatalogue(top, pb.materials, pb.bodies, cat);
  const auto& mat_index = cat.mat_index;
  const auto& mat_names = cat.mat_names;
  const auto& body_index = cat.body_index;
  const auto& body_names = cat.body_names;

  readLine(top.required("line"), pb, mat_index, mat_names, body_index, body_names);

  // Anchor: x defaults to 0, z to the seabed elevation at x.
  pb.anchor_x = 0.0;
  bool anchor_z_given = false;
  if (presentAndNotNull(top, "anchor")) {
    const Map a(top.at("anchor"), {"x", "y", "z"});
    pb.anchor_x = a.number("x", 0.0, Range::Any);
    pb.anchor_y = a.number("y", 0.0, Range::Any);
    if (a.has("z")) {
      anchor_z_given = true;
      const Item zi = a.at("z");
      pb.anchor_z = readNumber(zi);
      if (pb.anchor_z > 0.0) zi.fail("must be <= 0 (z = 0 is the mean sea surface, z up)");
      const double bottom = pb.environment.seabedElevation(pb.anchor_x, pb.anchor_y);
      if (pb.anchor_z < bottom - 1e-9 * std::max(1.0, std::fabs(bottom)))
        zi.fail("below the seabed (seabed at z = " + formatNumber(bottom) + " m at x = " +
                formatNumber(pb.anchor_x) + " m)");
    }
  }
  if (!anchor_z_given) pb.anchor_z = pb.environment.seabedElevation(pb.anchor_x, pb.anchor_y);

  if (top.has("free_end")) {
    const Item fe = top.at("free_end");
    if (presentAndNotNull(top, "anchor"))
      fe.fail("give either anchor (a moored line) or free_end (a towed line), not both");
    pb.lower_end = Problem::LowerEnd::Free;
    if (!fe.node.IsNull()) {
      const Map f(fe, {"body"});
      if (f.has("body")) pb.end_body = lookup(f.at("body"), body_index, body_names, "body");
    }
  }
  readTop(top.required("top"), pb.top, body_index, body_names);
  if (presentAndNotNull(top, "solver")) readSolver(top.at("solver"), pb.static_options);
  if (presentAndNotNull(top, "dynamics")) readDynamics(top.at("dynamics"), pb.dynamics, pb.totalLength());
  pb.dynamics.gnss.track = relativeTo(pb.dynamics.gnss.track, base_dir);
  if (presentAndNotNull(top, "limits")) readLimits(top.at("limits"), pb.limits);

  std::string msg = pb.static_options.validate();
  if (msg.empty()) msg = pb.validate();
  if (!msg.empty()) throw ProblemError(msg);
  return pb;
}

}  // namespace sections

using namespace sections;

Problem loadProblemFromString(const std::string& yaml_text) { return loadProblemFromString(yaml_text, ""); }

Problem loadProblemFromString(const std::string& yaml_text, const std::string& base_dir) {
  const YAML::Node root = parseYaml(yaml_text);
  try {
    return parse(root, base_dir);
  } catch (const YAML::Exception& e) {  // should not happen: all access is checked above
    throw ProblemError(std::string("YAML error: ") + e.what());
  }
}

Problem loadProblemFromFile(const std::string& path) {
  const std::string text = readFileText(path);
  try {
    // Files named in the problem (seabed grid) are relative to its directory.
    const std::string dir = std::filesystem::path(path).parent_path().string();
    Problem pb = loadProblemFromString(text, dir);
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
