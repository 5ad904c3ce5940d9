// GNSS ship tracks (core/model/gnss.hpp): the local datum against the ellipsoid's closed-form
// radii, the compass-to-REP-103 heading, the antenna lever arm, the smoother against the exact
// solution of its ODE (lag 2 tau on a ramp, critically damped step), bad fixes rejected and
// counted with the state kept, heading interpolation across north.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mooring_dynamics/core/io/gnss_track_io.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/model/gnss.hpp"

using namespace mooring_dynamics::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
// WGS84: semi-major axis [m] and flattening, the ellipsoid GeographicLib uses by default.
constexpr double kA = 6378137.0, kF = 1.0 / 298.257223563;

/// Meridian and prime-vertical radii of curvature at latitude phi [m] (closed forms).
double meridianRadius(double phi) {
  const double e2 = kF * (2.0 - kF), s = std::sin(phi);
  return kA * (1.0 - e2) / std::pow(1.0 - e2 * s * s, 1.5);
}
double primeVerticalRadius(double phi) {
  const double e2 = kF * (2.0 - kF), s = std::sin(phi);
  return kA / std::sqrt(1.0 - e2 * s * s);
}

// A 0.001 deg step is ~100 m: the local tangent plane departs from the arc by ~(d/R)^2 ~ 1e-10
// relative, and the radius changes along the step by ~1e-5 relative; 1e-4 catches any wrong
// radius (the flattening alone changes it by 3e-3).
constexpr double kRadiusRel = 1e-4;

TEST(LocalDatum, SmallStepsFollowTheEllipsoidRadii) {
  for (double lat : {0.0, 41.5, -63.0}) {
    const LocalDatum d(lat, -70.0);
    const double step = 0.001;
    const Eigen::Vector2d north = d.eastNorth(lat + step, -70.0);
    const Eigen::Vector2d east = d.eastNorth(lat, -70.0 + step);
    EXPECT_NEAR(north.y(), meridianRadius(lat * kDeg) * step * kDeg, kRadiusRel * north.y()) << lat;
    EXPECT_NEAR(east.x(), primeVerticalRadius(lat * kDeg) * std::cos(lat * kDeg) * step * kDeg, kRadiusRel * east.x())
        << lat;
    EXPECT_NEAR(north.x(), 0.0, 1e-6);
    EXPECT_NEAR(east.y(), 0.0, 1e-3);  // the parallel curves away from the tangent plane: ~d^2/(2R) tan(lat)
  }
}

TEST(Heading, CompassToRep103Yaw) {
  EXPECT_NEAR(yawFromHeadingDeg(0.0), kPi / 2, 1e-15);     // north
  EXPECT_NEAR(yawFromHeadingDeg(90.0), 0.0, 1e-15);        // east
  EXPECT_NEAR(yawFromHeadingDeg(180.0), -kPi / 2, 1e-15);  // south
  EXPECT_NEAR(std::abs(yawFromHeadingDeg(270.0)), kPi, 1e-15);
  EXPECT_NEAR(yawFromHeadingDeg(450.0), 0.0, 1e-14);
}

// --- TrackSmoother ----------------------------------------------------------------------------

// The smoother is integrated exactly for inputs linear between samples: its samples match the
// closed form to rounding.
constexpr double kExact = 1e-9;

