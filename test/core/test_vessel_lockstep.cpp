// The vessel's lockstep driver: the sample policy (bad poses, stamps, start away from the file's
// pose) and the same bits whatever the thread count.
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "system_test_util.hpp"

using namespace mooring_dynamics::core;
using mooring_dynamics::core::testing_util::fourLegVessel;

namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;

DynamicOptions options() {
  DynamicOptions o;
  o.dt = 0.25;
  o.duration = 1.0;
  return o;
}

RigidPose surged(double x, double yaw_deg = 0.0) { return RigidPose::fromRollPitchYaw({x, 0, 0}, 0, 0, yaw_deg * kDegree); }
}  // namespace

TEST(VesselLockstep, BadPosesAndStampsAreDroppedAndTheStateKept) {
  VesselLockstep run(fourLegVessel(10.0), options());
  EXPECT_EQ(run.onSample(100.0, surged(0.0)).outcome, VesselLockstep::Outcome::Started);
  EXPECT_EQ(run.onSample(100.5, surged(0.1)).outcome, VesselLockstep::Outcome::Advanced);
  const VesselWrench before = run.wrench();
  RigidPose nan_q = surged(0.2);
  nan_q.orientation.x() = std::nan("");
  RigidPose long_q = surged(0.2);
  long_q.orientation.coeffs() *= 1.01;
  RigidPose inf_p = surged(0.2);
  inf_p.position.y() = INFINITY;
  for (const RigidPose& bad : {nan_q, long_q, inf_p}) {
    const auto r = run.onSample(101.0, bad);
    EXPECT_EQ(r.outcome, VesselLockstep::Outcome::Dropped);
    EXPECT_FALSE(r.publish);
    EXPECT_NE(r.message.find("pose."), std::string::npos) << r.message;
  }
  EXPECT_EQ(run.onSample(100.5, surged(0.2)).outcome, VesselLockstep::Outcome::Dropped);  // duplicate stamp
  EXPECT_EQ(run.onSample(100.2, surged(0.2)).outcome, VesselLockstep::Outcome::Dropped);  // back 0.3 s
  EXPECT_EQ(run.dropped(), 5);
  EXPECT_EQ(run.wrench().force_world, before.force_world);
  EXPECT_EQ(run.lastTime(), 100.5);
  // A quaternion off unit by less than the tolerance is taken (and normalized).
  RigidPose near = surged(0.2);
  near.orientation.coeffs() *= 1.0 + 0.5 * kUnitQuaternionTolerance;
  EXPECT_EQ(run.onSample(101.0, near).outcome, VesselLockstep::Outcome::Advanced);
  // A bag loop (back by more than loop_back) restarts from statics there.
  EXPECT_EQ(run.onSample(50.0, surged(0.0)).outcome, VesselLockstep::Outcome::Reinitialised);
  EXPECT_EQ(run.solverTime(), 0.0);
}

TEST(VesselLockstep, FirstSampleAwayFromTheFilePoseStartsFromItsOwnStatics) {
  const SystemProblem s = fourLegVessel(10.0);
  VesselLockstep run(s, options());
  const RigidPose away = surged(5.0, 3.0);
  ASSERT_EQ(run.onSample(0.0, away).outcome, VesselLockstep::Outcome::Started);
  const VesselStaticResult st = solveVesselStatic(s, away);
  // [N] both are the statics at that pose, solved the same way.
  const double tol = 1e-6 * std::abs(st.wrench.force_world.z());
  EXPECT_NEAR((run.wrench().force_world - st.wrench.force_world).norm(), 0.0, tol);
  EXPECT_NEAR((run.wrench().moment_world - st.wrench.moment_world).norm(), 0.0, 30.0 * tol);
  EXPECT_LT(run.wrench().force_body.x(), 0.0);  // surged: pulled back
}

