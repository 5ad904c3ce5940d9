// Tests of the sweep summary (io/sweep_summary.hpp): line statistics of a case from its series
// file against hand sums (single line with an MBL; a system's free buoy), the storm grouping and
// its Gumbel most probable maximum, and the CSV columns.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/sweep_summary.hpp"

namespace md = mooring_dynamics::core;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(MD_SOURCE_DIR) + "/test/data/";
constexpr double kSum = 1e-12;  // hand sums of a few numbers: rounding only

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("md_test_sweep_summary_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const char* const kLine = R"(name: leg
model: 3d
environment: {depth: 120}
materials:
  chain: {EA: 6.44e7, EI: 10, mass: 3.73, wet_weight: 31.85, diameter: 0.0495, cdn: 0.5, cdt: 0.05, mbl: 1.0e5}
  wire: {EA: 6.44e7, EI: 10, mass: 1, wet_weight: 5, diameter: 0.02, cdn: 1.2, cdt: 0.01, mbl: 4.0e4}
line:
  - {material: chain, length: 50, spacing: 5}
  - {material: wire, length: 100, spacing: 5}
anchor: {x: 0, y: 0, z: -100}
top: {position: {x: 100, y: 0, z: 0}}
)";

}  // namespace

TEST(SweepSummary, SingleLineStatisticsAgainstHandSums) {
  const fs::path dir = tempDir("line");
  std::ofstream(dir / "case.yaml") << kLine;
  std::ofstream(dir / "timeseries.csv") << "t,top_tension,anchor_tension,top_x,top_y,top_z\n"
                                           "0,1000,900,100,0,0\n"
                                           "1,1200,900,103,0,0\n"
                                           "2,800,900,97,-3,0\n"
                                           "3,1400,900,101,1,0\n";
  const auto s = md::caseLineStats((dir / "case.yaml").string(), dir.string(), 1.0, "c1", "s1");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].line, "line");
  EXPECT_EQ(s[0].case_name, "c1");
  EXPECT_EQ(s[0].storm, "s1");
  EXPECT_EQ(s[0].samples, 3u);  // t = 0 skipped
  EXPECT_EQ(s[0].max, 1400.0);
  const double mean = (1200.0 + 800.0 + 1400.0) / 3.0;
  EXPECT_NEAR(s[0].mean, mean, kSum * mean);
  const double var = (std::pow(1200 - mean, 2) + std::pow(800 - mean, 2) + std::pow(1400 - mean, 2)) / 3.0;
  EXPECT_NEAR(s[0].std, std::sqrt(var), kSum * mean);
  EXPECT_EQ(s[0].mbl, 4.0e4);  // the weaker material, wire
  EXPECT_NEAR(s[0].utilization, 1400.0 / 4.0e4, kSum);
  // Offsets from the first sample (100, 0): 3, hypot(3, 3), hypot(1, 1).
  EXPECT_NEAR(s[0].top_offset, std::hypot(3.0, 3.0), kSum * 10);
  fs::remove_all(dir);
}

TEST(SweepSummary, SystemLinesWithoutMblAndTheirBuoysOffset) {
  const fs::path dir = tempDir("system");
  std::ofstream(dir / "system_timeseries.csv") << "t,buoy_x,buoy_y,buoy_z,leg_e_top_tension,leg_nw_top_tension,leg_sw_top_tension\n"
                                                  "0,1,2,0,500,600,700\n"
                                                  "0.5,5,-1,0,550,650,640\n";
  const auto s = md::caseLineStats(kData + "small_system.yaml", dir.string(), 0.0, "c", "st");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1].line, "leg_nw");
  EXPECT_EQ(s[1].max, 650.0);
  EXPECT_NEAR(s[1].mean, 625.0, kSum * 625);
  EXPECT_NEAR(s[1].std, 25.0, kSum * 625);
  EXPECT_EQ(s[2].max, 700.0);
  EXPECT_EQ(s[1].mbl, 0.0);
  EXPECT_TRUE(std::isnan(s[1].utilization));
  EXPECT_NEAR(s[0].top_offset, 5.0, kSum * 5);  // (4, -3) from the first sample: all legs top at the buoy
  // A missing column names the file and the column.
  std::ofstream(dir / "system_timeseries.csv") << "t,buoy_x,buoy_y,buoy_z,leg_e_top_tension\n0,1,2,0,500\n";
  try {
    md::caseLineStats(kData + "small_system.yaml", dir.string(), 0.0, "c", "st");
    ADD_FAILURE() << "no error";
  } catch (const md::ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'leg_nw_top_tension'"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(SweepSummary, StormsFitTheirSeedsMaxima) {
  std::vector<md::CaseLineStats> cases;
  const double maxima[4] = {100.0, 110.0, 120.0, 130.0};
  for (int k = 0; k < 4; ++k) {
    md::CaseLineStats c;
    c.case_name = "storm-a_seed-" + std::to_string(k);
    c.storm = "storm-a";
    c.line = "leg";
    c.max = maxima[k];
    c.mbl = 400.0;
    cases.push_back(c);
  }
  md::CaseLineStats lone;
  lone.case_name = "storm-b_seed-0";
  lone.storm = "storm-b";
  lone.line = "leg";
  lone.max = 90.0;
  cases.push_back(lone);
  const auto st = md::stormLineStats(cases, md::GumbelMethod::Moments);
  ASSERT_EQ(st.size(), 2u);
  EXPECT_EQ(st[0].storm, "storm-a");
  EXPECT_EQ(st[0].seeds, 4u);
  EXPECT_EQ(st[0].max_of_max, 130.0);
  EXPECT_NEAR(st[0].mean_of_max, 115.0, kSum * 115);
  // Sample std of 100..130 step 10: sqrt(500/3); beta = std sqrt(6)/pi; mpm = mean - gamma beta.
  const double beta = std::sqrt(500.0 / 3.0) * std::sqrt(6.0) / M_PI;
  EXPECT_NEAR(st[0].fit.scale, beta, kSum * 115);
  EXPECT_NEAR(st[0].mpm, 115.0 - 0.57721566490153286 * beta, kSum * 115);
  EXPECT_NEAR(st[0].mpm_utilization, st[0].mpm / 400.0, kSum);
  EXPECT_FALSE(st[1].fitted);  // one seed: no fit
  EXPECT_TRUE(std::isnan(st[1].mpm));
  std::ostringstream csv;
  md::writeStormLineStatsCsv(csv, st, md::GumbelMethod::Moments);
  EXPECT_EQ(csv.str().substr(0, csv.str().find('\n')),
            "storm,line,seeds,max_of_max,mean_of_max,std_of_max,gumbel_fit,gumbel_location,gumbel_scale,mpm,mbl,mpm_utilization,"
            "mean_tension,limit_state,t_c_mean,t_c_dyn,design_tension,characteristic_strength,design_utilization,design_pass");
  EXPECT_NE(csv.str().find("\nstorm-b,leg,1,90,90,,,,,,,,0,,,,,,,\n"), std::string::npos) << csv.str();
  std::ostringstream cc;
  md::writeCaseLineStatsCsv(cc, {cases[0]});
  EXPECT_EQ(cc.str(), "case,storm,line,samples,max_tension,mean_tension,std_tension,mbl,utilization,top_offset\n"
                      "storm-a_seed-0,storm-a,leg,0,100,0,0,400,0,0\n");
}

