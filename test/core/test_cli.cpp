// Tests of the cable_sim command-line tool: runs the built binary (path from the CABLE_SIM_EXE
// compile definition, set in CMakeLists.txt) on small problem files written to a temp directory and
// checks exit codes, messages and output files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

#ifdef CABLE_SIM_EXE
const char* const kExe = CABLE_SIM_EXE;
#else
const char* const kExe = nullptr;
#endif

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void writeText(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
  ASSERT_TRUE(f.good()) << p;
}

std::size_t countLines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
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

struct RunResult {
  int code = -1;
  std::string out;
  std::string err;
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(kExe, nullptr) << "CABLE_SIM_EXE is not defined: see the test_cli lines in CMakeLists.txt";
    ASSERT_TRUE(fs::exists(kExe)) << "cable_sim binary not found at " << kExe;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("md_test_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }

  fs::path file(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    writeText(p, text);
    return p;
  }

  RunResult run(const std::vector<std::string>& args) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    std::string cmd = shellQuote(kExe);
    for (const auto& a : args) cmd += " " + shellQuote(a);
    cmd += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string());
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    return r;
  }

  fs::path dir_;
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

TEST_F(CliTest, DynamicIsNotYetImplemented) {
  const fs::path p = file("good.yaml", kGoodProblem);
  const RunResult r = run({"dynamic", p.string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not yet implemented"), std::string::npos) << r.err;
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
}

}  // namespace
