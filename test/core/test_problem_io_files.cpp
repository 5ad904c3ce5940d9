// YAML problem loader, problem files and the files they name: a file's errors start with its path
// and a good file without a name takes its stem; seabed grid and current table files, relative to
// the problem file, their errors naming the key, the file, the row and the constraint; every
// shipped config/*.yaml loads, the paper's configs match its appendix, and the documentation's
// complete example loads. The problem as text: test_problem_io.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "problem_io_test_util.hpp"

using namespace mooring_dynamics::core;
using namespace mooring_dynamics::core::testing_util;

TEST(ProblemIo, FileErrors) {
  EXPECT_ERROR_HAS(std::string(), "empty");
  try {
    loadProblemFromFile("/nonexistent/problem.yaml");
    FAIL() << "no exception";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/problem.yaml"), std::string::npos) << e.what();
  }
  // A bad file: the message starts with the path.
  const std::string path = ::testing::TempDir() + "md_bad_problem.yaml";
  {
    std::ofstream f(path);
    f << mutate("depth: 100", "depth: -5");
  }
  try {
    loadProblemFromFile(path);
    FAIL() << "no exception";
  } catch (const ProblemError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path + ": ", 0), 0u) << m;
    EXPECT_NE(m.find("environment.depth = -5"), std::string::npos) << m;
  }
  // A good file without a name gets the file stem as its name.
  const std::string good = ::testing::TempDir() + "md_minimal.yaml";
  {
    std::ofstream f(good);
    f << kMinimal;
  }
  EXPECT_EQ(loadProblemFromFile(good).name, "md_minimal");
  std::remove(path.c_str());
  std::remove(good.c_str());
}

TEST(ProblemIo, SeabedGridFileIsRelativeToTheProblemFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "md_grid_test";
  fs::create_directories(dir / "sub");
  {
    std::ofstream g(dir / "sub" / "bay.grid");
    g << "# x0 y0 dx dy nx ny\n-100 -100 100 100 3 3\n130 120 110\n125 115 105\n120 110 100\n";
  }
  const std::string yaml = mutate("seabed: {stiffness: 2.0e5, damping: 10, profile: [[-100, 100], [0, 100], [200, 80]]}",
                                  "seabed: {stiffness: 2.0e5, damping: 10, grid_file: sub/bay.grid}");
  {
    std::ofstream f(dir / "problem.yaml");
    f << yaml;
  }
  const Problem p = loadProblemFromFile((dir / "problem.yaml").string());
  const SeabedGrid& g = p.environment.seabed.grid;
  ASSERT_EQ(g.nx, 3u);
  EXPECT_EQ(g.depths[8], 100.0);
  EXPECT_EQ(g.source, (dir / "sub" / "bay.grid").string());
  EXPECT_TRUE(p.environment.seabed.profile.empty());
  // The anchor's default z is the grid's depth under it (x = -1.5, y = 0).
  constexpr double kTol = 1e-12;  // bilinear weights on O(100) depths
  EXPECT_NEAR(p.anchor_z, -(115.0 + 1.5 * 0.1), kTol);
  // The same text from a string: relative to base_dir, or to the working directory without one.
  EXPECT_EQ(loadProblemFromString(yaml, dir.string()).environment.seabed.grid.depths, g.depths);
  EXPECT_ERROR_HAS(yaml, "environment.seabed.grid_file = \"sub/bay.grid\"", "sub/bay.grid: cannot read file",
                   "(line 8)");
  fs::remove_all(dir);
}

TEST(ProblemIo, SeabedGridErrors) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "md_grid_errors";
  fs::create_directories(dir);
  {
    std::ofstream g(dir / "short.grid");
    g << "0 0 10 10 2 2\n100 100\n";
  }
  auto withSeabed = [](const std::string& seabed) { return minimalWith("environment:\n  seabed: " + seabed + "\n"); };
  auto errorIn = [&](const std::string& text) {
    try {
      loadProblemFromString(text, dir.string());
    } catch (const ProblemError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string shortMsg = errorIn(withSeabed("{grid_file: short.grid}"));
  for (const char* part : {"environment.seabed.grid_file = \"short.grid\"", "short.grid:2:",
                           "ends after 1 rows of depths: expected ny = 2", "(line 9)"})
    EXPECT_NE(shortMsg.find(part), std::string::npos) << shortMsg << " lacks " << part;
  const std::string missing = errorIn(withSeabed("{grid_file: nothere.grid}"));
  EXPECT_NE(missing.find((dir / "nothere.grid").string() + ": cannot read file"), std::string::npos) << missing;
  const std::string both = errorIn(withSeabed("{profile: [[0, 100], [10, 90]], grid_file: short.grid}"));
  EXPECT_NE(both.find("environment.seabed: has both profile and grid_file"), std::string::npos) << both;
  EXPECT_ERROR_HAS(withSeabed("{grid_file: \"\"}"), "environment.seabed.grid_file", "must name a grid file");
  EXPECT_ERROR_HAS(withSeabed("{grid_file: [a]}"), "environment.seabed.grid_file");
  fs::remove_all(dir);
}

TEST(ProblemIo, ShippedConfigsLoad) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(MD_SOURCE_DIR) / "config";
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    // Not every YAML in config/ need be a problem file (e.g. ROS parameter files): a problem file
    // has top-level "materials:" and "line:".
    std::ifstream f(entry.path());
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (!std::regex_search(text, std::regex("(^|\n)materials:")) || !std::regex_search(text, std::regex("(^|\n)line:")))
      continue;
    ++n;
    SCOPED_TRACE(entry.path().string());
    Problem p;
    EXPECT_NO_THROW(p = loadProblemFromFile(entry.path().string()));
    EXPECT_FALSE(p.name.empty());
    EXPECT_FALSE(p.segments.empty());
  }
  EXPECT_GE(n, 4);
}

