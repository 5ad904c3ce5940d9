// Tests of the sweep files (io/sweep_io.hpp): expansion and case names, the edits (set a key, a
// whole section, a list item; remove a line by name) on problem, system and vessel files, the
// files a case names kept pointing at the same file, the manifest, and errors naming key, value
// and constraint.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/sweep_io.hpp"

namespace md = mooring_dynamics::core;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(MD_SOURCE_DIR) + "/test/data/";
const std::string kConfig = std::string(MD_SOURCE_DIR) + "/config/";

/// The exception message of loading `text` as a sweep ("" when it loads).
std::string loadError(const std::string& text) {
  try {
    md::loadSweepFromString(text, kData);
  } catch (const md::ProblemError& e) {
    return e.what();
  }
  return "";
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("md_test_sweep_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const char* const kSystemSweep = R"(
name: buoy
base: small_system.yaml
set:
  dynamics.duration: 4
  environment.waves: {type: jonswap, hs: 1.0, tp: 6, components: 20, ramp: 2}
variations:
  - {name: storm, values: [{label: hs1, set: {environment.waves.hs: 1.0, environment.waves.tp: 6}},
                           {label: hs2, set: {environment.waves.hs: 2.0, environment.waves.tp: 7}}]}
  - {name: heading, key: environment.waves.direction_deg, range: {from: 0, to: 90, step: 45}}
  - {name: seed, key: environment.waves.seed, values: [1, 2], seeds: true}
  - name: damage
    values:
      - {label: intact}
      - {label: no-e, remove: ["lines[name=leg_e]", points.anchor_e]}
statistics: {gumbel_fit: mle, skip_time: 1.5}
)";

}  // namespace

TEST(SweepIo, ExpandsTheProductInVariationOrderWithStableNames) {
  const md::SweepSpec s = md::loadSweepFromString(kSystemSweep, kData);
  EXPECT_EQ(s.name, "buoy");
  EXPECT_EQ(s.gumbel, md::GumbelMethod::MaximumLikelihood);
  EXPECT_EQ(s.skip_time, 1.5);
  ASSERT_EQ(s.variations.size(), 4u);
  EXPECT_TRUE(s.variations[2].seeds);
  const std::vector<md::SweepCase> cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 2u * 3u * 2u * 2u);
  EXPECT_EQ(cases.front().name, "storm-hs1_heading-0_seed-1_damage-intact");
  EXPECT_EQ(cases[1].name, "storm-hs1_heading-0_seed-1_damage-no-e");  // the last variation fastest
  EXPECT_EQ(cases[2].name, "storm-hs1_heading-0_seed-2_damage-intact");
  EXPECT_EQ(cases.back().name, "storm-hs2_heading-90_seed-2_damage-no-e");
  // The storm leaves the seed out: the two seeds of a storm, heading and damage share it.
  EXPECT_EQ(cases[0].storm, "storm-hs1_heading-0_damage-intact");
  EXPECT_EQ(cases[2].storm, cases[0].storm);
  EXPECT_NE(cases[1].storm, cases[0].storm);
  // Names are unique.
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t j = i + 1; j < cases.size(); ++j) EXPECT_NE(cases[i].name, cases[j].name);
  // The range's values and their numbers (for plots).
  ASSERT_EQ(s.variations[1].values.size(), 3u);
  EXPECT_EQ(s.variations[1].values[2].label, "90");
  EXPECT_TRUE(s.variations[1].values[2].numeric);
  EXPECT_EQ(s.variations[1].values[2].number, 90.0);
  EXPECT_FALSE(s.variations[0].values[0].numeric);  // two keys set: no single number
}

