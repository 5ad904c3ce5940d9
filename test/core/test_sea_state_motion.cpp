// Hull motion from RAOs and a sea state (core/model/sea_state_motion.hpp), against what the RAO
// means independently of the code that applies it:
//  * one regular wave: the heave and pitch of the poses (read back from the pose, not from the
//    motion sums) have the RAO's amplitude and phase relative to the elevation that WaveField
//    gives at the reference point, to 0.5 % (issue "Design storms", Checks);
//  * a 3-hour JONSWAP sea: the variance (m0) of heave, surge and pitch of the record against
//    integral |X(f)|^2 S(f) df of an analytic RAO and jonswapSpectrum, to 3 %;
//  * the twist against central differences of the poses;
//  * a sea with energy outside the table is an error naming the band.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/rao.hpp"
#include "mooring_dynamics/core/model/sea_state_motion.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

using namespace mooring_dynamics::core;
using C = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kG = 9.80665;
constexpr double kDepth = 200.0;

// Tolerances (one-line reasons).
/// The bound for a regular wave's amplitude and phase (a fit over whole periods is exact
/// up to rounding, so this checks the conventions, not the fit).
constexpr double kRegularRelTol = 0.005;
/// 0.5 % of a radian of phase.
constexpr double kRegularPhaseTol = 0.005;
/// The bound on m0 over 3 hours. Sources of difference: the 200-component discretisation
/// and Hs rescaling of WaveField (< 0.5 %), linear interpolation of the tabulated RAO (< 0.5 %
/// with 0.02 rad/s steps), and the cross terms of the finite record (~1 %).
constexpr double kM0RelTol = 0.03;
/// Central differences over +-1 ms of motions with periods >= 3 s: truncation ~ (w dt)^2 / 6.
constexpr double kTwistRelTol = 1e-4;

/// Analytic RAOs of a made-up hull (rad/m for rotations), smooth in omega, and the same for
/// every heading (a hull that does not care where the waves come from keeps the check simple).
std::array<C, 6> analyticRao(double w) {
  const C heave = 1.0 / C(1.0 - (w / 0.6) * (w / 0.6), 2.0 * 0.2 * w / 0.6);
  const C pitch = C(0.0, 0.5 * w * w / kG) / C(1.0 - (w / 0.5) * (w / 0.5), 2.0 * 0.3 * w / 0.5);
  const C surge = C(0.0, -0.8) / C(1.0 + w * w, 0.0);
  return {surge, 0.1 * surge, heave, 0.2 * pitch, pitch, 0.05 * pitch};
}

RaoTable analyticTable(double w_lo = 0.1, double w_hi = 3.0, double dw = 0.02) {
  std::vector<double> omega, headings;
  for (double w = w_lo; w <= w_hi + 1e-9; w += dw) omega.push_back(w);
  for (int h = 0; h < 360; h += 30) headings.push_back(h);
  std::array<std::vector<C>, 6> v;
  for (std::size_t ih = 0; ih < headings.size(); ++ih)
    for (double w : omega) {
      const std::array<C, 6> x = analyticRao(w);
      for (int d = 0; d < 6; ++d) v[d].push_back(x[d]);
    }
  return RaoTable(omega, headings, v);
}

/// The hull: mean position off the origin, yawed 30 deg, RAO reference point ahead of the origin.
RigidPose meanPose() { return RigidPose::fromRollPitchYaw(Eigen::Vector3d(100.0, 50.0, 0.0), 0.0, 0.0, 30.0 * kDeg); }
const Eigen::Vector3d kRef(12.0, 0.0, -2.0);

/// Pitch of the pose relative to the mean hull (R = R_0 Rz Ry Rx; R_0^T R (2,0) = -sin(pitch)).
double relativePitch(const RigidPose& p) {
  const Eigen::Matrix3d rel =
      meanPose().orientation.toRotationMatrix().transpose() * p.orientation.toRotationMatrix();
  return std::asin(-rel(2, 0));
}
/// The reference point's displacement from its mean place, in the mean hull axes.
Eigen::Vector3d refDisplacement(const RigidPose& p) {
  const RigidPose m = meanPose();
  return m.orientation.conjugate() * (p.apply(kRef) - m.apply(kRef));
}

/// Complex amplitude of x(t) at frequency w over whole periods: (2/N) sum x e^{-i w t}.
C fourier(const std::vector<double>& x, const std::vector<double>& t, double w) {
  C s(0.0, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) s += x[i] * std::exp(C(0.0, -w * t[i]));
  return 2.0 * s / static_cast<double>(x.size());
}

/// Integral of |X(2 pi f)|^2 S(f) over (0, 1 Hz], composite Simpson (S beyond: negligible).
double responseM0(int dof, double hs, double tp, double gamma) {
  const int n = 200000;
  const double f1 = 1.0, h = f1 / n;
  double sum = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double f = i * h;
    const double y = std::norm(analyticRao(2.0 * kPi * f)[dof]) * jonswapSpectrum(f, hs, tp, gamma);
    sum += (i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * y;
  }
  return sum * h / 3.0;
}

}  // namespace

