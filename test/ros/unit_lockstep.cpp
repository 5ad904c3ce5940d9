// Unit tests of the ROS-free lockstep policy (LockstepDriver) and health summary
// (LockstepMonitor), no master needed. Problem: test/data/small_catenary.yaml (150 m of chain,
// anchor (0, -100) m, static top (100, 0) m, 76 nodes), dt = 0.1 s.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/nodes/lockstep.hpp"
#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"

using namespace mooring_dynamics;
using ros_bridge::LockstepDriver;
using ros_bridge::LockstepMonitor;
using O = LockstepDriver::Outcome;

namespace {

constexpr double kDt = 0.1;       // [s] base step
constexpr double kTopX = 100.0;   // [m] static top of the test problem
constexpr double kTopZ = 0.0;
// Statics re-solved at the same top converge to the same shape: 1e-6 relative is far above the
// solver tolerance (1e-9 on sigma) and far below any physical change tested here.
constexpr double kSameStatics = 1e-6;

core::Problem problem() { return core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/test/data/small_catenary.yaml"); }

}  // namespace

TEST(LockstepDriver, StartAdvanceAndGap) {
  ros_bridge::LockstepOptions o;
  o.max_gap = 2.0;
  LockstepDriver d(problem(), kDt, o);
  EXPECT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).outcome, O::Started);
  const auto a = d.onSample(0.1, kTopX, 0.0, kTopZ + 0.01);
  EXPECT_EQ(a.outcome, O::Advanced);
  EXPECT_NEAR(a.advanced, 0.1, 1e-12);
  EXPECT_GE(a.report.steps, 1);
  // 2.5 s later (> max_gap): re-initialised from statics at the new sample.
  const auto g = d.onSample(2.6, kTopX, 0.0, kTopZ);
  EXPECT_EQ(g.outcome, O::Reinitialised);
  EXPECT_TRUE(g.publish);
  EXPECT_NE(g.message.find("gap of 2.5 s"), std::string::npos) << g.message;
  EXPECT_DOUBLE_EQ(d.solverTime(), 0.0);
  // 1.9 s later (< max_gap): advanced over the gap.
  EXPECT_EQ(d.onSample(4.5, kTopX, 0.0, kTopZ).outcome, O::Advanced);
  EXPECT_NEAR(d.solverTime(), 1.9, 1e-9);
}

TEST(LockstepDriver, JumpDroppedThenReinitialised) {
  LockstepDriver d(problem(), kDt);  // max_speed 50 m/s, 3 jumps re-initialise
  d.onSample(0.0, kTopX, 0.0, kTopZ);
  d.onSample(0.1, kTopX, 0.0, kTopZ);
  // 20 m in 0.1 s = 200 m/s: dropped.
  auto j = d.onSample(0.2, kTopX - 20.0, 0.0, kTopZ);
  EXPECT_EQ(j.outcome, O::Dropped);
  EXPECT_FALSE(j.publish);
  EXPECT_NE(j.message.find("max_speed = 50 m/s"), std::string::npos) << j.message;
  // A good sample resets the count.
  EXPECT_EQ(d.onSample(0.3, kTopX, 0.0, kTopZ).outcome, O::Advanced);
  EXPECT_EQ(d.onSample(0.4, kTopX - 20.0, 0.0, kTopZ).outcome, O::Dropped);
  EXPECT_EQ(d.onSample(0.5, kTopX - 20.0, 0.0, kTopZ).outcome, O::Dropped);
  const auto r = d.onSample(0.6, kTopX - 20.0, 0.0, kTopZ);
  EXPECT_EQ(r.outcome, O::Reinitialised) << r.message;
  EXPECT_NEAR(d.state().nodes.back().x, kTopX - 20.0, 1e-6);
}

