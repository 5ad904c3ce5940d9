// rostest: bad message streams into the lockstep nodes (issue 22). Each test sends one named bad
// stream and checks, from the node's /diagnostics, that the specific counter grew by the expected
// count (a counter of the node itself, not of this test), that a good sample sent after it is
// answered (the node keeps publishing), and that every number the node published during the whole
// run is finite (tensions, positions, forces, wrenches).
//
//   test_bad_streams.test          LineStreams.*   LockstepNode on test/data/small_catenary.yaml
//   test_bad_streams.vessel.test   VesselStreams.* VesselNode on test/data/small_vessel.yaml
// A step that fails at its smallest cut (the fragile files): test_step_failure.cpp. The harness
// (the node's outputs and /diagnostics, Stream): bad_streams_harness.hpp.
//
// Decisions documented in docs/ros_interface.md ("Bad input"):
// a stamp far in the future is a gap (restart from statics there) and the next normal stamp a bag
// loop (restart again); an unused orientation (line node) is accepted and counted.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/VesselStatics.h"
#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"
#include "bad_streams_harness.hpp"

namespace md = mooring_dynamics;
namespace lk = mooring_dynamics::ros_bridge::lockstep_keys;
namespace vk = mooring_dynamics::ros_bridge::vessel_keys;
using namespace bad_streams_test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

geometry_msgs::PoseStamped withPosition(geometry_msgs::PoseStamped m, int axis, double v) {
  (axis == 0 ? m.pose.position.x : axis == 1 ? m.pose.position.y : m.pose.position.z) = v;
  return m;
}
geometry_msgs::PoseStamped withQuaternion(geometry_msgs::PoseStamped m, double x, double y, double z, double w) {
  m.pose.orientation.x = x;
  m.pose.orientation.y = y;
  m.pose.orientation.z = z;
  m.pose.orientation.w = w;
  return m;
}

/// Sends `bad` at the next stamp and checks it is not answered once a later good one is.
void sendUnanswered(const geometry_msgs::PoseStamped& bad) {
  g_h->send(bad);
  const ros::Time probe = g_h->next();
  g_h->send(g_h->good(probe));
  ASSERT_TRUE(g_h->waitAnswer(probe));
  EXPECT_EQ(g_h->answers(bad.header.stamp), 0) << "the bad sample was answered";
}

// ---------------------------------------------------------------------------------------------
// Streams common to both nodes (the key differs where the nodes differ).

