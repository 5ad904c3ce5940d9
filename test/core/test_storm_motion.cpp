// Storm motion tables (core/model/storm_motion.hpp): the heave variance of a long record against
// the realized spectrum, the realized spectrum against jonswapSpectrum, reproducibility by seed,
// the twist against central differences of the poses, the still start, the sign conventions of
// pitch and roll, the point-speed helper, and the errors for bad fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/storm_motion.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Tolerances (one-line reasons).
/// Mean square of a 3 h record (after the ramp) of the 200-component sum against sum(a_i^2)/2:
/// the cross terms a_i a_j cos((w_i - w_j) t + ...) average to O(1 / (|w_i - w_j| T)); neighbours
/// are ~2 pi df = 0.01 rad/s apart, so over T = 10780 s each pair leaves ~1 % of its product, and
/// the sum over the pairs (random phases) leaves a fraction of a percent of m0: measured over seeds
/// 1..40, 0.5 % rms, at most 1.5 %. Twice that worst case:
constexpr double kHeaveVarianceRelTol = 0.03;
/// sum(a_i^2)/2 (the spectrum's energy in [0.5, 3.5] fp) against the integral of S over (0, inf):
/// short by the energy above 3.5 fp, 0.8 % for Pierson-Moskowitz (gamma 1), less for gamma > 1.
constexpr double kSpectrumSumRelTol = 0.02;
/// The components' energy against a fine Simpson integral over the band: both integrate the same
/// smooth S (8 intervals per band against 200000 over (0, 20 fp)).
constexpr double kBandEnergyRelTol = 1e-6;
/// Central differences: truncation <= dt^2 / 6 max|x'''|, bounded from the components below;
/// the rotation's product terms (rates times angles, both small) get this margin on top.
constexpr double kRotationMargin = 1.5;
/// Ratio of the central differences' worst errors at dt and dt/2, 4 for a second-order error:
/// the worst sample moves a little between the two grids.
constexpr double kSecondOrderRatioTol = 0.3;
/// Rounding of the differences of positions of a few metres over 2 dt = 0.02 s.
constexpr double kRoundingFloor = 1e-10;
/// The surface slope at the origin and the pitch/roll it gives, written out again by hand.
constexpr double kHandValueTol = 1e-12;

StormMotionOptions storm(std::uint32_t seed = 1) {
  StormMotionOptions o;
  o.hs = 4.0;
  o.tp = 9.0;
  o.seed = seed;
  return o;
}

/// Integral of jonswapSpectrum over (a fp, b fp), composite Simpson; (0, 20 fp) stands for
/// (0, inf) (the tail beyond: ~1e-5 of m0).
double spectrumIntegral(double hs, double tp, double gamma, double a = 0.0, double b = 20.0) {
  const double fa = a / tp, fb = b / tp;
  const int n = 200000;
  const double h = (fb - fa) / n;
  double s = jonswapSpectrum(fa, hs, tp, gamma) + jonswapSpectrum(fb, hs, tp, gamma);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * jonswapSpectrum(fa + i * h, hs, tp, gamma);
  return s * h / 3.0;
}

/// Bound of |(r f)'''| for the ramp r(t) = (1 - cos(pi t / T)) / 2 (|r^(n)| <= (pi/T)^n / 2 for
/// n >= 1, |r| <= 1) and a signal with |f^(m)| <= F[m].
double rampedJerkBound(const double F[4], double ramp) {
  const double w = kPi / ramp;
  const double R[4] = {1.0, 0.5 * w, 0.5 * w * w, 0.5 * w * w * w};
  return R[0] * F[3] + 3.0 * R[1] * F[2] + 3.0 * R[2] * F[1] + R[3] * F[0];
}

/// vee of the skew part of a 3 x 3 matrix.
Eigen::Vector3d veeSkew(const Eigen::Matrix3d& W) {
  return 0.5 * Eigen::Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
}

// ---- (a) heave variance against the spectrum --------------------------------------------------