TEST(LockstepDriver, ResetAndReinitialiseAt) {
  LockstepDriver d(problem(), kDt);
  EXPECT_EQ(d.reset().outcome, O::Dropped) << "nothing to reset before the first sample";
  d.onSample(0.0, kTopX, 0.0, kTopZ);
  for (int k = 1; k <= 5; ++k) d.onSample(0.1 * k, kTopX - 0.1 * k, 0.0, kTopZ);
  const auto r = d.reset();
  EXPECT_EQ(r.outcome, O::Reinitialised);
  ASSERT_TRUE(r.publish);
  EXPECT_DOUBLE_EQ(d.solverTime(), 0.0);
  EXPECT_NEAR(d.state().nodes.back().x, kTopX - 0.5, 1e-9);
  // Equal to a static solve at that top.
  core::Problem p = problem();
  p.top.type = core::TopBoundary::Type::Position;
  p.top.x = kTopX - 0.5;
  p.top.z = kTopZ;
  LockstepDriver fresh(p, kDt);
  const double t_ref = fresh.onSample(0.0, kTopX - 0.5, 0.0, kTopZ).publish ? fresh.state().nodes.back().tension : 0.0;
  EXPECT_NEAR(d.state().nodes.back().tension, t_ref, kSameStatics * t_ref);
  // The next sample advances from the reset state at the old time base.
  EXPECT_EQ(d.onSample(0.6, kTopX - 0.5, 0.0, kTopZ).outcome, O::Advanced);
  EXPECT_NEAR(d.solverTime(), 0.1, 1e-9);

  // Out of reach (the line reaches 180 m): refused, the run goes on.
  const auto far = d.reinitialiseAt(400.0, 0.0, 0.0, "test");
  EXPECT_FALSE(far.publish);
  EXPECT_TRUE(d.started());
  EXPECT_NE(far.message.find("the run goes on unchanged"), std::string::npos) << far.message;
  EXPECT_EQ(d.onSample(0.7, kTopX - 0.5, 0.0, kTopZ).outcome, O::Advanced);
  const auto near = d.reinitialiseAt(kTopX - 1.0, 0.0, kTopZ, "test");
  EXPECT_TRUE(near.publish);
  EXPECT_NEAR(d.state().nodes.back().x, kTopX - 1.0, 1e-9);
}

TEST(LockstepDriver, BadSamples) {
  LockstepDriver d(problem(), kDt);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(d.onSample(0.0, nan, 0.0, 0.0).outcome, O::Dropped);
  EXPECT_FALSE(d.started());
  // Out of reach at the start: statics fail, start_failed, still not started.
  const auto s = d.onSample(0.0, 400.0, 0.0, 0.0);
  EXPECT_EQ(s.outcome, O::Dropped);
  EXPECT_TRUE(s.start_failed);
  EXPECT_FALSE(d.started());
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).outcome, O::Started);
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).outcome, O::Dropped);   // same stamp
  EXPECT_EQ(d.onSample(-0.5, kTopX, 0.0, kTopZ).outcome, O::Dropped);  // back by 0.6 s
  EXPECT_EQ(d.onSample(-1.5, kTopX, 0.0, kTopZ).outcome, O::Reinitialised);  // back by 1.6 s: bag loop
}

namespace {

/// The real 2-D solver behind a switch: while `fail_from` is set, advanceTo goes only halfway
/// (the last converged step of a failing advance) and reports a failure, as the core does when a
/// step fails at its smallest cut (it keeps the last converged step).
struct FailSwitch {
  bool on = false;
};
class HalfwayFailingSolver final : public ros_bridge::LockstepSolver {
 public:
  HalfwayFailingSolver(std::unique_ptr<ros_bridge::LockstepSolver> s, std::shared_ptr<FailSwitch> sw)
      : s_(std::move(s)), sw_(std::move(sw)) {}
  const core::StaticResult& initialStatic() const override { return s_->initialStatic(); }
  void setTopSegment(double t0, double x0, double y0, double z0, double t1, double x1, double y1, double z1) override {
    s_->setTopSegment(t0, x0, y0, z0, t1, x1, y1, z1);
  }
  core::StepReport advanceTo(double t) override {
    if (!sw_->on) return s_->advanceTo(t);
    const double half = s_->time() + 0.5 * (t - s_->time());
    core::StepReport r = s_->advanceTo(half);
    r.ok = false;
    r.message = "t = " + std::to_string(t) + " s: forced failure (test)";
    return r;
  }
  core::StaticResult snapshot() const override { return s_->snapshot(); }
  double time() const override { return s_->time(); }