TEST(ProblemIo, PaperConfigsMatchAppendix) {
  const std::string dir = std::string(MD_SOURCE_DIR) + "/config/";
  {
    const Problem p = loadProblemFromFile(dir + "chain_mooring.yaml");
    ASSERT_EQ(p.segments.size(), 7u);
    EXPECT_NEAR(p.totalLength(), 80.78, 1e-9);
    EXPECT_EQ(p.top.type, TopBoundary::Type::Buoy);
    double ux = 0, uy = 0;
    p.environment.currentAt(-30.0, ux, uy);
    EXPECT_NEAR(ux, 0.5, 1e-12);
  }
  {
    const Problem p = loadProblemFromFile(dir + "s_tether.yaml");
    EXPECT_NEAR(p.totalLength(), 2184.0, 1e-9);
    EXPECT_DOUBLE_EQ(p.anchor_z, -1860.0);
    ASSERT_EQ(p.environment.current.size(), 8u);
    EXPECT_DOUBLE_EQ(p.environment.current[6].speed, 0.25);
    std::size_t large = 0, medium = 0, dock = 0;
    for (const auto& s : p.segments)
      for (const auto& b : s.bodies) {
        const std::string& n = p.bodies[b.body].name;
        large += n == "float_large";
        medium += n == "float_medium";
        dock += n == "auv_dock";
      }
    EXPECT_EQ(large, 8u);
    EXPECT_EQ(medium, 17u);
    EXPECT_EQ(dock, 1u);
  }
  {
    const Problem p = loadProblemFromFile(dir + "catenary_seabed.yaml");
    EXPECT_DOUBLE_EQ(p.anchor_z, -100.0);
    EXPECT_EQ(p.top.type, TopBoundary::Type::Position);
  }
}

TEST(ProblemIo, DocumentationExampleLoads) {
  const std::string yaml = documentedYaml("## Complete example");
  ASSERT_FALSE(yaml.empty());
  Problem p;
  EXPECT_NO_THROW(p = loadProblemFromString(yaml));
  EXPECT_EQ(p.segments.size(), 3u);
  EXPECT_EQ(p.top.type, TopBoundary::Type::Buoy);
}

namespace {
/// Writes `text` to `name` in the test's temporary directory and returns the path.
std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream f(path, std::ios::binary);
  f << text;
  return path;
}
}  // namespace

TEST(ProblemIo, CurrentProfileFromACsvFileIsTheInlineProfile) {
  // The same three points inline and in a CSV file (header, a comment, a relative path): the
  // same table, point for point.
  const std::string inline_text = minimalWith(R"(environment:
  depth: 100
  current:
    - {depth: 0, speed: 0.7, direction_deg: 10}
    - {depth: 50.5, speed: 0.4, direction_deg: 20}
    - {depth: 100, speed: 0.1, direction_deg: -30}
)");
  writeTemp("md_current.csv", "depth,speed,direction_deg\n# from the ADCP\n0,0.7,10\n50.5,0.4,20\n100,0.1,-30\n");
  const std::string file =
      writeTemp("md_current_file.yaml", minimalWith("environment:\n  depth: 100\n  current: {file: md_current.csv}\n"));
  const Problem a = loadProblemFromString(inline_text);
  const Problem b = loadProblemFromFile(file);
  ASSERT_EQ(b.environment.current.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(b.environment.current[i].depth, a.environment.current[i].depth) << i;
    EXPECT_EQ(b.environment.current[i].speed, a.environment.current[i].speed) << i;
    EXPECT_EQ(b.environment.current[i].direction, a.environment.current[i].direction) << i;
  }
}

TEST(ProblemIo, CurrentFileErrorsNameTheKeyTheFileTheRowAndTheConstraint) {
  auto errorWith = [](const std::string& csv) {
    writeTemp("md_bad_current.csv", csv);
    const std::string path =
        writeTemp("md_bad_current.yaml", minimalWith("environment:\n  current: {file: md_bad_current.csv}\n"));
    try {
      loadProblemFromFile(path);
    } catch (const ProblemError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string m = errorWith("depth,speed,direction_deg\n0,0.5,0\n10,0.4,0\n10,0.3,0\n");
  EXPECT_NE(m.find("environment.current.file = \"md_bad_current.csv\""), std::string::npos) << m;
  EXPECT_NE(m.find("md_bad_current.csv:4: depth = 10: must increase along the profile (previous depth = 10)"),
            std::string::npos) << m;
  m = errorWith("0,0.5,0\n10,-0.4,0\n");
  EXPECT_NE(m.find("md_bad_current.csv:2: speed = -0.4: must be >= 0"), std::string::npos) << m;
  m = errorWith("0,0.5\n");
  EXPECT_NE(m.find("md_bad_current.csv:1"), std::string::npos) << m;
  m = errorWith("0,0.5,0\n");
  EXPECT_NE(m.find("at least 2 rows"), std::string::npos) << m;
  // A missing file names it; {file} does not mix with the other forms' keys.
  std::remove((::testing::TempDir() + "md_bad_current.csv").c_str());
  const std::string missing =
      writeTemp("md_bad_current.yaml", minimalWith("environment:\n  current: {file: md_bad_current.csv}\n"));
  try {
    loadProblemFromFile(missing);
    ADD_FAILURE() << "a missing current file loaded";
  } catch (const ProblemError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read file"), std::string::npos) << e.what();
  }
  EXPECT_ERROR_HAS(minimalWith("environment:\n  current: {file: x.csv, speed: 1}\n"), "speed");
}
