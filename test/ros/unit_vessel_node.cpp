// Unit tests without a master for the moored-vessel node's pieces: the converter (poses, wrenches,
// VesselStatics requests and responses) and VesselMonitor (counts, levels, the failed line named,
// utilization).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/utilization.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace core = mooring_dynamics::core;
namespace rb = mooring_dynamics::ros_bridge;
using mooring_dynamics::VesselStatics;

namespace {

const std::string kProblem = std::string(MD_SOURCE_DIR) + "/test/data/small_vessel.yaml";

std::string valueOf(const rb::VesselMonitor::Status& s, const std::string& key) {
  for (const auto& kv : s.values)
    if (kv.first == key) return kv.second;
  return "<missing>";
}

}  // namespace

TEST(VesselConverter, PoseRoundTripKeepsTheNumbers) {
  geometry_msgs::Pose m;
  m.position.x = 1.25;
  m.position.y = -2.5;
  m.position.z = 0.125;
  m.orientation.z = std::sin(0.1);
  m.orientation.w = std::cos(0.1);
  const core::RigidPose p = rb::toRigidPose(m);
  EXPECT_EQ(p.position.x(), 1.25);
  EXPECT_EQ(p.orientation.z(), std::sin(0.1));
  EXPECT_EQ(p.orientation.w(), std::cos(0.1));
  const geometry_msgs::Pose back = rb::toPoseMsg(p);
  EXPECT_EQ(back.position.y, -2.5);
  EXPECT_EQ(back.orientation.z, m.orientation.z);
  // Not normalized here: a non-unit quaternion reaches VesselLockstep, which rejects it.
  m.orientation.w = 2.0;
  EXPECT_FALSE(rb::toRigidPose(m).validate("pose").empty());
}

TEST(VesselConverter, WrenchesAndFairleadShares) {
  const core::SystemProblem s = core::loadSystemFromFile(kProblem);
  const core::RigidPose pose = core::RigidPose::fromRollPitchYaw(Eigen::Vector3d(1.0, 0.5, 0.0), 0.0, 0.0, 0.05);
  const core::VesselStaticResult r = core::solveVesselStatic(s, pose);
  ASSERT_TRUE(r.system.summary.converged) << r.system.summary.message;
  const ros::Time stamp(12.5);
  const geometry_msgs::WrenchStamped b = rb::toBodyWrench(r.wrench, "base_link", stamp);
  EXPECT_EQ(b.header.frame_id, "base_link");
  EXPECT_EQ(b.header.stamp, stamp);
  EXPECT_EQ(b.wrench.force.x, r.wrench.force_body.x());
  EXPECT_EQ(b.wrench.torque.z, r.wrench.moment_body.z());
  const geometry_msgs::WrenchStamped w = rb::toWorldWrench(r.wrench, "world", stamp);
  EXPECT_EQ(w.wrench.force.y, r.wrench.force_world.y());
  ASSERT_EQ(r.wrench.fairleads.size(), 3u);
  double f[3] = {0, 0, 0}, m[3] = {0, 0, 0};
  for (const core::FairleadForce& ff : r.wrench.fairleads) {
    const geometry_msgs::WrenchStamped fw = rb::toFairleadWrench(ff, r.pose, "world", stamp);
    f[0] += fw.wrench.force.x;
    f[1] += fw.wrench.force.y;
    f[2] += fw.wrench.force.z;
    m[0] += fw.wrench.torque.x;
    m[1] += fw.wrench.torque.y;
    m[2] += fw.wrench.torque.z;
    const geometry_msgs::TransformStamped t = rb::fairleadTransform(ff, r.pose, "world", "fl", stamp);
    EXPECT_EQ(t.transform.translation.x, ff.position.x());
    EXPECT_EQ(t.child_frame_id, "fl");
  }
  const double scale = r.wrench.force_world.norm() + 1.0, mscale = r.wrench.moment_world.norm() + 1.0;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f[i], r.wrench.force_world[i], 1e-9 * scale);
    EXPECT_NEAR(m[i], r.wrench.moment_world[i], 1e-9 * mscale);
  }
}