TEST(VesselLockstep, SameBitsOnOneAndTwoThreads) {
  std::vector<Eigen::Vector3d> series[2];
  for (int k = 0; k < 2; ++k) {
    VesselLockstepOptions lo;
    lo.threads = k + 1;
    VesselLockstep run(fourLegVessel(10.0), options(), lo);
    for (int i = 0; i <= 20; ++i) {
      const double t = 0.2 * i;
      run.onSample(t, surged(0.5 * std::sin(0.6 * t), 2.0 * std::sin(0.3 * t)));
      series[k].push_back(run.wrench().force_world);
      series[k].push_back(run.wrench().moment_world);
    }
  }
  ASSERT_EQ(series[0].size(), series[1].size());
  for (std::size_t i = 0; i < series[0].size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(series[0][i][c], series[1][i][c]) << i;
}

// A 16 Hz source with solve_interval 0.25 s: the samples between solves are held (answered from
// the last solve, counted) and the solved ones give the same bits as a run fed only those (the
// vessel moves on the straight segment between solved samples either way). Times are binary
// fractions, so that "0.25 s since the last solve" is exact.
TEST(VesselLockstep, SamplesWithinTheSolveIntervalAreHeldAndTheSolvesMatchACoarseRun) {
  constexpr double kRate = 16.0;  // [Hz] the source
  VesselLockstepOptions decimated;
  decimated.solve_interval = 0.25;
  VesselLockstep fast(fourLegVessel(10.0), options(), decimated), coarse(fourLegVessel(10.0), options());
  auto pose = [](double t) { return surged(0.5 * std::sin(0.6 * t), 2.0 * std::sin(0.3 * t)); };
  long held = 0, solved = 0;
  for (int i = 0; i <= 48; ++i) {
    const double t = i / kRate;
    const VesselWrench before = fast.wrench();
    const auto r = fast.onSample(t, pose(t));
    if (i % 4 != 0) {
      EXPECT_EQ(r.outcome, VesselLockstep::Outcome::Held) << t;
      EXPECT_FALSE(r.publish);
      EXPECT_EQ(fast.wrench().force_world, before.force_world);  // the last solve's
      EXPECT_EQ(fast.lastTime(), t);
      ++held;
      continue;
    }
    EXPECT_EQ(r.outcome, i == 0 ? VesselLockstep::Outcome::Started : VesselLockstep::Outcome::Advanced) << t;
    ++solved;
    coarse.onSample(t, pose(t));
    EXPECT_EQ(fast.lastSolvedTime(), t);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(fast.wrench().force_world[c], coarse.wrench().force_world[c]) << t;
      EXPECT_EQ(fast.wrench().moment_world[c], coarse.wrench().moment_world[c]) << t;
    }
  }
  EXPECT_EQ(fast.held(), held);
  EXPECT_EQ(solved, 13);
  // Held samples still pass the checks: a stamp back, a bad pose are dropped, not held.
  EXPECT_EQ(fast.onSample(3.0 - 1.0 / kRate, pose(3.0)).outcome, VesselLockstep::Outcome::Dropped);
  RigidPose bad = pose(3.0625);
  bad.position.x() = std::nan("");
  EXPECT_EQ(fast.onSample(3.0625, bad).outcome, VesselLockstep::Outcome::Dropped);
  EXPECT_EQ(fast.held(), held);
  EXPECT_EQ(fast.dropped(), 2);
}

// A 1 kHz source whose times are stamps in nanoseconds differenced in double (as the node's
// stamp - epoch): 0.1 s after a solve can come out a hair short of 0.1. Within
// kIntervalTolerance it counts: a solve every 100 samples, none at 101.
TEST(VesselLockstep, AOneKilohertzSourceIsSolvedEveryHundredSamples) {
  VesselLockstepOptions lo;
  lo.solve_interval = 0.1;
  VesselLockstep run(fourLegVessel(10.0), options(), lo);
  constexpr long kEpochNs = 1234567890123456789;  // a stamp in ns, far from 0 as a real clock's
  std::vector<long> solved_at;
  for (long k = 0; k <= 1000; ++k) {
    const double t = static_cast<double>((kEpochNs + k * 1000000) - kEpochNs) * 1e-9;
    const auto r = run.onSample(t, surged(0.1 * std::sin(t)));
    if (r.outcome != VesselLockstep::Outcome::Held) solved_at.push_back(k);
  }
  ASSERT_EQ(solved_at.size(), 11u);
  for (std::size_t i = 0; i < solved_at.size(); ++i) EXPECT_EQ(solved_at[i], static_cast<long>(100 * i));
}

