// A moored vessel's computed motion (core/solvers/vessel_motion_source.hpp) driving the lines in
// lockstep (core/solvers/vessel_lockstep.hpp):
//  * in still water, released 0.2 m off its equilibrium in surge, the hull's slow surge swings at
//    the natural period 2 pi sqrt((m + a11) / k11) with k11 the mooring stiffness of the statics
//    (mooringStiffness, as `cable_sim stiffness`), to 2 % (issue "Design storms", Checks);
//  * with a steady mean force and damping the hull settles where the mooring's restoring force,
//    from a static solve at the settled pose, balances it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/vessel_lockstep.hpp"
#include "mooring_dynamics/core/solvers/vessel_motion_source.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kData = std::string(MD_SOURCE_DIR) + "/test/data/";

/// The bound. Differences from the closed form: the chain's own inertia and drag (1.4 t of
/// chain against 400 t of hull), the catenary's stiffness varying over +-0.2 m, the one-step lag.
constexpr double kNaturalPeriodRelTol = 0.02;
/// The statics' restoring force at the settled offset against the mean force: what is left of
/// the decay after 30 natural periods near critical damping, and the one-step lag (< 0.1 %).
constexpr double kSettledForceRelTol = 0.01;

SystemProblem smallVessel(double x0) {
  SystemProblem s = loadSystemFromFile(kData + "small_vessel.yaml");
  s.vessel.low_frequency = true;
  s.vessel.slow.mass = 4.0e5;
  s.vessel.slow.yaw_inertia = 1.0e7;
  s.vessel.slow.added_mass = Eigen::Vector3d(2.0e4, 2.0e5, 5.0e6);
  s.placeVessel(RigidPose::fromRollPitchYaw(Eigen::Vector3d(x0, 0.0, 0.0), 0.0, 0.0, 0.0));
  return s;
}

/// Runs `duration` s; returns the vessel's x at every sample.
std::vector<double> run(const SystemProblem& s, double duration) {
  VesselLockstep lock(s, s.dynamics);
  VesselMotionSource src(s);
  std::vector<double> xs;
  const double dt = s.dynamics.dt;
  const long n = static_cast<long>(std::floor(duration / dt + 1e-9));
  for (long k = 0; k <= n; ++k) {
    const PoseSample p = src.sample(static_cast<double>(k) * dt);
    const VesselLockstep::Result r = lock.onSample(p.t, p.pose, &p.twist);
    EXPECT_TRUE(r.outcome == VesselLockstep::Outcome::Started || r.outcome == VesselLockstep::Outcome::Advanced)
        << "t = " << p.t << ": " << r.message;
    src.advance(dt, lock.wrench());
    xs.push_back(p.pose.position.x());
  }
  return xs;
}

}  // namespace

TEST(VesselMotionSource, FreeSurgeSwingsAtTheMooringsNaturalPeriod) {
  const SystemProblem s = smallVessel(0.2);
  const StiffnessResult k = mooringStiffness(smallVessel(0.0), RigidPose());
  ASSERT_TRUE(k.converged) << k.message;
  const double want = 2.0 * kPi * std::sqrt((s.vessel.slow.mass + s.vessel.slow.added_mass.x()) / k.K(0, 0));
  ASSERT_GT(want, 20.0) << "a slow period, many steps of 0.1 s";
  const std::vector<double> xs = run(s, 3.2 * want);
  double first = -1.0, last = -1.0;
  int downs = 0;
  for (std::size_t i = 1; i < xs.size(); ++i)
    if (xs[i - 1] > 0.0 && xs[i] <= 0.0) {  // downward crossings of the equilibrium
      const double tc = s.dynamics.dt * (static_cast<double>(i) - xs[i] / (xs[i] - xs[i - 1]));
      if (first < 0.0) first = tc;
      last = tc;
      ++downs;
    }
  ASSERT_GE(downs, 3);
  const double period = (last - first) / (downs - 1);
  EXPECT_NEAR(period / want, 1.0, kNaturalPeriodRelTol) << "measured " << period << " s, closed form " << want << " s";
}

TEST(VesselMotionSource, MeanForceSettlesWhereTheMooringBalancesIt) {
  SystemProblem s = smallVessel(0.0);
  const StiffnessResult k = mooringStiffness(s, RigidPose());
  ASSERT_TRUE(k.converged) << k.message;
  const double force = 0.5 * k.K(0, 0);  // about a 0.5 m offset
  s.vessel.slow.mean_force = Eigen::Vector3d(force, 0.0, 0.0);
  // A hull ten times lighter (a natural period of ~110 s instead of ~350 s) at critical damping,
  // 2 sqrt(k m): settles to 0.1 % in about 8 / omega = 140 s.
  s.vessel.slow.mass = 4.0e4;
  s.vessel.slow.added_mass.x() = 2.0e3;
  s.vessel.slow.damping = Eigen::Vector3d(2.0 * std::sqrt(k.K(0, 0) * 4.2e4), 1.0e5, 1.0e7);
  const std::vector<double> xs = run(s, 250.0);
  const double x_end = xs.back();
  ASSERT_LT(std::abs(x_end - xs[xs.size() - 101]), 1e-3 * x_end) << "still moving over the last 10 s";
  // The statics at the settled pose, independently of the dynamics: its restoring force is F.
  const VesselStaticResult st = solveVesselStatic(s, RigidPose::fromRollPitchYaw(Eigen::Vector3d(x_end, 0.0, 0.0), 0.0, 0.0, 0.0));
  ASSERT_TRUE(st.system.summary.converged);
  EXPECT_NEAR(-st.wrench.force_world.x() / force, 1.0, kSettledForceRelTol)
      << "settled at " << x_end << " m; restoring " << -st.wrench.force_world.x() << " N against " << force << " N";
}