TEST(VesselConverter, StaticsRequestNamesTheField) {
  const core::RigidPose file_pose;
  VesselStatics::Request q;
  q.pose.orientation.w = 1.0;
  EXPECT_TRUE(rb::vesselStaticsFromRequest(q, file_pose).ok);

  VesselStatics::Request nan_pos = q;
  nan_pos.pose.position.y = std::nan("");
  rb::VesselStaticsRequest r = rb::vesselStaticsFromRequest(nan_pos, file_pose);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("pose.position"), std::string::npos) << r.error;

  VesselStatics::Request bad_q = q;
  bad_q.pose.orientation.w = 0.5;
  r = rb::vesselStaticsFromRequest(bad_q, file_pose);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("pose.orientation"), std::string::npos) << r.error;
  bad_q.use_file_pose = true;  // the request's pose is then ignored
  EXPECT_TRUE(rb::vesselStaticsFromRequest(bad_q, file_pose).ok);

  VesselStatics::Request dof = q;
  dof.offset_dof = "sideways";
  r = rb::vesselStaticsFromRequest(dof, file_pose);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("offset_dof = \"sideways\""), std::string::npos) << r.error;
  dof.offset_dof = "yaw";
  dof.offset_range = 95.0;
  dof.offset_steps = 5;
  r = rb::vesselStaticsFromRequest(dof, file_pose);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("offset_range = 95"), std::string::npos) << r.error;
  dof.offset_range = 10.0;
  dof.offset_steps = 1;
  r = rb::vesselStaticsFromRequest(dof, file_pose);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("offset_steps = 1"), std::string::npos) << r.error;
  dof.offset_steps = 5;
  r = rb::vesselStaticsFromRequest(dof, file_pose);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.angular);
  ASSERT_EQ(r.offsets.size(), 5u);
  EXPECT_NEAR(r.offsets.front(), -10.0 * M_PI / 180.0, 1e-15);
  EXPECT_NEAR(r.offsets[2], 0.0, 1e-15);
}

TEST(VesselConverter, StaticsResponse) {
  const core::SystemProblem s = core::loadSystemFromFile(kProblem);
  VesselStatics::Request q;
  q.use_file_pose = true;
  q.want_stiffness = true;
  const rb::VesselStaticsRequest r = rb::vesselStaticsFromRequest(q, s.vessel.pose);
  ASSERT_TRUE(r.ok);
  const core::StiffnessResult k = core::mooringStiffness(s, r.pose);
  VesselStatics::Response res;
  rb::toVesselStaticsResponse(s, k.at, &k, nullptr, r, res);
  EXPECT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.stiffness[6 * 5 + 5], k.K(5, 5));
  EXPECT_EQ(res.stiffness[6 * 0 + 1], k.K(0, 1));  // row-major
  EXPECT_EQ(res.stiffness[6 * 1 + 0], k.K(1, 0));
  EXPECT_EQ(res.line_names.size(), 3u);
  EXPECT_TRUE(res.offsets.empty());
}

