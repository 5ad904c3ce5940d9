// buildMesh: interval counts, spacing, junctions between segments and at inline bodies, and the
// node bookkeeping (arclength, material and segment indices) around them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"

using namespace mooring_dynamics::core;

namespace {

// Node arclengths are sums of a few O(10 m) values: a few ulps of 100 m.
constexpr double kArcTol = 1e-12;

Material material(const std::string& name) {
  Material m;
  m.name = name;
  m.EA = 1e7;
  m.EI = 1e-2;
  m.wet_weight = 100.0;
  m.diameter = 0.03;
  return m;
}

Problem baseProblem() {
  Problem p;
  p.materials = {material("wire"), material("chain"), material("rope")};
  Body b;
  b.name = "float";
  p.bodies = {b, b, b};
  p.bodies[1].name = "clump";
  p.bodies[2].name = "instrument";
  return p;
}

Segment segment(std::size_t mat, double length, double spacing, std::vector<BodyPlacement> bodies = {}) {
  Segment s;
  s.material = mat;
  s.length = length;
  s.spacing = spacing;
  s.bodies = std::move(bodies);
  return s;
}

/// Indices of the zero-length intervals.
std::vector<std::size_t> junctions(const Mesh& m) {
  std::vector<std::size_t> j;
  for (std::size_t i = 0; i < m.intervals.size(); ++i)
    if (m.intervals[i].h == 0.0) j.push_back(i);
  return j;
}

/// Structural invariants every mesh must satisfy.
void expectConsistent(const Mesh& m, double total_length) {
  ASSERT_EQ(m.nodes.size(), m.intervals.size() + 1);
  EXPECT_EQ(m.nodes.front().s, 0.0);
  EXPECT_NEAR(m.nodes.back().s, total_length, kArcTol);
  for (std::size_t j = 0; j < m.intervals.size(); ++j) {
    EXPECT_GE(m.nodes[j + 1].s, m.nodes[j].s) << "node " << j + 1;
    EXPECT_NEAR(m.nodes[j + 1].s - m.nodes[j].s, m.intervals[j].h, kArcTol) << "interval " << j;
    EXPECT_GE(m.intervals[j].h, 0.0);
    if (m.intervals[j].h > 0.0) {
      EXPECT_TRUE(m.intervals[j].bodies.empty()) << "interval " << j << " has length and bodies";
      // Both ends of a cable interval belong to the interval's material.
      EXPECT_EQ(m.nodes[j].material, m.intervals[j].material) << "interval " << j;
      EXPECT_EQ(m.nodes[j + 1].material, m.intervals[j].material) << "interval " << j;
      EXPECT_EQ(m.nodes[j].segment, m.nodes[j + 1].segment) << "interval " << j;
    }
  }
}

}  // namespace

TEST(Mesh, SingleSegmentIntervalCountAndUniformSpacing) {
  struct Case { double L, spacing; std::size_t n; };
  // ceil(L / spacing); 2.1 / 0.7 evaluates to 3.0000000000000004 in floating point, but the
  // segment is three spacings long and must get three intervals, not four.
  for (const Case c : {Case{10.0, 3.0, 4}, Case{10.0, 2.5, 4}, Case{10.0, 20.0, 1}, Case{2.1, 0.7, 3},
                       Case{7.0, 1.0, 7}, Case{100.0, 0.9, 112}}) {
    Problem p = baseProblem();
    p.segments = {segment(1, c.L, c.spacing)};
    const Mesh m = buildMesh(p);
    ASSERT_EQ(m.intervals.size(), c.n) << "L=" << c.L << " spacing=" << c.spacing;
    double sum = 0.0;
    for (const auto& iv : m.intervals) {
      EXPECT_NEAR(iv.h, c.L / static_cast<double>(c.n), kArcTol);
      EXPECT_EQ(iv.material, 1u);
      sum += iv.h;
    }
    EXPECT_NEAR(sum, c.L, kArcTol);
    EXPECT_TRUE(junctions(m).empty());
    for (const auto& nd : m.nodes) {
      EXPECT_EQ(nd.material, 1u);
      EXPECT_EQ(nd.segment, 0u);
    }
    expectConsistent(m, c.L);
    EXPECT_NEAR(m.minSpacing(), c.L / static_cast<double>(c.n), kArcTol);
  }
}

