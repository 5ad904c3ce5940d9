// Tests of the cable_sim command-line tool: runs the built binary (path from the CABLE_SIM_EXE
// compile definition, set in CMakeLists.txt) on small problem files written to a temp directory and
// checks exit codes, messages and output files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace md_cli_test;

namespace {

std::size_t countLines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// A fully suspended elastic catenary: 100 m of line, top at (80, 0), anchor at (0, -60).
// Spacing 10 m gives 11 nodes; small and quick.
const char* const kGoodProblem = R"(name: small catenary
environment: {depth: 80, seabed: {stiffness: 1.0e6}}
materials:
  wire: {EA: 1.0e8, EI: 1.0, GJ: 1.0, mass: 11.82, added_mass: 1.63, wet_weight: 100.0,
         diameter: 0.045, cdn: 1.2, cdt: 0.01}
line:
  - {material: wire, length: 100.0, spacing: 10.0}
anchor: {x: 0, z: -60}
top:
  position: {x: 80, z: 0}
)";

class CliTest : public CliFixture {
 protected:
  CliTest() : CliFixture("test_cli") {}

  fs::path file(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    writeText(p, text);
    return p;
  }
};

// ---- usage errors: exit 2 ------------------------------------------------------------------

TEST_F(CliTest, UnknownOptionIsUsageError) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const RunResult r = run({"static", p.string(), "--bogus"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--bogus"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--help"), std::string::npos) << "should point to --help: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(CliTest, UnknownGlobalOptionOrCommandIsUsageError) {
  EXPECT_EQ(run({"--bogus"}).code, 2);
  const RunResult r = run({"frobnicate"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("frobnicate"), std::string::npos) << r.err;
  EXPECT_EQ(run({}).code, 2);
}

TEST_F(CliTest, MissingOrExtraArgumentsAreUsageErrors) {
  const fs::path p = file("good.yaml", kGoodProblem);
  EXPECT_EQ(run({"static"}).code, 2);
  EXPECT_EQ(run({"static", p.string(), p.string()}).code, 2);
  EXPECT_EQ(run({"static", p.string(), "--out"}).code, 2);  // option without its value
  EXPECT_EQ(run({"static", p.string(), "--table=yes"}).code, 2);  // flag given a value
}

TEST_F(CliTest, MalformedOptionValuesAreUsageErrors) {
  const fs::path p = file("good.yaml", kGoodProblem);
  for (const char* v : {"0", "-1", "abc", "nan", "inf", "1x"}) {
    const RunResult r = run({"static", p.string(), "--spacing-scale", v});
    EXPECT_EQ(r.code, 2) << "--spacing-scale " << v << ": " << r.err;
    EXPECT_NE(r.err.find("spacing-scale"), std::string::npos) << r.err;
  }
  for (const char* v : {"0", "-2", "1.5", "x"})
    EXPECT_EQ(run({"static", p.string(), "--table-stride", v}).code, 2) << "--table-stride " << v;
  // A scale that would give an absurd node count is refused before anything is allocated.
  EXPECT_EQ(run({"static", p.string(), "--spacing-scale", "1e-9"}).code, 2);
}