TEST(VesselMonitor, CountsDropsAndNamesTheFailedLine) {
  rb::VesselMonitorOptions o;
  o.motion_timeout = 100.0;
  rb::VesselMonitor m({"a", "a_2", "b"}, o, 0.0);
  using O = core::VesselLockstep::Outcome;
  core::VesselLockstep::Result started;
  started.outcome = O::Started;
  started.publish = true;
  const std::vector<double> top{1.0, 2.0, 3.0};
  m.onMotionReceived(0.1);
  m.onResult(started, 0.1, 0.01, 0.0, &top, 0.0);
  core::VesselLockstep::Result dropped;
  dropped.message = "pose.orientation = (x 0, y 0, z 0, w 1.1): norm 1.1, must be 1 within 0.001";
  m.onMotionReceived(0.2);
  m.onResult(dropped, 0.2, 0.0, 0.0, nullptr, 0.0);
  core::VesselLockstep::Result adv;
  adv.outcome = O::Advanced;
  adv.publish = true;
  m.onMotionReceived(0.3);
  m.onResult(adv, 0.3, 0.01, 0.1, &top, 0.1);
  std::vector<rb::VesselMonitor::Status> s = m.summarise(0.4);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::WARN);
  EXPECT_EQ(valueOf(s[0], "samples dropped"), "1");
  EXPECT_NE(s[0].message.find("norm 1.1"), std::string::npos) << s[0].message;
  EXPECT_EQ(s[2].line, "a_2");
  EXPECT_EQ(valueOf(s[2], "top tension [N]"), "2");
  EXPECT_EQ(s[3].level, rb::VesselMonitor::OK);
  EXPECT_EQ(valueOf(s[0], "fallback steps (total)"), "none");

  // Fallback steps (docs/method.md "Slack and snap"): a value per line and named in the overall
  // status, not a warning (a storm's slack-and-snap steps are expected).
  m.onFallbackSteps({0, 3, 1});
  s = m.summarise(0.45);
  EXPECT_EQ(valueOf(s[0], "fallback steps (total)"), "fallback steps: 3 on a_2, 1 on b");
  EXPECT_EQ(valueOf(s[2], "fallback steps (total)"), "3");
  EXPECT_EQ(valueOf(s[1], "fallback steps (total)"), "0");
  EXPECT_EQ(s[2].level, rb::VesselMonitor::OK);

  EXPECT_EQ(m.failedLine("restarted from statics after a failure: t = 1.2 s: line a_2: step failed"), 1);
  EXPECT_EQ(m.failedLine("no line here"), -1);
  core::VesselLockstep::Result fail;
  fail.outcome = O::RecoveredFailure;
  fail.publish = true;
  fail.message = "restarted from statics after a failure: t = 1.2 s: line b: smallest step cut failed";
  m.onMotionReceived(0.5);
  m.onResult(fail, 0.5, 0.01, 0.0, &top, 0.0);
  s = m.summarise(0.6);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::ERROR);
  EXPECT_EQ(s[3].level, rb::VesselMonitor::ERROR);
  EXPECT_EQ(valueOf(s[3], "converged"), "false");
  EXPECT_EQ(s[1].level, rb::VesselMonitor::OK);
  EXPECT_NE(m.lastEvent().find("line b failed"), std::string::npos) << m.lastEvent();
  EXPECT_NE(m.lastEvent().find("restarted from statics"), std::string::npos);
  // The next window: the line is fine again, the totals remember.
  s = m.summarise(0.7);
  EXPECT_EQ(s[3].level, rb::VesselMonitor::OK);
  EXPECT_EQ(valueOf(s[3], "failures (window / total)"), "0 / 1");
  EXPECT_EQ(valueOf(s[0], "samples dropped"), "1");
}