TEST(StormMotion, HeaveVarianceOfALongRecordIsTheRealizedSpectrumsM0) {
  StormMotionOptions o = storm(3);
  o.duration = 3.0 * 3600.0;
  o.dt = 0.5;
  o.heave_gain = 0.8;
  const StormMotion motion(o);
  const double m0 = motion.elevationVariance();
  const std::vector<PoseSample> s = generateStormMotion(o);
  ASSERT_EQ(s.size(), 21601u);
  double sum = 0.0;
  std::size_t n = 0;
  for (const PoseSample& p : s) {
    if (p.t < o.ramp) continue;
    sum += p.pose.position.z() * p.pose.position.z();
    ++n;
  }
  const double mean_square = sum / static_cast<double>(n);
  EXPECT_NEAR(mean_square / (o.heave_gain * o.heave_gain * m0), 1.0, kHeaveVarianceRelTol);
  // The summary's std: heave_gain Hs / 4 within the same tolerance (and the band's 0.5 %).
  const StormMotionStats st = stormMotionStats(s, o.ramp);
  EXPECT_NEAR(st.heave_std / (o.heave_gain * o.hs / 4.0), 1.0, kHeaveVarianceRelTol);
}

TEST(StormMotion, RealizedComponentsCarryTheJonswapEnergy) {
  for (double gamma : {1.0, 3.3, 7.0}) {
    StormMotionOptions o = storm();
    o.gamma = gamma;
    const StormMotion motion(o);
    const double integral = spectrumIntegral(o.hs, o.tp, gamma);
    EXPECT_NEAR(integral / (o.hs * o.hs / 16.0), 1.0, 1e-4) << "gamma " << gamma;  // jonswapSpectrum's normalisation
    EXPECT_NEAR(motion.elevationVariance() / integral, 1.0, kSpectrumSumRelTol) << "gamma " << gamma;
    EXPECT_NEAR(motion.elevationVariance() / spectrumIntegral(o.hs, o.tp, gamma, 0.5, 3.5), 1.0, kBandEnergyRelTol)
        << "gamma " << gamma;
    // One component per band, in increasing order, inside [0.5, 3.5] fp.
    const std::vector<StormComponent>& c = motion.components();
    ASSERT_EQ(c.size(), 200u);
    const double fp = 1.0 / o.tp, df = 3.0 * fp / 200.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_GE(c[i].frequency, 0.5 * fp + static_cast<double>(i) * df - 1e-15);
      EXPECT_LT(c[i].frequency, 0.5 * fp + static_cast<double>(i + 1) * df + 1e-15);
    }
  }
}

// ---- (b) reproducibility ----------------------------------------------------------------------

TEST(StormMotion, SameSeedSameBitsAnotherSeedDiffers) {
  StormMotionOptions o = storm(42);
  o.duration = 120.0;
  o.mean_offset = 4.0;
  o.drift_amplitude = 2.0;
  const std::vector<PoseSample> a = generateStormMotion(o);
  const std::vector<PoseSample> b = generateStormMotion(o);
  ASSERT_EQ(a.size(), b.size());
  auto bits = [](const PoseSample& p) {
    std::vector<double> v{p.t};
    for (int i = 0; i < 3; ++i) v.push_back(p.pose.position[i]);
    for (int i = 0; i < 4; ++i) v.push_back(p.pose.orientation.coeffs()[i]);
    for (int i = 0; i < 3; ++i) v.push_back(p.twist.linear[i]);
    for (int i = 0; i < 3; ++i) v.push_back(p.twist.angular[i]);
    return v;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::vector<double> x = bits(a[i]), y = bits(b[i]);
    ASSERT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0) << "sample " << i;
  }
  o.seed = 43;
  const std::vector<PoseSample> c = generateStormMotion(o);
  int differ = 0;
  for (std::size_t i = 1; i < a.size(); ++i) differ += a[i].pose.position.z() != c[i].pose.position.z();
  EXPECT_EQ(differ, static_cast<int>(a.size()) - 1);  // every sample after t = 0
}

// ---- (c) the twist is the derivative of the poses ---------------------------------------------

/// A storm with every motion on, through the ramp (20 s) and after it.
StormMotionOptions everyMotion(double dt) {
  StormMotionOptions o = storm(5);
  o.heading_deg = 30.0;
  o.yaw_deg = 20.0;
  o.duration = 40.0;
  o.dt = dt;
  o.mean_offset = 4.0;
  o.mean_offset_heading_deg = 210.0;
  o.drift_amplitude = 3.0;
  o.drift_period = 30.0;
  return o;
}