 private:
  std::unique_ptr<ros_bridge::LockstepSolver> s_;
  std::shared_ptr<FailSwitch> sw_;
};

ros_bridge::LockstepSolverFactory failingFactory(std::shared_ptr<FailSwitch> sw) {
  return [sw](const core::Problem& p) -> std::unique_ptr<ros_bridge::LockstepSolver> {
    return std::make_unique<HalfwayFailingSolver>(ros_bridge::makeSolver2D()(p), sw);
  };
}

}  // namespace

// A failing sample keeps the last good state (the solver's last converged step, halfway here),
// publishes it with converged false, and the next sample continues from it: the top moves on
// from where the failed segment had it at that step.
TEST(LockstepDriver, FailureKeepsTheLastGoodStateAndContinues) {
  auto sw = std::make_shared<FailSwitch>();
  ros_bridge::LockstepOptions o;
  LockstepDriver d(problem(), kDt, o, failingFactory(sw));
  ASSERT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).outcome, O::Started);
  ASSERT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ + 0.1).outcome, O::Advanced);
  sw->on = true;
  const auto f = d.onSample(0.3, kTopX, 0.0, kTopZ + 0.3);
  EXPECT_EQ(f.outcome, O::Failed);
  EXPECT_EQ(f.reason, LockstepDriver::Reason::SolverFailed);
  EXPECT_TRUE(f.publish);
  EXPECT_FALSE(f.report.ok);
  EXPECT_NE(f.message.find("forced failure"), std::string::npos) << f.message;
  EXPECT_NE(f.message.find("last good state"), std::string::npos) << f.message;
  EXPECT_FALSE(d.state().summary.converged);
  // The kept state is the solver's at its last converged time 0.2 s (halfway through 0.1 -> 0.3):
  // the same bits as the solver run without the driver on the same segments to 0.2 s.
  EXPECT_NEAR(d.solverTime(), 0.2, 1e-12);
  {
    auto ref = ros_bridge::makeSolver2D()(d.problem());
    const double x0 = ref->initialStatic().nodes.back().x, z0 = ref->initialStatic().nodes.back().z;
    ref->setTopSegment(0.0, x0, 0.0, z0, 0.1, kTopX, 0.0, kTopZ + 0.1);
    ASSERT_TRUE(ref->advanceTo(0.1).ok);
    ref->setTopSegment(0.1, kTopX, 0.0, kTopZ + 0.1, 0.3, kTopX, 0.0, kTopZ + 0.3);
    ASSERT_TRUE(ref->advanceTo(0.2).ok);
    const core::StaticResult want = ref->snapshot();
    ASSERT_EQ(want.nodes.size(), d.state().nodes.size());
    for (std::size_t j = 0; j < want.nodes.size(); ++j) {
      ASSERT_EQ(d.state().nodes[j].z, want.nodes[j].z) << j;
      ASSERT_EQ(d.state().nodes[j].tension, want.nodes[j].tension) << j;
    }
  }
  for (const auto& n : d.state().nodes) ASSERT_TRUE(std::isfinite(n.tension) && std::isfinite(n.x) && std::isfinite(n.z));
  sw->on = false;
  const auto a = d.onSample(0.4, kTopX, 0.0, kTopZ + 0.4);
  EXPECT_EQ(a.outcome, O::Advanced) << a.message;
  EXPECT_NEAR(a.advanced, 0.2, 1e-12) << "from the last good state at 0.2 s to 0.4 s";
  EXPECT_TRUE(d.state().summary.converged);
  EXPECT_NEAR(d.solverTime(), 0.4, 1e-12);
}

