// TensionPeak: the largest tension along a line and its utilization T / MBL, checked against hand
// sums on made-up states.
#include <gtest/gtest.h>

#include "mooring_dynamics/core/model/utilization.hpp"

using namespace mooring_dynamics::core;

namespace {

NodeState node(double s, double T, int segment) {
  NodeState n;
  n.s = s;
  n.tension = T;
  n.segment = segment;
  return n;
}

// Two segments: chain (MBL 1000 N) below, rope (MBL 100 N) above.
struct Line {
  std::vector<Material> materials;
  std::vector<Segment> segments;
  Line() {
    materials.resize(2);
    materials[0].name = "chain";
    materials[0].mbl = 1000.0;
    materials[1].name = "rope";
    materials[1].mbl = 100.0;
    segments.resize(2);
    segments[0].material = 0;
    segments[1].material = 1;
  }
};

}  // namespace

TEST(Utilization, LargestRatioNotLargestTension) {
  const Line l;
  // The chain carries the largest tension (500 N, ratio 0.5); the rope the largest ratio (80 / 100).
  const std::vector<NodeState> nodes{node(0.0, 500.0, 0), node(10.0, 400.0, 0), node(10.0, 80.0, 1),
                                     node(20.0, 60.0, 1)};
  const TensionPeak p = tensionPeak(l.materials, l.segments, nodes);
  EXPECT_FALSE(p.empty);
  EXPECT_EQ(p.max_tension, 500.0);
  EXPECT_EQ(p.s_max, 0.0);
  ASSERT_TRUE(p.has_mbl);
  EXPECT_EQ(p.utilization, 80.0 / 100.0);
  EXPECT_EQ(p.s_util, 10.0);
  EXPECT_EQ(p.mbl, 100.0);
  EXPECT_EQ(p.material, "rope");
}

TEST(Utilization, NoMblGivenReportsNone) {
  Line l;
  l.materials[0].mbl = 0.0;
  l.materials[1].mbl = 0.0;
  const TensionPeak p = tensionPeak(l.materials, l.segments, {node(0.0, 5.0, 0), node(1.0, 7.0, 1)});
  EXPECT_EQ(p.max_tension, 7.0);
  EXPECT_FALSE(p.has_mbl);
  EXPECT_NE(tensionPeakText(p, false).find("no mbl given"), std::string::npos);
}

TEST(Utilization, PeakOverStatesKeepsTheTimeOfEach) {
  const Line l;
  TensionPeak p;
  p.add(l.materials, l.segments, {node(0.0, 300.0, 0), node(20.0, 50.0, 1)}, 1.0);   // u = 0.3, 0.5
  p.add(l.materials, l.segments, {node(0.0, 900.0, 0), node(20.0, 40.0, 1)}, 2.0);   // u = 0.9, 0.4
  p.add(l.materials, l.segments, {node(0.0, 100.0, 0), node(20.0, 20.0, 1)}, 3.0);
  EXPECT_EQ(p.max_tension, 900.0);
  EXPECT_EQ(p.t_max, 2.0);
  EXPECT_EQ(p.utilization, 0.9);
  EXPECT_EQ(p.t_util, 2.0);
  EXPECT_EQ(p.material, "chain");
  const std::string txt = tensionPeakText(p, true);
  EXPECT_NE(txt.find("utilization 0.900 of mbl 1000.0 N (chain)"), std::string::npos) << txt;
}

TEST(Utilization, SlackLengthCountsIntervalsWithBothNodesSlack) {
  Line l;
  l.materials[0].EA = 1e7;  // slack below EA kSlackStrain / 2 = 5 N
  l.materials[0].compression = false;
  l.materials[1].EA = 1e7;
  l.materials[1].compression = true;  // slack at T <= 0
  const std::vector<NodeState> nodes{node(0.0, 100.0, 0), node(2.0, 4.0, 0),  node(5.0, 0.0, 0),
                                     node(9.0, 0.0, 1),   node(10.0, -3.0, 1), node(12.0, 1.0, 1)};
  // Slack intervals: [2, 5], [5, 9], [9, 10]: 8 m.
  EXPECT_EQ(slackLength(l.materials, l.segments, nodes), 8.0);
}
