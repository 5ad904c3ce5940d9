// Two-way coupling (test/ros/test_vessel.test): vessel_sim drives the cable node with its fairlead
// pose (relayed by the test) and takes the cable's wrench back. The vessel's poses and the cable's
// wrenches alternate one for one (every pose stamp gets a wrench with that stamp, and the vessel
// advances only after it),
// the wrench pulls the vessel down, and the vessel moves as its equations of motion say: the surge
// and heave published are those of the mass-spring-dampers of companions.hpp driven by the ramped
// wave force and by the wrenches the cable node sent back, integrated here independently (RK4 in
// fine substeps on the continuous wave force), within the error of the vessel's own first-order
// steps; and the vessel's model replayed on the wrenches gives its poses to rounding (each step
// took the wrench answering the pose before it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace md = mooring_dynamics::ros_bridge;

namespace {
// vessel_sim's step and test_vessel.test's ramp (its other parameters: VesselOptions' defaults).
constexpr double kDt = 0.1;    // [s]
constexpr double kRamp = 1.0;  // [s]
constexpr double kStampTol = 1e-6;  // [s] stamps of start + k dt, to the nanosecond and the sum's rounding
constexpr double kTwoPi = 6.283185307179586;
// The vessel's semi-implicit Euler (the forces held over each 0.1 s step, explicit coupling)
// against the continuous equations: its O(dt) lag, half a step of phase on the 8 s wave and the
// 1.6 s heave transient, is about 3 cm on these metre motions over the first 8 s (2.7 cm in heave,
// 2.6 cm in surge under the static cable force, computed apart; 2.1 and 2.4 cm in the coupled run).
// A 5 % heavier or stiffer vessel in the equations moves them by 1.5 and 4 cm.
constexpr double kEulerTol = 0.04;  // [m]
// vessel_sim's start and its model replayed here: the same operations on the same numbers.
constexpr double kReplayTol = 1e-9;  // [m]

/// One degree of freedom m q'' + c q' + k (q - q_rest) = F_wave(t) + F_cable(t), F_cable held
/// over [k dt, (k + 1) dt) at cable[k]; q(0) = q0 at rest. RK4 with 100 substeps per step; the
/// wave force continuous. Returns q at the step times.
std::vector<double> respond(double m, double c, double k, double q0, double q_rest, double wave_amplitude,
                            bool cosine, double period, const std::vector<double>& cable) {
  auto ramp = [](double t) { return t >= kRamp ? 1.0 : t <= 0.0 ? 0.0 : 0.5 * (1.0 - std::cos(M_PI * t / kRamp)); };
  auto wave = [&](double t) {
    const double ph = kTwoPi * t / period;
    return ramp(t) * wave_amplitude * (cosine ? std::cos(ph) : std::sin(ph));
  };
  std::vector<double> out{q0};
  double q = q0, v = 0.0, t = 0.0;
  const int sub = 100;
  const double h = kDt / sub;
  for (double Fc : cable) {
    auto acc = [&](double tt, double qq, double vv) { return (wave(tt) + Fc - c * vv - k * (qq - q_rest)) / m; };
    for (int i = 0; i < sub; ++i) {
      const double a1 = acc(t, q, v), v1 = v;
      const double a2 = acc(t + 0.5 * h, q + 0.5 * h * v1, v + 0.5 * h * a1), v2 = v + 0.5 * h * a1;
      const double a3 = acc(t + 0.5 * h, q + 0.5 * h * v2, v + 0.5 * h * a2), v3 = v + 0.5 * h * a2;
      const double a4 = acc(t + h, q + h * v3, v + h * a3), v4 = v + h * a3;
      q += h / 6.0 * (v1 + 2.0 * v2 + 2.0 * v3 + v4);
      v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
      t += h;
    }
    out.push_back(q);
  }
  return out;
}
}  // namespace