/// Largest difference between the twists and the central differences of the poses: the linear
/// and the angular velocity, component-wise, body frame.
void centralDifferenceErrors(const std::vector<PoseSample>& s, double& worst_linear, double& worst_angular) {
  worst_linear = worst_angular = 0.0;
  for (std::size_t k = 1; k + 1 < s.size(); ++k) {
    const RigidPose& a = s[k - 1].pose;
    const RigidPose& b = s[k + 1].pose;
    const RigidPose& p = s[k].pose;
    const double span = s[k + 1].t - s[k - 1].t;
    const Eigen::Vector3d v_cd = p.toBody((b.position - a.position) / span);
    const Eigen::Matrix3d R = p.orientation.toRotationMatrix();
    const Eigen::Vector3d w_cd =
        veeSkew(R.transpose() * (b.orientation.toRotationMatrix() - a.orientation.toRotationMatrix()) / span);
    worst_linear = std::max(worst_linear, (v_cd - s[k].twist.linear).cwiseAbs().maxCoeff());
    worst_angular = std::max(worst_angular, (w_cd - s[k].twist.angular).cwiseAbs().maxCoeff());
  }
}

TEST(StormMotion, TwistAgreesWithCentralDifferencesOfThePoses) {
  const StormMotionOptions o = everyMotion(0.01);
  const StormMotion motion(o);
  const std::vector<PoseSample> s = generateStormMotion(o);
  // Bounds of the derivatives of the unramped signals.
  double E[4] = {0, 0, 0, 0}, G[4] = {0, 0, 0, 0};  // elevation, slope
  for (const StormComponent& c : motion.components())
    for (int m = 0; m < 4; ++m) {
      E[m] += c.amplitude * std::pow(c.omega, m);
      G[m] += c.amplitude * c.k * std::pow(c.omega, m);
    }
  const double wd = 2.0 * kPi / o.drift_period;
  const double D[4] = {o.mean_offset + o.drift_amplitude, o.drift_amplitude * wd, o.drift_amplitude * wd * wd,
                       o.drift_amplitude * wd * wd * wd};
  double H[4], P[4];
  for (int m = 0; m < 4; ++m) {
    H[m] = o.heave_gain * E[m];
    P[m] = (o.pitch_gain + o.roll_gain) * G[m];
  }
  const double h2 = o.dt * o.dt / 6.0;
  const double tol_linear = h2 * (rampedJerkBound(H, o.ramp) + rampedJerkBound(D, o.ramp)) + kRoundingFloor;
  const double tol_angular = kRotationMargin * h2 * rampedJerkBound(P, o.ramp) + kRoundingFloor;
  double worst_linear = 0.0, worst_angular = 0.0;
  centralDifferenceErrors(s, worst_linear, worst_angular);
  EXPECT_LE(worst_linear, tol_linear);
  EXPECT_LE(worst_angular, tol_angular);
  // The comparison sees the motion: the rates are far above the tolerances.
  double v_max = 0.0, w_max = 0.0;
  for (const PoseSample& p : s) {
    v_max = std::max(v_max, p.twist.linear.norm());
    w_max = std::max(w_max, p.twist.angular.norm());
  }
  EXPECT_GT(v_max, 100.0 * tol_linear);
  EXPECT_GT(w_max, 100.0 * tol_angular);
}

TEST(StormMotion, CentralDifferenceErrorIsSecondOrder) {
  // Halving dt divides the differences' error by 4 (measured 4.00 for both): the twist is the
  // derivative of the poses, not off by a term of first order.
  double l1 = 0.0, a1 = 0.0, l2 = 0.0, a2 = 0.0;
  centralDifferenceErrors(generateStormMotion(everyMotion(0.02)), l1, a1);
  centralDifferenceErrors(generateStormMotion(everyMotion(0.01)), l2, a2);
  EXPECT_NEAR(l1 / l2, 4.0, kSecondOrderRatioTol);
  EXPECT_NEAR(a1 / a2, 4.0, kSecondOrderRatioTol);
}

// ---- (d) the still start ----------------------------------------------------------------------

TEST(StormMotion, FirstSampleIsTheStillPoseAtRest) {
  StormMotionOptions o = storm(9);
  o.yaw_deg = 25.0;
  o.mean_offset = 4.0;
  o.drift_amplitude = 3.0;
  o.duration = 10.0;
  const std::vector<PoseSample> s = generateStormMotion(o);
  ASSERT_FALSE(s.empty());
  const PoseSample& p = s.front();
  EXPECT_EQ(p.t, 0.0);
  EXPECT_TRUE(p.has_twist);
  const RigidPose still = RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, 25.0 * kDeg);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(p.pose.position[i], 0.0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(p.pose.orientation.coeffs()[i], still.orientation.coeffs()[i]);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(p.twist.linear[i], 0.0);
    EXPECT_EQ(p.twist.angular[i], 0.0);
  }
  // The next sample has moved (the ramp starts at once, smoothly).
  EXPECT_NE(s[1].pose.position.z(), 0.0);
  EXPECT_LT(std::abs(s[1].pose.position.z()), 1e-3);
}

