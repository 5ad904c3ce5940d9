#include "mooring_dynamics/core/model/utilization.hpp"

#include <cstdio>

namespace mooring_dynamics {
namespace core {

void TensionPeak::add(const std::vector<Material>& materials, const std::vector<Segment>& segments,
                      const std::vector<NodeState>& nodes, double t) {
  const double slack = slackLength(materials, segments, nodes);
  if (slack > slack_length) {
    slack_length = slack;
    t_slack = t;
  }
  for (const NodeState& n : nodes) {
    if (empty || n.tension > max_tension) {
      max_tension = n.tension;
      s_max = n.s;
      t_max = t;
      empty = false;
    }
    const std::size_t seg = static_cast<std::size_t>(n.segment);
    if (seg >= segments.size() || segments[seg].material >= materials.size()) continue;
    const Material& m = materials[segments[seg].material];
    if (!(m.mbl > 0.0)) continue;
    const double u = n.tension / m.mbl;
    if (!has_mbl || u > utilization) {
      has_mbl = true;
      utilization = u;
      s_util = n.s;
      t_util = t;
      mbl = m.mbl;
      material = m.name;
    }
  }
}

TensionPeak tensionPeak(const std::vector<Material>& materials, const std::vector<Segment>& segments,
                        const std::vector<NodeState>& nodes) {
  TensionPeak p;
  p.add(materials, segments, nodes);
  return p;
}

double slackLength(const std::vector<Material>& materials, const std::vector<Segment>& segments,
                   const std::vector<NodeState>& nodes) {
  auto slack = [&](const NodeState& n) {
    const std::size_t seg = static_cast<std::size_t>(n.segment);
    if (seg >= segments.size() || segments[seg].material >= materials.size()) return n.tension <= 0.0;
    const Material& m = materials[segments[seg].material];
    return m.compression ? n.tension <= 0.0 : n.tension < 0.5 * m.slackBand();
  };
  double length = 0.0;
  for (std::size_t i = 1; i < nodes.size(); ++i)
    if (slack(nodes[i - 1]) && slack(nodes[i])) length += nodes[i].s - nodes[i - 1].s;
  return length;
}

namespace {
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

std::string tensionPeakText(const TensionPeak& p, bool with_time) {
  if (p.empty) return "no nodes";
  std::string o = fmt("%.1f", p.max_tension) + " N at s = " + fmt("%.2f", p.s_max) + " m";
  if (with_time) o += ", t = " + fmt("%g", p.t_max) + " s";
  if (with_time && p.slack_length > 0.0)
    o += "; slack up to " + fmt("%.2f", p.slack_length) + " m of line at t = " + fmt("%g", p.t_slack) + " s";
  if (!p.has_mbl) return o + "; utilization: no mbl given";
  o += "; utilization " + fmt("%.3f", p.utilization) + " of mbl " + fmt("%.1f", p.mbl) + " N (" + p.material +
       ") at s = " + fmt("%.2f", p.s_util) + " m";
  if (with_time) o += ", t = " + fmt("%g", p.t_util) + " s";
  return o;
}

}  // namespace core
}  // namespace mooring_dynamics