// restartAt: the lines from statics at the sample (a solver too far behind its source), counted
// as a restart of reason Behind; a NaN pose is dropped instead.
TEST(VesselLockstep, RestartAtStartsFromTheStaticsAtTheSample) {
  VesselLockstep run(fourLegVessel(10.0), options());
  run.onSample(0.0, surged(0.0));
  run.onSample(0.25, surged(0.2));
  RigidPose bad = surged(1.0);
  bad.position.z() = std::nan("");
  EXPECT_EQ(run.restartAt(5.0, bad, "behind").outcome, VesselLockstep::Outcome::Dropped);
  const auto r = run.restartAt(5.0, surged(1.0), "behind");
  EXPECT_EQ(r.outcome, VesselLockstep::Outcome::Reinitialised);
  EXPECT_EQ(r.reason, VesselLockstep::Reason::Behind);
  EXPECT_EQ(run.solverTime(), 0.0);
  EXPECT_EQ(run.lastTime(), 5.0);
  const VesselStaticResult st = solveVesselStatic(fourLegVessel(10.0), surged(1.0));
  EXPECT_NEAR((run.wrench().force_world - st.wrench.force_world).norm(), 0.0, 1e-6 * std::abs(st.wrench.force_world.z()));
}

TEST(VesselLockstep, OptionsNameTheField) {
  VesselLockstepOptions lo;
  lo.threads = 0;
  EXPECT_NE(lo.validate().find("threads"), std::string::npos);
  lo = VesselLockstepOptions();
  lo.solve_interval = -0.1;
  EXPECT_NE(lo.validate().find("solve_interval = -0.1"), std::string::npos);
  lo = VesselLockstepOptions();
  lo.loop_back = -1;
  EXPECT_NE(lo.validate().find("loop_back"), std::string::npos);
}

// One line fails (injected at solver time 1.0 s): the sample is answered (LinesRestarted, the
// line named), that line alone restarts from statics, and the other lines' states and the
// wrench's other shares go on bit for bit as in a run without the failure.
TEST(VesselLockstep, AFailedLineRestartsAloneAndIsNamed) {
  VesselLockstep clean(fourLegVessel(10.0), options()), failing(fourLegVessel(10.0), options());
  failing.setFailureInjection([](std::size_t line, double t1) { return line == 2 && std::abs(t1 - 1.0) < 1e-9; });
  bool seen = false;
  for (int i = 0; i <= 12; ++i) {
    const double t = 100.0 + 0.25 * i;  // any epoch: solver time = t - 100
    const RigidPose p = surged(0.5 * std::sin(0.6 * (t - 100.0)), 2.0 * std::sin(0.3 * (t - 100.0)));
    const VesselLockstep::Result rc = clean.onSample(t, p), rf = failing.onSample(t, p);
    ASSERT_TRUE(rc.publish);
    ASSERT_TRUE(rf.publish);
    if (i == 4) {
      seen = true;
      EXPECT_EQ(rf.outcome, VesselLockstep::Outcome::LinesRestarted) << rf.message;
      EXPECT_EQ(rf.failed_lines, std::vector<std::size_t>{2});
      EXPECT_NE(rf.message.find("line leg2: failure injected (test hook)"), std::string::npos) << rf.message;
      EXPECT_NE(rf.message.find("the other lines go on"), std::string::npos) << rf.message;
    } else {
      EXPECT_EQ(rf.outcome, i == 0 ? VesselLockstep::Outcome::Started : VesselLockstep::Outcome::Advanced) << i;
    }
    const std::vector<StaticResult> lc = clean.lines(), lf = failing.lines();
    for (std::size_t k : {0u, 1u, 3u}) {
      ASSERT_EQ(lc[k].nodes.size(), lf[k].nodes.size());
      for (std::size_t n = 0; n < lc[k].nodes.size(); ++n) {
        EXPECT_EQ(lc[k].nodes[n].x, lf[k].nodes[n].x) << "line " << k << " sample " << i;
        EXPECT_EQ(lc[k].nodes[n].tension, lf[k].nodes[n].tension) << "line " << k << " sample " << i;
      }
    }
  }
  EXPECT_TRUE(seen);
}

