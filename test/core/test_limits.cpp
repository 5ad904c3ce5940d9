// Resource limits (limits.hpp): the node estimate against the mesh actually built, the limits'
// own validation, and the refusals with the key, the estimate and the limit in the message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/limits.hpp"
#include "mooring_dynamics/core/model/model.hpp"

using namespace mooring_dynamics::core;

namespace {

Problem lineOf(const std::vector<Segment>& segs) {
  Problem p;
  Material m;
  m.name = "wire";
  m.EA = 1e7;
  m.EI = 1;
  m.mass = 1;
  m.wet_weight = 1;
  m.diameter = 0.01;
  p.materials = {m};
  Body b;
  b.name = "float";
  p.bodies = {b};
  p.segments = segs;
  return p;
}

Segment seg(double length, double spacing, std::vector<double> bodies_at = {}) {
  Segment s;
  s.length = length;
  s.spacing = spacing;
  for (double a : bodies_at) s.bodies.push_back(BodyPlacement{0, a});
  return s;
}

bool has(const std::string& msg, const std::string& part) { return msg.find(part) != std::string::npos; }

}  // namespace

TEST(Limits, NodeEstimateIsTheMeshNodeCountOrAbove) {
  // The mesh buildMesh makes is the independent reference: equal without bodies, an upper bound
  // with them (a body at a segment end adds no piece).
  const std::vector<std::vector<Segment>> cases = {
      {seg(150, 2)},
      {seg(45, 0.5), seg(0.76, 0.5), seg(3.5, 0.5)},
      {seg(10, 3)},
      {seg(1, 1)},
      {seg(100, 10, {25, 50}), seg(20, 1)},
      {seg(100, 10, {0, 100})},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const double built = static_cast<double>(buildMesh(lineOf(cases[i])).nodes.size());
    const double est = estimateLineNodes(cases[i]);
    bool any_body = false;
    for (const auto& s : cases[i]) any_body = any_body || !s.bodies.empty();
    if (any_body) EXPECT_GE(est, built) << "case " << i;
    else EXPECT_EQ(est, built) << "case " << i;
  }
  // Absurd spacings cannot overflow: the estimate is a double.
  EXPECT_GT(estimateLineNodes({seg(150, 1e-300)}), 1e300);
  EXPECT_TRUE(std::isinf(estimateLineNodes({seg(1e300, 1e-300)})));
}

TEST(Limits, LimitsThemselvesAreValidated) {
  ResourceLimits l;
  EXPECT_EQ(l.validate(), "");
  l.max_nodes = 0;
  EXPECT_TRUE(has(l.validate(), "limits.max_nodes"));
  l = ResourceLimits{};
  l.max_steps = std::nan("");
  EXPECT_TRUE(has(l.validate(), "limits.max_steps"));
  l = ResourceLimits{};
  l.max_memory_mb = 1e300;
  EXPECT_TRUE(has(l.validate(), "limits.max_memory_mb"));
  l = ResourceLimits{};
  l.max_input_mb = 300;  // over what readFileText reads at all (256 MB)
  EXPECT_TRUE(has(l.validate(), "limits.max_input_mb = 300"));
}

TEST(Limits, EachLimitRefusesWithItsKey) {
  ResourceLimits lim;
  DynamicOptions dyn;  // duration 0: statics only
  lim.max_memory_mb = 1e8;  // the node and step limits alone first
  EXPECT_EQ(checkResources(estimateResources(1e6, dyn, true, 0), lim, "K"), "");
  const std::string n = checkResources(estimateResources(1e6 + 1, dyn, true, 0), lim, "line[0].spacing = 1e-05");
  EXPECT_TRUE(has(n, "line[0].spacing = 1e-05") && has(n, "limits.max_nodes") && has(n, "1e+06")) << n;

  dyn.duration = 100;
  dyn.dt = 1e-5;  // exactly 1e7 steps: within
  EXPECT_EQ(checkResources(estimateResources(100, dyn, false, 0), lim, "K"), "");
  dyn.dt = 1e-6;
  const std::string s = checkResources(estimateResources(100, dyn, false, 0), lim, "K");
  EXPECT_TRUE(has(s, "dynamics.duration = 100") && has(s, "dynamics.dt = 1e-06") && has(s, "limits.max_steps")) << s;

  // Memory: 1e4 snapshots of 1e5 nodes at kBytesPerSnapshotNode each.
  lim = ResourceLimits{};
  dyn.dt = 0.01;
  dyn.snapshot_interval = 0.01;
  const ResourceEstimate e = estimateResources(1e5, dyn, false, 0);
  EXPECT_NEAR(e.snapshots, 1e4, 2.0);
  EXPECT_GT(e.memory_mb, 1e4 * 1e5 * kBytesPerSnapshotNode / (1024.0 * 1024.0) * 0.99);
  const std::string m = checkResources(e, lim, "K");
  EXPECT_TRUE(has(m, "estimated memory") && has(m, "limits.max_memory_mb")) << m;
  lim.max_memory_mb = 1e6;
  EXPECT_EQ(checkResources(e, lim, "K"), "");
  // The per-node working set: 3-D beyond 4096 MB at 2e5 nodes (6.1 GB), 2-D statics within (0.4 GB).
  DynamicOptions st;
  EXPECT_NE(checkResources(estimateResources(2e5, st, true, 0), ResourceLimits{}, "K"), "");
  EXPECT_EQ(checkResources(estimateResources(2e5, st, false, 0), ResourceLimits{}, "K"), "");
}

TEST(Limits, ProblemValidateNamesTheSpacingAndTheSegmentLength) {
  Problem p = lineOf({seg(150, 2)});
  p.top.x = 100;
  p.top.z = 0;
  EXPECT_EQ(p.validate(), "");
  p.segments[0].spacing = 200;
  const std::string e = p.validate();
  EXPECT_TRUE(has(e, "line[0].spacing = 200") && has(e, "line[0].length = 150")) << e;
  p.segments[0].spacing = 1e-4;  // 1.5e6 nodes
  const std::string n = p.validate();
  EXPECT_TRUE(has(n, "line[0].spacing = 0.0001") && has(n, "limits.max_nodes")) << n;
  p.limits.max_nodes = 2e6;
  EXPECT_EQ(p.validate(), "");
}

TEST(Limits, DtLongerThanTheRunIsRefused) {
  DynamicOptions d;
  d.duration = 5;
  d.dt = 5;
  EXPECT_EQ(d.validate(), "");
  d.dt = 1e20;
  EXPECT_TRUE(has(d.validate(), "dynamics.dt = 1e+20")) << d.validate();
}
