// Motion RAO tables (core/model/rao.hpp): exact values at the nodes, bilinear interpolation
// reproducing a function linear in frequency and heading, the wrap at 360 deg, the port-starboard
// fold, and the errors for frequencies outside the table and headings in wide gaps.
#include <gtest/gtest.h>

#include <array>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/rao.hpp"

using namespace mooring_dynamics::core;
using C = std::complex<double>;

namespace {

/// Interpolation of values linear in (omega, beta) is exact up to rounding of a few operations.
constexpr double kRoundingTol = 1e-12;

/// A function linear in omega and in beta on each heading interval (so bilinear interpolation
/// returns it exactly): mode d gets a distinct complex slope.
C linearValue(int d, double omega, double beta) {
  return C(1.0 + d + 2.0 * omega + 0.01 * beta, -0.5 * d + omega - 0.02 * beta);
}

RaoTable table(const std::vector<double>& omega, const std::vector<double>& headings) {
  std::array<std::vector<C>, RaoTable::kDofs> v;
  for (int d = 0; d < RaoTable::kDofs; ++d)
    for (double h : headings)
      for (double w : omega) v[d].push_back(linearValue(d, w, h));
  return RaoTable(omega, headings, v);
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(RaoTable, ExactAtNodesAndBilinearBetween) {
  const RaoTable t = table({0.2, 0.5, 1.0, 2.0}, {0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0});
  for (int d = 0; d < RaoTable::kDofs; ++d) {
    EXPECT_EQ(t.at(0.5, 90.0)[d], linearValue(d, 0.5, 90.0));
    // Between nodes: the linear function comes back.
    const C got = t.at(0.73, 100.0)[d];
    EXPECT_NEAR(std::abs(got - linearValue(d, 0.73, 100.0)), 0.0, kRoundingTol) << raoDofName(d);
  }
}

TEST(RaoTable, HeadingsWrapAt360) {
  // Tabulated 0..315 every 45: 350 deg lies between 315 and 360 = 0, a quarter of the way... from 315
  // 35/45 of the way to 0. The interpolated value is that weighted mean of the two columns.
  const RaoTable t = table({0.5, 1.0}, {0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0});
  const double w = 35.0 / 45.0;
  for (int d = 0; d < RaoTable::kDofs; ++d) {
    const C want = (1.0 - w) * linearValue(d, 0.5, 315.0) + w * linearValue(d, 0.5, 0.0);
    EXPECT_NEAR(std::abs(t.at(0.5, 350.0)[d] - want), 0.0, kRoundingTol);
    EXPECT_NEAR(std::abs(t.at(0.5, -10.0)[d] - want), 0.0, kRoundingTol) << "-10 deg is 350 deg";
    EXPECT_NEAR(std::abs(t.at(0.5, 710.0)[d] - want), 0.0, kRoundingTol) << "710 deg is 350 deg";
  }
}

TEST(RaoTable, PortStarboardFoldNegatesSwayRollYaw) {
  RaoTable t = table({0.5, 1.0}, {0.0, 45.0, 90.0, 135.0, 180.0});
  t.symmetry = RaoSymmetry::PortStarboard;
  const std::array<C, RaoTable::kDofs> port = t.at(0.7, 60.0), starboard = t.at(0.7, 300.0);
  for (int d = 0; d < RaoTable::kDofs; ++d) {
    const double sign = (d == 1 || d == 3 || d == 5) ? -1.0 : 1.0;
    EXPECT_NEAR(std::abs(starboard[d] - sign * port[d]), 0.0, kRoundingTol) << raoDofName(d);
  }
  RaoTable wide = table({0.5, 1.0}, {0.0, 90.0, 200.0});
  wide.symmetry = RaoSymmetry::PortStarboard;
  EXPECT_TRUE(contains(wide.check(0.7, 10.0), "above 180")) << wide.check(0.7, 10.0);
  RaoTable part = table({0.5, 1.0}, {90.0, 180.0});
  part.symmetry = RaoSymmetry::PortStarboard;
  EXPECT_TRUE(contains(part.check(0.7, 30.0), "outside the table's headings 90 to 180")) << part.check(0.7, 30.0);
}

TEST(RaoTable, FrequenciesOutsideTheTable) {
  RaoTable t = table({0.4, 1.0, 2.0}, {0.0, 90.0, 180.0, 270.0});
  const std::string e = t.check(0.3, 0.0);
  EXPECT_TRUE(contains(e, "frequency 0.3 rad/s is outside the table's 0.4 to 2 rad/s")) << e;
  EXPECT_THROW(t.at(2.5, 0.0), std::invalid_argument);
  t.extend = RaoExtend::Zero;
  for (const C& v : t.at(2.5, 0.0)) EXPECT_EQ(v, C(0.0, 0.0));
  t.extend = RaoExtend::Hold;
  for (int d = 0; d < RaoTable::kDofs; ++d) EXPECT_EQ(t.at(2.5, 0.0)[d], linearValue(d, 2.0, 0.0));
}

TEST(RaoTable, HeadingInAWideGapIsAnError) {
  const RaoTable one = table({0.5, 1.0}, {180.0});
  EXPECT_TRUE(one.check(0.7, 180.0).empty()) << "the tabulated heading itself";
  const std::string e = one.check(0.7, 170.0);
  EXPECT_TRUE(contains(e, "heading 170 deg falls in a gap of 360 deg")) << e;
  const RaoTable two = table({0.5, 1.0}, {0.0, 180.0});
  EXPECT_FALSE(two.check(0.7, 90.0).empty());
  const RaoTable four = table({0.5, 1.0}, {0.0, 90.0, 180.0, 270.0});
  EXPECT_TRUE(four.check(0.7, 300.0).empty()) << "a 90 deg gap is accepted";
}

TEST(RaoTable, BadTablesNameTheValue) {
  std::array<std::vector<C>, RaoTable::kDofs> v;
  for (auto& x : v) x.assign(2, C(1.0, 0.0));
  try {
    RaoTable({1.0, 0.5}, {0.0}, v);
    FAIL() << "decreasing frequencies accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "frequencies must increase (1 then 0.5 rad/s)")) << e.what();
  }
  try {
    RaoTable({0.5, 1.0}, {360.0}, v);
    FAIL() << "heading 360 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "heading 360 deg: must be in [0, 360)")) << e.what();
  }
  v[4].pop_back();
  EXPECT_THROW(RaoTable({0.5, 1.0}, {0.0}, v), std::invalid_argument);
}