// Utilization as the line node's monitor: the largest T / MBL over each line's nodes whose
// material has an MBL, WARN above max_utilization for that line and, naming it, for the run.
// Hand sums: line a has 700 N in chain (MBL 1000 N) and 900 N in rope (no MBL): utilization 0.7
// (not at the largest tension); line b 500 N in chain: 0.5; line c only rope: none.
TEST(VesselMonitor, UtilizationAboveTheLimitWarnsAndNamesTheLine) {
  std::vector<core::Material> mats(2);
  mats[0].name = "chain";
  mats[0].mbl = 1000.0;
  mats[1].name = "rope";
  std::vector<core::Segment> segs(2);
  segs[0].material = 0;
  segs[1].material = 1;
  auto node = [](int seg, double T) {
    core::NodeState n;
    n.segment = seg;
    n.tension = T;
    return n;
  };
  const std::vector<core::TensionPeak> peaks{
      core::tensionPeak(mats, segs, {node(0, 600.0), node(0, 700.0), node(1, 900.0)}),
      core::tensionPeak(mats, segs, {node(0, 500.0), node(1, 400.0)}),
      core::tensionPeak(mats, {segs[1]}, {node(0, 2000.0)})};
  rb::VesselMonitorOptions o;
  o.motion_timeout = 100.0;
  o.max_utilization = 0.6;
  rb::VesselMonitor m({"a", "b", "c"}, o, 0.0);
  core::VesselLockstep::Result adv;
  adv.outcome = core::VesselLockstep::Outcome::Advanced;
  adv.publish = true;
  const std::vector<double> top{900.0, 500.0, 2000.0};
  m.onMotionReceived(0.1);
  m.onResult(adv, 0.1, 0.01, 0.1, &top, 0.1, &peaks);
  std::vector<rb::VesselMonitor::Status> s = m.summarise(0.2);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::WARN);
  EXPECT_NE(s[0].message.find("line a utilization 0.700 > 0.6 (max tension 900.0 N)"), std::string::npos)
      << s[0].message;
  EXPECT_EQ(s[0].message.find("line b"), std::string::npos) << s[0].message;
  EXPECT_EQ(s[1].level, rb::VesselMonitor::WARN);
  EXPECT_NE(s[1].message.find("utilization 0.700 > 0.6"), std::string::npos) << s[1].message;
  EXPECT_EQ(valueOf(s[1], "utilization (T / MBL)"), "0.7");
  EXPECT_EQ(valueOf(s[1], "max tension [N]"), "900");
  EXPECT_EQ(s[2].level, rb::VesselMonitor::OK);
  EXPECT_EQ(valueOf(s[2], "utilization (T / MBL)"), "0.5");
  EXPECT_EQ(s[3].level, rb::VesselMonitor::OK);  // no MBL: no utilization, never a warning
  EXPECT_EQ(valueOf(s[3], "utilization (T / MBL)"), "-");
  EXPECT_EQ(valueOf(s[3], "utilization (max, total)"), "-");
  // Line a eases to 550 N in chain: OK again, the run's largest utilization remembered.
  const std::vector<core::TensionPeak> eased{core::tensionPeak(mats, segs, {node(0, 550.0), node(1, 300.0)}),
                                             peaks[1], peaks[2]};
  m.onMotionReceived(0.3);
  m.onResult(adv, 0.3, 0.01, 0.1, &top, 0.2, &eased);
  s = m.summarise(0.4);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::OK) << s[0].message;
  EXPECT_EQ(s[1].level, rb::VesselMonitor::OK) << s[1].message;
  EXPECT_EQ(valueOf(s[1], "utilization (T / MBL)"), "0.55");
  EXPECT_EQ(valueOf(s[1], "utilization (max, total)"), "0.7");
  // Exactly at the limit is not above it (the line node's rule, T / MBL > max_utilization).
  const std::vector<core::TensionPeak> at{core::tensionPeak(mats, segs, {node(0, 600.0)}), peaks[1], peaks[2]};
  m.onResult(adv, 0.5, 0.01, 0.1, &top, 0.3, &at);
  s = m.summarise(0.6);
  EXPECT_EQ(s[1].level, rb::VesselMonitor::OK) << s[1].message;
}

// demo_monitor reads the real-time factor from the run status of any of the three dynamic nodes
// (it showed "-" for the vessel node, whose status is "<node> vessel lockstep"), never from a
// per-line status or another node's.
TEST(DemoMonitor, RecognisesTheRunStatusOfEveryDynamicNode) {
  const std::string n = "/mooring_dynamics_node";
  EXPECT_TRUE(rb::isRunStatusName("mooring_dynamics: /mooring_dynamics_node lockstep", n));
  EXPECT_TRUE(rb::isRunStatusName("mooring_dynamics: /mooring_dynamics_node vessel lockstep", n));
  EXPECT_TRUE(rb::isRunStatusName("mooring_dynamics: /mooring_dynamics_node system lockstep", n));
  EXPECT_FALSE(rb::isRunStatusName("mooring_dynamics: /mooring_dynamics_node line bow", n));
  EXPECT_FALSE(rb::isRunStatusName("mooring_dynamics: /other_node vessel lockstep", n));
  EXPECT_FALSE(rb::isRunStatusName("mooring_dynamics: /mooring_dynamics_node_2 lockstep", n));
}