TEST(SeaStateMotion, RegularWaveHeaveAndPitchHaveTheRaosAmplitudeAndPhase) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Regular;
  spec.height = 2.0;
  spec.period = 2.0 * kPi / 0.62;             // a tabulated frequency (0.1 + 26 x 0.02)
  spec.direction = (30.0 + 150.0) * kDeg;    // 150 deg relative to the hull yawed 30 deg
  const WaveField sea(spec, kDepth, kG);
  const RaoTable raos = analyticTable();
  const SeaStateMotion motion(sea, raos, meanPose(), kRef);
  const double w = 2.0 * kPi / spec.period;
  std::vector<double> t, eta, heave, pitch, surge;
  const int per_period = 64, periods = 20;
  for (int i = 0; i < per_period * periods; ++i) {
    const double ti = i * spec.period / per_period;
    const PoseSample s = motion.at(ti);
    const Eigen::Vector3d ref_mean = meanPose().apply(kRef);
    t.push_back(ti);
    eta.push_back(sea.elevation(ref_mean.x(), ref_mean.y(), ti));
    heave.push_back(refDisplacement(s.pose).z());
    surge.push_back(refDisplacement(s.pose).x());
    pitch.push_back(relativePitch(s.pose));
  }
  const C z_eta = fourier(eta, t, w);
  ASSERT_NEAR(std::abs(z_eta), 1.0, kRegularRelTol) << "the wave's amplitude is H / 2";
  const std::array<C, 6> want = raos.at(w, 150.0);
  for (const auto& [name, dof, series] : {std::tuple<const char*, int, const std::vector<double>*>{"heave", 2, &heave},
                                          {"pitch", 4, &pitch}, {"surge", 0, &surge}}) {
    const C got = fourier(*series, t, w) / z_eta;  // the response per unit elevation, phase relative to it
    EXPECT_NEAR(std::abs(got) / std::abs(want[dof]), 1.0, kRegularRelTol) << name;
    EXPECT_NEAR(std::arg(got / want[dof]), 0.0, kRegularPhaseTol) << name << ": phase lead";
  }
}

TEST(SeaStateMotion, ThreeHourRecordsVarianceIsRaoSquaredTimesTheSpectrum) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Jonswap;
  spec.hs = 4.0;
  spec.tp = 9.0;
  spec.gamma = 3.3;
  spec.components = 200;
  spec.seed = 7;
  spec.direction = 200.0 * kDeg;
  const WaveField sea(spec, kDepth, kG);
  const SeaStateMotion motion(sea, analyticTable(), meanPose(), kRef);
  const double duration = 3.0 * 3600.0, dt = 0.5;
  std::array<double, 3> s{}, ss{};
  long n = 0;
  for (double ti = 0.0; ti <= duration; ti += dt, ++n) {
    const PoseSample p = motion.at(ti);
    const Eigen::Vector3d d = refDisplacement(p.pose);
    const std::array<double, 3> x{d.x(), d.z(), relativePitch(p.pose)};
    for (int k = 0; k < 3; ++k) {
      s[k] += x[k];
      ss[k] += x[k] * x[k];
    }
  }
  const std::array<int, 3> dofs{0, 2, 4};
  const std::array<const char*, 3> names{"surge", "heave", "pitch"};
  for (int k = 0; k < 3; ++k) {
    const double var = ss[k] / n - (s[k] / n) * (s[k] / n);
    const double m0 = responseM0(dofs[k], spec.hs, spec.tp, spec.gamma);
    EXPECT_NEAR(var / m0, 1.0, kM0RelTol) << names[k] << ": record " << var << ", integral " << m0;
  }
}

TEST(SeaStateMotion, TwistIsTheDerivativeOfThePoses) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Jonswap;
  spec.hs = 6.0;
  spec.tp = 10.0;
  spec.direction = 80.0 * kDeg;
  spec.ramp = 20.0;
  const WaveField sea(spec, kDepth, kG);
  const SeaStateMotion motion(sea, analyticTable(), meanPose(), kRef);
  const double h = 1e-3;
  for (double ti : {5.0, 33.3, 71.0}) {
    const PoseSample s = motion.at(ti), a = motion.at(ti - h), b = motion.at(ti + h);
    const Eigen::Vector3d v_fd = (b.pose.position - a.pose.position) / (2.0 * h);
    const Eigen::Vector3d v = s.pose.orientation * s.twist.linear;
    EXPECT_LE((v - v_fd).norm(), kTwistRelTol * v.norm() + 1e-9) << "t = " << ti;
    // Angular velocity: R^T dR/dt ~ the skew matrix of the body rate.
    const Eigen::Matrix3d dr = (b.pose.orientation.toRotationMatrix() - a.pose.orientation.toRotationMatrix()) / (2.0 * h);
    const Eigen::Matrix3d skew = s.pose.orientation.toRotationMatrix().transpose() * dr;
    const Eigen::Vector3d w_fd(skew(2, 1), skew(0, 2), skew(1, 0));
    EXPECT_LE((s.twist.angular - w_fd).norm(), kTwistRelTol * s.twist.angular.norm() + 1e-9) << "t = " << ti;
  }
  /// The still start: r(0) = 0 leaves p_0 + R_0 r - R_0 r, the mean position up to rounding.
  constexpr double kStillStartTol = 1e-12;
  EXPECT_LE((motion.at(0.0).pose.position - meanPose().position).norm(), kStillStartTol) << "the ramp starts from the mean pose";
}

TEST(SeaStateMotion, EnergyOutsideTheTableIsAnErrorNamingTheBand) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Jonswap;
  spec.hs = 4.0;
  spec.tp = 9.0;
  const WaveField sea(spec, kDepth, kG);  // 0.5 fp .. 4 fp: 0.35 to 2.8 rad/s
  try {
    SeaStateMotion(sea, analyticTable(0.5, 2.0), meanPose(), kRef);
    FAIL() << "accepted a sea wider than the table";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("outside the RAO table's 0.5 to 2 rad/s"), std::string::npos) << m;
    EXPECT_NE(m.find("raos.extend: zero or hold"), std::string::npos) << m;
  }
  RaoTable held = analyticTable(0.5, 2.0);
  held.extend = RaoExtend::Hold;
  EXPECT_NO_THROW(SeaStateMotion(sea, held, meanPose(), kRef));
}