// failures_to_reinit failures in a row: statics re-solved at the sample (RecoveredFailure); a
// success in between resets the count.
TEST(LockstepDriver, RepeatedFailuresReinitialise) {
  auto sw = std::make_shared<FailSwitch>();
  ros_bridge::LockstepOptions o;
  o.failures_to_reinit = 3;
  LockstepDriver d(problem(), kDt, o, failingFactory(sw));
  ASSERT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).outcome, O::Started);
  sw->on = true;
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).outcome, O::Failed);
  EXPECT_EQ(d.onSample(0.2, kTopX, 0.0, kTopZ).outcome, O::Failed);
  sw->on = false;
  EXPECT_EQ(d.onSample(0.3, kTopX, 0.0, kTopZ).outcome, O::Advanced);
  sw->on = true;
  EXPECT_EQ(d.onSample(0.4, kTopX, 0.0, kTopZ).outcome, O::Failed);
  EXPECT_EQ(d.onSample(0.5, kTopX, 0.0, kTopZ).outcome, O::Failed);
  const auto r = d.onSample(0.6, kTopX + 0.5, 0.0, kTopZ);
  EXPECT_EQ(r.outcome, O::RecoveredFailure) << r.message;
  EXPECT_TRUE(r.publish);
  EXPECT_NEAR(d.state().nodes.back().x, kTopX + 0.5, 1e-9) << "statics re-solved with the top at the sample";
  EXPECT_TRUE(d.state().summary.converged);
  EXPECT_NEAR(d.solverTime(), 0.0, 1e-12);
}

TEST(LockstepDriver, ReasonsOfDropsAndReinitialisations) {
  using R = LockstepDriver::Reason;
  ros_bridge::LockstepOptions o;
  o.max_gap = 2.0;
  LockstepDriver d(problem(), kDt, o);
  EXPECT_EQ(d.onSample(0.0, kTopX, 0.0, kTopZ).reason, R::None);
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).reason, R::None);
  EXPECT_EQ(d.onSample(0.1, kTopX, 0.0, kTopZ).reason, R::SameStamp);
  EXPECT_EQ(d.onSample(0.05, kTopX, 0.0, kTopZ).reason, R::StampBack);
  EXPECT_EQ(d.onSample(0.2, std::nan(""), 0.0, kTopZ).reason, R::NonFinite);
  EXPECT_EQ(d.onSample(0.2, kTopX, 0.5, kTopZ).reason, R::OffPlane);
  EXPECT_EQ(d.onSample(0.2, kTopX + 50.0, 0.0, kTopZ).reason, R::Jump);
  const auto gap = d.onSample(1e6, kTopX, 0.0, kTopZ);  // a stamp far in the future: a gap
  EXPECT_EQ(gap.outcome, O::Reinitialised);
  EXPECT_EQ(gap.reason, R::Gap);
  const auto back = d.onSample(0.3, kTopX, 0.0, kTopZ);  // and back again: a bag loop
  EXPECT_EQ(back.outcome, O::Reinitialised);
  EXPECT_EQ(back.reason, R::LoopBack);
  EXPECT_EQ(d.reset().reason, R::Request);
  const auto far = d.onSample(0.4, 1e4, 0.0, 0.0);  // out of reach, three times: the restart fails
  EXPECT_EQ(far.reason, R::Jump);
  d.onSample(0.5, 1e4, 0.0, 0.0);
  const auto third = d.onSample(0.6, 1e4, 0.0, 0.0);
  EXPECT_EQ(third.reason, R::StartFailed);
  EXPECT_TRUE(third.start_failed);
}

