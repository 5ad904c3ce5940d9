// Readers of motion RAO tables (core/io/rao_io.hpp): a WAMIT `.4` text written here by hand
// (periods to frequencies, rotations divided by ULEN, Re/Im kept, the lag convention conjugated,
// heading 360 = 0) and the CSV form (degrees per metre, polar values), and the errors naming the
// line and the constraint.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <sstream>
#include <string>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/rao_io.hpp"

using namespace mooring_dynamics::core;
using C = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Values printed with 7 significant digits in the text below and read back.
constexpr double kParseTol = 1e-12;

/// Mode d at (period, heading): a distinct complex value (nondimensional, as WAMIT writes it).
C wamitValue(int mode, double period, double beta) { return C(0.1 * mode + 0.01 * period, 0.001 * beta - 0.2 * mode); }

std::string wamitText(const std::vector<double>& periods, const std::vector<double>& headings, int skip_mode = 0) {
  std::ostringstream s;
  for (double per : periods)
    for (double b : headings)
      for (int m = 1; m <= 6; ++m) {
        if (m == skip_mode) continue;
        const C x = wamitValue(m, per, b);
        s << "  " << per << "  " << b << "  " << m << "  " << std::abs(x) << "  " << std::arg(x) * 180.0 / kPi << "  "
          << x.real() << "  " << x.imag() << "\n";
      }
  return s.str();
}

RaoSource wamit(double ulen = 10.0) {
  RaoSource how;
  how.format = RaoSource::Format::Wamit;
  how.ulen = ulen;
  return how;
}