// A line whose step fails at its smallest cut: the last good state is kept (every line restored
// to the last converged step) and published (Failed, the line named); the next sample continues
// from it; failures_to_reinit failures in a row restart from statics at the sample's pose. The
// policy of a run that does not restart failed lines alone (restart_failed_lines false, cable_sim).
// Forced: 4 Newton iterations per step and no step cutting, which a gentle surge needs at most 3
// of and a 5 m lurch in one step cannot do; max_speed 0 lets the lurch through.
TEST(VesselLockstep, AFailedStepKeepsTheLastGoodStateAndContinues) {
  using O = VesselLockstep::Outcome;
  DynamicOptions o = options();
  o.max_iterations = 4;
  o.max_cut_levels = 0;
  o.fallback = false;  // the step must fail: no fallback step to take it
  VesselLockstepOptions lo;
  lo.max_speed = 0.0;
  lo.failures_to_reinit = 3;
  lo.restart_failed_lines = false;
  VesselLockstep run(fourLegVessel(10.0), o, lo);
  ASSERT_EQ(run.onSample(0.0, surged(0.0)).outcome, O::Started);
  ASSERT_EQ(run.onSample(0.25, surged(0.01)).outcome, O::Advanced);
  const VesselWrench before = run.wrench();
  const std::vector<StaticResult> lines_before = run.lines();

  const auto f = run.onSample(0.5, surged(5.0));
  EXPECT_EQ(f.outcome, O::Failed) << f.message;
  EXPECT_EQ(f.reason, VesselLockstep::Reason::SolverFailed);
  EXPECT_TRUE(f.publish);
  EXPECT_NE(f.message.find("line "), std::string::npos) << f.message;
  EXPECT_NE(f.message.find("last good state"), std::string::npos) << f.message;
  // One base step per sample and no cutting: nothing converged, so the kept state is the last
  // sample's, bit for bit.
  EXPECT_EQ(run.solverTime(), 0.25);
  EXPECT_EQ(run.lastTime(), 0.25);
  EXPECT_EQ(run.wrench().force_world, before.force_world);
  EXPECT_EQ(run.wrench().moment_world, before.moment_world);
  const std::vector<StaticResult> lines_kept = run.lines();
  ASSERT_EQ(lines_kept.size(), lines_before.size());
  for (std::size_t i = 0; i < lines_kept.size(); ++i)
    for (std::size_t j = 0; j < lines_kept[i].nodes.size(); ++j)
      ASSERT_EQ(lines_kept[i].nodes[j].tension, lines_before[i].nodes[j].tension) << i << " " << j;

  // The next gentle sample continues from it (over 0.25 -> 0.75 s).
  const auto a = run.onSample(0.75, surged(0.02));
  EXPECT_EQ(a.outcome, O::Advanced) << a.message;
  EXPECT_EQ(run.solverTime(), 0.75);

  // Three lurches in a row: kept, kept, then restarted from statics at the third pose.
  EXPECT_EQ(run.onSample(1.0, surged(5.0)).outcome, O::Failed);
  EXPECT_EQ(run.onSample(1.25, surged(5.0)).outcome, O::Failed);
  const auto r = run.onSample(1.5, surged(5.0));
  EXPECT_EQ(r.outcome, O::RecoveredFailure) << r.message;
  EXPECT_EQ(r.reason, VesselLockstep::Reason::SolverFailed);
  EXPECT_EQ(run.solverTime(), 0.0);
  const VesselStaticResult st = solveVesselStatic(fourLegVessel(10.0), surged(5.0));
  EXPECT_NEAR((run.wrench().force_world - st.wrench.force_world).norm(), 0.0,
              1e-6 * std::abs(st.wrench.force_world.z()));
}

