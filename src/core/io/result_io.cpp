// Writing static results: JSON, CSV and plain-text summaries. Hand-written, no extra library.
#include "mooring_dynamics/core/io/result_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/utilization.hpp"

namespace mooring_dynamics {
namespace core {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

/// Full-precision number (round-trips a double); JSON has no NaN/Inf, so those become null.
std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string csvNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += ch;  // UTF-8 passes through unchanged
        }
    }
  }
  return out + "\"";
}

template <class Get>
void jsonArray(std::ostream& out, const char* key, const std::vector<NodeState>& nodes, Get get,
               bool last = false) {
  out << "    \"" << key << "\": [";
  for (std::size_t i = 0; i < nodes.size(); ++i) out << (i ? ", " : "") << get(nodes[i]);
  out << "]" << (last ? "\n" : ",\n");
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

const char* topTypeName(const TopBoundary& top) {
  switch (top.type) {
    case TopBoundary::Type::Force: return "force";
    case TopBoundary::Type::Position: return "position";
    case TopBoundary::Type::Buoy: return "buoy";
    case TopBoundary::Type::Body: return "body";
  }
  return "unknown";
}

}  // namespace

void writeStaticJson(std::ostream& out, const Problem& problem, const StaticResult& r) {
  const SolverSummary& sm = r.summary;
  out << "{\n";
  out << "  \"name\": " << jsonString(problem.name) << ",\n";
  out << "  \"top_boundary\": " << jsonString(topTypeName(problem.top)) << ",\n";
  out << "  \"summary\": {\n";
  out << "    \"converged\": " << (sm.converged ? "true" : "false") << ",\n";
  out << "    \"iterations\": " << sm.iterations << ",\n";
  out << "    \"error\": " << jsonNumber(sm.error) << ",\n";
  out << "    \"relaxation\": " << jsonNumber(sm.relaxation) << ",\n";
  out << "    \"message\": " << jsonString(sm.message) << "\n";
  out << "  },\n";
  const bool three_d = problem.formulation == Formulation::ThreeD;
  out << "  \"model\": " << jsonString(three_d ? "3d" : "2d") << ",\n";
  auto vec = [&](double x, double y, double z) {
    return "{\"x\": " + jsonNumber(x) + (three_d ? ", \"y\": " + jsonNumber(y) : std::string()) +
           ", \"z\": " + jsonNumber(z) + "}";
  };
  out << "  \"top_force\": " << vec(r.top_force_x, r.top_force_y, r.top_force_z) << ",\n";
  out << "  \"anchor_force\": " << vec(r.anchor_force_x, r.anchor_force_y, r.anchor_force_z) << ",\n";
  out << "  \"top_tension\": " << jsonNumber(r.topTension()) << ",\n";
  out << "  \"buoy_draft\": " << jsonNumber(r.buoy_draft) << ",\n";
  if (r.drifting)
    out << "  \"drift_velocity\": {\"x\": " << jsonNumber(r.drift_vx) << ", \"y\": " << jsonNumber(r.drift_vy)
        << ", \"speed\": " << jsonNumber(std::hypot(r.drift_vx, r.drift_vy)) << "},\n";
  out << "  \"node_count\": " << r.nodes.size() << ",\n";
  out << "  \"nodes\": {\n";
  const auto& n = r.nodes;
  jsonArray(out, "s", n, [](const NodeState& v) { return jsonNumber(v.s); });
  jsonArray(out, "x", n, [](const NodeState& v) { return jsonNumber(v.x); });
  if (three_d) jsonArray(out, "y", n, [](const NodeState& v) { return jsonNumber(v.y); });
  jsonArray(out, "z", n, [](const NodeState& v) { return jsonNumber(v.z); });
  jsonArray(out, "tension", n, [](const NodeState& v) { return jsonNumber(v.tension); });
  jsonArray(out, "shear", n, [](const NodeState& v) { return jsonNumber(v.shear); });
  jsonArray(out, "angle", n, [](const NodeState& v) { return jsonNumber(v.angle); });
  jsonArray(out, "curvature", n, [](const NodeState& v) { return jsonNumber(v.curvature); });
  jsonArray(out, "strain", n, [](const NodeState& v) { return jsonNumber(v.strain); });
  if (three_d) {
    jsonArray(out, "shear_b", n, [](const NodeState& v) { return jsonNumber(v.shear_b); });
    jsonArray(out, "curvature_b", n, [](const NodeState& v) { return jsonNumber(v.curvature_b); });
    jsonArray(out, "twist", n, [](const NodeState& v) { return jsonNumber(v.twist); });
    jsonArray(out, "azimuth", n, [](const NodeState& v) { return jsonNumber(v.azimuth); });
  }
  jsonArray(out, "segment", n, [](const NodeState& v) { return std::to_string(v.segment); }, true);
  out << "  },\n";
  if (three_d)
    out << "  \"units\": {\"s\": \"m\", \"x\": \"m\", \"y\": \"m\", \"z\": \"m\", \"tension\": \"N\", "
           "\"shear\": \"N, along e2\", \"shear_b\": \"N, along e3\", \"angle\": \"rad, tangent from vertical\", "
           "\"azimuth\": \"rad, tangent's horizontal direction ccw from +x\", \"curvature\": \"1/m, Omega3\", "
           "\"curvature_b\": \"1/m, Omega2\", \"twist\": \"1/m, Omega1\", \"strain\": \"-\", "
           "\"force\": \"N\", \"buoy_draft\": \"m\", \"drift_velocity\": \"m/s\"}\n";
  else
    out << "  \"units\": {\"s\": \"m\", \"x\": \"m\", \"z\": \"m\", \"tension\": \"N\", \"shear\": \"N\", "
           "\"angle\": \"rad from vertical, positive toward +x\", \"curvature\": \"1/m\", \"strain\": \"-\", "
           "\"force\": \"N\", \"buoy_draft\": \"m\"}\n";
  out << "}\n";
}

