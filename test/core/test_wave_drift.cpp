// Wave drift on a hull (core/model/wave_drift.hpp), against closed forms:
//  * one regular wave: the drift is a^2 D at every instant, in both modes;
//  * two components: Newman's force is a1^2 D1 + a2^2 D2 + 2 a1 a2 sqrt(D1 D2) cos(dw t + phi),
//    the difference-frequency beat and nothing at the sum frequency;
//  * a 3-hour JONSWAP sea: the time average of the slowly varying force is the mean drift
//    sum a_i^2 D_i, and its standard deviation that of the double sum's closed form;
//  * the hull turned by 90 deg sees the waves from another heading (coefficients re-read).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include "mooring_dynamics/core/model/rao.hpp"
#include "mooring_dynamics/core/model/wave_drift.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

using namespace mooring_dynamics::core;
using C = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDepth = 200.0;
constexpr double kG = 9.80665;

/// Closed forms evaluated in another order of summation: rounding only.
constexpr double kClosedFormRelTol = 1e-9;
/// The time average of the difference-frequency sum over 3 hours: the cross terms of 300
/// components whose differences are >= 1/(3 h) apart average to a few tenths of a percent of the
/// mean; 2 % leaves room for the slowest pairs.
constexpr double kTimeAverageRelTol = 0.02;

/// Drift coefficients of a made-up hull [N/m^2, N m/m^2]: surge pushes along the waves (negative
/// for head seas at 180 deg), sway with sin(beta), growing with omega^2.
RaoTable driftTable() {
  std::vector<double> omega, headings;
  for (double w = 0.1; w <= 3.0 + 1e-9; w += 0.05) omega.push_back(w);
  for (int h = 0; h < 360; h += 15) headings.push_back(h);
  std::array<std::vector<C>, 6> v;
  for (auto& d : v) d.resize(omega.size() * headings.size());
  for (std::size_t ih = 0; ih < headings.size(); ++ih)
    for (std::size_t iw = 0; iw < omega.size(); ++iw) {
      const double b = headings[ih] * kPi / 180.0, w2 = omega[iw] * omega[iw];
      const std::size_t k = ih * omega.size() + iw;
      v[0][k] = 4.0e4 * w2 * std::cos(b);
      v[1][k] = 9.0e4 * w2 * std::sin(b);
      v[5][k] = 2.0e5 * w2 * std::sin(2.0 * b);
    }
  return RaoTable(omega, headings, v);
}

/// The table's value at a tabulated (omega, heading): the closed forms use the definition above.
Eigen::Vector3d exactD(double w, double beta_deg) {
  const double b = beta_deg * kPi / 180.0;
  return Eigen::Vector3d(4.0e4 * w * w * std::cos(b), 9.0e4 * w * w * std::sin(b), 2.0e5 * w * w * std::sin(2.0 * b));
}

WaveSpec irregular(int n, double direction_deg) {
  WaveSpec s;
  s.type = WaveSpec::Type::Jonswap;
  s.hs = 4.0;
  s.tp = 9.0;
  s.components = n;
  s.seed = 7;
  s.direction = direction_deg * kPi / 180.0;
  s.random_frequencies = true;
  s.f_max_factor = 3.0;
  return s;
}

}  // namespace

TEST(WaveDrift, RegularWaveIsTheMeanDriftAtEveryInstant) {
  WaveSpec s;
  s.type = WaveSpec::Type::Regular;
  s.height = 3.0;
  s.period = 2.0 * kPi / 0.6;  // omega 0.6: a tabulated frequency
  s.direction = kPi;            // head seas for a hull at yaw 0
  const WaveField sea(s, kDepth, kG);
  const RaoTable table = driftTable();
  const Eigen::Vector3d expected = 1.5 * 1.5 * exactD(0.6, 180.0);
  for (bool newman : {true, false}) {
    WaveDrift drift(sea, table, newman);
    for (double t : {0.0, 1.3, 7.7, 55.0}) {
      const Eigen::Vector3d f = drift.force(t, RigidPose(), Eigen::Vector3d(12.0, -3.0, 0.0));
      EXPECT_NEAR(f.x(), expected.x(), kClosedFormRelTol * std::abs(expected.x())) << "newman " << newman;
      EXPECT_NEAR(f.y(), 0.0, 1e-6 * std::abs(expected.x()));
    }
    EXPECT_LT(expected.x(), 0.0);  // head seas push the hull aft
  }
}