TEST(TrackSmoother, StepResponseIsCriticallyDamped) {
  const double tau = 4.0, w = 1.0 / tau;
  TrackSmoother s(tau);
  s.start(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  // A step of 10 m reached within 1e-6 s (a ramp that short is a step to the filter).
  s.update(1e-6, Eigen::Vector2d(10.0, 0.0));
  double peak = 0.0;
  for (int k = 1; k <= 60; ++k) {
    const double t = k * 0.5;
    const double x = s.update(t, Eigen::Vector2d(10.0, 0.0)).x();
    const double exact = 10.0 * (1.0 - (1.0 + w * t) * std::exp(-w * t));
    EXPECT_NEAR(x, exact, 1e-4) << t;  // the 1e-6 s ramp shifts the step by 5e-7 s
    peak = std::max(peak, x);
  }
  EXPECT_LE(peak, 10.0);  // critically damped: no overshoot
}

TEST(TrackSmoother, RampComesOutTwoTauLate) {
  const double tau = 5.0, V = 2.0;
  TrackSmoother s(tau);
  s.start(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(V, 0.0));  // steady state from the start
  for (int k = 1; k <= 100; ++k) {
    const double t = k * 0.7;
    const Eigen::Vector2d x = s.update(t, Eigen::Vector2d(V * t, 0.0));
    EXPECT_NEAR(x.x(), V * (t - 2.0 * tau), kExact * V * t + kExact) << t;
    EXPECT_NEAR(s.velocity().x(), V, kExact);
  }
}

TEST(TrackSmoother, NoiseIsReducedInVelocity) {
  // White position noise sigma at 1 Hz: differenced raw, the velocity noise is sigma sqrt(2) per
  // second; through the smoother (tau = 5 s) the velocity's variance is sigma^2 h w^3 / 4
  // (the integral of |s H(s)|^2 for H = w^2 / (s + w)^2), std ~0.045 sigma: a factor > 20 less.
  const double sigma = 2.0, tau = 5.0;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  TrackSmoother s(tau);
  s.start(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  double sum2 = 0.0;
  int n = 0;
  for (int k = 1; k <= 20000; ++k) {
    s.update(k, Eigen::Vector2d(noise(rng), 0.0));
    if (k > 100) {
      sum2 += s.velocity().x() * s.velocity().x();
      ++n;
    }
  }
  const double vstd = std::sqrt(sum2 / n);
  const double predicted = sigma * std::sqrt(std::pow(1.0 / tau, 3) / 4.0);
  EXPECT_NEAR(vstd, predicted, 0.3 * predicted);  // 30 %: first-order hold vs white noise, finite run
  EXPECT_LT(vstd, sigma * std::sqrt(2.0) / 20.0);
}

TEST(TrackSmoother, OffIsTheInput) {
  TrackSmoother s(0.0);
  s.start(0.0, Eigen::Vector2d(1.0, 2.0), Eigen::Vector2d::Zero());
  const Eigen::Vector2d x = s.update(2.0, Eigen::Vector2d(5.0, 2.0));
  EXPECT_EQ(x, Eigen::Vector2d(5.0, 2.0));
  EXPECT_EQ(s.velocity(), Eigen::Vector2d(2.0, 0.0));
}

// --- GnssTrack --------------------------------------------------------------------------------

GnssOptions rawOptions() {
  GnssOptions o;
  o.enabled = true;
  o.smoothing_time = 0.0;
  return o;
}

GnssFix fixAt(double t, double lat, double lon) {
  GnssFix f;
  f.t = t;
  f.latitude_deg = lat;
  f.longitude_deg = lon;
  return f;
}

TEST(GnssTrack, FirstFixLandsOnTheStartAndTheLeverArmIsTurnedByTheHeading) {
  GnssOptions o = rawOptions();
  o.antenna = Eigen::Vector3d(10.0, 2.0, 15.0);  // 10 m forward, 2 m to port, on the mast
  RigidPose start;
  start.position = Eigen::Vector3d(100.0, 50.0, -3.0);
  GnssTrack track(o, start, Eigen::Vector2d::Zero());
  ASSERT_TRUE(track.addHeading(0.0, yawFromHeadingDeg(0.0)).ok());  // heading north
  const GnssTrack::Result a = track.addFix(fixAt(0.0, 41.5, -70.0));
  ASSERT_TRUE(a.ok()) << a.message;
  EXPECT_EQ(a.pose.position, start.position);
  // 1 s later the antenna is 0.0001 deg (~11 m) further north, the heading still north: the body
  // origin (10 m south and 2 m east of the antenna: body x = north, body y = west) moves with it.
  ASSERT_TRUE(track.addHeading(1.0, yawFromHeadingDeg(0.0)).ok());
  const GnssTrack::Result b = track.addFix(fixAt(1.0, 41.5001, -70.0));
  ASSERT_TRUE(b.ok()) << b.message;
  EXPECT_NEAR(b.pose.position.x() - a.pose.position.x(), 0.0, 1e-6);
  EXPECT_NEAR(b.pose.position.y() - a.pose.position.y(), meridianRadius(41.5 * kDeg) * 0.0001 * kDeg,
              kRadiusRel * 12.0);
  EXPECT_EQ(b.pose.position.z(), -3.0);  // the start's elevation
  // Turning to east at the same antenna position moves the origin: it was 10 m south and 2 m east
  // of the antenna, it is now 10 m west and 2 m south (body x = east, body y = north).
  ASSERT_TRUE(track.addHeading(2.0, yawFromHeadingDeg(90.0)).ok());
  const GnssTrack::Result c = track.addFix(fixAt(2.0, 41.5001, -70.0));
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_NEAR(c.pose.position.x() - b.pose.position.x(), -10.0 - 2.0, 1e-6);
  EXPECT_NEAR(c.pose.position.y() - b.pose.position.y(), 10.0 - 2.0, 1e-6);
  const Eigen::Vector3d forward = c.pose.orientation * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(forward.x(), 1.0, 1e-12);  // body x points east
}

TEST(GnssTrack, BadFixesAreRejectedCountedAndLeaveTheStateAlone) {
  GnssOptions o = rawOptions();
  o.max_speed = 10.0;
  o.jump_tolerance = 5.0;
  o.max_horizontal_sigma = 3.0;
  GnssTrack track(o, RigidPose(), Eigen::Vector2d::Zero());
  EXPECT_EQ(track.addFix(fixAt(0.0, 10.0, 20.0)).verdict, GnssTrack::Verdict::NoHeading);
  track.addHeading(0.0, 0.0);
  ASSERT_TRUE(track.addFix(fixAt(0.0, 10.0, 20.0)).ok());
  GnssFix nofix = fixAt(1.0, 10.0, 20.0);
  nofix.has_fix = false;
  EXPECT_EQ(track.addFix(nofix).verdict, GnssTrack::Verdict::NoFix);
  EXPECT_EQ(track.addFix(fixAt(1.0, std::nan(""), 20.0)).verdict, GnssTrack::Verdict::BadValue);
  EXPECT_EQ(track.addFix(fixAt(1.0, 91.0, 20.0)).verdict, GnssTrack::Verdict::BadValue);
  EXPECT_EQ(track.addFix(fixAt(1.0, 10.0, -181.0)).verdict, GnssTrack::Verdict::BadValue);
  GnssFix noisy = fixAt(1.0, 10.0, 20.0);
  noisy.horizontal_variance = 16.0;  // 4 m > 3 m
  EXPECT_EQ(track.addFix(noisy).verdict, GnssTrack::Verdict::Covariance);
  EXPECT_EQ(track.addFix(fixAt(0.0, 10.0, 20.0)).verdict, GnssTrack::Verdict::Backward);   // duplicate
  EXPECT_EQ(track.addFix(fixAt(-1.0, 10.0, 20.0)).verdict, GnssTrack::Verdict::Backward);  // backward
  // 0.001 deg of latitude (~110 m) in 1 s: more than 10 m/s * 1 s + 5 m.
  const GnssTrack::Result jump = track.addFix(fixAt(1.0, 10.001, 20.0));
  EXPECT_EQ(jump.verdict, GnssTrack::Verdict::Jump);
  EXPECT_NE(jump.message.find("max_speed"), std::string::npos) << jump.message;
  // 14 m in 1 s is within 10 + 5 m: accepted, from where the last good fix left the state.
  const GnssTrack::Result good = track.addFix(fixAt(1.0, 10.0 + 14.0 / 110574.0, 20.0));
  ASSERT_TRUE(good.ok()) << good.message;
  EXPECT_NEAR(good.pose.position.y(), 14.0, 0.1);
  const auto& c = track.counts();
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::NoHeading)], 1);
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::NoFix)], 1);
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::BadValue)], 3);
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::Covariance)], 1);
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::Backward)], 2);
  EXPECT_EQ(c[static_cast<std::size_t>(GnssTrack::Verdict::Jump)], 1);
}

