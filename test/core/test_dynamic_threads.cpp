// dynamics.threads = 2 in the 2-D and 3-D dynamic solvers (dynamics2d.cpp, dynamics3d.cpp): a
// second thread takes the upper half of every Newton iteration (water, node terms and interval
// rows, the two-ended elimination's upper sweep, the vector work) and of each accepted step's
// spatial rows; in 2-D the water and the interval rows split by their cost (the S-tether's
// wave sums, the junctions of both shipped files), not at the meeting node. Each thread does the
// operations it would do alone, so the series must be the same bit for bit as with one thread.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"

using namespace mooring_dynamics::core;

namespace {

struct Case {
  const char* file;  // under the source folder
  double duration;   // [s] long enough for contact events, cuts, the sea to build up
  bool to_3d;        // a 2-D file run in the 3-D model
  double spacing = 0.0;  // [m] > 0: every segment's node spacing (a 2-D line long enough for two threads)
};

/// Runs the case with one and with two threads and compares the counts and series exactly.
template <class Run>
void expectSameSeriesOnTwoThreads(const Case& c, Run run) {
  Problem p = loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/" + c.file);
  if (c.to_3d) p.formulation = Formulation::ThreeD;
  if (c.spacing > 0.0)
    for (Segment& g : p.segments) g.spacing = c.spacing;
  p.dynamics.duration = c.duration;
  Problem p2 = p;
  p2.dynamics.threads = 2;
  const DynamicSeries one = run(p), two = run(p2);
  ASSERT_TRUE(one.completed) << c.file << ": " << one.message;
  ASSERT_TRUE(two.completed) << c.file << ": " << two.message;
  EXPECT_EQ(two.threads, 2) << c.file << ": the second thread did not run";
  EXPECT_EQ(two.steps, one.steps) << c.file;
  EXPECT_EQ(two.cuts, one.cuts) << c.file;
  EXPECT_EQ(two.newton_iterations, one.newton_iterations) << c.file;
  EXPECT_EQ(two.jacobians, one.jacobians) << c.file;
  ASSERT_EQ(two.t.size(), one.t.size()) << c.file;
  for (std::size_t k = 0; k < one.t.size(); ++k) {
    ASSERT_EQ(two.top_tension[k], one.top_tension[k]) << c.file << " t = " << one.t[k];
    ASSERT_EQ(two.anchor_tension[k], one.anchor_tension[k]) << c.file << " t = " << one.t[k];
    ASSERT_EQ(two.top_x[k], one.top_x[k]) << c.file << " t = " << one.t[k];
    ASSERT_EQ(two.top_y[k], one.top_y[k]) << c.file << " t = " << one.t[k];
    ASSERT_EQ(two.top_z[k], one.top_z[k]) << c.file << " t = " << one.t[k];
  }
  ASSERT_EQ(two.snapshots.size(), one.snapshots.size()) << c.file;
  for (std::size_t i = 0; i < one.snapshots.size(); ++i)
    for (std::size_t j = 0; j < one.snapshots[i].nodes.size(); ++j) {
      ASSERT_EQ(two.snapshots[i].nodes[j].x, one.snapshots[i].nodes[j].x) << c.file;
      ASSERT_EQ(two.snapshots[i].nodes[j].tension, one.snapshots[i].nodes[j].tension) << c.file;
    }
}

}  // namespace

// 2-D: the shipped chain mooring (AxPack junctions, seabed contact and lift-off, cut steps) at
// 0.4 m spacing (about 205 nodes: its 170 at 0.5 m run on one thread, below
// DynamicSolver2D::kMinNodesForTwoThreads) and the S-tether (274 nodes; wave kinematics at every
// node, clump bodies).
TEST(DynamicThreads, TwoDimensionalSeriesAreTheSameBitForBit) {
  for (const Case c : {Case{"config/chain_mooring.yaml", 24.0, false, 0.4}, Case{"config/s_tether.yaml", 30.0, false}})
    expectSameSeriesOnTwoThreads(c, [](const Problem& p) { return runDynamic(p); });
}

// A 2-D line below kMinNodesForTwoThreads asked for two threads runs on one (a second thread
// costs more than it takes off there: scripts/threads_bench) and says so; the series is the
// same either way.
TEST(DynamicThreads, AShortTwoDimensionalLineRunsOnOneThread) {
  Problem p = loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/chain_mooring.yaml");
  p.dynamics.threads = 2;
  DynamicSolver2D solver(p);
  ASSERT_LT(solver.nodeArclengths().size(), static_cast<std::size_t>(DynamicSolver2D::kMinNodesForTwoThreads));
  EXPECT_EQ(solver.threads(), 1);
  p.dynamics.duration = 2.0;
  EXPECT_EQ(runDynamic(p).threads, 1);
}

// 3-D: the 3-D chain mooring (seabed contact, cuts, out-of-plane heave), the S-tether in 3-D (its
// random sea) and the towed array (a free lower end, modified Newton: residual-only evaluations).
TEST(DynamicThreads, ThreeDimensionalSeriesAreTheSameBitForBit) {
  for (const Case c : {Case{"config/chain_mooring_3d.yaml", 20.0, false}, Case{"config/s_tether.yaml", 20.0, true},
                       Case{"config/towed_array.yaml", 30.0, false}})
    expectSameSeriesOnTwoThreads(c, [](const Problem& p) { return runDynamic3D(p); });
}