// ---- conventions ------------------------------------------------------------------------------

TEST(StormMotion, DeckTiltsWithTheSurface) {
  // After the ramp: pitch = -pitch_gain g cos(heading - yaw), roll = roll_gain g sin(heading - yaw),
  // g the slope along the travel direction; so a surface rising toward the bow lifts the bow and
  // one rising to port lifts the port side.
  StormMotionOptions o = storm(11);
  o.heading_deg = 60.0;
  o.yaw_deg = 10.0;
  const StormMotion motion(o);
  int bow_checked = 0, port_checked = 0;
  for (double t = 30.0; t < 90.0; t += 0.7) {
    double slope = 0.0;
    for (const StormComponent& c : motion.components()) slope -= c.amplitude * c.k * std::sin(c.phase - c.omega * t);
    const double rel = (o.heading_deg - o.yaw_deg) * kDeg;
    const double gx = slope * std::cos(rel), gy = slope * std::sin(rel);
    const PoseSample p = motion.at(t);
    const Eigen::Matrix3d R = p.pose.orientation.toRotationMatrix();
    const double pitch = std::asin(-R(2, 0)), roll = std::atan2(R(2, 1), R(2, 2));
    EXPECT_NEAR(pitch, -o.pitch_gain * gx, kHandValueTol);
    EXPECT_NEAR(roll, o.roll_gain * gy, kHandValueTol);
    const double bow_rise = p.pose.apply(Eigen::Vector3d(10, 0, 0)).z() - p.pose.apply(Eigen::Vector3d(-10, 0, 0)).z();
    const double port_rise = p.pose.apply(Eigen::Vector3d(0, 10, 0)).z() - p.pose.apply(Eigen::Vector3d(0, -10, 0)).z();
    if (std::abs(gx) > 1e-3) {
      EXPECT_GT(bow_rise * gx, 0.0) << "t = " << t;
      ++bow_checked;
    }
    if (std::abs(gy) > 1e-3) {
      EXPECT_GT(port_rise * gy, 0.0) << "t = " << t;
      ++port_checked;
    }
    // Yaw stays at yaw_deg: the body x axis, projected on the horizontal, points there.
    const Eigen::Vector3d x_axis = R.col(0);
    EXPECT_NEAR(std::atan2(x_axis.y(), x_axis.x()), o.yaw_deg * kDeg, kHandValueTol);
  }
  EXPECT_GT(bow_checked, 20);
  EXPECT_GT(port_checked, 20);
}

TEST(StormMotion, OffsetAndDriftAlongTheOffsetHeading) {
  StormMotionOptions o = storm();
  o.hs = 1.0;
  o.mean_offset = 4.0;
  o.mean_offset_heading_deg = 210.0;
  o.drift_amplitude = 3.0;
  o.drift_period = 100.0;
  const StormMotion motion(o);
  const Eigen::Vector2d dir(std::cos(210.0 * kDeg), std::sin(210.0 * kDeg));
  for (double t : {25.0, 50.0, 75.0, 137.0}) {
    const Eigen::Vector3d p = motion.at(t).pose.position;
    const double expected = 4.0 + 3.0 * std::sin(2.0 * kPi * t / 100.0);
    EXPECT_NEAR(p.x(), expected * dir.x(), kHandValueTol);
    EXPECT_NEAR(p.y(), expected * dir.y(), kHandValueTol);
  }
}

TEST(StormMotion, PointVerticalSpeedFromTheTwistAndFromDifferences) {
  StormMotionOptions o = storm(2);
  o.duration = 60.0;
  o.dt = 0.01;
  const std::vector<PoseSample> s = generateStormMotion(o);
  const Eigen::Vector3d fairlead(45.0, 15.0, -8.0);
  double t_twist = 0.0, t_cd = 0.0;
  const double v_twist = maxPointVerticalSpeed(s, fairlead, &t_twist);
  std::vector<PoseSample> poses_only;
  for (const PoseSample& p : s) poses_only.emplace_back(p.t, p.pose);
  const double v_cd = maxPointVerticalSpeed(poses_only, fairlead, &t_cd);
  EXPECT_GT(v_twist, 1.0);            // Hs 4 m: metres per second at a fairlead 45 m forward
  EXPECT_NEAR(v_cd, v_twist, 1e-3 * v_twist);  // central differences at dt = 0.01 s: O(1e-5) relative
  EXPECT_NEAR(t_cd, t_twist, 0.011);
  // At the origin the vertical speed is the heave rate: the largest |vz| of the twist.
  double heave_rate = 0.0;
  for (const PoseSample& p : s)
    heave_rate = std::max(heave_rate, std::abs(motionFromBodyTwist(p.pose, p.twist).velocity.z()));
  EXPECT_NEAR(maxPointVerticalSpeed(s, Eigen::Vector3d::Zero()), heave_rate, 1e-15);
  EXPECT_EQ(maxPointVerticalSpeed({}, fairlead), 0.0);
}