TEST(WaveDrift, TwoComponentsBeatAtTheDifferenceFrequencyOnly) {
  const WaveField sea(irregular(2, 150.0), kDepth, kG);
  const std::vector<WaveComponent>& c = sea.components();
  ASSERT_EQ(c.size(), 2u);
  const RaoTable table = driftTable();
  WaveDrift drift(sea, table, true);
  const double beta = 150.0;
  const Eigen::Vector3d xref(5.0, 20.0, 0.0);
  // The coefficients at the components' frequencies: linear in omega between tabulated ones
  // (150 deg is a tabulated heading).
  auto interp = [&](double w) {
    const double w0 = 0.1 + 0.05 * std::floor((w - 0.1) / 0.05);
    const double f = (w - w0) / 0.05;
    return Eigen::Vector3d((1.0 - f) * exactD(w0, beta) + f * exactD(w0 + 0.05, beta));
  };
  const Eigen::Vector3d d1 = interp(c[0].omega), d2 = interp(c[1].omega);
  auto phaseAt = [&](const WaveComponent& w, double t) {
    return w.omega * t - w.k * (xref.x() * std::cos(w.direction) + xref.y() * std::sin(w.direction)) - w.phase;
  };
  for (double t : {0.0, 3.0, 40.0, 333.3}) {
    const Eigen::Vector3d f = drift.force(t, RigidPose(), xref);
    for (int k = 0; k < 3; ++k) {
      const double a1 = c[0].amplitude, a2 = c[1].amplitude;
      // T_12 + T_21 with T_ij = sgn(D_j) sqrt|D_i D_j|: (sgn D_1 + sgn D_2) sqrt|D_1 D_2|.
      const double sgn_sum = (d1[k] < 0.0 ? -1.0 : 1.0) + (d2[k] < 0.0 ? -1.0 : 1.0);
      const double sym = sgn_sum * a1 * a2 * std::sqrt(std::abs(d1[k] * d2[k])) *
                         std::cos(phaseAt(c[0], t) - phaseAt(c[1], t));
      const double expected = a1 * a1 * d1[k] + a2 * a2 * d2[k] + sym;
      EXPECT_NEAR(f[k], expected, 1e-6 * (std::abs(a1 * a1 * d1[k]) + std::abs(a2 * a2 * d2[k])))
          << "dof " << k << " t " << t;
    }
  }
}

TEST(WaveDrift, ThreeHourAverageIsTheMeanDrift) {
  const WaveField sea(irregular(300, 160.0), kDepth, kG);
  const RaoTable table = driftTable();
  WaveDrift slow(sea, table, true);
  WaveDrift mean(sea, table, false);
  const Eigen::Vector3d fm = mean.force(1000.0, RigidPose(), Eigen::Vector3d::Zero());
  EXPECT_TRUE(fm.isApprox(slow.meanForce(0.0), kClosedFormRelTol));
  // The closed-form mean: sum a_i^2 D_i with D from the definition (interpolation error < 1 %
  // at 0.05 rad/s steps of a quadratic in omega is covered by the tolerance).
  Eigen::Vector3d by_hand = Eigen::Vector3d::Zero();
  for (const WaveComponent& c : sea.components())
    by_hand += c.amplitude * c.amplitude * exactD(c.omega, c.direction * 180.0 / kPi);
  for (int k : {0, 1}) EXPECT_NEAR(fm[k], by_hand[k], kTimeAverageRelTol * std::abs(by_hand[k])) << k;
  const double dt = 0.5, duration = 10800.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  long n = 0;
  for (double t = 0.0; t < duration; t += dt, ++n) sum += slow.force(t, RigidPose(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d avg = sum / static_cast<double>(n);
  for (int k : {0, 1}) EXPECT_NEAR(avg[k], fm[k], kTimeAverageRelTol * std::abs(fm[k])) << "dof " << k;
}

TEST(WaveDrift, TurningTheHullChangesTheRelativeHeading) {
  WaveSpec s;
  s.type = WaveSpec::Type::Regular;
  s.height = 2.0;
  s.period = 2.0 * kPi / 0.8;
  s.direction = kPi / 2.0;  // waves travel toward +y
  const WaveField sea(s, kDepth, kG);
  const RaoTable table = driftTable();
  WaveDrift drift(sea, table, false);
  // Hull at yaw 0: beam seas from starboard (beta 90): pure sway. Turned to yaw 90 deg: following seas.
  const Eigen::Vector3d beam = drift.force(0.0, RigidPose(), Eigen::Vector3d::Zero());
  const RigidPose turned = RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, kPi / 2.0);
  const Eigen::Vector3d following = drift.force(0.0, turned, Eigen::Vector3d::Zero());
  const Eigen::Vector3d d90 = exactD(0.8, 90.0), d0 = exactD(0.8, 0.0);
  EXPECT_NEAR(beam.y(), d90.y(), kClosedFormRelTol * std::abs(d90.y()));
  EXPECT_NEAR(following.x(), d0.x(), kClosedFormRelTol * std::abs(d0.x()));
  EXPECT_NEAR(following.y(), 0.0, 1e-9 * std::abs(d0.x()));
}