TEST(Mesh, SegmentJunctionIsZeroLengthInterval) {
  Problem p = baseProblem();
  // 10 m at 3 m spacing -> 4 intervals of 2.5 m; 5 m at 1 m -> 5 intervals of 1 m; 9 m at 4 m -> 3.
  p.segments = {segment(1, 10.0, 3.0), segment(0, 5.0, 1.0), segment(2, 9.0, 4.0)};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 24.0);
  ASSERT_EQ(m.intervals.size(), 4u + 1u + 5u + 1u + 3u);
  EXPECT_EQ(junctions(m), (std::vector<std::size_t>{4, 10}));
  EXPECT_TRUE(m.intervals[4].bodies.empty());
  EXPECT_TRUE(m.intervals[10].bodies.empty());

  // Per-segment spacing and materials.
  for (std::size_t j = 0; j < 4; ++j) { EXPECT_NEAR(m.intervals[j].h, 2.5, kArcTol); EXPECT_EQ(m.intervals[j].material, 1u); }
  for (std::size_t j = 5; j < 10; ++j) { EXPECT_NEAR(m.intervals[j].h, 1.0, kArcTol); EXPECT_EQ(m.intervals[j].material, 0u); }
  for (std::size_t j = 11; j < 14; ++j) { EXPECT_NEAR(m.intervals[j].h, 3.0, kArcTol); EXPECT_EQ(m.intervals[j].material, 2u); }

  // Both sides of the first junction: the nodes sit at s = 10 and belong to their own segment.
  EXPECT_NEAR(m.nodes[4].s, 10.0, kArcTol);
  EXPECT_EQ(m.nodes[4].s, m.nodes[5].s);
  EXPECT_EQ(m.nodes[4].material, 1u);
  EXPECT_EQ(m.nodes[4].segment, 0u);
  EXPECT_EQ(m.nodes[5].material, 0u);
  EXPECT_EQ(m.nodes[5].segment, 1u);
  // Second junction at s = 15.
  EXPECT_NEAR(m.nodes[10].s, 15.0, kArcTol);
  EXPECT_EQ(m.nodes[10].s, m.nodes[11].s);
  EXPECT_EQ(m.nodes[10].material, 0u);
  EXPECT_EQ(m.nodes[10].segment, 1u);
  EXPECT_EQ(m.nodes[11].material, 2u);
  EXPECT_EQ(m.nodes[11].segment, 2u);
  // Anchor and top nodes.
  EXPECT_EQ(m.nodes.front().material, 1u);
  EXPECT_EQ(m.nodes.front().segment, 0u);
  EXPECT_EQ(m.nodes.back().material, 2u);
  EXPECT_EQ(m.nodes.back().segment, 2u);

  EXPECT_NEAR(m.minSpacing(), 1.0, kArcTol);
}

TEST(Mesh, BodySplitsSegmentOnZeroLengthInterval) {
  Problem p = baseProblem();
  // Body 2 at 3.5 m of a 10 m segment, spacing 1: pieces of 3.5 m (4 intervals of 0.875 m) and
  // 6.5 m (7 intervals of 6.5/7 m), with the body's zero-length interval between them.
  p.segments = {segment(0, 10.0, 1.0, {{2, 3.5}})};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 10.0);
  ASSERT_EQ(m.intervals.size(), 4u + 1u + 7u);
  ASSERT_EQ(junctions(m), (std::vector<std::size_t>{4}));
  EXPECT_EQ(m.intervals[4].bodies, (std::vector<std::size_t>{2}));
  EXPECT_NEAR(m.nodes[4].s, 3.5, kArcTol);
  EXPECT_NEAR(m.nodes[5].s, 3.5, kArcTol);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR(m.intervals[j].h, 0.875, kArcTol);
  for (std::size_t j = 5; j < 12; ++j) EXPECT_NEAR(m.intervals[j].h, 6.5 / 7.0, kArcTol);
  // A body inside a segment does not change material or segment.
  for (const auto& nd : m.nodes) {
    EXPECT_EQ(nd.material, 0u);
    EXPECT_EQ(nd.segment, 0u);
  }
  EXPECT_NEAR(m.minSpacing(), 0.875, kArcTol);
}