// The line check over storms (designCheckStorms): T_c,mean is the mean over the seeds of each
// case's mean tension, T_c,dyn = MPM - T_c,mean, the factors by limit state, by hand.
TEST(SweepSummary, DesignCheckOfStormsByHand) {
  std::vector<md::CaseLineStats> cases;
  for (const char* storm : {"a", "b"})
    for (int k = 0; k < 2; ++k) {
      md::CaseLineStats c;
      c.case_name = std::string(storm) + "_seed-" + std::to_string(k);
      c.storm = storm;
      c.line = "leg";
      c.max = 300.0 + 20.0 * k;  // maxima 300, 320
      c.mean = 100.0 + 10.0 * k;  // means 100, 110: T_c,mean 105
      c.mbl = 500.0;
      cases.push_back(c);
    }
  auto st = md::stormLineStats(cases, md::GumbelMethod::Moments);
  ASSERT_EQ(st.size(), 2u);
  md::designCheckStorms(st, {false, true}, 1);
  const double mpm = st[0].mpm;
  EXPECT_NEAR(st[0].mean_tension, 105.0, kSum * 105);
  EXPECT_EQ(st[0].limit_state, md::LimitState::Uls);
  EXPECT_NEAR(st[0].design.design_tension, 1.10 * 105.0 + 1.50 * (mpm - 105.0), kSum * 500);
  EXPECT_NEAR(st[0].design.strength, 0.95 * 500.0, kSum * 500);
  EXPECT_EQ(st[1].limit_state, md::LimitState::Als);
  EXPECT_NEAR(st[1].design.design_tension, 1.00 * 105.0 + 1.10 * (mpm - 105.0), kSum * 500);
  std::ostringstream csv;
  md::writeStormLineStatsCsv(csv, st, md::GumbelMethod::Moments);
  EXPECT_NE(csv.str().find(",ULS,105,"), std::string::npos) << csv.str();
  EXPECT_NE(csv.str().find(",ALS,105,"), std::string::npos) << csv.str();
}

// The vessel's offset in a case, from vessel_x and vessel_y of a hand-written vessel series:
// distances from the first sample after skip_time, by hand; no vessel series: false.
TEST(SweepSummary, VesselOffsetAgainstHandSums) {
  const fs::path dir = tempDir("vessel_offset");
  std::ofstream(dir / "vessel_timeseries.csv") << "t,fx_body,vessel_x,vessel_y,vessel_z\n"
                                                  "0,1,10,20,0\n"
                                                  "1,1,13,24,0\n"   // 5 m, before skip_time
                                                  "2,1,10,23,0\n"   // 3 m
                                                  "3,1,16,28,0\n"   // 10 m
                                                  "4,1,10,20,0\n";  // 0 m
  md::CaseVesselOffset o;
  ASSERT_TRUE(md::caseVesselOffset(dir.string(), 1.5, "c1", "s", 2, o));
  EXPECT_NEAR(o.max, 10.0, kSum);
  EXPECT_NEAR(o.mean, (3.0 + 10.0 + 0.0) / 3.0, kSum);
  ASSERT_EQ(o.trace.size(), 2u) << "every 2nd of the 3 samples used";
  EXPECT_NEAR(o.trace[1].first, 0.0, kSum);
  std::ostringstream csv;
  md::writeCaseVesselOffsetCsv(csv, {o});
  EXPECT_EQ(csv.str(), "case,storm,max_offset,mean_offset\nc1,s,10,4.33333333333\n");
  const fs::path none = tempDir("no_vessel");
  EXPECT_FALSE(md::caseVesselOffset(none.string(), 0.0, "c", "s", 1, o));
  fs::remove_all(dir);
  fs::remove_all(none);
}
