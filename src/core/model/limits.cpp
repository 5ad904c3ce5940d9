#include "mooring_dynamics/core/model/limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string limitKey(const std::string& key, double value, double lo, double hi) {
  return "limits." + key + " = " + num(value) + ": must be a number in [" + num(lo) + ", " + num(hi) + "]";
}

}  // namespace

std::string ResourceLimits::validate() const {
  // A limit may be raised, not abolished: beyond these the estimates themselves lose meaning
  // (node indices are 32-bit in places, step counters long).
  constexpr double kCeilNodes = 1.0e9, kCeilSteps = 1.0e15, kCeilMemoryMb = 1.0e9;
  if (!(std::isfinite(max_nodes) && max_nodes >= 2.0 && max_nodes <= kCeilNodes))
    return limitKey("max_nodes", max_nodes, 2.0, kCeilNodes);
  if (!(std::isfinite(max_steps) && max_steps >= 1.0 && max_steps <= kCeilSteps))
    return limitKey("max_steps", max_steps, 1.0, kCeilSteps);
  if (!(std::isfinite(max_memory_mb) && max_memory_mb >= 1.0 && max_memory_mb <= kCeilMemoryMb))
    return limitKey("max_memory_mb", max_memory_mb, 1.0, kCeilMemoryMb);
  constexpr double kFloorInputMb = 0.01, kCeilInputMb = 256.0;  // (readFileText reads at most 256 MB)
  if (!(std::isfinite(max_input_mb) && max_input_mb >= kFloorInputMb && max_input_mb <= kCeilInputMb))
    return limitKey("max_input_mb", max_input_mb, kFloorInputMb, kCeilInputMb);
  return {};
}

double estimateLineNodes(const std::vector<Segment>& segments) {
  // buildMesh (mesh.cpp): ceil(length / spacing - 1e-9) intervals per piece, at least one, plus a
  // node at every joint between segments and at every body junction. Exact without bodies.
  double nodes = 1.0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    const double ratio = s.length / s.spacing;
    nodes += std::isfinite(ratio) ? std::max(1.0, std::ceil(ratio - 1e-9)) : HUGE_VAL;
    // Each body adds its junction node and splits a piece, whose rounding up may add an interval.
    nodes += (i > 0 ? 1.0 : 0.0) + 2.0 * static_cast<double>(s.bodies.size());
  }
  return nodes;
}

ResourceEstimate estimateResources(double nodes, const DynamicOptions& dyn, bool three_d, std::size_t record_columns) {
  ResourceEstimate e;
  e.nodes = nodes;
  const bool dynamic = dyn.duration > 0.0 && dyn.dt > 0.0;
  double bytes = nodes * (three_d ? kBytesPerNode3d : dynamic ? kBytesPerNode2dDynamic : kBytesPerNode2dStatic);
  if (dynamic) {
    e.duration = dyn.duration;
    e.dt = dyn.dt;
    e.steps = dyn.duration / dyn.dt;
    const double dout = dyn.output_interval > 0.0 ? dyn.output_interval : dyn.dt;
    e.samples = std::floor(dyn.duration / dout) + 2.0;
    if (dyn.snapshot_interval > 0.0) e.snapshots = e.samples / std::max(1.0, std::round(dyn.snapshot_interval / dout));
    // Each sample: time, top and anchor tension, top x, y, z, and 4 values per recorded node.
    bytes += e.samples * 8.0 * (6.0 + static_cast<double>(record_columns));
    bytes += e.snapshots * nodes * kBytesPerSnapshotNode;
  }
  e.memory_mb = bytes / (1024.0 * 1024.0);
  return e;
}

std::string checkResources(const ResourceEstimate& est, const ResourceLimits& lim, const std::string& nodes_key) {
  if (!(est.nodes <= lim.max_nodes))
    return nodes_key + ": gives about " + num(est.nodes) + " nodes in all, beyond limits.max_nodes = " +
           num(lim.max_nodes) + " (a larger spacing gives fewer nodes; to run it anyway raise limits.max_nodes)";
  if (!(est.steps <= lim.max_steps))
    return "dynamics.duration = " + num(est.duration) + " s / dynamics.dt = " + num(est.dt) + " s: about " +
           num(est.steps) + " time steps, beyond limits.max_steps = " +
           num(lim.max_steps) + " (to run it anyway raise limits.max_steps)";
  if (!(est.memory_mb <= lim.max_memory_mb))
    return "estimated memory " + num(est.memory_mb) + " MB (" + num(est.nodes) + " nodes, " + num(est.samples) +
           " samples, " + num(est.snapshots) + " snapshots of dynamics.snapshot_interval), beyond limits.max_memory_mb = " +
           num(lim.max_memory_mb) + " (a larger dynamics.snapshot_interval or spacing needs less; to run it anyway "
           "raise limits.max_memory_mb)";
  return {};
}

std::string validateSpacing(const std::vector<Segment>& segments, const std::string& prefix) {
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    const std::string k = prefix + "[" + std::to_string(i) + "]";
    if (!(std::isfinite(s.spacing) && s.spacing > 0.0))
      return k + ".spacing = " + num(s.spacing) + ": must be > 0";
    // Equal is fine (one interval); beyond the length the segment collapses to a single
    // interval whatever the spacing says.
    if (s.spacing > s.length)
      return k + ".spacing = " + num(s.spacing) + ": must be <= the segment length " + k + ".length = " +
             num(s.length) + " m (a spacing beyond the segment collapses it to one interval)";
  }
  return {};
}

}  // namespace core
}  // namespace mooring_dynamics