TEST(SweepIo, CaseFilesCarryTheEditsAndLoad) {
  const md::SweepSpec s = md::loadSweepFromString(kSystemSweep, kData);
  const std::vector<md::SweepCase> cases = md::expandSweep(s);
  const md::SweepCase& c = cases.back();  // hs2, heading 90, seed 2, leg_e removed
  const md::SystemProblem p = md::loadSystemFromString(md::caseProblemText(s, c, kData), kData);
  EXPECT_EQ(p.environment.waves.hs, 2.0);
  EXPECT_EQ(p.environment.waves.tp, 7.0);
  EXPECT_EQ(p.environment.waves.seed, 2u);
  EXPECT_NEAR(p.environment.waves.direction, M_PI / 2, 1e-15);
  EXPECT_EQ(p.dynamics.duration, 4.0);
  ASSERT_EQ(p.lines.size(), 2u);
  EXPECT_EQ(p.lines[0].name, "leg_nw");
  EXPECT_EQ(p.points.size(), 3u);
  const md::SystemProblem p0 = md::loadSystemFromString(md::caseProblemText(s, cases.front(), kData), kData);
  EXPECT_EQ(p0.lines.size(), 3u);
  EXPECT_EQ(p0.environment.waves.hs, 1.0);
  EXPECT_EQ(p0.environment.waves.direction, 0.0);
}

TEST(SweepIo, SingleLineAndListItemsByIndex) {
  const md::SweepSpec s = md::loadSweepFromString(R"(
base: small_catenary.yaml
variations:
  - {name: spacing, key: "line[0].spacing", values: [2, 5]}
  - {name: len, key: line.0.length, values: [150, 151.5]}
)", kData);
  const auto cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[3].name, "spacing-5_len-151.5");
  const md::Problem p = md::loadProblemFromString(md::caseProblemText(s, cases[3], kData), kData);
  ASSERT_EQ(p.segments.size(), 1u);
  EXPECT_EQ(p.segments[0].spacing, 5.0);
  EXPECT_EQ(p.segments[0].length, 151.5);
}

TEST(SweepIo, VesselLineRemovedByNameAndTheMotionTableStillFound) {
  const fs::path dir = tempDir("vessel");
  const fs::path case_dir = dir / "out" / "cases";
  fs::create_directories(case_dir);
  const md::SweepSpec s = md::loadSweepFromString(
      "base: " + kConfig + "spread_mooring.yaml\n"
      "variations:\n"
      "  - name: damage\n"
      "    values: [{label: intact}, {label: no-bp1, remove: \"vessel.lines[name=bow_port_1]\"}]\n",
      dir.string());
  const auto cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 2u);
  const std::string text = md::caseProblemText(s, cases[1], case_dir.string());
  // The motion table is named relative to where the case file goes, and resolves to the same file.
  const md::SystemProblem p = md::loadSystemFromString(text, case_dir.string());
  EXPECT_EQ(p.lines.size(), 7u);
  for (const auto& l : p.lines) EXPECT_NE(l.name, "bow_port_1");
  EXPECT_EQ(fs::canonical(p.vessel.motion_table), fs::canonical(kConfig + "spread_mooring_motion.csv"));
  const std::string named = YAML::Load(text)["vessel"]["motion_table"].as<std::string>();
  EXPECT_TRUE(fs::path(named).is_relative()) << named;
  fs::remove_all(dir);
}

TEST(SweepIo, ManifestRoundTrip) {
  const md::SweepSpec s = md::loadSweepFromString(kSystemSweep, kData);
  const auto cases = md::expandSweep(s);
  const fs::path dir = tempDir("manifest");
  const fs::path f = dir / "manifest.yaml";
  std::ofstream(f) << md::manifestText(md::manifestOf(s, cases));
  const md::SweepManifest m = md::loadManifestFromFile(f.string());
  EXPECT_EQ(m.name, "buoy");
  EXPECT_EQ(m.gumbel, md::GumbelMethod::MaximumLikelihood);
  EXPECT_EQ(m.skip_time, 1.5);
  ASSERT_EQ(m.variations.size(), 4u);
  EXPECT_EQ(m.variations[1].labels, (std::vector<std::string>{"0", "45", "90"}));
  EXPECT_EQ(m.variations[1].numbers[1], 45.0);
  EXPECT_TRUE(std::isnan(m.variations[0].numbers[0]));
  EXPECT_TRUE(m.variations[2].seeds);
  ASSERT_EQ(m.cases.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(m.cases[i].name, cases[i].name);
    EXPECT_EQ(m.cases[i].storm, cases[i].storm);
    EXPECT_EQ(m.cases[i].choice, cases[i].choice);
  }
  fs::remove_all(dir);
}

