// Linear waves: dispersion relation, spectra, realized seas and their kinematics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/waves.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

// Tolerances (one-line reasons).
/// Newton on the dispersion relation converges to a few ulps of omega^2.
constexpr double kDispersionResidualTol = 1e-12;
/// Shallow-water limit: k h tanh(k h) = x gives k h = sqrt(x) (1 + x/6 + ...); x ~ 1e-5 below.
constexpr double kShallowLimitTol = 1e-5;
/// Closed-form kinematics vs. the same formulas written out: only rounding differs.
constexpr double kHandValueTol = 1e-12;
/// Central differences with step kFdStep: truncation ~ (k step)^2 / 6 relative, far below this.
constexpr double kFdRelTol = 1e-6;
constexpr double kFdStep = 1e-3;
/// elevationRate and w(z = 0) are the same sum, evaluated separately: rounding only.
constexpr double kKinematicTol = 1e-12;
/// Sample variance of a 3 h record of a 200-component sea vs. its exact variance: the record is
/// ~19 repeat periods (1/df = 571 s), cross terms between components average out to ~1%.
constexpr double kRealizedHsRelTol = 0.03;
/// Numerical integral of S(f) on a fine grid up to 20 fp (PM tail beyond: 8e-6 of m0).
constexpr double kSpectrumIntegralRelTol = 1e-4;

WaveSpec regular(double height, double period, double direction_deg = 0.0) {
  WaveSpec s;
  s.type = WaveSpec::Type::Regular;
  s.height = height;
  s.period = period;
  s.direction = direction_deg * kPi / 180.0;
  return s;
}

WaveSpec jonswap(double hs, double tp, double gamma = 3.3, std::uint32_t seed = 1) {
  WaveSpec s;
  s.type = WaveSpec::Type::Jonswap;
  s.hs = hs;
  s.tp = tp;
  s.gamma = gamma;
  s.seed = seed;
  return s;
}

double dispersionResidual(double omega, double k, double h) {
  return std::abs(kG * k * std::tanh(k * h) - omega * omega) / (omega * omega);
}