void nanPosition(const std::string& key) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 0, kNaN));
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void infPosition(const std::string& key) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 2, kInf));
  sendUnanswered(withPosition(g_h->good(g_h->next()), 0, -kInf));
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
void backwardStamp(const std::string& key) {
  Stream s;
  g_h->settle();
  // Back by 0.4567 s (<= loop_back, 1 s), off the 0.1 s grid of the earlier good samples.
  sendUnanswered(g_h->good(g_h->now() - ros::Duration(0.4567)));
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void duplicateStamp(const std::string& key) {
  Stream s;
  const ros::Time t = g_h->next();
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->waitAnswer(t));
  g_h->send(g_h->good(t));
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->settle());
  EXPECT_EQ(g_h->answers(t), 1) << "a duplicate stamp was answered again";
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
/// A stamp 1e6 s ahead: a gap over ~max_gap, so the run restarts from statics there (published
/// with that stamp); the next normal stamp goes back by 1e6 s, more than ~loop_back: a bag loop,
/// restarted again. Both answered.
void farFutureStamp(const std::string& gap_key, const std::string& loop_key) {
  Stream s;
  const ros::Time far = g_h->now() + ros::Duration(1e6);
  g_h->send(g_h->good(far));
  EXPECT_TRUE(g_h->waitAnswer(far));
  s.after();
  EXPECT_EQ(s.grew(gap_key), 1) << s.changes();
  EXPECT_EQ(s.grew(loop_key), 1) << s.changes();
}
void hugeJump(const std::string& key) {
  Stream s;
  auto m = g_h->good(g_h->next());
  m.pose.position.x += 1000.0;  // 1 km in 0.1 s: 10 km/s > max_speed (50 m/s)
  sendUnanswered(m);
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
/// The source really moved: jumps_to_reinit (3) jumps in a row to a reachable place restart there.
/// The speed is taken from the last accepted sample, so the third sample, 0.3 s after it, must
/// still be too fast: 20 m down (66 m/s over 0.3 s, above max_speed = 50 m/s).
void repeatedJumps(const std::string& key) {
  constexpr double kDrop = 20.0;  // [m]
  Stream s;
  for (int i = 0; i < 3; ++i) {
    auto m = g_h->good(g_h->next());
    m.pose.position.z -= kDrop;
    g_h->send(m);
  }
  ASSERT_TRUE(g_h->waitAnswer(g_h->now())) << "the third jump restarts and is answered";
  // Back to the good track: jumps again (from the new place), and the third restarts again.
  for (int i = 0; i < 3; ++i) g_h->send(g_h->good(g_h->next()));
  ASSERT_TRUE(g_h->waitAnswer(g_h->now()));
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
/// 2000 samples at 1 kHz, 1 ms of stamp apart. The node answers every sample it receives, once,
/// in order; its input queue (100) holds what arrives while it works, and what a slower node
/// cannot take in time the transport drops before the node sees it (compare the samples sent
/// with `motion samples`). Checked: the node's own counts agree with this test's answers.
void burst() {
  Stream s;
  ros::WallRate rate(kBurstRate);
  std::vector<ros::Time> stamps;
  for (int i = 0; i < kBurst; ++i) {
    g_h->setTime(g_h->now() + ros::Duration(1.0 / kBurstRate));
    stamps.push_back(g_h->now());
    g_h->send(g_h->good(g_h->now()));
    rate.sleep();
  }
  // The last sample that got through is answered within the timeout; wait until answers stop.
  int answered = -1;
  for (int quiet = 0; quiet < 20;) {
    int n = 0;
    for (const auto& t : stamps) n += g_h->answers(t) > 0 ? 1 : 0;
    quiet = n == answered ? quiet + 1 : 0;
    answered = n;
    ros::WallDuration(0.05).sleep();
  }
  // Answered more than once: none (the last one answered excepted: a silent source gets the last
  // state republished, the line node's ~republish_when_silent).
  int twice = 0, last = -1;
  for (int i = 0; i < kBurst; ++i)
    if (g_h->answers(stamps[static_cast<std::size_t>(i)]) > 0) last = i;
  for (int i = 0; i < last; ++i) twice += g_h->answers(stamps[static_cast<std::size_t>(i)]) > 1 ? 1 : 0;
  s.after();
  const long received = s.grew("motion samples");
  EXPECT_EQ(twice, 0) << "a sample answered twice";
  EXPECT_EQ(received, answered + 1) << "every sample the node received (and the settling one) was answered; sent "
                                    << kBurst << ", " << s.changes();
  EXPECT_EQ(s.grew("states published"), answered + 1) << s.changes();
  EXPECT_GE(answered, 100) << "at least a queue's worth of the burst";
  ::testing::Test::RecordProperty("burst_sent", kBurst);
  ::testing::Test::RecordProperty("burst_answered", answered);
  std::printf("burst: %d samples sent at %g Hz, %d received and answered\n", kBurst, kBurstRate, answered);
}
void silentTopic(bool republishes) {
  Stream s;
  const ros::Time last = g_h->now();
  const int before = g_h->answers(last);
  // ~motion_timeout is 0.5 s in the launch files: 1.5 s of silence.
  ros::WallDuration(1.5).sleep();
  const Diag d = g_h->freshDiag();
  EXPECT_EQ(d.level, 1) << d.message;  // WARN
  EXPECT_NE(d.message.find("no motion for"), std::string::npos) << d.message;
  if (republishes) {
    EXPECT_GT(g_h->answers(last), before) << "the last good state is republished while silent";
  }
  const Diag& a = s.after();
  EXPECT_EQ(a.message.find("no motion for"), std::string::npos) << a.message;
}
void wrongFrame(const std::string& key) {
  Stream s;
  auto m = g_h->good(g_h->next());
  m.header.frame_id = "nowhere";  // no tf to world: dropped after ~tf_timeout
  sendUnanswered(m);
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void zeroStamp(const std::string& key) {
  Stream s;
  auto m = g_h->good(ros::Time(0));
  g_h->send(m);
  ASSERT_TRUE(g_h->settle());
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void alternating(const std::string& key) {
  Stream s;
  std::vector<ros::Time> good;
  for (int i = 0; i < 10; ++i) {
    good.push_back(g_h->next());
    g_h->send(g_h->good(good.back()));
    g_h->send(withPosition(g_h->good(g_h->next()), 2, kNaN));
  }
  ASSERT_TRUE(g_h->waitAnswer(good.back()));
  for (const auto& t : good) EXPECT_EQ(g_h->answers(t), 1) << t.toSec();
  s.after();
  EXPECT_EQ(s.grew(key), 10) << s.changes();
}
/// 1 ns after the last accepted stamp: a tiny but valid step, answered with finite values.
void nanosecondStep() {
  Stream s;
  const ros::Time t = g_h->next();
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->waitAnswer(t));
  const ros::Time t1 = t + ros::Duration(0, 1);
  g_h->setTime(t1);
  g_h->send(g_h->good(t1));
  EXPECT_TRUE(g_h->waitAnswer(t1));
  s.after();
}
void resetThenContinue(const std::string& key) {
  Stream s;
  std_srvs::Trigger tr;
  ASSERT_TRUE(g_h->call("reset", tr));
  EXPECT_TRUE(tr.response.success) << tr.response.message;
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// LockstepNode (one line, model: 2d).

TEST(LineStreams, NanPosition) { nanPosition(lk::kNonFinite); }
TEST(LineStreams, InfPosition) { infPosition(lk::kNonFinite); }
TEST(LineStreams, NanQuaternionAcceptedAndCounted) {
  // The line's top is a moment-free point: the orientation is not used, so a bad one does not
  // drop the sample; it is counted (and a non-finite one warns).
  Stream s;
  const auto m = withQuaternion(g_h->good(g_h->next()), kNaN, 0, 0, 1);
  g_h->send(m);
  EXPECT_TRUE(g_h->waitAnswer(m.header.stamp));
  const Diag& d = s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonFinite), 1) << s.changes();
  (void)d;
}
TEST(LineStreams, InfQuaternionAcceptedAndCounted) {
  Stream s;
  const auto m = withQuaternion(g_h->good(g_h->next()), 0, kInf, 0, 1);
  g_h->send(m);
  EXPECT_TRUE(g_h->waitAnswer(m.header.stamp));
  s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonFinite), 1) << s.changes();
}
TEST(LineStreams, ZeroAndNonUnitQuaternionsAcceptedAndCounted) {
  Stream s;
  const auto a = withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 0);
  const auto b = withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 1.1);
  g_h->send(a);
  g_h->send(b);
  EXPECT_TRUE(g_h->waitAnswer(b.header.stamp));
  EXPECT_EQ(g_h->answers(a.header.stamp), 1);
  s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonUnit), 2) << s.changes();
}
TEST(LineStreams, BackwardStamp) { backwardStamp(lk::kStampBack); }
TEST(LineStreams, DuplicateStamp) { duplicateStamp(lk::kSameStamp); }
TEST(LineStreams, FarFutureStamp) { farFutureStamp(lk::kReinitGap, lk::kReinitLoop); }
TEST(LineStreams, HugeJump) { hugeJump(lk::kJump); }
TEST(LineStreams, RepeatedJumpsRestart) { repeatedJumps(lk::kReinitJumps); }
TEST(LineStreams, FarAwayPoseCannotStart) {
  // Three jumps in a row to a point 10 km away: the restart there fails (out of reach), counted
  // and ERROR; the next good sample starts the run again from statics.
  Stream s;
  for (int i = 0; i < 3; ++i) g_h->send(withPosition(g_h->good(g_h->next()), 0, 1e4));
  const Diag& d = s.after();
  EXPECT_EQ(s.grew(lk::kStartFailed), 1) << s.changes();
  EXPECT_EQ(s.grew(lk::kJump), 2) << s.changes();
  (void)d;
}
TEST(LineStreams, Burst1kHz) { burst(); }
TEST(LineStreams, SilentTopic) { silentTopic(true); }
TEST(LineStreams, WrongFrameId) { wrongFrame(lk::kUnknownFrame); }
TEST(LineStreams, ZeroStamp) { zeroStamp(lk::kZeroStamp); }
TEST(LineStreams, OffPlaneY) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 1, 0.5));  // model: 2d, |y| > 1 mm
  s.after();
  EXPECT_EQ(s.grew(lk::kOffPlane), 1) << s.changes();
}
TEST(LineStreams, AlternatingGoodAndBad) { alternating(lk::kNonFinite); }
TEST(LineStreams, NanosecondStep) { nanosecondStep(); }
TEST(LineStreams, SolveStaticBadValues) {
  Stream s;
  md::SolveStatic nan_req;
  nan_req.request.mode = md::SolveStatic::Request::TOP_POSITION;
  nan_req.request.top_position.x = kNaN;
  ASSERT_TRUE(g_h->call("solve_static", nan_req));
  EXPECT_FALSE(nan_req.response.success);
  EXPECT_NE(nan_req.response.message.find("top_position.x = nan"), std::string::npos) << nan_req.response.message;
  md::SolveStatic neg_force;
  neg_force.request.mode = md::SolveStatic::Request::TOP_FORCE;
  neg_force.request.top_force.z = -kInf;
  ASSERT_TRUE(g_h->call("solve_static", neg_force));
  EXPECT_FALSE(neg_force.response.success);
  EXPECT_NE(neg_force.response.message.find("top_force.z"), std::string::npos) << neg_force.response.message;
  md::SolveStatic mode;
  mode.request.mode = 7;
  ASSERT_TRUE(g_h->call("solve_static", mode));
  EXPECT_FALSE(mode.response.success);
  EXPECT_NE(mode.response.message.find("mode = 7"), std::string::npos) << mode.response.message;
  md::SolveStatic y;
  y.request.mode = md::SolveStatic::Request::TOP_POSITION;
  y.request.top_position.x = g_h->x0_;
  y.request.top_position.y = 5.0;
  ASSERT_TRUE(g_h->call("solve_static", y));
  EXPECT_FALSE(y.response.success);
  EXPECT_NE(y.response.message.find("top_position.y = 5"), std::string::npos) << y.response.message;
  md::SolveStatic far;
  far.request.mode = md::SolveStatic::Request::TOP_POSITION;
  far.request.top_position.x = 1e4;
  far.request.reinitialise = true;
  ASSERT_TRUE(g_h->call("solve_static", far));
  EXPECT_FALSE(far.response.success);
  EXPECT_FALSE(far.response.reinitialised);
  s.after();
  EXPECT_EQ(s.grew(lk::kRequestRejected), 5) << s.changes();
  EXPECT_EQ(s.grew(lk::kReinitRequest), 0) << "a rejected request does not touch the run";
}
TEST(LineStreams, ResetThenContinue) { resetThenContinue(lk::kReinitRequest); }