TEST(SweepIo, ErrorsNameKeyValueAndConstraint) {
  const std::string base = "base: small_system.yaml\n";
  auto has = [](const std::string& msg, const std::string& part) {
    return msg.find(part) != std::string::npos;
  };
  std::string e = loadError("base: nope.yaml\n");
  EXPECT_TRUE(has(e, "base = \"nope.yaml\"") && has(e, "no such file")) << e;
  e = loadError(base + "variations: [{name: d, values: [{label: x, remove: \"lines[name=leg_q]\"}]}]\n");
  EXPECT_TRUE(has(e, "variation 'd', value 'x'") && has(e, "lines[name=leg_q]") && has(e, "leg_e, leg_nw, leg_sw")) << e;
  e = loadError(base + "variations: [{name: d, key: \"lines[7].name\", values: [a]}]\n");
  EXPECT_TRUE(has(e, "lines[7].name") && has(e, "the list has 3 items")) << e;
  e = loadError(base + "variations: [{name: h, key: environment.waves.direction_deg, range: {from: 10, to: 0, step: 5}}]\n");
  EXPECT_TRUE(has(e, "variations[0].range.to = 0") && has(e, "must be >= from")) << e;
  e = loadError(base + "variations: [{name: h, key: environment.waves.direction_deg, range: {from: 0, to: 10, step: 0}}]\n");
  EXPECT_TRUE(has(e, "variations[0].range.step = 0") && has(e, "> 0")) << e;
  e = loadError(base + "variations: [{name: wave_dir, key: environment.waves.direction_deg, values: [0]}]\n");
  EXPECT_TRUE(has(e, "variations[0].name = \"wave_dir\"") && has(e, "letters and digits")) << e;
  e = loadError(base + "variations: [{name: h, key: environment.waves.direction_deg, values: [0, 0]}]\n");
  EXPECT_TRUE(has(e, "label '0'")) << e;
  e = loadError(base + "variations: [{name: h, key: environment.waves.direction_deg, values: [0], range: {from: 0, to: 1, step: 1}}]\n");
  EXPECT_TRUE(has(e, "not both")) << e;
  e = loadError(base + "variations: [{name: h, values: [{set: {dynamics.dt: 0.1}}]}]\n");
  EXPECT_TRUE(has(e, "label")) << e;
  e = loadError(base + "variations: [{name: h, key: \"lines[nme=x]\", values: [1]}]\n");
  EXPECT_TRUE(has(e, "[nme=x]") && has(e, "[name=NAME]")) << e;
  e = loadError(base + "variations: [{name: h, key: a, values: [1]}, {name: h, key: b, values: [1]}]\n");
  EXPECT_TRUE(has(e, "two variations have this name")) << e;
  e = loadError(base + "statistics: {gumbel_fit: lsq}\n");
  EXPECT_TRUE(has(e, "statistics.gumbel_fit = \"lsq\"") && has(e, "moments or mle")) << e;
  e = loadError(base + "variatons: []\n");
  EXPECT_TRUE(has(e, "did you mean \"variations\"")) << e;
  e = loadError(base + "variations: [{name: s, key: a, values: [1], seeds: true}, {name: t, key: b, values: [1], seeds: true}]\n");
  EXPECT_TRUE(has(e, "one variation at most")) << e;
}

TEST(SweepIo, AFileTheSweepSetsIsRelativeToTheSweepFile) {
  const fs::path dir = tempDir("pathset");
  // The sweep "lives" in config/ and names a motion table there for a base file in test/data/.
  const md::SweepSpec s = md::loadSweepFromString("base: " + kData + "small_vessel.yaml\n"
                                                  "set: {vessel.motion_table: spread_mooring_motion.csv}\n",
                                                  kConfig);
  const auto cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_EQ(cases[0].name, "base");
  const md::SystemProblem p = md::loadSystemFromString(md::caseProblemText(s, cases[0], dir.string()), dir.string());
  EXPECT_EQ(fs::canonical(p.vessel.motion_table), fs::canonical(kConfig + "spread_mooring_motion.csv"));
  fs::remove_all(dir);
}