TEST_F(CliTest, DynamicWithoutDynamicsSectionExitsThree) {
  const fs::path p = file("good.yaml", kGoodProblem);  // no dynamics: section, so no duration
  const RunResult r = run({"dynamic", p.string(), "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("dynamics.duration"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "timeseries.csv"));
}

// ---- help and version --------------------------------------------------------------------

TEST_F(CliTest, HelpListsCommandsAndExitCodes) {
  const RunResult r = run({"--help"});
  EXPECT_EQ(r.code, 0);
  for (const char* s : {"static", "dynamic", "Exit codes", "0  success", "2  usage", "3  bad input",
                        "4  solver did not converge", "5  I/O error"})
    EXPECT_NE(r.out.find(s), std::string::npos) << "missing '" << s << "' in:\n" << r.out;
  EXPECT_EQ(run({"-h"}).code, 0);

  const RunResult s = run({"static", "--help"});
  EXPECT_EQ(s.code, 0);
  for (const char* o : {"--out", "--table", "--table-stride", "--spacing-scale", "static.json", "static_nodes.csv"})
    EXPECT_NE(s.out.find(o), std::string::npos) << "missing '" << o << "' in:\n" << s.out;
  EXPECT_EQ(run({"help", "static"}).out, s.out);
}

TEST_F(CliTest, VersionMatchesPackageXml) {
  const std::string xml = readText(fs::path(MD_SOURCE_DIR) / "package.xml");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(xml, m, std::regex("<version>([^<]+)</version>")));
  const RunResult r = run({"--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "cable_sim " + m[1].str() + "\n");
}

// ---- bad input: exit 3, message names the key -------------------------------------------

TEST_F(CliTest, BadValueExitsThreeAndNamesKey) {
  std::string text = kGoodProblem;
  text.replace(text.find("EA: 1.0e8"), 9, "EA: -5");
  const fs::path p = file("bad_ea.yaml", text);
  const fs::path out = dir_ / "out";
  const RunResult r = run({"static", p.string(), "--out", out.string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("materials.wire.EA"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-5"), std::string::npos) << "should show the value: " << r.err;
  EXPECT_FALSE(fs::exists(out / "static.json")) << "no results for a rejected problem";
}

TEST_F(CliTest, MisspelledKeyExitsThreeAndNamesKey) {
  std::string text = kGoodProblem;
  text.replace(text.find("spacing:"), 8, "spaceing:");
  const RunResult r = run({"static", file("typo.yaml", text).string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("spaceing"), std::string::npos) << r.err;
}

TEST_F(CliTest, UnknownMaterialExitsThreeAndNamesKey) {
  std::string text = kGoodProblem;
  text.replace(text.find("material: wire"), 14, "material: wier");
  const RunResult r = run({"static", file("unknown_material.yaml", text).string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("material"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("wier"), std::string::npos) << r.err;
}

TEST_F(CliTest, MissingOrMalformedFileExitsThree) {
  const RunResult r = run({"static", (dir_ / "does_not_exist.yaml").string()});
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("does_not_exist.yaml"), std::string::npos) << r.err;
  EXPECT_EQ(run({"static", file("broken.yaml", "line: [ {material: \n").string()}).code, 3);
}

// ---- success: exit 0, files written --------------------------------------------------------

TEST_F(CliTest, GoodProblemExitsZeroAndWritesFiles) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const fs::path out = dir_ / "results" / "nested";  // created on demand
  const RunResult r = run({"static", p.string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("small catenary"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("converged"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("NOT converged"), std::string::npos) << r.out;

  ASSERT_TRUE(fs::exists(out / "static.json"));
  ASSERT_TRUE(fs::exists(out / "static_nodes.csv"));
  const std::string json = readText(out / "static.json");
  EXPECT_NE(json.find("\"converged\": true"), std::string::npos) << json.substr(0, 400);
  EXPECT_NE(json.find("\"node_count\": 11"), std::string::npos) << json.substr(0, 600);

  const std::string csv = readText(out / "static_nodes.csv");
  EXPECT_EQ(csv.rfind("node,s,x,z,tension", 0), 0u) << csv.substr(0, 200);
  EXPECT_EQ(countLines(csv), 1u + 11u);  // header + 11 nodes (100 m at 10 m spacing)
  // Last row: the top node sits at the prescribed position (80, 0).
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  std::istringstream row(last);
  std::string node, s, x, z;
  std::getline(row, node, ',');
  std::getline(row, s, ',');
  std::getline(row, x, ',');
  std::getline(row, z, ',');
  EXPECT_EQ(node, "10");
  EXPECT_NEAR(std::stod(s), 100.0, 1e-9);
  EXPECT_NEAR(std::stod(x), 80.0, 1e-6);
  EXPECT_NEAR(std::stod(z), 0.0, 1e-6);
}

TEST_F(CliTest, WithoutOutWritesNoFiles) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const RunResult r = run({"static", p.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name == "good.yaml" || name == "stdout.txt" || name == "stderr.txt") << "unexpected " << name;
  }
}

TEST_F(CliTest, TableAndStride) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const RunResult plain = run({"static", p.string()});
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.out.find("tension [N]"), std::string::npos) << "no table without --table";

  const RunResult full = run({"static", p.string(), "--table"});
  ASSERT_EQ(full.code, 0) << full.err;
  EXPECT_NE(full.out.find("tension [N]"), std::string::npos) << full.out;
  EXPECT_EQ(countLines(full.out), countLines(plain.out) + 1 /*blank*/ + 1 /*header*/ + 11);

  // Stride 4 on 11 nodes: 0, 4, 8 and the last (10). --table-stride implies --table.
  const RunResult thin = run({"static", p.string(), "--table-stride=4"});
  ASSERT_EQ(thin.code, 0) << thin.err;
  EXPECT_EQ(countLines(thin.out), countLines(plain.out) + 2 + 4) << thin.out;
}

TEST_F(CliTest, SpacingScaleRefinesTheMesh) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const fs::path out = dir_ / "fine";
  const RunResult r = run({"static", p.string(), "--spacing-scale", "0.5", "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(countLines(readText(out / "static_nodes.csv")), 1u + 21u);  // 5 m spacing: 20 intervals
  const RunResult c = run({"static", p.string(), "--spacing-scale=2.5", "--out", (dir_ / "coarse").string()});
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(countLines(readText(dir_ / "coarse" / "static_nodes.csv")), 1u + 5u);  // 25 m: 4 intervals
}

// ---- not converged: exit 4, results still written -------------------------------------------

TEST_F(CliTest, NonConvergenceExitsFourAndStillWritesResults) {
  const std::string text = std::string(kGoodProblem) + "solver:\n  static: {max_iterations: 1}\n";
  const fs::path out = dir_ / "out";
  const RunResult r = run({"static", file("one_iteration.yaml", text).string(), "--out", out.string()});
  EXPECT_EQ(r.code, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("NOT converged"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(out / "static.json"));
  EXPECT_NE(readText(out / "static.json").find("\"converged\": false"), std::string::npos);
  EXPECT_EQ(countLines(readText(out / "static_nodes.csv")), 1u + 11u);
}

// ---- output errors: exit 5 ---------------------------------------------------------------

TEST_F(CliTest, UnwritableOutputExitsFive) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const fs::path blocker = file("not_a_dir", "x");
  const RunResult r = run({"static", p.string(), "--out", (blocker / "sub").string()});
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_NE(r.err.find("not_a_dir"), std::string::npos) << r.err;
  const RunResult r2 = run({"static", p.string(), "--out", blocker.string()});  // exists, is a file
  EXPECT_EQ(r2.code, 5) << r2.err;
  EXPECT_NE(r2.err.find("cannot create output directory '" + blocker.string() + "' ("), std::string::npos) << r2.err;
}

// ---- dynamic and plot ------------------------------------------------------------------------

// A slack suspended line (100 m between points 92 m apart), 10 nodes, heaved at the top for 2 s
// (positions prescribed, so the top follows the sinusoid closely).
const char* const kDynamicProblem = R"(name: small dynamic line
environment: {depth: 80, seabed: {stiffness: 1.0e6}}
materials:
  wire: {EA: 1.0e8, EI: 1.0, GJ: 1.0, mass: 11.82, added_mass: 1.63, wet_weight: 100.0,
         diameter: 0.045, cdn: 1.2, cdt: 0.01}
line:
  - {material: wire, length: 100.0, spacing: 11.5}
anchor: {x: 0, z: -60}
top:
  position: {x: 70, z: 0}
dynamics:
  duration: 2
  dt: 0.1
  snapshot_interval: 1
  record_s: [0, 100]
  top_motion: {type: sinusoid, amplitude_z: 0.5, period: 5, prescribe: position}
)";

/// Split one CSV line into its cells.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string c;
  while (std::getline(in, c, ',')) out.push_back(c);
  return out;
}

std::string lastLine(const std::string& text) {
  if (text.size() < 2) return text;
  return text.substr(text.rfind('\n', text.size() - 2) + 1);
}

bool isPng(const fs::path& p) {
  const std::string head = readText(p).substr(0, 8);
  return head == std::string("\x89PNG\r\n\x1a\n", 8);
}

// Every command that writes a folder says which and why it cannot (one helper, makeOutputDir);
// `dynamic` says so before the run, not after it.
TEST_F(CliTest, DynamicToAnOutputThatIsAFileExitsFiveAndSaysWhyBeforeRunning) {
  const fs::path p = file("dyn.yaml", kDynamicProblem);
  const fs::path blocker = file("a_file", "x");
  const RunResult r = run({"dynamic", p.string(), "--out", blocker.string()});
  EXPECT_EQ(r.code, 5) << r.err;
  // The path and the system's reason (here "Not a directory").
  EXPECT_NE(r.err.find("cannot create output directory '" + blocker.string() + "' ("), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("completed"), std::string::npos) << "no run before the check: " << r.out;
}

TEST_F(CliTest, DynamicWritesTimeseriesSnapshotsAndSummary) {
  const fs::path p = file("dyn.yaml", kDynamicProblem);
  const fs::path out = dir_ / "dyn";
  const RunResult r = run({"dynamic", p.string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << "no progress bar when stderr is not a terminal: " << r.err;
  for (const char* s : {"small dynamic line", "completed", "lambda_inf=-0.5", "top tension", "mean", "std", "min",
                        "max", "static top", "steps", "cuts", "Newton iterations", "wall time", "real-time factor",
                        "timeseries.csv", "dynamic_summary.json"})
    EXPECT_NE(r.out.find(s), std::string::npos) << "missing '" << s << "' in:\n" << r.out;
  EXPECT_EQ(r.out.find("NOT"), std::string::npos) << r.out;

  // Time series: header, then t = 0, 0.1, ..., 2 (21 samples).
  const std::string ts = readText(out / "timeseries.csv");
  EXPECT_EQ(ts.substr(0, ts.find('\n')),
            "t,top_tension,anchor_tension,top_x,top_z,tension_s0,x_s0,z_s0,tension_s100,x_s100,z_s100");
  EXPECT_EQ(countLines(ts), 1u + 21u) << ts.substr(0, 300);
  const std::vector<std::string> last = cells(lastLine(ts));
  ASSERT_EQ(last.size(), 11u);
  EXPECT_NEAR(std::stod(last[0]), 2.0, 1e-9);
  // The file's top motion reaches the solver: positions prescribed (fed back through the top
  // velocity over 5 steps), so the top is near where the heave puts it; on this 11.5 m mesh the
  // tracking lag stays within a few centimetres (kTopTrackingTol) while the heave moves 0.3 m.
  constexpr double kTopTrackingTol = 0.05;  // [m]
  EXPECT_NEAR(std::stod(last[3]), 70.0, kTopTrackingTol);
  EXPECT_NEAR(std::stod(last[4]), 0.5 * std::sin(0.8 * 3.14159265358979), kTopTrackingTol);
  EXPECT_NEAR(std::stod(last[9]), std::stod(last[3]), 1e-9);          // the s = 100 node is the top
  EXPECT_GT(std::stod(last[1]), 0.0);

  // Snapshots every second: t = 0, 1, 2, each with the 10 nodes.
  const std::string snaps = readText(out / "snapshots.csv");
  EXPECT_EQ(snaps.rfind("t,node,s,x,z,tension\n", 0), 0u) << snaps.substr(0, 100);
  EXPECT_EQ(countLines(snaps), 1u + 3u * 10u);
  EXPECT_EQ(countLines(readText(out / "static_nodes.csv")), 1u + 10u);

  const std::string js = readText(out / "dynamic_summary.json");
  for (const char* s : {"\"problem\": \"small dynamic line\"", "\"name\": \"lambda_inf=-0.5\"", "\"alpha_m\": ",
                        "\"alpha_k\": ", "\"gamma\": ", "\"dt\": 0.1", "\"duration\": 2", "\"completed\": true",
                        "\"message\": ", "\"mean\": ", "\"std\": ", "\"min\": ", "\"max\": ", "\"steps\": ",
                        "\"cuts\": ", "\"newton_iterations\": ", "\"wall_seconds\": ", "\"real_time_factor\": ",
                        "\"static_top_tension\": ", "\"samples\": 21"})
    EXPECT_NE(js.find(s), std::string::npos) << "missing '" << s << "' in:\n" << js;
}

TEST_F(CliTest, DynamicSchemeAndOverrides) {
  const fs::path p = file("dyn.yaml", kDynamicProblem);
  const RunResult box = run({"dynamic", p.string(), "--scheme", "box", "--no-progress", "--out", (dir_ / "box").string()});
  ASSERT_EQ(box.code, 0) << box.err;
  EXPECT_NE(box.out.find("box"), std::string::npos) << box.out;
  const std::string js = readText(dir_ / "box" / "dynamic_summary.json");
  EXPECT_NE(js.find("\"name\": \"box\", \"alpha_m\": 0.5, \"alpha_k\": 0.5, \"gamma\": 0.5"), std::string::npos) << js;

  const RunResult l = run({"dynamic", p.string(), "--lambda-inf=-0.3", "--duration", "1", "--dt", "0.05", "--out",
                           (dir_ / "l").string()});
  ASSERT_EQ(l.code, 0) << l.err;
  EXPECT_NE(l.out.find("lambda_inf=-0.3"), std::string::npos) << l.out;
  EXPECT_EQ(countLines(readText(dir_ / "l" / "timeseries.csv")), 1u + 21u);  // 1 s at 0.05 s
  EXPECT_NE(readText(dir_ / "l" / "dynamic_summary.json").find("\"dt\": 0.05"), std::string::npos);

  // Without --out: summary only, no files.
  const RunResult none = run({"dynamic", p.string()});
  ASSERT_EQ(none.code, 0) << none.err;
  EXPECT_FALSE(fs::exists(dir_ / "timeseries.csv"));
}

TEST_F(CliTest, DynamicUsageErrors) {
  const fs::path p = file("dyn.yaml", kDynamicProblem);
  const std::vector<std::vector<std::string>> bad = {
      {"dynamic"},
      {"dynamic", p.string(), "--scheme", "boxx"},
      {"dynamic", p.string(), "--scheme", "box", "--lambda-inf", "-0.5"},
      {"dynamic", p.string(), "--lambda-inf", "1"},
      {"dynamic", p.string(), "--lambda-inf", "x"},
      {"dynamic", p.string(), "--dt", "0"},
      {"dynamic", p.string(), "--duration", "-1"},
      {"dynamic", p.string(), "--no-progress=yes"},
      {"plot"},
  };
  for (const auto& args : bad) {
    const RunResult r = run(args);
    EXPECT_EQ(r.code, 2) << args.back() << ": " << r.err;
  }
  const RunResult h = run({"dynamic", "--help"});
  EXPECT_EQ(h.code, 0);
  for (const char* o : {"--out", "--duration", "--dt", "--scheme", "--lambda-inf", "--no-progress", "timeseries.csv",
                        "snapshots.csv", "dynamic_summary.json"})
    EXPECT_NE(h.out.find(o), std::string::npos) << "missing '" << o << "' in:\n" << h.out;
  EXPECT_NE(run({"--help"}).out.find("plot"), std::string::npos);
}

TEST_F(CliTest, DynamicBadKeyExitsThreeAndNamesKey) {
  std::string text = kDynamicProblem;
  text.replace(text.find("snapshot_interval"), 17, "snapshot_intervall");
  const RunResult r = run({"dynamic", file("typo.yaml", text).string(), "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("dynamics.snapshot_intervall"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown key"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "timeseries.csv"));

  std::string bad_dt = kDynamicProblem;
  bad_dt.replace(bad_dt.find("dt: 0.1"), 7, "dt: -0.1");
  const RunResult d = run({"dynamic", file("bad_dt.yaml", bad_dt).string()});
  EXPECT_EQ(d.code, 3) << d.err;
  EXPECT_NE(d.err.find("dynamics.dt = -0.1"), std::string::npos) << d.err;
}

TEST_F(CliTest, DynamicRunThatStopsExitsFourAndWritesWhatItHas) {
  // One Newton iteration per step, no step cutting and no fallback step: the first step cannot
  // converge.
  std::string text = kDynamicProblem;
  text += "  max_iterations: 1\n  max_cut_levels: 0\n  tolerance: 1.0e-12\n  fallback: false\n";
  const fs::path out = dir_ / "out";
  const RunResult r = run({"dynamic", file("stop.yaml", text).string(), "--out", out.string()});
  EXPECT_EQ(r.code, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("stopped"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("did NOT complete"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(out / "timeseries.csv"));
  EXPECT_GE(countLines(readText(out / "timeseries.csv")), 2u);  // header and at least t = 0
  EXPECT_LT(countLines(readText(out / "timeseries.csv")), 22u);
  EXPECT_NE(readText(out / "dynamic_summary.json").find("\"completed\": false"), std::string::npos);
}

TEST_F(CliTest, PlotWritesPngs) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "gnuplot not installed (scripts/setup installs gnuplot-nox)";
  const fs::path p = file("dyn.yaml", kDynamicProblem);
  const fs::path out = dir_ / "dyn";
  ASSERT_EQ(run({"dynamic", p.string(), "--out", out.string()}).code, 0);

  const RunResult r = run({"plot", out.string()});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  for (const char* png : {"top_tension.png", "shapes.png"}) {
    ASSERT_TRUE(fs::exists(out / png)) << png;
    EXPECT_GT(fs::file_size(out / png), 1000u) << png;
    EXPECT_TRUE(isPng(out / png)) << png;
  }
  EXPECT_NE(readText(out / "plot.gp").find("small dynamic line"), std::string::npos) << "title names the problem";

  const fs::path pngs = dir_ / "pngs" / "nested";
  const RunResult r2 = run({"plot", out.string(), "--out", pngs.string()});
  ASSERT_EQ(r2.code, 0) << r2.err;
  EXPECT_TRUE(isPng(pngs / "top_tension.png"));
  EXPECT_TRUE(isPng(pngs / "shapes.png"));
}

TEST_F(CliTest, PlotWithoutResultsExitsThree) {
  const RunResult r = run({"plot", dir_.string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("timeseries.csv"), std::string::npos) << r.err;
}

}  // namespace

// ---- model: 3d ----------------------------------------------------------------------------------

// The small catenary turned out of the x-z plane (top at 45 deg), with a current across it.
const char* const k3DProblem = R"(name: small 3-D catenary
model: 3d
environment:
  depth: 80
  seabed: {stiffness: 1.0e6}
  current: {speed: 0.3, direction_deg: 90}
materials:
  wire: {EA: 1.0e8, EI: 1.0, GJ: 1.0, mass: 11.82, added_mass: 1.63, wet_weight: 100.0,
         diameter: 0.045, cdn: 1.2, cdt: 0.01}
line:
  - {material: wire, length: 100.0, spacing: 10.0}
anchor: {x: 0, y: 0, z: -60}
top:
  position: {x: 56.5685424949, y: 56.5685424949, z: 0}
dynamics:
  duration: 1.0
  dt: 0.1
  record_s: [50]
  top_motion: {type: sinusoid, amplitude_y: 0.3, period: 5}
)";

TEST_F(CliTest, ThreeDimensionalModelWritesYColumns) {
  const fs::path p = file("line3d.yaml", k3DProblem);
  const fs::path out = dir_ / "s3";
  const RunResult r = run({"static", p.string(), "--out", out.string(), "--table"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3-D"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("y [m]"), std::string::npos) << r.out;
  const std::string csv = readText(out / "static_nodes.csv");
  EXPECT_EQ(csv.rfind("node,s,x,y,z,tension,shear,shear_b", 0), 0u) << csv.substr(0, 200);
  const std::vector<std::string> top = cells(lastLine(csv));
  EXPECT_NEAR(std::stod(top[2]), 56.5685424949, 1e-6);
  EXPECT_NEAR(std::stod(top[3]), 56.5685424949, 1e-6);
  const std::string json = readText(out / "static.json");
  EXPECT_NE(json.find("\"model\": \"3d\""), std::string::npos) << json.substr(0, 300);
  EXPECT_NE(json.find("\"y\": ["), std::string::npos);

  const fs::path dout = dir_ / "d3";
  const RunResult d = run({"dynamic", p.string(), "--out", dout.string()});
  ASSERT_EQ(d.code, 0) << d.out << d.err;
  const std::string ts = readText(dout / "timeseries.csv");
  EXPECT_EQ(ts.substr(0, ts.find('\n')), "t,top_tension,anchor_tension,top_x,top_y,top_z,tension_s50,x_s50,y_s50,z_s50");
  EXPECT_EQ(countLines(ts), 1u + 11u);
  EXPECT_NE(readText(dout / "dynamic_summary.json").find("\"model\": \"3d\""), std::string::npos);
}

TEST_F(CliTest, TwoDimensionalModelRejectsYAndSaysWhy) {
  std::string text = k3DProblem;
  text.replace(text.find("model: 3d\n"), 10, "");
  const RunResult r = run({"static", file("line2d.yaml", text).string()});
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("top.position.y"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("model: 3d"), std::string::npos) << r.err;
}

// A system whose line step fails at its smallest cut stops as a single line's run does: the
// samples up to the last good state are written, dynamic_summary.json says "completed": false, the
// exit code is 4 and stderr says where it stopped. Forced: the three-leg buoy in 4 m waves with 2
// Newton iterations per step, no step cutting and no fallback step, which the first seconds (waves ramped in over
// 6 s) still converge and a full wave does not.
TEST_F(CliTest, SystemDynamicRunThatStopsExitsFourAndWritesUpToTheLastGoodState) {
  std::string text = readText("config/three_leg_buoy.yaml");
  text = text.substr(0, text.find("\ndynamics:") + 1);
  const std::string wind = "  wind: {speed: 10, direction_deg: 45}";
  ASSERT_NE(text.find(wind), std::string::npos);
  text.replace(text.find(wind), wind.size(), wind + "\n  waves: {type: regular, height: 4, period: 6, ramp: 6}");
  text += "dynamics: {duration: 10, dt: 0.5, max_iterations: 2, max_cut_levels: 0, fallback: false}\n";
  const fs::path out = dir_ / "stop";
  const RunResult r = run({"dynamic", file("stop_system.yaml", text).string(), "--out", out.string()});
  EXPECT_EQ(r.code, 4) << r.out << r.err;
  EXPECT_NE(r.out.find("system dynamic run STOPPED"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line leg_"), std::string::npos) << "names the failed line: " << r.out;
  const std::string ts = readText(out / "system_timeseries.csv");
  const std::size_t rows = countLines(ts) - 1;
  EXPECT_GE(rows, 2u) << "the start and at least one good sample:\n" << ts;
  EXPECT_LT(rows, 21u) << "not the whole run:\n" << ts;
  // The last row written is the last good state; stdout, stderr and the summary give its time.
  std::string last = ts.substr(0, ts.size() - 1);
  last = last.substr(last.rfind('\n') + 1);
  const std::string t_last = last.substr(0, last.find(','));
  EXPECT_DOUBLE_EQ(std::stod(t_last), 0.5 * static_cast<double>(rows - 1)) << "samples every dt from 0:\n" << ts;
  EXPECT_NE(r.out.find("last good      t = " + t_last + " s"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("stopped at t = " + t_last + " s of 10 s"), std::string::npos) << r.err;
  const std::string js = readText(out / "dynamic_summary.json");
  EXPECT_NE(js.find("\"completed\": false"), std::string::npos) << js;
  EXPECT_NE(js.find("\"simulated_time\": " + t_last + ","), std::string::npos) << js;
  EXPECT_NE(js.find("\"kind\": \"system\""), std::string::npos) << js;
}

TEST_F(CliTest, SystemFileStaticWritesEveryLine) {
  const fs::path out = dir_ / "sys";
  const RunResult r = run({"static", "config/three_leg_buoy.yaml", "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  for (const char* s : {"system of 3 lines and 4 points", "converged", "leg_e", "leg_nw", "leg_sw", "draft"})
    EXPECT_NE(r.out.find(s), std::string::npos) << "missing '" << s << "' in:\n" << r.out;
  const std::string js = readText(out / "system.json");
  EXPECT_NE(js.find("\"converged\": true"), std::string::npos) << js.substr(0, 300);
  EXPECT_NE(js.find("\"name\": \"buoy\", \"type\": \"buoy\""), std::string::npos) << js;
  for (const char* l : {"leg_e", "leg_nw", "leg_sw"})
    EXPECT_EQ(countLines(readText(out / (std::string("static_nodes_") + l + ".csv"))), 1u + 151u) << l;
  // Dynamics: the buoy left free in its current and wind stays at its equilibrium.
  const fs::path dout = dir_ / "sysdyn";
  const RunResult d = run({"dynamic", "config/three_leg_buoy.yaml", "--duration", "5", "--out", dout.string()});
  ASSERT_EQ(d.code, 0) << d.out << d.err;
  EXPECT_NE(d.out.find("system dynamic run completed"), std::string::npos) << d.out;
  const std::string ts = readText(dout / "system_timeseries.csv");
  EXPECT_EQ(ts.substr(0, ts.find('\n')), "t,buoy_x,buoy_y,buoy_z,leg_e_top_tension,leg_nw_top_tension,leg_sw_top_tension");
  EXPECT_EQ(countLines(ts), 1u + 11u);
  // The branched array too: lines below its junction float follow it as moving anchors.
  const RunResult b = run({"dynamic", "config/branched_array.yaml", "--duration", "3", "--dt", "1"});
  EXPECT_EQ(b.code, 0) << b.out << b.err;
  EXPECT_NE(b.out.find("system dynamic run completed"), std::string::npos) << b.out;
}