/// Integral of S over (0, 20 fp) by composite Simpson on a uniform grid.
template <class F>
double integrate(F s, double fp) {
  const double b = 20.0 * fp;
  const int n = 200000;
  const double h = b / n;
  double sum = s(b);  // s(0) = 0
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * s(i * h);
  return sum * h / 3.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Dispersion

TEST(Waves, DispersionResidualFromShallowToDeep) {
  for (double h : {0.5, 5.0, 50.0, 500.0, 5000.0})
    for (double omega : {1e-3, 0.05, 0.3, 1.0, 3.0, 10.0, 30.0}) {
      const double k = waveNumber(omega, h, kG);
      ASSERT_TRUE(std::isfinite(k) && k > 0.0) << "h " << h << " omega " << omega;
      EXPECT_LT(dispersionResidual(omega, k, h), kDispersionResidualTol) << "h " << h << " omega " << omega;
    }
  EXPECT_EQ(waveNumber(0.0, 100.0, kG), 0.0);
  EXPECT_THROW(waveNumber(1.0, 0.0, kG), std::invalid_argument);
  EXPECT_THROW(waveNumber(1.0, 10.0, -1.0), std::invalid_argument);
}

TEST(Waves, DispersionLimits) {
  // Deep: k h = 1e4 -> tanh = 1 exactly in double.
  const double omega = 2.0;
  EXPECT_NEAR(waveNumber(omega, 5000.0, kG) / (omega * omega / kG), 1.0, kDispersionResidualTol);
  // Shallow: x = omega^2 h / g = 1e-5.
  const double h = 1.0, w = std::sqrt(1e-5 * kG / h);
  EXPECT_NEAR(waveNumber(w, h, kG) / (w / std::sqrt(kG * h)), 1.0, kShallowLimitTol);
  // Intermediate, from wave tables: T = 10 s, h = 50 m: h/L0 = 0.320 -> h/L = 0.3305, L = 151.3 m
  // (deep water L0 = g T^2 / 2 pi = 156.1 m).
  const double k = waveNumber(2.0 * kPi / 10.0, 50.0, kG);
  EXPECT_NEAR(2.0 * kPi / k, 151.3, 0.05);
}

// ---------------------------------------------------------------------------------------------
// Regular waves

TEST(Waves, RegularDeepWaterHandValues) {
  // H = 2 m, T = 5 s in 1000 m of water: deep (k h = 161): k = omega^2/g, u = a omega e^{kz}.
  const WaveField wf(regular(2.0, 5.0), 1000.0, kG);
  ASSERT_EQ(wf.components().size(), 1u);
  const double omega = 2.0 * kPi / 5.0, k = omega * omega / kG, lambda = 2.0 * kPi / k;
  EXPECT_NEAR(wf.components()[0].k, k, 1e-12 * k);
  EXPECT_NEAR(lambda, 39.0327, 1e-3);  // g T^2 / (2 pi)
  EXPECT_NEAR(wf.elevation(0, 0, 0), 1.0, kHandValueTol);          // crest at the origin at t = 0
  EXPECT_NEAR(wf.elevation(lambda / 4, 0, 0), 0.0, kHandValueTol);  // mean level, crest approaching
  EXPECT_NEAR(wf.elevation(0, 0, 2.5), -1.0, kHandValueTol);        // trough half a period later
  EXPECT_NEAR(wf.elevation(0, 123.0, 0), 1.0, kHandValueTol);        // long-crested along y
  double vx, vy, vz;
  wf.velocity(0, 0, 0, 0, vx, vy, vz);  // under the crest: u = a omega, w = 0
  EXPECT_NEAR(vx, omega, kHandValueTol);
  EXPECT_NEAR(vy, 0.0, kHandValueTol);
  EXPECT_NEAR(vz, 0.0, kHandValueTol);
  wf.velocity(0, 0, -lambda / 2, 0, vx, vy, vz);  // half a wavelength down: e^{-pi}
  EXPECT_NEAR(vx, omega * std::exp(-kPi), kHandValueTol);
  // A quarter wavelength ahead of the crest, which approaches: the surface rises at its fastest,
  // w = dEta/dt = a omega, u = 0.
  wf.velocity(lambda / 4, 0, 0, 0, vx, vy, vz);
  EXPECT_NEAR(vx, 0.0, kHandValueTol);
  EXPECT_NEAR(vz, omega, kHandValueTol);
  EXPECT_NEAR(wf.elevationRate(lambda / 4, 0, 0), omega, kHandValueTol);
  double ax, ay, az;
  wf.acceleration(0, 0, 0, 0, ax, ay, az);  // under the crest: a_x = 0, a_z = -a omega^2
  EXPECT_NEAR(ax, 0.0, kHandValueTol);
  EXPECT_NEAR(az, -omega * omega, kHandValueTol);
}

TEST(Waves, RegularFiniteDepthAndDirection) {
  // H = 3 m, T = 8 s, h = 30 m, travelling toward 90 deg (north).
  const double h = 30.0, a = 1.5, omega = 2.0 * kPi / 8.0;
  const WaveField wf(regular(3.0, 8.0, 90.0), h, kG);
  const double k = waveNumber(omega, h, kG);
  const double x = 7.0, y = 11.0, z = -12.0, t = 3.0;
  const double th = k * y - omega * t;  // direction +y
  EXPECT_NEAR(wf.elevation(x, y, t), a * std::cos(th), kHandValueTol);
  EXPECT_NEAR(wf.elevationRate(x, y, t), a * omega * std::sin(th), kHandValueTol);
  double vx, vy, vz;
  wf.velocity(x, y, z, t, vx, vy, vz);
  EXPECT_NEAR(vx, 0.0, kHandValueTol);
  EXPECT_NEAR(vy, a * omega * std::cosh(k * (z + h)) / std::sinh(k * h) * std::cos(th), kHandValueTol);
  EXPECT_NEAR(vz, a * omega * std::sinh(k * (z + h)) / std::sinh(k * h) * std::sin(th), kHandValueTol);
  double ax, ay, az;
  wf.acceleration(x, y, z, t, ax, ay, az);
  EXPECT_NEAR(ay, a * omega * omega * std::cosh(k * (z + h)) / std::sinh(k * h) * std::sin(th), kHandValueTol);
  EXPECT_NEAR(az, -a * omega * omega * std::sinh(k * (z + h)) / std::sinh(k * h) * std::cos(th), kHandValueTol);

  // Above the mean surface: the values at z = 0; below the bottom: those at z = -h (w = 0 there).
  double ux0, uy0, uz0, ux1, uy1, uz1;
  wf.velocity(x, y, 0.0, t, ux0, uy0, uz0);
  wf.velocity(x, y, 1.2, t, ux1, uy1, uz1);
  EXPECT_EQ(uy0, uy1);
  EXPECT_EQ(uz0, uz1);
  wf.velocity(x, y, -h, t, ux0, uy0, uz0);
  wf.velocity(x, y, -h - 5.0, t, ux1, uy1, uz1);
  EXPECT_EQ(uy0, uy1);
  EXPECT_NEAR(uz0, 0.0, kHandValueTol);
}

TEST(Waves, DeepWaterNoOverflowAndBranchesAgree) {
  // T = 1 s in 5000 m: k h ~ 2e4, cosh(k h) overflows; the exp form must give a omega e^{kz}.
  const WaveField wf(regular(0.2, 1.0), 5000.0, kG);
  const double omega = 2.0 * kPi, k = omega * omega / kG;
  double vx, vy, vz;
  for (double z : {0.0, -0.5, -3.0, -100.0, -4999.0, -5000.0}) {
    wf.velocity(0, 0, z, 0, vx, vy, vz);
    ASSERT_TRUE(std::isfinite(vx) && std::isfinite(vz)) << z;
    EXPECT_NEAR(vx, 0.1 * omega * std::exp(k * z), kHandValueTol) << z;
  }
  // Either side of the k h = 20 switch, both forms equal cosh(k(z+h))/sinh(kh) (long double here).
  for (double kh : {19.999, 20.001}) {
    const double h = 10.0, omega2 = std::sqrt(kG * (kh / h) * std::tanh(kh));
    WaveSpec s = regular(2.0, 2.0 * kPi / omega2);
    const WaveField f(s, h, kG);
    const double kk = f.components()[0].k;
    for (double z : {0.0, -1.0, -5.0, -10.0}) {
      f.velocity(0, 0, z, 0, vx, vy, vz);
      const long double ref = omega2 * std::cosh(static_cast<long double>(kk) * (z + h)) /
                              std::sinh(static_cast<long double>(kk) * h);
      EXPECT_NEAR(vx, static_cast<double>(ref), 1e-13 * omega2) << kh << " " << z;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Kinematic consistency (random, oblique, finite-depth sea)

TEST(Waves, ContinuityByFiniteDifferences) {
  for (double h : {25.0, 3000.0}) {  // intermediate depth, and deep (exp branch for most components)
    WaveSpec s = jonswap(3.0, 9.0);
    s.components = 40;
    s.direction = 30.0 * kPi / 180.0;
    const WaveField wf(s, h, kG);
    for (double z : {-0.5, -4.0, -12.0, -20.0})
      for (double t : {0.0, 17.3, 101.0}) {
        const double x = 3.0, y = -2.0, e = kFdStep;
        double xp[3], xm[3], yp[3], ym[3], zp[3], zm[3];
        wf.velocity(x + e, y, z, t, xp[0], xp[1], xp[2]);
        wf.velocity(x - e, y, z, t, xm[0], xm[1], xm[2]);
        wf.velocity(x, y + e, z, t, yp[0], yp[1], yp[2]);
        wf.velocity(x, y - e, z, t, ym[0], ym[1], ym[2]);
        wf.velocity(x, y, z + e, t, zp[0], zp[1], zp[2]);
        wf.velocity(x, y, z - e, t, zm[0], zm[1], zm[2]);
        const double dudx = (xp[0] - xm[0]) / (2 * e);
        const double dvdy = (yp[1] - ym[1]) / (2 * e);
        const double dwdz = (zp[2] - zm[2]) / (2 * e);
        const double scale = std::abs(dudx) + std::abs(dvdy) + std::abs(dwdz) + 1e-12;
        EXPECT_LT(std::abs(dudx + dvdy + dwdz), kFdRelTol * scale + 1e-10)
            << "h " << h << " z " << z << " t " << t << " terms " << dudx << " " << dvdy << " " << dwdz;
        EXPECT_GT(std::abs(dwdz), 1e-4);  // not trivially zero
      }
  }
}

TEST(Waves, SurfaceKinematicCondition) {
  WaveSpec s = jonswap(3.0, 9.0);
  s.direction = -60.0 * kPi / 180.0;
  const WaveField wf(s, 40.0, kG);
  for (double t : {0.0, 3.7, 250.0, 1000.5}) {
    const double x = 12.0, y = 5.0;
    double vx, vy, vz;
    wf.velocity(x, y, 0.0, t, vx, vy, vz);
    const double rate = wf.elevationRate(x, y, t);
    EXPECT_NEAR(rate, vz, kKinematicTol * (1.0 + std::abs(vz))) << t;
    const double fd = (wf.elevation(x, y, t + kFdStep) - wf.elevation(x, y, t - kFdStep)) / (2 * kFdStep);
    EXPECT_NEAR(rate, fd, kFdRelTol * (1.0 + std::abs(rate))) << t;
  }
}

TEST(Waves, AccelerationIsTimeDerivativeOfVelocity) {
  WaveSpec s = jonswap(3.0, 9.0);
  s.direction = 45.0 * kPi / 180.0;
  s.ramp = 30.0;
  const WaveField wf(s, 60.0, kG);
  for (double t : {5.0, 15.0, 29.0, 40.0, 400.0})  // during the ramp (dR/dt terms) and after
    for (double z : {0.0, -3.0, -30.0}) {
      double ax, ay, az, p[3], m[3];
      wf.acceleration(1.0, 2.0, z, t, ax, ay, az);
      wf.velocity(1.0, 2.0, z, t + kFdStep, p[0], p[1], p[2]);
      wf.velocity(1.0, 2.0, z, t - kFdStep, m[0], m[1], m[2]);
      const double fd[3] = {(p[0] - m[0]) / (2 * kFdStep), (p[1] - m[1]) / (2 * kFdStep),
                            (p[2] - m[2]) / (2 * kFdStep)};
      const double a[3] = {ax, ay, az};
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(a[i], fd[i], kFdRelTol * (1.0 + std::abs(a[i]))) << "t " << t << " z " << z << " i " << i;
      const double rate = wf.elevationRate(1.0, 2.0, t);
      const double efd = (wf.elevation(1.0, 2.0, t + kFdStep) - wf.elevation(1.0, 2.0, t - kFdStep)) / (2 * kFdStep);
      EXPECT_NEAR(rate, efd, kFdRelTol * (1.0 + std::abs(rate))) << t;
    }
}

TEST(Waves, RampStartsFromRest) {
  WaveSpec s = regular(2.0, 10.0);
  s.ramp = 20.0;
  const WaveField ramped(s, 100.0, kG);
  s.ramp = 0.0;
  const WaveField full(s, 100.0, kG);
  EXPECT_EQ(ramped.elevation(0, 0, 0.0), 0.0);
  EXPECT_EQ(ramped.elevation(0, 0, -5.0), 0.0);
  EXPECT_NEAR(ramped.elevation(0, 0, 10.0), 0.5 * full.elevation(0, 0, 10.0), kHandValueTol);
  EXPECT_EQ(ramped.elevation(0, 0, 25.0), full.elevation(0, 0, 25.0));
  double vx, vy, vz;
  ramped.velocity(0, 0, -1.0, 0.0, vx, vy, vz);
  EXPECT_EQ(vx, 0.0);
  EXPECT_EQ(vz, 0.0);
}

// The wave follower's one-pass elevation and rate: the elevation is elevation()'s bit for bit,
// the rate its time derivative (central differences), before,
// during and after the ramp, on a random sea travelling at an angle.
TEST(Waves, ElevationAndRateInOnePass) {
  WaveSpec s;
  s.type = WaveSpec::Type::PiersonMoskowitz;
  s.hs = 9.8;
  s.tp = 16.0;
  s.direction = 0.4;
  s.ramp = 20.0;
  const WaveField f(s, 1860.0, kG);
  constexpr double kStep = 1e-4;        // [s]
  // [m/s]: step^2 times the third derivative (~1e-8), and at the ramp's ends, where R'' jumps by
  // (pi / ramp)^2 / 2 = 0.012 1/s^2, step / 2 times that times the elevation (~1.5e-6).
  constexpr double kRateTol = 1e-5;
  for (double t : {-1.0, 0.0, 3.7, 19.9, 20.0, 250.3}) {
    double eta, rate;
    f.elevationAndRate(120.0, -35.0, t, eta, rate);
    EXPECT_EQ(eta, f.elevation(120.0, -35.0, t)) << "t " << t;
    EXPECT_EQ(rate, f.elevationRate(120.0, -35.0, t)) << "t " << t;
    const double fd = (f.elevation(120.0, -35.0, t + kStep) - f.elevation(120.0, -35.0, t - kStep)) / (2.0 * kStep);
    EXPECT_NEAR(rate, fd, kRateTol) << "t " << t;
  }
  double eta = 1.0, rate = 1.0;
  WaveField().elevationAndRate(0.0, 0.0, 1.0, eta, rate);
  EXPECT_EQ(eta, 0.0);
  EXPECT_EQ(rate, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Spectra and random seas

TEST(Waves, SpectraIntegrateToHsSquaredOver16) {
  const double hs = 4.0, tp = 10.0, fp = 1.0 / tp, m0 = hs * hs / 16.0;
  const double pm = integrate([&](double f) { return piersonMoskowitzSpectrum(f, hs, tp); }, fp);
  EXPECT_NEAR(pm / m0, 1.0, kSpectrumIntegralRelTol);
  for (double gamma : {1.0, 2.0, 3.3, 7.0}) {
    const double j = integrate([&](double f) { return jonswapSpectrum(f, hs, tp, gamma); }, fp);
    EXPECT_NEAR(j / m0, 1.0, kSpectrumIntegralRelTol) << "gamma " << gamma;
  }
  // gamma = 1 is Pierson-Moskowitz.
  for (double f : {0.05, 0.1, 0.13, 0.3})
    EXPECT_NEAR(jonswapSpectrum(f, hs, tp, 1.0), piersonMoskowitzSpectrum(f, hs, tp),
                1e-12 * piersonMoskowitzSpectrum(f, hs, tp));
  // Hand value of the PM form at the peak: 5/16 Hs^2 Tp e^{-5/4}.
  EXPECT_NEAR(piersonMoskowitzSpectrum(fp, hs, tp), 5.0 / 16.0 * hs * hs * tp * std::exp(-1.25), 1e-12);
  EXPECT_EQ(piersonMoskowitzSpectrum(0.0, hs, tp), 0.0);
  EXPECT_EQ(jonswapSpectrum(-1.0, hs, tp, 3.3), 0.0);
}

TEST(Waves, SpectralPeakAtOneOverTp) {
  const double hs = 2.0, tp = 7.0, fp = 1.0 / tp, step = 1e-4 * fp;
  for (int which = 0; which < 2; ++which) {
    double best_f = 0.0, best_s = -1.0;
    for (double f = 0.5 * fp; f < 2.0 * fp; f += step) {
      const double s = which == 0 ? piersonMoskowitzSpectrum(f, hs, tp) : jonswapSpectrum(f, hs, tp, 3.3);
      if (s > best_s) best_s = s, best_f = f;
    }
    EXPECT_NEAR(best_f, fp, 1.01 * step) << (which == 0 ? "PM" : "JONSWAP");
  }
  // JONSWAP peak = gamma times the PM peak, up to the normalisation factor (about 0.62 for 3.3).
  const double ratio = jonswapSpectrum(fp, hs, tp, 3.3) / piersonMoskowitzSpectrum(fp, hs, tp);
  EXPECT_GT(ratio, 3.3 * 0.55);
  EXPECT_LT(ratio, 3.3 * 0.7);
}

TEST(Waves, RandomSeaComponents) {
  WaveSpec s = jonswap(4.0, 10.0);
  s.components = 100;
  s.f_min_factor = 0.6;
  s.f_max_factor = 3.0;
  const WaveField wf(s, 200.0, kG);
  ASSERT_EQ(wf.components().size(), 100u);
  const double fp = 0.1, df = (3.0 - 0.6) * fp / 100;
  double var = 0.0;
  for (std::size_t i = 0; i < wf.components().size(); ++i) {
    const WaveComponent& c = wf.components()[i];
    EXPECT_NEAR(c.omega, 2 * kPi * (0.6 * fp + (i + 0.5) * df), 1e-12);
    EXPECT_LT(dispersionResidual(c.omega, c.k, 200.0), kDispersionResidualTol);
    EXPECT_GE(c.phase, 0.0);
    EXPECT_LT(c.phase, 2 * kPi);
    var += 0.5 * c.amplitude * c.amplitude;
  }
  EXPECT_NEAR(var, 1.0, 1e-12);  // Hs^2/16: amplitudes scaled to the requested Hs
  // Amplitudes follow sqrt(2 S df) up to one common factor (the energy outside the band).
  const double c0 = wf.components()[10].amplitude / std::sqrt(2 * jonswapSpectrum(wf.components()[10].omega / (2 * kPi), 4.0, 10.0, 3.3) * df);
  const double c1 = wf.components()[40].amplitude / std::sqrt(2 * jonswapSpectrum(wf.components()[40].omega / (2 * kPi), 4.0, 10.0, 3.3) * df);
  EXPECT_NEAR(c0 / c1, 1.0, 1e-12);
  EXPECT_GT(c0, 1.0);
  EXPECT_LT(c0, 1.01);
  // Phases come straight from the mt19937 sequence (fixed by the C++ standard): seed 1 -> 1791095845 first.
  EXPECT_DOUBLE_EQ(wf.components()[0].phase, 2 * kPi * 1791095845.0 / 4294967296.0);
}

TEST(Waves, RealizedHsFromLongRecord) {
  for (auto type : {WaveSpec::Type::Jonswap, WaveSpec::Type::PiersonMoskowitz}) {
    WaveSpec s = jonswap(5.0, 11.0, 3.3, 42);
    s.type = type;
    const WaveField wf(s, 150.0, kG);
    const double dt = 0.5, duration = 3 * 3600.0;
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (double t = 0.0; t < duration; t += dt, ++n) {
      const double e = wf.elevation(10.0, -4.0, t);
      sum += e;
      sum2 += e * e;
    }
    const double mean = sum / n, var = sum2 / n - mean * mean;
    EXPECT_NEAR(4.0 * std::sqrt(var), 5.0, kRealizedHsRelTol * 5.0);
    EXPECT_NEAR(mean, 0.0, 0.05);
  }
}

TEST(Waves, SeedReproducibility) {
  const WaveField a(jonswap(3.0, 8.0, 3.3, 7), 100.0, kG);
  const WaveField b(jonswap(3.0, 8.0, 3.3, 7), 100.0, kG);
  const WaveField c(jonswap(3.0, 8.0, 3.3, 8), 100.0, kG);
  int differ = 0;
  for (double t = 0.0; t < 100.0; t += 3.3) {
    EXPECT_EQ(a.elevation(1.0, 2.0, t), b.elevation(1.0, 2.0, t));
    differ += std::abs(a.elevation(1.0, 2.0, t) - c.elevation(1.0, 2.0, t)) > 1e-3;
  }
  EXPECT_GT(differ, 20);
}

TEST(Waves, EmptyField) {
  const WaveField none(WaveSpec{}, 100.0, kG);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.elevation(0, 0, 1), 0.0);
  double vx = 1, vy = 1, vz = 1;
  none.velocity(0, 0, -1, 1, vx, vy, vz);
  EXPECT_EQ(vx, 0.0);
  EXPECT_EQ(vz, 0.0);
  const WaveField dflt;
  EXPECT_TRUE(dflt.empty());
}

// ---------------------------------------------------------------------------------------------
// Validation

TEST(Waves, ValidateMessagesNameKeyAndValue) {
  EXPECT_EQ(WaveSpec{}.validate(), "");
  EXPECT_EQ(regular(1.0, 8.0).validate(), "");
  EXPECT_EQ(jonswap(2.0, 9.0).validate(), "");

  auto msg = [](WaveSpec s) { return s.validate(); };
  WaveSpec r = regular(1.0, 8.0);
  EXPECT_EQ(msg([&] { auto s = r; s.height = -1; return s; }()), "environment.waves.height = -1: must be > 0");
  EXPECT_EQ(msg([&] { auto s = r; s.period = 0; return s; }()), "environment.waves.period = 0: must be > 0");
  EXPECT_EQ(msg([&] { auto s = r; s.ramp = -2; return s; }()), "environment.waves.ramp = -2: must be finite and >= 0");
  EXPECT_EQ(msg([&] { auto s = r; s.direction = std::nan(""); return s; }()).find("environment.waves.direction_deg = "), 0u);
  WaveSpec j = jonswap(2.0, 9.0);
  EXPECT_EQ(msg([&] { auto s = j; s.hs = -1; return s; }()), "environment.waves.hs = -1: must be > 0");
  EXPECT_EQ(msg([&] { auto s = j; s.tp = 0; return s; }()), "environment.waves.tp = 0: must be > 0");
  EXPECT_EQ(msg([&] { auto s = j; s.tp = std::numeric_limits<double>::infinity(); return s; }()),
            "environment.waves.tp = inf: must be finite");
  EXPECT_EQ(msg([&] { auto s = j; s.gamma = 0.5; return s; }()),
            "environment.waves.gamma = 0.5: must be >= 1 (1 = Pierson-Moskowitz)");
  EXPECT_EQ(msg([&] { auto s = j; s.components = 0; return s; }()),
            "environment.waves.components = 0: must be in [1, 10000]");
  EXPECT_EQ(msg([&] { auto s = j; s.components = 10001; return s; }()),
            "environment.waves.components = 10001: must be in [1, 10000]");
  EXPECT_EQ(msg([&] { auto s = j; s.f_min_factor = 1.2; return s; }()),
            "environment.waves.f_min_factor = 1.2: must be in (0, 1)");
  EXPECT_EQ(msg([&] { auto s = j; s.f_max_factor = 0.9; return s; }()),
            "environment.waves.f_max_factor = 0.9: must be finite and > 1");
  // gamma is not used by Pierson-Moskowitz; the regular keys are not used by random seas.
  WaveSpec pm = j;
  pm.type = WaveSpec::Type::PiersonMoskowitz;
  pm.gamma = 0.0;
  pm.height = -1.0;
  EXPECT_EQ(pm.validate(), "");
  // The constructor refuses an invalid spec with the same message.
  try {
    WaveField wf([&] { auto s = j; s.hs = -1; return s; }(), 100.0, kG);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("environment.waves.hs = -1: must be > 0"), std::string::npos);
  }
  EXPECT_THROW(WaveField(regular(1.0, 8.0), -5.0, kG), std::invalid_argument);
}

// frequencies: random puts each component at a random place in its own bin (the record no longer
// repeats after 1/df) and leaves the phases and Hs as they are; spreading_s draws one direction
// per component from cos^(2s)(t/2), whose mean resultant length E[cos t] is s / (s + 1).
TEST(Waves, RandomFrequenciesStayInTheirBinsAndKeepThePhases) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::Jonswap;
  spec.hs = 4.0;
  spec.tp = 9.0;
  spec.seed = 11;
  const WaveField centred(spec, 200.0, kG);
  spec.random_frequencies = true;
  const WaveField random(spec, 200.0, kG);
  const double fp = 1.0 / spec.tp, df = (spec.f_max_factor - spec.f_min_factor) * fp / spec.components;
  double m0 = 0.0, off_centre = 0.0;
  for (std::size_t i = 0; i < random.components().size(); ++i) {
    const double f = random.components()[i].omega / (2.0 * kPi);
    const double lo = spec.f_min_factor * fp + static_cast<double>(i) * df;
    EXPECT_GE(f, lo);
    EXPECT_LT(f, lo + df);
    off_centre = std::max(off_centre, std::abs(f - (lo + 0.5 * df)) / df);
    EXPECT_EQ(random.components()[i].phase, centred.components()[i].phase) << "the phases keep their stream";
    m0 += 0.5 * random.components()[i].amplitude * random.components()[i].amplitude;
  }
  /// 200 uniform draws: the farthest from its bin's centre is beyond 0.4 df with probability 1 - 0.8^200.
  constexpr double kSomeDrawFarFromCentre = 0.4;
  EXPECT_GT(off_centre, kSomeDrawFarFromCentre);
  EXPECT_NEAR(4.0 * std::sqrt(m0), spec.hs, 1e-12) << "Hs matched exactly, as with centred bins";
}

TEST(Waves, SpreadingDirectionsFollowCos2s) {
  WaveSpec spec;
  spec.type = WaveSpec::Type::PiersonMoskowitz;
  spec.hs = 2.0;
  spec.tp = 8.0;
  spec.components = 10000;
  spec.direction = 0.7;
  for (double s : {1.0, 4.0, 15.0}) {
    spec.spreading_s = s;
    const WaveField sea(spec, 200.0, kG);
    double sum_cos = 0.0, sum_sin = 0.0;
    for (const WaveComponent& c : sea.components()) {
      sum_cos += std::cos(c.direction - spec.direction);
      sum_sin += std::sin(c.direction - spec.direction);
    }
    const double n = static_cast<double>(sea.components().size());
    /// Sampling error of a mean of 10000 draws of cos t (std < 1): 5 standard errors.
    constexpr double kMeanOf10000Tol = 5.0 / 100.0;
    EXPECT_NEAR(sum_cos / n, s / (s + 1.0), kMeanOf10000Tol) << "s = " << s;
    EXPECT_NEAR(sum_sin / n, 0.0, kMeanOf10000Tol) << "symmetric about the mean direction, s = " << s;
  }
}