TEST(GnssTrack, HeadingIsInterpolatedAcrossNorthAndGapsAreReported) {
  GnssOptions o = rawOptions();
  o.max_heading_gap = 1.5;
  GnssTrack track(o, RigidPose(), Eigen::Vector2d::Zero());
  track.addHeading(0.0, yawFromHeadingDeg(350.0));
  track.addHeading(2.0, yawFromHeadingDeg(10.0));
  const GnssTrack::Result r = track.addFix(fixAt(1.0, 0.0, 0.0));
  ASSERT_TRUE(r.ok());
  const Eigen::Vector3d fwd = r.pose.orientation * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(fwd.y(), 1.0, 1e-12);  // midway between 350 and 10 deg: north, not south
  EXPECT_EQ(track.headingGapsReported(), 0);
  const GnssTrack::Result late = track.addFix(fixAt(4.0, 0.0, 0.0));  // 2 s after the last heading
  ASSERT_TRUE(late.ok());
  EXPECT_DOUBLE_EQ(late.heading_gap, 2.0);
  EXPECT_EQ(track.headingGapsReported(), 1);
}

TEST(GnssOptions, ValidationNamesTheKey) {
  GnssOptions o;
  o.smoothing_time = -1.0;
  EXPECT_NE(o.validate().find("dynamics.gnss.smoothing_time = -1"), std::string::npos) << o.validate();
  o = GnssOptions();
  o.datum_from_first_fix = false;
  o.datum_latitude_deg = 95.0;
  EXPECT_NE(o.validate().find("dynamics.gnss.datum.latitude_deg = 95"), std::string::npos) << o.validate();
}