TEST(VesselLockstep, ReasonsOfDropsAndRestarts) {
  using R = VesselLockstep::Reason;
  VesselLockstep run(fourLegVessel(10.0), options());
  EXPECT_EQ(run.onSample(10.0, surged(0.0)).reason, R::None);
  RigidPose p = surged(0.0);
  p.position.x() = std::nan("");
  EXPECT_EQ(run.onSample(10.5, p).reason, R::NonFinitePosition);
  p = surged(0.0);
  p.orientation.w() = INFINITY;
  EXPECT_EQ(run.onSample(10.5, p).reason, R::NonFiniteOrientation);
  p = surged(0.0);
  p.orientation.coeffs().setZero();
  EXPECT_EQ(run.onSample(10.5, p).reason, R::NonUnitOrientation);
  EXPECT_EQ(run.onSample(std::nan(""), surged(0.0)).reason, R::NonFiniteTime);
  const BodyTwist bad_twist{Eigen::Vector3d(std::nan(""), 0.0, 0.0), Eigen::Vector3d::Zero()};
  EXPECT_EQ(run.onSample(10.5, surged(0.0), &bad_twist).reason, R::BadTwist);
  EXPECT_EQ(run.onSample(10.0, surged(0.0)).reason, R::SameStamp);
  EXPECT_EQ(run.onSample(9.5, surged(0.0)).reason, R::StampBack);
  EXPECT_EQ(run.onSample(10.25, surged(100.0)).reason, R::Jump);
  EXPECT_EQ(run.onSample(1e6, surged(0.0)).reason, R::Gap);       // far in the future: a gap
  EXPECT_EQ(run.onSample(10.5, surged(0.0)).reason, R::LoopBack);  // and back: a bag loop
  EXPECT_EQ(run.reset().reason, R::Reset);
  EXPECT_EQ(run.dropped(), 8);
}

// A fairlead winch (VesselLockstep::winchLine): before the first sample and for an unknown line
// it says why not; hauling a leg in 1 m at 0.5 m/s shortens it to the metre, the other legs
// untouched in length, and the leg settles on the statics of the system with that leg 1 m
// shorter (vessel held at the same pose).
TEST(VesselLockstep, AFairleadWinchHaulsItsLineInToTheStaticsOfTheShorterLeg) {
  // The chain still rings 58 s after the winch stops: +-30 N of 44 kN (measured).
  constexpr double kSettledRelTol = 2e-3;
  const SystemProblem s = fourLegVessel(10.0);
  DynamicOptions o = options();
  o.duration = 60.0;
  VesselLockstep run(s, o);
  std::string note;
  const double none = std::nan("");
  EXPECT_NE(run.winchLine(s.lines[0].name, -0.5, none, note).find("no motion sample yet"), std::string::npos);
  ASSERT_EQ(run.onSample(0.0, surged(0.0)).outcome, VesselLockstep::Outcome::Started);
  EXPECT_NE(run.winchLine("nope", -0.5, none, note).find("no line of that name"), std::string::npos);
  const std::vector<double> L0 = run.lineLengths();
  ASSERT_EQ(run.winchLine(s.lines[0].name, -0.5, L0[0] - 1.0, note), "");
  EXPECT_NE(note.find("there at t = 2 s"), std::string::npos) << note;
  for (int k = 1; k <= 240; ++k)
    ASSERT_EQ(run.onSample(0.25 * k, surged(0.0)).outcome, VesselLockstep::Outcome::Advanced) << k;
  const std::vector<double> L1 = run.lineLengths();
  EXPECT_NEAR(L1[0], L0[0] - 1.0, 1e-9);
  for (std::size_t i = 1; i < L0.size(); ++i) EXPECT_EQ(L1[i], L0[i]);
  SystemProblem shorter = s;
  shorter.lines[0].segments.back().length -= 1.0;
  const VesselStaticResult st = solveVesselStatic(shorter, surged(0.0));
  ASSERT_TRUE(st.system.summary.converged);
  const double want = st.system.lines[0].nodes.back().tension;
  EXPECT_GT(want, run.dynamics().line(0).nodes.front().tension);  // (a sanity check of the reading)
  EXPECT_NEAR(run.dynamics().line(0).nodes.back().tension, want, kSettledRelTol * want);
}
