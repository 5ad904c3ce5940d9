// rostest: a step that fails at its smallest cut in the lockstep nodes (issue 22): the node keeps
// the last good state, publishes it for that sample (converged false), reports ERROR naming the
// line, and continues on the next sample; three failures in a row restart from statics.
//
//   test_step_failure.test         LineFailure.*    LockstepNode on test/data/fragile_catenary.yaml
//   test_step_failure.vessel.test  VesselFailure.*  VesselNode on test/data/fragile_vessel.yaml
// The fragile files allow 4 Newton iterations per step (a gentle step needs at most 3) and no step
// cutting, and the launch sets ~max_speed 0, so that a lurch of the top or the vessel reaches the
// solver and its step fails: the node keeps the last good state, publishes it for that sample
// (converged false), reports ERROR naming the line, and continues on the next sample.
// The harness (the node's outputs and /diagnostics, Stream) is test_bad_streams.cpp's:
// bad_streams_harness.hpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"
#include "bad_streams_harness.hpp"

namespace md = mooring_dynamics;
namespace lk = mooring_dynamics::ros_bridge::lockstep_keys;
namespace vk = mooring_dynamics::ros_bridge::vessel_keys;
using namespace bad_streams_test;

namespace {

constexpr double kLurch = 5.0;  // [m] in 0.1 s: far more than 4 Newton iterations can follow

bool sameState(const md::CableState& a, const md::CableState& b) {
  if (a.positions.size() != b.positions.size()) return false;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    if (a.positions[i].x != b.positions[i].x || a.positions[i].y != b.positions[i].y ||
        a.positions[i].z != b.positions[i].z || a.tension[i] != b.tension[i])
      return false;
  return a.top_force.x == b.top_force.x && a.top_force.z == b.top_force.z;
}

/// Gentle samples, then one lurch: the answer to the lurch is the previous answer's state (the
/// step failed at once: one base step per sample, no cutting), bit for bit, marked not converged;
/// ERROR names the line; the next gentle sample is answered from there, converged.
void failureKeepsLastGoodState(const std::vector<std::string>& lines, const std::string& kept_key) {
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(g_h->settle());
  const ros::Time good = g_h->now();
  Stream s;
  auto m = g_h->good(g_h->next());
  m.pose.position.x += kLurch;
  g_h->send(m);
  ASSERT_TRUE(g_h->waitAnswer(m.header.stamp)) << "the failed sample is answered (with the last good state)";
  for (const auto& l : lines) {
    md::CableState before, failed;
    ASSERT_TRUE(g_h->state(l, good, before)) << l;
    ASSERT_TRUE(g_h->waitState(l, m.header.stamp, failed)) << l;
    EXPECT_TRUE(before.converged) << l;
    EXPECT_FALSE(failed.converged) << l << ": the kept state is not the state at this stamp";
    EXPECT_TRUE(sameState(before, failed)) << l << ": the last good state, bit for bit";
  }
  geometry_msgs::WrenchStamped wb, wf;
  ASSERT_TRUE(g_h->wrench(good, wb));
  ASSERT_TRUE(g_h->wrench(m.header.stamp, wf));
  EXPECT_EQ(wb.wrench.force.x, wf.wrench.force.x);
  EXPECT_EQ(wb.wrench.force.z, wf.wrench.force.z);
  EXPECT_EQ(wb.wrench.torque.z, wf.wrench.torque.z);
  const Diag d = g_h->waitDiag("last good state");
  EXPECT_EQ(d.level, 2) << d.message;  // ERROR
  bool named = false;
  for (const auto& l : lines) named = named || d.message.find("line " + l) != std::string::npos;
  EXPECT_TRUE(named) << "the message names the failed line: " << d.message;
  // The next gentle sample continues from the kept state and converges.
  const Diag& a = s.after();
  EXPECT_EQ(s.grew(kept_key), 1) << s.changes();
  md::CableState next;
  ASSERT_TRUE(g_h->waitState(lines[0], g_h->now(), next));
  EXPECT_TRUE(next.converged);
  (void)a;
}

/// Three lurches in a row (~failures_to_reinit, 3): two kept states, then a restart from statics
/// at the third sample's pose, converged.
void repeatedFailuresRestart(const std::vector<std::string>& lines, const std::string& kept_key,
                             const std::string& restart_key) {
  ASSERT_TRUE(g_h->settle());
  Stream s;
  ros::Time last;
  for (int i = 1; i <= 3; ++i) {
    auto m = g_h->good(g_h->next());
    m.pose.position.x += kLurch;
    g_h->send(m);
    last = m.header.stamp;
  }
  ASSERT_TRUE(g_h->waitAnswer(last));
  md::CableState st;
  ASSERT_TRUE(g_h->waitState(lines[0], last, st));
  EXPECT_TRUE(st.converged) << "restarted from statics at the sample";
  // Back to the gentle track: 5 m back in 0.1 s fails again; the third time restarts again.
  for (int i = 0; i < 3; ++i) g_h->send(g_h->good(g_h->next()));
  ASSERT_TRUE(g_h->waitAnswer(g_h->now()));
  s.after();
  EXPECT_EQ(s.grew(kept_key), 4) << s.changes();
  EXPECT_EQ(s.grew(restart_key), 2) << s.changes();
}

}  // namespace

TEST(LineFailure, KeepsLastGoodStatePublishesAndContinues) {
  failureKeepsLastGoodState({"fragile catenary"}, lk::kFailedKept);
}
TEST(LineFailure, RepeatedFailuresRestartFromStatics) {
  repeatedFailuresRestart({"fragile catenary"}, lk::kFailedKept, lk::kReinitFailures);
}
TEST(VesselFailure, KeepsLastGoodStatePublishesAndContinues) {
  failureKeepsLastGoodState({"bow", "port_quarter", "stbd_quarter"}, vk::kFailedKept);
}
TEST(VesselFailure, RepeatedFailuresRestartFromStatics) {
  repeatedFailuresRestart({"bow", "port_quarter", "stbd_quarter"}, vk::kFailedKept, vk::kRestartFailures);
}

int main(int argc, char** argv) { return harnessMain(argc, argv, "test_step_failure"); }