// --- Track files and the problem section --------------------------------------------------------

TEST(GnssTrackIo, ParsesRowsAndNamesBadCells) {
  const auto rows = parseGnssTrack("t,latitude,longitude,heading\n0,41.5,-70.6,90\n1,41.5,-70.59999,91.5\n", "x.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].heading_deg, 91.5);
  try {
    parseGnssTrack("0,41.5,-70.6,90\n1,41.5,abc,90\n", "x.csv");
    FAIL() << "no error";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv:2: column longitude = \"abc\""), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseGnssTrack("1,41.5,-70.6,90\n1,41.5,-70.6,90\n", "x.csv"), ProblemError);  // t not increasing
  EXPECT_THROW(parseGnssTrack("1,41.5,-70.6\n", "x.csv"), ProblemError);                      // 3 columns
}

TEST(GnssSection, ReadFromTheDynamicsSection) {
  const std::string base = R"(
model: 3d
materials:
  rope: {EA: 1.0e6, EI: 1, GJ: 1, mass: 1, added_mass: 0, wet_weight: 5, diameter: 0.02, cdn: 1.2, cdt: 0.01}
line: [{material: rope, length: 120, spacing: 4}]
anchor: {x: 0, z: -100}
top: {position: {x: 60, y: 0, z: 0}}
)";
  const Problem p = loadProblemFromString(base + R"(dynamics:
  dt: 0.5
  gnss: {track: ship.csv, datum: {latitude_deg: 41.5, longitude_deg: -70.6}, antenna: [1, 2, 3], smoothing_time: 8}
)",
                                          "/data");
  EXPECT_TRUE(p.dynamics.gnss.enabled);
  EXPECT_EQ(p.dynamics.gnss.track, "/data/ship.csv");
  EXPECT_FALSE(p.dynamics.gnss.datum_from_first_fix);
  EXPECT_EQ(p.dynamics.gnss.antenna, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.dynamics.gnss.smoothing_time, 8.0);
  try {
    loadProblemFromString(base + "dynamics: {gnss: {smoothing_time: -2}}\n");
    FAIL() << "no error";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("dynamics.gnss.smoothing_time"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadProblemFromString(base + "dynamics: {gnss: {datum: somewhere}}\n"), ProblemError);
  EXPECT_THROW(loadProblemFromString(base + "dynamics: {gnss: {antenna: [1, 2]}}\n"), ProblemError);
  EXPECT_THROW(loadProblemFromString(base + "dynamics: {gnss: {speed: 3}}\n"), ProblemError);  // unknown key
}

}  // namespace