// A line that failed and restarted alone (VesselLockstep's LinesRestarted): the run and that
// line are ERROR and named, the others stay OK, and the simulated time still counts.
TEST(VesselMonitor, ALineRestartedAloneIsNamedTheOthersStayOk) {
  rb::VesselMonitorOptions o;
  o.motion_timeout = 100.0;
  rb::VesselMonitor m({"bow", "port", "stbd"}, o, 0.0);
  core::VesselLockstep::Result r;
  r.outcome = core::VesselLockstep::Outcome::LinesRestarted;
  r.publish = true;
  r.failed_lines = {1};
  r.message = "line port: failure injected (test hook) (t = 1 s); restarted from statics at the vessel's pose there: "
              "port; the other lines go on";
  const std::vector<double> top{1.0, 2.0, 3.0};
  m.onMotionReceived(0.1);
  m.onResult(r, 0.1, 0.05, 0.1, &top, 1.0);
  const std::vector<rb::VesselMonitor::Status> s = m.summarise(0.2);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::ERROR);
  EXPECT_NE(s[0].message.find("line(s) port failed and restarted alone"), std::string::npos) << s[0].message;
  EXPECT_EQ(valueOf(s[0], "real-time factor (window)"), "2") << "0.1 s simulated in 0.05 s";
  EXPECT_EQ(s[1].level, rb::VesselMonitor::OK);
  EXPECT_EQ(s[2].level, rb::VesselMonitor::ERROR);
  EXPECT_EQ(valueOf(s[2], "converged"), "false");
  EXPECT_NE(s[2].message.find("failure injected"), std::string::npos) << s[2].message;
  EXPECT_EQ(s[3].level, rb::VesselMonitor::OK);
  EXPECT_EQ(valueOf(s[0], "line failed: restarted alone (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "line failed: last good state kept (window / total)"), "0 / 0");
}

// A failed sample that kept the last good state (VesselLockstep::Outcome::Failed): ERROR naming the
// line, the overall and the line's message say the state is kept, and the causes are counted apart.
TEST(VesselMonitor, KeptStateAfterAFailureAndCountsByCause) {
  rb::VesselMonitorOptions o;
  o.motion_timeout = 100.0;
  rb::VesselMonitor m({"bow", "stern"}, o, 0.0);
  using O = core::VesselLockstep::Outcome;
  using R = core::VesselLockstep::Reason;
  const std::vector<double> top{1.0, 2.0};
  core::VesselLockstep::Result r;
  r.outcome = O::Started;
  r.publish = true;
  m.onResult(r, 0.1, 0.0, 0.0, &top, 0.0);
  for (R reason : {R::NonFiniteOrientation, R::NonUnitOrientation, R::NonUnitOrientation, R::SameStamp, R::Jump}) {
    core::VesselLockstep::Result d;
    d.reason = reason;
    d.message = "bad";
    m.onResult(d, 0.2, 0.0, 0.0, nullptr, 0.0);
  }
  m.onInputRejected(0.2, "header.stamp = 0", rb::vessel_keys::kZeroStamp);
  m.onRequestRejected(0.2, "~solve_static: invalid request: offset_steps = 0");
  core::VesselLockstep::Result f;
  f.outcome = O::Failed;
  f.reason = R::SolverFailed;
  f.publish = true;
  f.message = "t = 1 s: line stern: did not converge; the last good state (t = 0.9 s) is kept";
  m.onResult(f, 0.3, 0.0, 0.0, &top, 0.9);
  const std::vector<rb::VesselMonitor::Status> s = m.summarise(0.4);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].level, rb::VesselMonitor::ERROR);
  EXPECT_NE(s[0].message.find("line stern failed; the last good state is kept and published"), std::string::npos)
      << s[0].message;
  EXPECT_NE(s[0].message.find("service request"), std::string::npos) << s[0].message;
  EXPECT_EQ(s[2].level, rb::VesselMonitor::ERROR);
  EXPECT_NE(s[2].message.find("last good state is kept"), std::string::npos) << s[2].message;
  EXPECT_EQ(s[1].level, rb::VesselMonitor::OK);
  EXPECT_EQ(valueOf(s[0], "dropped: non-finite orientation (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "dropped: non-unit orientation (window / total)"), "2 / 2");
  EXPECT_EQ(valueOf(s[0], "dropped: same stamp (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "dropped: jump (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "dropped: zero stamp (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "dropped: stamp back (window / total)"), "0 / 0");
  EXPECT_EQ(valueOf(s[0], "service requests rejected (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "line failed: last good state kept (window / total)"), "1 / 1");
  EXPECT_EQ(valueOf(s[0], "restarted: line failures (window / total)"), "0 / 0");
  EXPECT_EQ(valueOf(s[0], "samples dropped"), "6");
  // The next window: the totals stay, the window counts restart.
  const std::vector<rb::VesselMonitor::Status> n = m.summarise(0.5);
  EXPECT_EQ(valueOf(n[0], "dropped: non-unit orientation (window / total)"), "0 / 2");
  EXPECT_EQ(n[2].level, rb::VesselMonitor::OK);
}