TEST(LockstepMonitor, FailureNamesTheLineAndCountsByReason) {
  ros_bridge::MonitorOptions mo;
  mo.motion_timeout = 100.0;
  mo.line_name = "tether";
  LockstepMonitor m(mo, 0.0);
  auto sw = std::make_shared<FailSwitch>();
  LockstepDriver d(problem(), kDt, ros_bridge::LockstepOptions(), failingFactory(sw));
  m.onResult(d.onSample(0.0, kTopX, 0.0, kTopZ), 0.1, 0.0, &d.state(), d.solverTime());
  m.onResult(d.onSample(0.0, kTopX, 0.0, kTopZ), 0.1, 0.0, nullptr, d.solverTime());  // same stamp
  m.onInputRejected(0.1, "header.stamp = 0", ros_bridge::lockstep_keys::kZeroStamp);
  m.onInputNote(0.1, "pose.orientation: norm 0 (unused)", ros_bridge::lockstep_keys::kOrientationNonUnit, false);
  m.onRequestRejected(0.1, "~solve_static: invalid request: top_position.x = nan: must be finite");
  sw->on = true;
  const auto f = d.onSample(0.1, kTopX, 0.0, kTopZ);
  m.onResult(f, 0.2, 0.0, &d.state(), d.solverTime());
  const auto s = m.summarise(0.3);
  EXPECT_EQ(s.level, LockstepMonitor::ERROR);
  EXPECT_EQ(s.message.find("1 solver failure(s) on line tether"), 0u) << s.message;
  EXPECT_NE(s.message.find("last good state"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("service request"), std::string::npos) << s.message;
  auto value = [&s](const std::string& k) {
    for (const auto& kv : s.values)
      if (kv.first == k) return kv.second;
    return std::string("missing");
  };
  EXPECT_EQ(value("dropped: same stamp (window / total)"), "1 / 1");
  EXPECT_EQ(value("dropped: zero stamp (window / total)"), "1 / 1");
  EXPECT_EQ(value("accepted: non-unit orientation (unused)" + std::string(" (window / total)")), "1 / 1");
  EXPECT_EQ(value("service requests rejected (window / total)"), "1 / 1");
  EXPECT_EQ(value("solver failed: last good state kept (window / total)"), "1 / 1");
  EXPECT_EQ(value("dropped: jump (window / total)"), "0 / 0");
  EXPECT_EQ(value("solver failures (window / total)"), "1 / 1");
  EXPECT_NE(value("last error").find("line tether"), std::string::npos) << value("last error");
}

TEST(LockstepMonitor, Levels) {
  ros_bridge::MonitorOptions mo;
  mo.motion_timeout = 1.0;
  LockstepMonitor m(mo, 0.0);
  auto s = m.summarise(0.5);
  EXPECT_EQ(s.level, LockstepMonitor::OK) << s.message;
  s = m.summarise(2.0);
  EXPECT_EQ(s.level, LockstepMonitor::WARN);
  EXPECT_NE(s.message.find("waiting for motion"), std::string::npos) << s.message;

  LockstepDriver d(problem(), kDt);
  m.onMotionReceived(2.1);
  auto r = d.onSample(0.0, kTopX, 0.0, kTopZ);
  m.onResult(r, 2.1, 0.0, &d.state(), d.solverTime());
  m.onMotionReceived(2.2);
  r = d.onSample(0.1, kTopX, 0.0, kTopZ);
  m.onResult(r, 2.2, 0.01, &d.state(), d.solverTime());  // 0.1 s simulated in 0.01 s: RTF 10
  s = m.summarise(2.3);
  EXPECT_EQ(s.level, LockstepMonitor::OK) << s.message;
  EXPECT_NE(s.message.find("real-time factor 10"), std::string::npos) << s.message;

  // Slow: 0.1 s simulated in 0.2 s -> RTF 0.5 < 1: WARN.
  m.onMotionReceived(2.4);
  r = d.onSample(0.2, kTopX, 0.0, kTopZ);
  m.onResult(r, 2.4, 0.2, &d.state(), d.solverTime());
  s = m.summarise(2.5);
  EXPECT_EQ(s.level, LockstepMonitor::WARN);
  EXPECT_NE(s.message.find("real-time factor 0.50 < 1"), std::string::npos) << s.message;

  // Silent for 3 s after motion: WARN naming the silence.
  s = m.summarise(5.5);
  EXPECT_EQ(s.level, LockstepMonitor::WARN);
  EXPECT_NE(s.message.find("no motion for 3.1 s"), std::string::npos) << s.message;

  // A rejected input and a solver failure in one window: ERROR first, then the warning.
  m.onMotionReceived(5.6);
  m.onInputRejected(5.6, "header.frame_id = \"nowhere\": no transform");
  LockstepDriver::Result fail;
  fail.outcome = O::RecoveredFailure;
  fail.publish = false;
  fail.message = "dynamic solver failed: t = 1 s";
  m.onResult(fail, 5.6, 0.01, nullptr, 0.0);
  s = m.summarise(5.7);
  EXPECT_EQ(s.level, LockstepMonitor::ERROR);
  EXPECT_EQ(s.message.find("1 solver failure"), 0u) << s.message;
  EXPECT_NE(s.message.find("nowhere"), std::string::npos) << s.message;
  bool last_error = false;
  for (const auto& kv : s.values)
    if (kv.first == "last error") last_error = kv.second.find("solver failed") != std::string::npos;
  EXPECT_TRUE(last_error);
}

TEST(LockstepMonitor, SlackEvents) {
  LockstepMonitor m;
  core::StaticResult st;
  st.nodes.resize(3);
  LockstepDriver::Result r;
  r.outcome = O::Advanced;
  r.publish = true;
  const double tensions[] = {100.0, -5.0, -1.0, 50.0, 0.0};  // slack, stays slack, taut, slack: 2 events
  for (double t : tensions) {
    for (auto& n : st.nodes) n.tension = 200.0;
    st.nodes[1].tension = t;
    m.onResult(r, 0.0, 0.0, &st, 0.0);
  }
  EXPECT_EQ(m.slackEvents(), 2);
  const auto s = m.summarise(0.1);
  EXPECT_EQ(s.level, LockstepMonitor::WARN);
  EXPECT_NE(s.message.find("line slack (min tension 0.0 N)"), std::string::npos) << s.message;
  for (const auto& kv : s.values)
    if (kv.first == "slack events (total)") {
      EXPECT_EQ(kv.second, "2");
    }
}

TEST(LockstepMonitor, UtilizationAboveTheLimitWarns) {
  // Segment 0 with MBL 1000 N, segment 1 without: utilization is the largest T / MBL over the
  // nodes of segment 0 (by hand: 700 / 1000), whatever the larger tension in segment 1.
  ros_bridge::MonitorOptions mo;
  mo.max_utilization = 0.6;
  mo.segment_mbl = {1000.0, 0.0};
  LockstepMonitor m(mo, 0.0);
  core::StaticResult st;
  st.nodes.resize(4);
  const double T[] = {700.0, 500.0, 900.0, 800.0};
  for (int i = 0; i < 4; ++i) {
    st.nodes[i].tension = T[i];
    st.nodes[i].segment = i < 2 ? 0 : 1;
  }
  LockstepDriver::Result r;
  r.outcome = O::Advanced;
  r.publish = true;
  m.onMotionReceived(0.0);
  m.onResult(r, 0.0, 0.0, &st, 0.0);
  auto s = m.summarise(0.1);
  EXPECT_EQ(s.level, LockstepMonitor::WARN);
  EXPECT_NE(s.message.find("utilization 0.700 > 0.6 (max tension 900.0 N)"), std::string::npos) << s.message;
  std::string now, peak;
  for (const auto& kv : s.values) {
    if (kv.first == "utilization (T / MBL)") now = kv.second;
    if (kv.first == "utilization (max, total)") peak = kv.second;
  }
  EXPECT_EQ(now, "0.7");
  EXPECT_EQ(peak, "0.7");
  // Below the limit: no warning from it, the run's peak kept.
  st.nodes[0].tension = 300.0;
  m.onMotionReceived(0.1);
  m.onResult(r, 0.1, 0.0, &st, 0.0);
  s = m.summarise(0.2);
  EXPECT_EQ(s.message.find("utilization"), std::string::npos) << s.message;
  for (const auto& kv : s.values) {
    if (kv.first == "utilization (max, total)") {
      EXPECT_EQ(kv.second, "0.7");
    }
  }
}

TEST(Markers, BodiesOfSTether) {
  const core::Problem p = core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/config/s_tether.yaml");
  const auto b = ros_bridge::bodyMarks(p);
  ASSERT_EQ(b.size(), 1u + 3u + 5u + 17u);
  EXPECT_EQ(b[0].name, "auv_dock");
  EXPECT_NEAR(b[0].s, 35.0, 1e-12);
  EXPECT_EQ(b[1].name, "float_large_0");
  EXPECT_TRUE(b[1].buoyant);
  EXPECT_FALSE(b[0].buoyant);
}