TEST(Mesh, UnsortedBodiesAreMeshedInArclengthOrder) {
  Problem p = baseProblem();
  p.segments = {segment(0, 12.0, 2.0, {{1, 9.0}, {0, 4.0}})};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 12.0);
  // 4 m -> 2 intervals, 5 m -> 3 intervals, 3 m -> 2 intervals, plus two junctions.
  ASSERT_EQ(m.intervals.size(), 2u + 1u + 3u + 1u + 2u);
  ASSERT_EQ(junctions(m), (std::vector<std::size_t>{2, 6}));
  EXPECT_EQ(m.intervals[2].bodies, (std::vector<std::size_t>{0}));
  EXPECT_EQ(m.intervals[6].bodies, (std::vector<std::size_t>{1}));
  EXPECT_NEAR(m.nodes[2].s, 4.0, kArcTol);
  EXPECT_NEAR(m.nodes[6].s, 9.0, kArcTol);
}

TEST(Mesh, BodiesAtTheSamePointShareOneJunction) {
  Problem p = baseProblem();
  p.segments = {segment(0, 10.0, 1.0, {{2, 6.0}, {0, 6.0}})};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 10.0);
  ASSERT_EQ(m.intervals.size(), 6u + 1u + 4u);
  ASSERT_EQ(junctions(m), (std::vector<std::size_t>{6}));
  std::vector<std::size_t> b = m.intervals[6].bodies;
  std::sort(b.begin(), b.end());
  EXPECT_EQ(b, (std::vector<std::size_t>{0, 2}));
}

TEST(Mesh, BodyAtSegmentEndMergesWithJunction) {
  Problem p = baseProblem();
  // Body 1 at the top of segment 0 and body 2 at the bottom of segment 1: both sit at the one
  // junction at s = 8.
  p.segments = {segment(1, 8.0, 2.0, {{1, 8.0}}), segment(2, 6.0, 2.0, {{2, 0.0}})};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 14.0);
  ASSERT_EQ(m.intervals.size(), 4u + 1u + 3u);
  ASSERT_EQ(junctions(m), (std::vector<std::size_t>{4}));
  std::vector<std::size_t> b = m.intervals[4].bodies;
  std::sort(b.begin(), b.end());
  EXPECT_EQ(b, (std::vector<std::size_t>{1, 2}));
  EXPECT_NEAR(m.nodes[4].s, 8.0, kArcTol);
  EXPECT_EQ(m.nodes[4].material, 1u);
  EXPECT_EQ(m.nodes[4].segment, 0u);
  EXPECT_EQ(m.nodes[5].material, 2u);
  EXPECT_EQ(m.nodes[5].segment, 1u);
}

TEST(Mesh, EveryPlacedBodyAppearsExactlyOnce) {
  Problem p = baseProblem();
  // Bodies at the anchor, inside, at a junction and at the top end.
  p.segments = {segment(0, 20.0, 3.0, {{0, 0.0}, {1, 7.3}}), segment(1, 15.0, 2.0, {{2, 15.0}, {1, 15.0}})};
  const Mesh m = buildMesh(p);
  expectConsistent(m, 35.0);
  std::vector<std::size_t> count(p.bodies.size(), 0);
  for (std::size_t j = 0; j < m.intervals.size(); ++j) {
    if (!m.intervals[j].bodies.empty()) {
      EXPECT_EQ(m.intervals[j].h, 0.0) << "interval " << j;
    }
    for (std::size_t b : m.intervals[j].bodies) ++count[b];
  }
  EXPECT_EQ(count, (std::vector<std::size_t>{1, 2, 1}));
  // Each body's junction is at its placement arclength.
  auto arcOf = [&](std::size_t body, double& s, int& seen) {
    seen = 0;
    for (std::size_t j = 0; j < m.intervals.size(); ++j)
      for (std::size_t b : m.intervals[j].bodies)
        if (b == body) { s = m.nodes[j].s; ++seen; }
  };
  double s = -1.0;
  int seen = 0;
  arcOf(0, s, seen);
  EXPECT_EQ(seen, 1);
  EXPECT_NEAR(s, 0.0, kArcTol);
  arcOf(2, s, seen);
  EXPECT_EQ(seen, 1);
  EXPECT_NEAR(s, 35.0, kArcTol);
}

TEST(Mesh, MinSpacingIgnoresJunctions) {
  Problem p = baseProblem();
  p.segments = {segment(0, 6.0, 2.0, {{0, 3.0}}), segment(1, 1.2, 0.5)};
  const Mesh m = buildMesh(p);
  // 3 m pieces at spacing 2 -> 2 intervals of 1.5 m; 1.2 m at 0.5 -> 3 intervals of 0.4 m.
  EXPECT_NEAR(m.minSpacing(), 0.4, kArcTol);
  EXPECT_GT(junctions(m).size(), 0u);
}