// A file named inside a section the sweep sets (vessel.raos: {file: ...}) is relative to the sweep
// file too, and the case file finds it from its own folder.
TEST(SweepIo, AFileInsideASectionTheSweepSetsIsRelativeToTheSweepFile) {
  const fs::path dir = tempDir("pathsection");
  const md::SweepSpec s = md::loadSweepFromString(
      "base: " + kData + "small_vessel.yaml\n"
      "set:\n"
      "  dynamics.duration: 10\n"
      "  vessel.sea_state: {type: jonswap, hs: 2, tp: 8, f_max_factor: 3}\n"
      "  vessel.raos: {file: spread_vessel.4, ulen: 1, symmetry: port_starboard}\n",
      kConfig);
  const auto cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 1u);
  const std::string text = md::caseProblemText(s, cases[0], dir.string());
  const md::SystemProblem p = md::loadSystemFromString(text, dir.string());
  EXPECT_EQ(fs::canonical(p.vessel.raos.file), fs::canonical(kConfig + "spread_vessel.4"));
  EXPECT_TRUE(fs::path(YAML::Load(text)["vessel"]["raos"]["file"].as<std::string>()).is_relative())
      << "written relative to the case folder";
  fs::remove_all(dir);
}

// The shipped design-storm sweep: 3 headings x (intact, one line broken) x 3 seeds, and every case
// file loads (the RAO and drift tables cover each case's sea: frequencies and headings relative
// to the hull); the broken cases have 7 lines, and they are the ALS storms.
TEST(SweepIo, ShippedSpreadMooringSweepCasesLoad) {
  const fs::path dir = tempDir("shipped_spread");
  const md::SweepSpec s = md::loadSweepFromFile(kConfig + "spread_mooring_sweep.yaml");
  const auto cases = md::expandSweep(s);
  ASSERT_EQ(cases.size(), 18u);
  EXPECT_EQ(s.design_class, 1);
  EXPECT_EQ(s.als_labels, std::vector<std::string>{"no-bow-stbd-2"});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const md::SystemProblem p = md::loadSystemFromString(md::caseProblemText(s, c, dir.string()), dir.string());
    EXPECT_TRUE(p.vessel.sea_state);
    EXPECT_TRUE(p.vessel.low_frequency && p.vessel.wave_drift);
    EXPECT_EQ(p.dynamics.duration, 10800.0) << "3-hour storms";
    const bool broken = c.name.find("no-bow-stbd-2") != std::string::npos;
    EXPECT_EQ(p.lines.size(), broken ? 7u : 8u);
  }
  fs::remove_all(dir);
}

// statistics.design_check: the consequence class and the ALS labels, checked against the
// variations, and carried by the manifest to `sweep --collect`.
TEST(SweepIo, DesignCheckSettingsAndTheManifest) {
  std::string text = kSystemSweep;
  text.replace(text.find("statistics: {gumbel_fit: mle, skip_time: 1.5}"), 46,
               "statistics: {gumbel_fit: mle, skip_time: 1.5, design_check: {consequence_class: 2, als: [no-e]}}");
  const md::SweepSpec s = md::loadSweepFromString(text, kData);
  EXPECT_EQ(s.design_class, 2);
  EXPECT_EQ(s.als_labels, std::vector<std::string>{"no-e"});
  const fs::path dir = tempDir("manifest_design");
  std::ofstream(dir / "manifest.yaml") << md::manifestText(md::manifestOf(s, md::expandSweep(s)));
  const md::SweepManifest m = md::loadManifestFromFile((dir / "manifest.yaml").string());
  EXPECT_EQ(m.design_class, 2);
  EXPECT_EQ(m.als_labels, std::vector<std::string>{"no-e"});
  fs::remove_all(dir);
  std::string bad = text;
  bad.replace(bad.find("als: [no-e]"), 11, "als: [no-q]");
  EXPECT_NE(loadError(bad).find("als: no variation has the label \"no-q\""), std::string::npos) << loadError(bad);
  bad = text;
  bad.replace(bad.find("consequence_class: 2"), 20, "consequence_class: 3");
  EXPECT_NE(loadError(bad).find("consequence_class = 3: must be 1 or 2"), std::string::npos) << loadError(bad);
}