TEST(Vessel, PosesAndWrenchesInLockstepAndTheVesselFollowsItsEquationsOfMotion) {
  ros::NodeHandle nh;
  std::map<uint64_t, geometry_msgs::PoseStamped> poses;
  std::map<uint64_t, geometry_msgs::WrenchStamped> wrenches;
  // The test relays the fairlead pose to the cable node (test_vessel.test): vessel_sim starts when
  // its pose has a subscriber, and this one is the only one, so the test sees every pose from the
  // static top on (a pose the cable node misses is sent again by vessel_sim).
  ros::Publisher relay = nh.advertise<geometry_msgs::PoseStamped>("/test_vessel/top_pose", 1000);
  ros::Subscriber a = nh.subscribe<geometry_msgs::PoseStamped>(
      "/vessel_sim/fairlead_pose", 1000, [&](const geometry_msgs::PoseStamped::ConstPtr& m) {
        poses[m->header.stamp.toNSec()] = *m;
        relay.publish(*m);
      });
  ros::Subscriber b = nh.subscribe<geometry_msgs::WrenchStamped>(
      "/mooring_dynamics_node/top_wrench", 1000, [&](const geometry_msgs::WrenchStamped::ConstPtr& m) {
        wrenches[m->header.stamp.toNSec()] = *m;
      });
  constexpr std::size_t kSteps = 81;  // one 8 s wave period of vessel time (about 1.6 s of wall time at speed 5)
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(40.0);
  while (ros::ok() && ros::WallTime::now() < end && poses.size() < kSteps) {
    ros::spinOnce();
    ros::WallDuration(0.005).sleep();
  }
  ASSERT_GE(poses.size(), kSteps) << "the vessel did not run";
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();
  // Every pose but the newest has been answered with a wrench of the same stamp.
  std::size_t answered = 0;
  for (const auto& kv : poses) {
    auto w = wrenches.find(kv.first);
    if (w == wrenches.end()) continue;
    ++answered;
    EXPECT_LT(w->second.wrench.force.z, 0.0) << "the line must pull the vessel down";
  }
  EXPECT_GE(answered + 1, poses.size()) << "poses without a wrench: the coupling is not in lockstep";

  // The poses in order, k dt after the first, each with the wrench that answered it.
  const uint64_t t0 = poses.begin()->first;
  std::vector<double> x, z, fx, fz;
  for (const auto& kv : poses) {
    const double t = 1e-9 * static_cast<double>(kv.first - t0);
    ASSERT_NEAR(t, kDt * static_cast<double>(x.size()), kStampTol) << "pose stamps k dt apart";
    x.push_back(kv.second.pose.position.x);
    z.push_back(kv.second.pose.position.z);
    auto w = wrenches.find(kv.first);
    if (w == wrenches.end()) break;
    fx.push_back(w->second.wrench.force.x);
    fz.push_back(w->second.wrench.force.z);
  }
  ASSERT_GE(fz.size() + 1, kSteps);
  // The vessel starts at the problem's static top, in equilibrium with the static cable force.
  const std::string problem_file = std::string(MD_SOURCE_DIR) + "/config/chain_mooring.yaml";
  const md::StaticTop top = md::staticTop(mooring_dynamics::core::loadProblemFromFile(problem_file));
  EXPECT_NEAR(x[0], top.x, kReplayTol);
  EXPECT_NEAR(z[0], top.z, kReplayTol);
  const md::VesselOptions o;
  const std::vector<double> zr = respond(o.mass, o.heave_damping, o.heave_stiffness, top.z,
                                         top.z - top.fz / o.heave_stiffness, o.wave_heave_force, false,
                                         o.wave_period, fz);
  const std::vector<double> xr = respond(o.mass, o.surge_damping, o.surge_stiffness, top.x,
                                         top.x - top.fx / o.surge_stiffness, o.wave_surge_force, true,
                                         o.wave_period, fx);
  double ez = 0.0, ex = 0.0, zmin = z[0], zmax = z[0], fz_dev = 0.0;
  for (std::size_t k = 0; k < kSteps; ++k) {  // the first 8 s, whatever the wall clock let through after
    EXPECT_NEAR(z[k], zr[k], kEulerTol) << "heave at t = " << kDt * k;
    EXPECT_NEAR(x[k], xr[k], kEulerTol) << "surge at t = " << kDt * k;
    ez = std::max(ez, std::abs(z[k] - zr[k]));
    ex = std::max(ex, std::abs(x[k] - xr[k]));
    zmin = std::min(zmin, z[k]);
    zmax = std::max(zmax, z[k]);
  }
  for (double f : fz) fz_dev = std::max(fz_dev, std::abs(f - top.fz));
  // Lockstep, explicit coupling: vessel_sim's own model stepped here with the wrench that
  // answered each pose gives the next pose to rounding, so each step took the answer to the pose
  // before it (steps on the wrench before that, up to 1 kN off in the first seconds, end 1.6 cm off).
  // The cable's force changes move the heave by about 6 mm, inside kEulerTol: this is what shows
  // that the vessel feels them.
  md::VesselOptions replay_options;
  replay_options.ramp = kRamp;
  md::VesselModel replay(replay_options, top.x, top.z, top.fx, top.fz);
  double replay_error = 0.0;
  for (std::size_t k = 0; k + 1 < kSteps; ++k) {
    replay.step(kDt, fx[k], fz[k]);
    EXPECT_NEAR(replay.x(), x[k + 1], kReplayTol) << "t = " << kDt * (k + 1);
    EXPECT_NEAR(replay.z(), z[k + 1], kReplayTol) << "t = " << kDt * (k + 1);
    replay_error = std::max({replay_error, std::abs(replay.x() - x[k + 1]), std::abs(replay.z() - z[k + 1])});
  }
  std::printf("coupled vessel over %zu steps: heave %.3f m to %.3f m, within %.4f m of its equations; surge within "
              "%.4f m; cable's vertical pull within %.1f N of the static %.1f N; the vessel's model replayed on the "
              "wrenches within %.2g m\n",
              kSteps - 1, zmin - top.z, zmax - top.z, ez, ex, fz_dev, top.fz, replay_error);
  // The premise: the wave force heaved the vessel by metres (about +-F / k = +-0.8 m), not the
  // Euler error.
  EXPECT_GT(zmax - zmin, 20.0 * kEulerTol);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_vessel");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