// ---------------------------------------------------------------------------------------------
// VesselNode (three lines, model: 3d).

TEST(VesselStreams, NanPosition) { nanPosition(vk::kNonFinitePosition); }
TEST(VesselStreams, InfPosition) { infPosition(vk::kNonFinitePosition); }
TEST(VesselStreams, NanQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, kNaN, 1));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonFiniteOrientation), 1) << s.changes();
}
TEST(VesselStreams, InfQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), kInf, 0, 0, 1));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonFiniteOrientation), 1) << s.changes();
}
TEST(VesselStreams, ZeroQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 0));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonUnitOrientation), 1) << s.changes();
}
TEST(VesselStreams, NonUnitQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 1.1));  // norm 1.1
  const auto near = withQuaternion(g_h->good(g_h->next()), 0, 0, 0.0015, 1.0);  // norm off 1 by 1.1e-6
  g_h->send(near);
  EXPECT_TRUE(g_h->waitAnswer(near.header.stamp)) << "accepted (normalized)";
  s.after();
  EXPECT_EQ(s.grew(vk::kNonUnitOrientation), 1) << "within 1e-3 of unit norm is accepted (normalized)";
}
TEST(VesselStreams, BackwardStamp) { backwardStamp(vk::kStampBack); }
TEST(VesselStreams, DuplicateStamp) { duplicateStamp(vk::kSameStamp); }
TEST(VesselStreams, FarFutureStamp) { farFutureStamp(vk::kRestartGap, vk::kRestartLoop); }
TEST(VesselStreams, HugeJump) { hugeJump(vk::kJump); }
TEST(VesselStreams, RepeatedJumpsRestart) { repeatedJumps(vk::kRestartJumps); }
TEST(VesselStreams, FarAwayPoseCannotStart) {
  // Three jumps in a row to a pose 10 km away: the restart there fails (no line reaches), counted;
  // the run goes on from its last good state with the next good sample.
  Stream s;
  for (int i = 0; i < 3; ++i) g_h->send(withPosition(g_h->good(g_h->next()), 0, 1e4));
  s.after();
  EXPECT_EQ(s.grew(vk::kStartFailed), 1) << s.changes();
  EXPECT_EQ(s.grew(vk::kJump), 2) << s.changes();
}
TEST(VesselStreams, Burst1kHz) { burst(); }
TEST(VesselStreams, SilentTopic) { silentTopic(false); }
TEST(VesselStreams, WrongFrameId) { wrongFrame(vk::kUnknownFrame); }
TEST(VesselStreams, ZeroStamp) { zeroStamp(vk::kZeroStamp); }
TEST(VesselStreams, AlternatingGoodAndBad) { alternating(vk::kNonFinitePosition); }
TEST(VesselStreams, NanosecondStep) { nanosecondStep(); }
TEST(VesselStreams, SolveStaticBadValues) {
  Stream s;
  md::VesselStatics nan_pose;
  nan_pose.request.pose.position.x = kNaN;
  nan_pose.request.pose.orientation.w = 1.0;
  ASSERT_TRUE(g_h->call("solve_static", nan_pose));
  EXPECT_FALSE(nan_pose.response.success);
  EXPECT_NE(nan_pose.response.message.find("pose.position"), std::string::npos) << nan_pose.response.message;
  md::VesselStatics q;
  q.request.pose.orientation.w = 2.0;
  ASSERT_TRUE(g_h->call("solve_static", q));
  EXPECT_FALSE(q.response.success);
  EXPECT_NE(q.response.message.find("orientation"), std::string::npos) << q.response.message;
  md::VesselStatics dof;
  dof.request.use_file_pose = true;
  dof.request.offset_dof = "sideways";
  dof.request.offset_range = 5.0;
  dof.request.offset_steps = 3;
  ASSERT_TRUE(g_h->call("solve_static", dof));
  EXPECT_FALSE(dof.response.success);
  EXPECT_NE(dof.response.message.find("sideways"), std::string::npos) << dof.response.message;
  md::VesselStatics range;
  range.request.use_file_pose = true;
  range.request.offset_dof = "surge";
  range.request.offset_range = -5.0;
  range.request.offset_steps = 3;
  ASSERT_TRUE(g_h->call("solve_static", range));
  EXPECT_FALSE(range.response.success);
  EXPECT_NE(range.response.message.find("offset_range"), std::string::npos) << range.response.message;
  md::VesselStatics steps;
  steps.request.use_file_pose = true;
  steps.request.offset_dof = "yaw";
  steps.request.offset_range = 5.0;
  steps.request.offset_steps = 0;
  ASSERT_TRUE(g_h->call("solve_static", steps));
  EXPECT_FALSE(steps.response.success);
  EXPECT_NE(steps.response.message.find("offset_steps"), std::string::npos) << steps.response.message;
  s.after();
  EXPECT_EQ(s.grew(vk::kRequestRejected), 5) << s.changes();
}
TEST(VesselStreams, ResetThenContinue) { resetThenContinue(vk::kRestartReset); }

int main(int argc, char** argv) { return harnessMain(argc, argv, "test_bad_streams"); }