void writeStaticCsv(std::ostream& out, const StaticResult& r, Formulation model) {
  const bool three_d = model == Formulation::ThreeD;
  out << (three_d ? "node,s,x,y,z,tension,shear,shear_b,angle_deg,azimuth_deg,curvature,curvature_b,twist,strain,segment\n"
                  : "node,s,x,z,tension,shear,angle_deg,curvature,strain,segment\n");
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    const NodeState& v = r.nodes[i];
    out << i << ',' << csvNumber(v.s) << ',' << csvNumber(v.x) << ',';
    if (three_d) out << csvNumber(v.y) << ',';
    out << csvNumber(v.z) << ',' << csvNumber(v.tension) << ',' << csvNumber(v.shear) << ',';
    if (three_d) out << csvNumber(v.shear_b) << ',';
    out << csvNumber(v.angle * kRadToDeg) << ',';
    if (three_d) out << csvNumber(v.azimuth * kRadToDeg) << ',';
    out << csvNumber(v.curvature) << ',';
    if (three_d) out << csvNumber(v.curvature_b) << ',' << csvNumber(v.twist) << ',';
    out << csvNumber(v.strain) << ',' << v.segment << '\n';
  }
}

std::string staticSummaryText(const Problem& problem, const StaticResult& r) {
  std::ostringstream o;
  const SolverSummary& sm = r.summary;
  o << (problem.name.empty() ? std::string("static solution") : problem.name) << ": "
    << (sm.converged ? "converged" : "NOT converged") << " after " << sm.iterations << " iterations (error "
    << fmt("%.3g", sm.error) << ", relaxation " << fmt("%.3g", sm.relaxation) << ")";
  // A converged Newton summary's message repeats the line above ("converged in N iterations
  // (sigma = ...)"): print a message only when it says something more.
  const bool repeats = sm.converged && sm.message.rfind("converged in ", 0) == 0;
  if (!sm.message.empty() && !repeats) o << " - " << sm.message;
  o << "\n";
  if (r.nodes.empty()) {
    o << "  no nodes in the result\n";
    return o.str();
  }
  const NodeState& top = r.nodes.back();
  const auto mn = std::min_element(r.nodes.begin(), r.nodes.end(),
                                   [](const NodeState& a, const NodeState& b) { return a.tension < b.tension; });
  const bool three_d = problem.formulation == Formulation::ThreeD;
  const std::string ty = three_d ? " m, y = " + fmt("%.2f", top.y) : std::string();
  const std::string fy = three_d ? " N, y = " + fmt("%.1f", r.top_force_y) : std::string();
  const std::string ay = three_d ? " N, y = " + fmt("%.1f", r.anchor_force_y) : std::string();
  o << "  top tension    " << fmt("%12.1f", r.topTension()) << " N   at x = " << fmt("%.2f", top.x) << ty
    << " m, z = " << fmt("%.2f", top.z) << " m\n";
  o << "  top force      x = " << fmt("%.1f", r.top_force_x) << fy << " N, z = " << fmt("%.1f", r.top_force_z)
    << " N\n";
  o << "  anchor force   x = " << fmt("%.1f", r.anchor_force_x) << ay << " N, z = " << fmt("%.1f", r.anchor_force_z)
    << " N\n";
  if (three_d) o << "  model          3-D (N = 13 with Euler parameters)\n";
  o << "  min tension    " << fmt("%12.1f", mn->tension) << " N   at s = " << fmt("%.2f", mn->s) << " m (node "
    << (mn - r.nodes.begin()) << ")\n";
  o << "  max tension    " << tensionPeakText(tensionPeak(problem.materials, problem.segments, r.nodes), false) << "\n";
  const double slack = slackLength(problem.materials, problem.segments, r.nodes);
  if (slack > 0.0) o << "  slack line     " << fmt("%.2f", slack) << " m (tension below the slack ramp)\n";
  if (problem.top.type == TopBoundary::Type::Buoy) o << "  buoy draft     " << fmt("%.3f", r.buoy_draft) << " m\n";
  if (r.drifting)
    o << "  drift velocity x = " << fmt("%.4f", r.drift_vx) << ", y = " << fmt("%.4f", r.drift_vy) << " m/s ("
      << fmt("%.4f", std::hypot(r.drift_vx, r.drift_vy)) << " m/s toward "
      << fmt("%.1f", std::atan2(r.drift_vy, r.drift_vx) * kRadToDeg) << " deg)\n";
  return o.str();
}

std::string staticTableText(const StaticResult& r, std::size_t stride, Formulation model) {
  if (stride == 0) stride = 1;
  const bool three_d = model == Formulation::ThreeD;
  std::ostringstream o;
  char buf[160];
  if (three_d)
    std::snprintf(buf, sizeof buf, "%6s %12s %12s %12s %12s %14s\n", "node", "s [m]", "x [m]", "y [m]", "z [m]",
                  "tension [N]");
  else
    std::snprintf(buf, sizeof buf, "%6s %12s %12s %12s %14s\n", "node", "s [m]", "x [m]", "z [m]", "tension [N]");
  o << buf;
  const std::size_t n = r.nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i % stride != 0 && i + 1 != n) continue;
    const NodeState& v = r.nodes[i];
    if (three_d)
      std::snprintf(buf, sizeof buf, "%6zu %12.3f %12.3f %12.3f %12.3f %14.2f\n", i, v.s, v.x, v.y, v.z, v.tension);
    else
      std::snprintf(buf, sizeof buf, "%6zu %12.3f %12.3f %12.3f %14.2f\n", i, v.s, v.x, v.z, v.tension);
    o << buf;
  }
  return o.str();
}

}  // namespace core
}  // namespace mooring_dynamics