// ---- (e) bad fields ---------------------------------------------------------------------------

TEST(StormMotion, EachBadFieldIsNamed) {
  const double nan = std::nan("");
  struct Case {
    const char* field;
    std::function<void(StormMotionOptions&)> set;
  };
  const std::vector<Case> cases = {
      {"hs", [](StormMotionOptions& o) { o.hs = 0.0; }},
      {"hs", [&](StormMotionOptions& o) { o.hs = nan; }},
      {"tp", [](StormMotionOptions& o) { o.tp = -9.0; }},
      {"gamma", [](StormMotionOptions& o) { o.gamma = 0.5; }},
      {"heading_deg", [&](StormMotionOptions& o) { o.heading_deg = nan; }},
      {"duration", [](StormMotionOptions& o) { o.duration = 0.0; }},
      {"dt", [](StormMotionOptions& o) { o.dt = 0.0; }},
      {"dt", [](StormMotionOptions& o) { o.dt = 1000.0; }},  // longer than the record
      {"dt", [](StormMotionOptions& o) { o.duration = 1e9; o.dt = 1e-3; }},  // too many samples
      {"components", [](StormMotionOptions& o) { o.components = 15; }},
      {"components", [](StormMotionOptions& o) { o.components = 10001; }},
      {"f_min_factor", [](StormMotionOptions& o) { o.f_min_factor = 1.0; }},
      {"f_max_factor", [](StormMotionOptions& o) { o.f_max_factor = 0.9; }},
      {"heave_gain", [](StormMotionOptions& o) { o.heave_gain = -1.0; }},
      {"pitch_gain", [](StormMotionOptions& o) { o.pitch_gain = -0.1; }},
      {"roll_gain", [&](StormMotionOptions& o) { o.roll_gain = nan; }},
      {"yaw_deg", [](StormMotionOptions& o) { o.yaw_deg = HUGE_VAL; }},
      {"mean_offset", [](StormMotionOptions& o) { o.mean_offset = -4.0; }},
      {"mean_offset_heading_deg", [&](StormMotionOptions& o) { o.mean_offset_heading_deg = nan; }},
      {"drift_amplitude", [](StormMotionOptions& o) { o.drift_amplitude = -3.0; }},
      {"drift_period", [](StormMotionOptions& o) { o.drift_period = 0.0; }},
      {"ramp", [](StormMotionOptions& o) { o.ramp = 0.0; }},
  };
  EXPECT_EQ(storm().validate(), "");
  for (const Case& c : cases) {
    StormMotionOptions o = storm();
    c.set(o);
    const std::string e = o.validate();
    const std::string prefix = std::string("storm.") + c.field + " = ";
    EXPECT_EQ(e.compare(0, prefix.size(), prefix), 0) << c.field << ": " << e;
    EXPECT_NE(e.find(": must"), std::string::npos) << e;  // the constraint follows the value
    EXPECT_THROW(generateStormMotion(o), std::invalid_argument) << c.field;
  }
  StormMotionOptions o = storm();
  o.gamma = 0.5;
  EXPECT_EQ(o.validate(), "storm.gamma = 0.5: must be finite and >= 1 (1 = Pierson-Moskowitz)");
}

}  // namespace

TEST(StormMotion, MooringStormSitsDownWaveWithADrift) {
  // The waves' mean drift force pushes the hull the way they travel: the offset points there.
  for (double heading : {30.0, 150.0, 300.0}) {
    const StormMotionOptions o = mooringStorm(6.0, 10.0, heading, 7, 120.0);
    EXPECT_EQ(o.validate(), "");
    EXPECT_EQ(o.hs, 6.0);
    EXPECT_EQ(o.tp, 10.0);
    EXPECT_EQ(o.seed, 7u);
    EXPECT_EQ(o.duration, 120.0);
    EXPECT_EQ(o.mean_offset, 4.0);
    EXPECT_EQ(o.drift_amplitude, 3.0);
    EXPECT_EQ(o.f_max_factor, 2.0);
    EXPECT_EQ(o.mean_offset_heading_deg, heading);
  }
}