std::string errorOf(const std::string& text, const RaoSource& how) {
  try {
    if (how.format == RaoSource::Format::Wamit) parseWamitRaos(text, "hull.4", how);
    else parseCsvRaos(text, "hull.csv", how);
  } catch (const ProblemError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(RaoIo, WamitPeriodsBecomeFrequenciesAndRotationsAreDividedByUlen) {
  const RaoTable t = parseWamitRaos(wamitText({20.0, 10.0, 5.0}, {0.0, 90.0, 180.0, 270.0}), "hull.4", wamit(10.0));
  ASSERT_EQ(t.omega().size(), 3u);
  EXPECT_NEAR(t.omega()[0], 2.0 * kPi / 20.0, kParseTol) << "sorted by frequency: the longest period first";
  EXPECT_NEAR(t.omega()[2], 2.0 * kPi / 5.0, kParseTol);
  ASSERT_EQ(t.headings().size(), 4u);
  for (int m = 1; m <= 6; ++m) {
    const C want = wamitValue(m, 10.0, 90.0) / (m >= 4 ? 10.0 : 1.0);
    EXPECT_NEAR(std::abs(t.value(m - 1, 1, 1) - want), 0.0, kParseTol) << "mode " << m;
  }
}

TEST(RaoIo, PhaseLagConventionIsConjugated) {
  RaoSource how = wamit(1.0);
  const RaoTable lead = parseWamitRaos(wamitText({10.0}, {0.0}), "hull.4", how);
  how.phase_lag = true;
  const RaoTable lag = parseWamitRaos(wamitText({10.0}, {0.0}), "hull.4", how);
  for (int d = 0; d < 6; ++d) EXPECT_EQ(lag.value(d, 0, 0), std::conj(lead.value(d, 0, 0)));
}

TEST(RaoIo, Heading360IsHeading0WhenTheValuesAgree) {
  std::string text = wamitText({10.0, 8.0}, {0.0, 90.0, 180.0, 270.0});
  // The 0 deg rows again as 360 deg.
  std::istringstream in(wamitText({10.0, 8.0}, {0.0}));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string per, beta, rest;
    cells >> per >> beta;
    std::getline(cells, rest);
    text += per + " 360 " + rest + "\n";
  }
  const RaoTable t = parseWamitRaos(text, "hull.4", wamit());
  EXPECT_EQ(t.headings().size(), 4u);
  // Another value at 360: an error naming both lines.
  const std::string e = errorOf(text + "10 360 3 1 0 0.9 0.1\n", wamit());
  EXPECT_TRUE(contains(e, "heave at heading 360 deg")) << e;
  EXPECT_TRUE(contains(e, "given already (hull.4:")) << e;
}

TEST(RaoIo, WamitErrorsNameTheLine) {
  const std::string good = wamitText({10.0}, {0.0});
  EXPECT_TRUE(contains(errorOf(good, wamit(0.0)), "ulen = 0: must be finite and > 0")) << errorOf(good, wamit(0.0));
  EXPECT_TRUE(contains(errorOf(wamitText({10.0}, {0.0}, 6), wamit()), "no yaw (mode 6) at omega"));
  EXPECT_TRUE(contains(errorOf(good + "10 0 7 1 0 1 0\n", wamit()), "hull.4:7: mode = 7: must be 1-6"));
  EXPECT_TRUE(contains(errorOf(good + "0 0 3 1 0 1 0\n", wamit()), "hull.4:7: period = 0: must be > 0"));
  EXPECT_TRUE(contains(errorOf(good + "10 0 3 1 0 nan 0\n", wamit()), "hull.4:7: value 6 = \"nan\": not a finite number"));
  EXPECT_TRUE(contains(errorOf(good + "10 0 3 1 0 1\n", wamit()), "hull.4:7: 6 values, expected 7"));
  EXPECT_TRUE(contains(errorOf("# nothing\n", wamit()), "hull.4: no motion RAO rows"));
}

TEST(RaoIo, CsvInDegreesPerMetre) {
  RaoSource how;
  how.format = RaoSource::Format::Csv;
  how.rotations_in_deg = true;
  std::string text = "omega,heading_deg,dof,amplitude,phase_deg\n";
  for (int d = 1; d <= 6; ++d) text += "0.5,180," + std::to_string(d) + ",2,90\n";
  const RaoTable t = parseCsvRaos(text, "hull.csv", how);
  EXPECT_NEAR(std::abs(t.value(2, 0, 0) - C(0.0, 2.0)), 0.0, kParseTol) << "heave 2 m/m leading by 90 deg";
  EXPECT_NEAR(std::abs(t.value(4, 0, 0) - C(0.0, 2.0 * kPi / 180.0)), 0.0, kParseTol) << "pitch 2 deg/m";
  EXPECT_TRUE(contains(errorOf("0.5,180,3,-1,0\n", how), "hull.csv:1: amplitude = -1: must be >= 0"));
  EXPECT_TRUE(contains(errorOf("0.5,180,0,1,0\n", how), "hull.csv:1: dof = 0: must be 1-6"));
  EXPECT_TRUE(contains(errorOf("-0.5,180,1,1,0\n", how), "hull.csv:1: omega = -0.5: must be > 0"));
}

// Mean drift tables: a WAMIT .8 text (forces / (rho g A^2 L), moments / (rho g A^2 L^2); the
// cross-heading rows skipped; heave, roll and pitch optional) and the SI CSV form.
TEST(DriftIo, WamitMeanDriftIsScaledToSi) {
  const double rho_g = 1025.0 * 9.80665, ulen = 10.0;
  std::ostringstream s;
  s << "# PER BETA1 BETA2 I |F| phase Re Im\n";
  for (double per : {8.0, 12.0})
    for (double b : {0.0, 90.0, 180.0}) {
      for (int m : {1, 2, 6}) s << per << " " << b << " " << b << " " << m << " 0 0 " << 0.1 * m + 0.01 * per + 0.001 * b << " 0\n";
      s << per << " " << b << " " << (b == 0.0 ? 90.0 : 0.0) << " 1 0 0 99 0\n";  // a cross-heading term
    }
  RaoSource how = wamit(ulen);
  const RaoTable t = parseWamitDrift(s.str(), "hull.8", how, rho_g);
  ASSERT_EQ(t.omega().size(), 2u);
  ASSERT_EQ(t.headings().size(), 3u);
  const auto x = t.at(2.0 * kPi / 12.0, 90.0);
  EXPECT_NEAR(x[0].real(), (0.1 + 0.12 + 0.09) * rho_g * ulen, kParseTol * rho_g * ulen * 10.0);
  EXPECT_NEAR(x[1].real(), (0.2 + 0.12 + 0.09) * rho_g * ulen, kParseTol * rho_g * ulen * 10.0);
  EXPECT_NEAR(x[5].real(), (0.6 + 0.12 + 0.09) * rho_g * ulen * ulen, kParseTol * rho_g * ulen * ulen * 10.0);
  EXPECT_EQ(x[2], C(0.0, 0.0));
}

TEST(DriftIo, MissingYawOrBadRowsNameTheLine) {
  RaoSource how = wamit();
  auto err = [&](const std::string& text) {
    try {
      parseWamitDrift(text, "hull.8", how, 1.0e4);
    } catch (const ProblemError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(err("10 0 0 1 0 0 1 0\n10 0 0 2 0 0 1 0\n").find("no yaw (mode 6)"), std::string::npos)
      << err("10 0 0 1 0 0 1 0\n10 0 0 2 0 0 1 0\n");
  EXPECT_NE(err("10 0 0 1 0 0 1\n").find("hull.8:1: 7 values, expected 8"), std::string::npos);
  EXPECT_NE(err("10 0 0 1 0 0 nan 0\n").find("hull.8:1: value 7"), std::string::npos);
  EXPECT_NE(err("0 0 0 1 0 0 1 0\n").find("period = 0"), std::string::npos);
}

TEST(DriftIo, CsvGivesSurgeSwayYawInSi) {
  RaoSource how;
  how.format = RaoSource::Format::Csv;
  const RaoTable t = parseCsvDrift("omega,heading_deg,surge,sway,yaw\n0.5,0,-1000,0,0\n0.5,90,0,-2000,300\n"
                                   "1.0,0,-4000,0,0\n1.0,90,0,-8000,1200\n",
                                   "drift.csv", how);
  const auto x = t.at(0.75, 45.0);
  EXPECT_NEAR(x[0].real(), 0.5 * (-1000.0 - 4000.0) * 0.5, 1e-9);
  EXPECT_NEAR(x[1].real(), 0.5 * (-2000.0 - 8000.0) * 0.5, 1e-9);
  EXPECT_NEAR(x[5].real(), 0.5 * (300.0 + 1200.0) * 0.5, 1e-9);
}
