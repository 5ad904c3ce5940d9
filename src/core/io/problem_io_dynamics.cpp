// Waves and dynamics section readers of problem_io.cpp (see problem_io_dynamics.hpp).
#include "mooring_dynamics/core/io/problem_io_dynamics.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace core {
namespace problem_io_detail {

using namespace yaml;

// ---------------------------------------------------------------------------------------------
// Waves

WaveSpec readWaves(const Item& it) {
  const Map w(it, {"type", "height", "period", "hs", "tp", "gamma", "components", "f_min_factor",
                   "f_max_factor", "seed", "direction_deg", "ramp", "frequencies", "spreading_s"});
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
  for (const char* k : {"hs", "tp", "components", "f_min_factor", "f_max_factor", "seed", "frequencies", "spreading_s"})
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
    if (w.has("frequencies")) {
      const Item fi = w.at("frequencies");
      const std::string f = readString(fi);
      if (f != "centred" && f != "random") fi.failQuoted("must be centred or random");
      ws.random_frequencies = f == "random";
    }
    if (w.has("spreading_s")) {
      const Item si = w.at("spreading_s");
      ws.spreading_s = readNumber(si);
      if (!(ws.spreading_s >= 0.0 && ws.spreading_s <= 1000.0)) si.fail("must be in [0, 1000] (0 = long-crested)");
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
  return ws;
}

// ---------------------------------------------------------------------------------------------
// Dynamics

namespace {

struct MotionTypeName {
  const char* name;
  TopMotion::Type type;
  const char* columns;    ///< table row layout in the x-z plane, nullptr for types without a table
  const char* columns3d;  ///< the same with a y column
};

const std::vector<MotionTypeName>& motionTypes() {
  static const std::vector<MotionTypeName> list = {
      {"hold", TopMotion::Type::Hold, nullptr, nullptr},
      {"sinusoid", TopMotion::Type::Sinusoid, nullptr, nullptr},
      {"position_table", TopMotion::Type::PositionTable, "[t, x, z]", "[t, x, y, z]"},
      {"velocity_table", TopMotion::Type::VelocityTable, "[t, vx, vz]", "[t, vx, vy, vz]"},
      {"force_table", TopMotion::Type::ForceTable, "[t, fx, fz]", "[t, fx, fy, fz]"},
      {"wave_follower", TopMotion::Type::WaveFollower, nullptr, nullptr},
      {"ship_track", TopMotion::Type::ShipTrack, nullptr, nullptr},
  };
  return list;
}

/// `type: ship_track` keys of a top_motion map: speed, heading_deg and the legs, each exactly one
/// of {straight: s}, {turn: {radius: m, angle_deg: deg}}, {heading_deg: deg}.
void readShipTrack(const Map& m, ShipTrack& st) {
  st = ShipTrack{};
  st.speed = m.number("speed", Range::Positive);
  st.heading = m.number("heading_deg", 0.0, Range::Any) * kDegToRad;
  if (!presentAndNotNull(m, "legs")) return;
  const std::string kinds = "a leg is exactly one of {straight: SECONDS}, {turn: {radius: M, angle_deg: DEG}}, "
                            "{heading_deg: DEG}";
  for (const Item& li : listItems(m.at("legs"))) {
    if (!li.node.IsMap()) li.wrongType("a map: " + kinds);
    const Map lm(li, {"straight", "turn", "heading_deg"});
    std::vector<std::string> given;
    for (const char* k : {"straight", "turn", "heading_deg"})
      if (lm.has(k)) given.push_back(k);
    if (given.size() != 1)
      throw ProblemError(li.path + ": " + (given.empty() ? std::string("no leg given") : "has " + joinList(given) + " at once") +
                         "; " + kinds + lineSuffix(li.mark));
    if (lm.has("straight")) {
      st.legs.push_back(ShipLeg::straight(lm.number("straight", Range::NonNegative)));
    } else if (lm.has("turn")) {
      const Map tm(lm.at("turn"), {"radius", "angle_deg"});
      const double radius = tm.number("radius", Range::Positive);
      st.legs.push_back(ShipLeg::turn(radius, tm.number("angle_deg", Range::Any) * kDegToRad));
    } else {
      st.legs.push_back(ShipLeg::headingChange(lm.number("heading_deg", Range::Any) * kDegToRad));
    }
  }
}

void readTopMotion(const Item& it, TopMotion& tm) {
  const Map m(it, {"type", "amplitude_x", "amplitude_y", "amplitude_z", "period", "phase_deg", "table", "speed",
                   "heading_deg", "legs", "prescribe"});
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
  for (const char* k : {"amplitude_x", "amplitude_y", "amplitude_z", "period", "phase_deg"})
    if (!sinusoid && m.has(k)) m.at(k).fail("only used with type: sinusoid");
  const bool ship = mt->type == TopMotion::Type::ShipTrack;
  for (const char* k : {"speed", "heading_deg", "legs"})
    if (!ship && m.has(k)) m.at(k).fail("only used with type: ship_track");
  if (mt->columns == nullptr && m.has("table"))
    m.at("table").fail("only used with type: position_table, velocity_table or force_table");

  if (sinusoid) {
    tm.amplitude_x = m.number("amplitude_x", 0.0, Range::Any);
    tm.amplitude_y = m.number("amplitude_y", 0.0, Range::Any);
    tm.amplitude_z = m.number("amplitude_z", 0.0, Range::Any);
    tm.period = m.number("period", Range::Positive);
    tm.phase = m.number("phase_deg", 0.0, Range::Any) * kDegToRad;
  }

  if (mt->columns != nullptr) {
    // Rows [t, a, c] in the x-z plane (y = 0) or [t, a, b, c] in 3-D; all rows the same width.
    const std::string both = std::string(mt->columns) + " or " + mt->columns3d;
    const Item tab = m.required("table", "rows " + both);
    const std::vector<Item> rows = listItems(tab);
    if (rows.empty()) tab.fail("needs at least one row " + both);
    std::size_t width = 0;
    for (const Item& r : rows) {
      if (!r.node.IsSequence() || (r.node.size() != 3 && r.node.size() != 4)) r.wrongType("a row " + both);
      if (width == 0) width = r.node.size();
      if (r.node.size() != width)
        throw ProblemError(r.path + " = " + render(r.node) + ": has " + std::to_string(r.node.size()) +
                           " values, the first row " + std::to_string(width) + "; all rows are " +
                           (width == 3 ? mt->columns : mt->columns3d) + lineSuffix(r.mark));
      double v[4] = {0.0, 0.0, 0.0, 0.0};  // the first `width` are read; zeroed for gcc -Wmaybe-uninitialized
      for (std::size_t j = 0; j < width; ++j)
        v[j] = readNumber(Item{r.node[j], r.path + "[" + std::to_string(j) + "]", markOf(r.node[j], r.mark)});
      if (!tm.table.empty() && !(v[0] > tm.table.back().t))
        r.fail("t must increase down the table (previous t = " + formatNumber(tm.table.back().t) + ")");
      tm.table.push_back(width == 3 ? TopMotion::Row(v[0], v[1], v[2]) : TopMotion::Row(v[0], v[1], v[2], v[3]));
    }
  }

  if (ship) readShipTrack(m, tm.ship_track);

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

/// dynamics.gnss: {track, datum: first_fix | {latitude_deg, longitude_deg}, antenna: [x, y, z],
/// smoothing_time, max_speed, max_horizontal_sigma, max_heading_gap}.
void readGnss(const Item& it, GnssOptions& g) {
  const Map m(it, {"track", "datum", "antenna", "smoothing_time", "max_speed", "jump_tolerance",
                   "max_horizontal_sigma", "max_heading_gap"});
  g = GnssOptions{};
  g.enabled = true;
  if (m.has("track")) g.track = readString(m.at("track"));
  if (m.has("datum")) {
    const Item di = m.at("datum");
    if (di.node.IsScalar()) {
      const std::string v = readString(di);
      if (v != "first_fix") di.failQuoted("must be first_fix or {latitude_deg: DEG, longitude_deg: DEG}");
    } else {
      const Map dm(di, {"latitude_deg", "longitude_deg"});
      g.datum_from_first_fix = false;
      g.datum_latitude_deg = dm.number("latitude_deg", Range::Any);
      g.datum_longitude_deg = dm.number("longitude_deg", Range::Any);
      if (std::abs(g.datum_latitude_deg) > 90.0) dm.at("latitude_deg").fail("must be in [-90, 90]");
      if (std::abs(g.datum_longitude_deg) > 180.0) dm.at("longitude_deg").fail("must be in [-180, 180]");
    }
  }
  if (m.has("antenna")) {
    const std::vector<Item> xyz = listItems(m.at("antenna"));
    if (xyz.size() != 3) m.at("antenna").fail("must be [x, y, z] in the body frame [m]");
    for (int i = 0; i < 3; ++i) g.antenna[i] = readNumber(xyz[static_cast<std::size_t>(i)]);
  }
  g.smoothing_time = m.number("smoothing_time", g.smoothing_time, Range::NonNegative);
  g.max_speed = m.number("max_speed", g.max_speed, Range::Positive);
  g.jump_tolerance = m.number("jump_tolerance", g.jump_tolerance, Range::NonNegative);
  g.max_horizontal_sigma = m.number("max_horizontal_sigma", g.max_horizontal_sigma, Range::Positive);
  g.max_heading_gap = m.number("max_heading_gap", g.max_heading_gap, Range::Positive);
}

/// Output grid, snapshots and recorded nodes (dt already read).
void readOutputs(const Map& m, DynamicOptions& d, double line_length) {
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
}

/// The time integrator: exactly one of scheme (Table 1 name), lambda_inf (eq. 29) or the three
/// parameters alpha_m, alpha_k, gamma.
void readScheme(const Map& m, DynamicOptions& d) {
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
}

/// Step control and the Newton iteration per step.
void readStepControl(const Map& m, DynamicOptions& d) {
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
  if (m.has("jacobian_reuse")) d.jacobian_reuse = readBool(m.at("jacobian_reuse"));
  if (m.has("jacobian_reuse_rate")) {
    const Item r = m.at("jacobian_reuse_rate");
    d.jacobian_reuse_rate = readNumber(r);
    if (!(d.jacobian_reuse_rate > 0.0 && d.jacobian_reuse_rate < 1.0)) r.fail("must be in (0, 1)");
  }
  if (m.has("damp_two_cycles")) d.damp_two_cycles = readBool(m.at("damp_two_cycles"));
  if (m.has("fallback")) d.fallback = readBool(m.at("fallback"));
  if (m.has("fallback_after_cuts")) {
    const Item fi = m.at("fallback_after_cuts");
    const long long v = readInteger(fi);
    if (v < 0 || v > 8) fi.fail("must be an integer in [0, 8]");
    d.fallback_after_cuts = static_cast<int>(v);
  }
  if (m.has("threads")) {
    const Item ti = m.at("threads");
    const long long v = readInteger(ti);
    if (v < 1 || v > 2) ti.fail("must be 1 or 2");
    d.threads = static_cast<int>(v);
  }
}

/// dynamics.events: a list of {type: release, end: top | anchor, t} and
/// {type: break, t [, s] | tension: N | mbl}, each with `line` in a system file.
void readEvents(const Item& it, DynamicOptions& d) {
  d.events.clear();
  const std::vector<Item> items = listItems(it);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Map m(items[i], {"type", "end", "t", "tension", "s", "line"});
    LineEvent e;
    const Item ti = m.required("type", "release or break");
    const std::string type = readString(ti);
    if (type == "release")
      e.type = LineEvent::Type::Release;
    else if (type == "break")
      e.type = LineEvent::Type::Break;
    else
      ti.failQuoted("unknown event (known: release, break)");
    if (e.type == LineEvent::Type::Release) {
      const Item ei = m.required("end", "top or anchor");
      const std::string end = readString(ei);
      if (end == "top")
        e.end = LineEvent::End::Top;
      else if (end == "anchor")
        e.end = LineEvent::End::Anchor;
      else
        ei.failQuoted("must be top or anchor");
    } else if (m.has("end")) {
      m.at("end").fail("a break parts the line where its tension is largest (or at s); end goes with a release");
    }
    if (m.has("t")) e.t = m.number("t", 0.0, Range::NonNegative);
    if (m.has("tension")) {
      const Item xi = m.at("tension");
      if (xi.node.IsScalar() && xi.node.Scalar() == "mbl")
        e.at_mbl = true;
      else
        e.tension = checked(xi, readNumber(xi), Range::Positive);
    }
    if (m.has("s")) e.s = m.number("s", 0.0, Range::NonNegative);
    if (m.has("line")) e.line = readString(m.at("line"));
    const std::string err = e.validate(items[i].path);
    if (!err.empty()) throw ProblemError(err + lineSuffix(items[i].mark));
    d.events.push_back(e);
  }
}

/// dynamics.winch: {rate: m/s | table: [[t, length], ...], min_length, max_length, line}.
void readWinch(const Item& it, Winch& w) {
  const Map m(it, {"rate", "table", "min_length", "max_length", "line"});
  w = Winch();
  w.given = true;
  if (m.has("rate")) w.rate = readNumber(m.at("rate"));
  if (m.has("table")) {
    const Item tab = m.at("table");
    const std::vector<Item> rows = listItems(tab);
    if (rows.empty()) tab.fail("needs at least one row [t, length]");
    for (const Item& r : rows) {
      if (!r.node.IsSequence() || r.node.size() != 2) r.wrongType("a row [t, length] ([s], [m])");
      std::vector<double> v(2);
      for (std::size_t j = 0; j < 2; ++j)
        v[j] = readNumber(Item{r.node[j], r.path + "[" + std::to_string(j) + "]", markOf(r.node[j], r.mark)});
      if (!w.table.empty() && !(v[0] > w.table.back()[0]))
        r.fail("t must increase down the table (previous t = " + formatNumber(w.table.back()[0]) + ")");
      w.table.push_back(v);
    }
  }
  w.min_length = m.number("min_length", 0.0, Range::NonNegative);
  w.max_length = m.number("max_length", 0.0, Range::NonNegative);
  if (m.has("line")) w.line = readString(m.at("line"));
  const std::string err = w.validate(it.path);
  if (!err.empty()) throw ProblemError(err + lineSuffix(it.mark));
}

}  // namespace

void readDynamics(const Item& it, DynamicOptions& d, double line_length) {
  const Map m(it, {"duration", "dt", "output_interval", "snapshot_interval", "record_s", "scheme", "lambda_inf",
                   "alpha_m", "alpha_k", "gamma", "max_cut_levels", "tolerance", "max_iterations", "relaxation",
                   "adaptive_relaxation", "jacobian_reuse", "jacobian_reuse_rate", "damp_two_cycles", "fallback", "fallback_after_cuts", "threads", "adaptive_mesh", "mesh_weight", "top_motion",
                   "gnss", "events", "winch"});
  d.duration = m.number("duration", d.duration, Range::Positive);
  d.dt = m.number("dt", d.dt, Range::Positive);
  readOutputs(m, d, line_length);
  readScheme(m, d);
  readStepControl(m, d);
  if (m.has("adaptive_mesh")) d.adaptive_mesh = readBool(m.at("adaptive_mesh"));
  d.mesh_weight = m.number("mesh_weight", d.mesh_weight, Range::NonNegative);

  if (presentAndNotNull(m, "top_motion")) readTopMotion(m.at("top_motion"), d.top_motion);
  if (m.has("gnss")) readGnss(m.at("gnss"), d.gnss);
  if (presentAndNotNull(m, "events")) readEvents(m.at("events"), d);
  if (presentAndNotNull(m, "winch")) readWinch(m.at("winch"), d.winch);
}

}  // namespace problem_io_detail
}  // namespace core
}  // namespace mooring_dynamics
