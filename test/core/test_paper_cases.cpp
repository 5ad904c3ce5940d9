// The paper's applications as CI checks (issue "House in order": scripts/paper_cases tabulates them
// but is not a test). Each shipped case is run as the validation report ran it and its figures are
// held to the report's tables (docs/validation.md, "The paper's applications"), which are set there
// beside the paper's figures and WHOI Cable's: a change that moves a paper figure fails here.
// A.3 and A.2 are 2-D, A.1 is 3-D; about 5 s in all on the 2-core development host.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"

using namespace mooring_dynamics::core;

namespace {

/// The report's tables give tensions to 1 N and depths to 0.1 m: a figure that moves by more than
/// the table's last digit moves the table.
constexpr double kTensionTableTol = 1.0;  // [N]
constexpr double kDepthTableTol = 0.05;   // [m]

struct Stats {
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;
};
Stats statsOf(const std::vector<double>& v) {
  Stats s;
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  for (double x : v) s.std += (x - s.mean) * (x - s.mean) / static_cast<double>(v.size());
  s.std = std::sqrt(s.std);
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

}  // namespace

TEST(PaperCases, A3ChainMooringLambdaMinusHalfRowOfTheReport) {
  // docs/validation.md, A.3 table, row "λ∞ = −0.5": mean 2261, std 634, min 1001, max 10 611 N;
  // static top tension 2222 N.
  const DynamicSeries r = runDynamic(loadProblemFromFile("config/chain_mooring.yaml"));
  ASSERT_TRUE(r.completed) << r.message;
  const Stats s = statsOf(r.top_tension);
  EXPECT_NEAR(r.top_tension.front(), 2222.0, kTensionTableTol);
  EXPECT_NEAR(s.mean, 2261.0, kTensionTableTol);
  EXPECT_NEAR(s.std, 634.0, kTensionTableTol);
  EXPECT_NEAR(s.min, 1001.0, kTensionTableTol);
  EXPECT_NEAR(s.max, 10611.0, kTensionTableTol);
  EXPECT_EQ(r.fallback_steps, 0) << "the paper's case needs no fallback step";
}

TEST(PaperCases, A2STetherAtHalfASecondRowOfTheReport) {
  // docs/validation.md, A.2 table: static top tension 8374 N (the paper's 8350 N, +0.3 %);
  // λ∞ = −0.5 at Δt = 0.5 s: mean 9043, std 2520 N (0 cuts).
  const DynamicSeries r = runDynamic(loadProblemFromFile("config/s_tether.yaml"));
  ASSERT_TRUE(r.completed) << r.message;
  const Stats s = statsOf(r.top_tension);
  EXPECT_NEAR(r.top_tension.front(), 8374.0, kTensionTableTol);
  EXPECT_NEAR(s.mean, 9043.0, kTensionTableTol);
  EXPECT_NEAR(s.std, 2520.0, kTensionTableTol);
  EXPECT_EQ(r.cuts, 0);
}

TEST(PaperCases, A1TowedArrayCase1RowOfTheReport) {
  // docs/validation.md, A.1 table, row "Case 1, λ∞ = −0.5": point A's depth 12.1 m in the steady
  // tow, 3.3 m at its shallowest in the turn, 10.9 m at the end; ship tension 95 778 N static,
  // 73 301 N at its least; no cuts.
  const Problem p = loadProblemFromFile("config/towed_array.yaml");
  const DynamicSeries r = runDynamic3D(p);
  ASSERT_TRUE(r.completed) << r.message;
  ASSERT_GE(r.node_z.size(), 1u);
  const std::vector<double>& zA = r.node_z[0];  // record_s[0]: point A
  EXPECT_NEAR(-zA.front(), 12.1, kDepthTableTol);
  EXPECT_NEAR(-*std::max_element(zA.begin(), zA.end()), 3.3, kDepthTableTol);
  EXPECT_NEAR(-zA.back(), 10.9, kDepthTableTol);
  EXPECT_NEAR(r.top_tension.front(), 95778.0, kTensionTableTol);
  EXPECT_NEAR(*std::min_element(r.top_tension.begin(), r.top_tension.end()), 73301.0, kTensionTableTol);
  EXPECT_EQ(r.cuts, 0);
}
