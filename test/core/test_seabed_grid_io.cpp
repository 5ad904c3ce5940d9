// Seabed grid files: a good file parses into the documented storage order; every bad input
// raises ProblemError naming the file, the line, the value found and the constraint; the shipped
// example grid loads.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/seabed_grid_io.hpp"

using namespace mooring_dynamics::core;

namespace {

SeabedGrid parse(const std::string& text) {
  std::istringstream in(text);
  return readSeabedGrid(in, "bay.grid");
}

/// The ProblemError message of parsing `text` ("" if it parsed).
std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const ProblemError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("WRONG EXCEPTION TYPE: ") + e.what();
  }
  return "";
}

#define EXPECT_ERROR_HAS(text, ...)                                              \
  do {                                                                           \
    const std::string msg_ = errorOf(text);                                      \
    ASSERT_FALSE(msg_.empty()) << "parsed without error";                        \
    for (const std::string& part_ : std::vector<std::string>{__VA_ARGS__})       \
      EXPECT_NE(msg_.find(part_), std::string::npos)                             \
          << "message \"" << msg_ << "\" lacks \"" << part_ << "\"";             \
  } while (0)

const char* kGood = R"(# a 3 x 2 grid
  10 -20 5 2.5 3 2   # x0 y0 dx dy nx ny

1 2 3       # y = -20
4 5 6.5     # y = -17.5
)";

}  // namespace

TEST(SeabedGridIo, ParsesHeaderAndRowsInFileOrder) {
  const SeabedGrid g = parse(kGood);
  EXPECT_EQ(g.x0, 10.0);
  EXPECT_EQ(g.y0, -20.0);
  EXPECT_EQ(g.dx, 5.0);
  EXPECT_EQ(g.dy, 2.5);
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  EXPECT_EQ(g.source, "bay.grid");
  ASSERT_EQ(g.depths, (std::vector<double>{1, 2, 3, 4, 5, 6.5}));
  // depths[iy * nx + ix] is the depth at (x0 + ix dx, y0 + iy dy): the file's rows are y.
  EXPECT_EQ(g.at(2, 0), 3.0);
  EXPECT_EQ(g.at(0, 1), 4.0);
  EXPECT_EQ(g.depthAt(20.0, -17.5), 6.5);
  EXPECT_EQ(g.validate(), "");
}

TEST(SeabedGridIo, AcceptsSignsExponentsAndWindowsLineEnds) {
  const SeabedGrid g = parse("+1e1 -2E1 5 2.5 3 2\r\n1.0e0 2 3\r\n4 5 6.5\r\n");
  EXPECT_EQ(g.x0, 10.0);
  EXPECT_EQ(g.y0, -20.0);
  EXPECT_EQ(g.depths.size(), 6u);
}

TEST(SeabedGridIo, HeaderErrors) {
  EXPECT_ERROR_HAS("", "bay.grid", "no header line", "x0 y0 dx dy nx ny");
  EXPECT_ERROR_HAS("# only a comment\n\n", "no header line");
  EXPECT_ERROR_HAS("\n0 0 5 5 3\n", "bay.grid:2:", "header has 5 values", "expected 6");
  EXPECT_ERROR_HAS("0 0 -5 5 3 2\n", "bay.grid:1:", "dx = -5", "must be > 0");
  EXPECT_ERROR_HAS("0 0 5 0 3 2\n", "bay.grid:1:", "dy = 0", "must be > 0");
  EXPECT_ERROR_HAS("0 0 5 5 2.5 2\n", "bay.grid:1:", "nx = 2.5", "must be an integer in [2,");
  EXPECT_ERROR_HAS("0 0 5 5 3 1\n", "bay.grid:1:", "ny = 1", "must be an integer in [2,");
  EXPECT_ERROR_HAS("0 0 5 5 3 1e9\n", "ny = 1e9", "must be an integer in [2,");
  EXPECT_ERROR_HAS("0 north 5 5 3 2\n", "bay.grid:1:", "y0 = \"north\"", "not a number");
  EXPECT_ERROR_HAS("nan 0 5 5 3 2\n", "bay.grid:1:", "x0 = nan", "must be finite");
  EXPECT_ERROR_HAS("0 0 inf 5 3 2\n", "dx = inf", "must be finite");
}

TEST(SeabedGridIo, DepthErrors) {
  // Wrong count in a row, named by row, its y and the expected nx.
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n4 5\n", "bay.grid:3:", "row 1 (y = 2 m) has 2 depths", "expected nx = 3");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3 4\n", "bay.grid:2:", "row 0 (y = 0 m) has 4 depths", "expected nx = 3");
  // Too few or too many rows.
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n# end\n", "bay.grid:2:", "ends after 1 rows of depths", "expected ny = 2");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n1 2 3\n1 2 3\n", "bay.grid:4:", "more than ny = 2 rows");
  // Bad values, named by row and column with their coordinates.
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n4 nan 6\n", "bay.grid:3:", "row 1 (y = 2 m), column 1 (x = 5 m): depth = nan",
                   "must be finite");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n4 5 -6\n", "bay.grid:3:", "column 2 (x = 10 m): depth = -6", "must be > 0");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 0 3\n4 5 6\n", "bay.grid:2:", "depth = 0", "must be > 0");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1 2 3\n4 5 6m\n", "bay.grid:3:", "depth = \"6m\"", "not a number");
  EXPECT_ERROR_HAS("0 0 5 2 3 2\n1,2,3\n4 5 6\n", "bay.grid:2:", "has 1 depths");
}

TEST(SeabedGridIo, FileErrorsAndTheShippedExample) {
  try {
    loadSeabedGrid("/nonexistent/bay.grid");
    FAIL() << "no exception";
  } catch (const ProblemError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/nonexistent/bay.grid: cannot read file"), std::string::npos) << m;
  }
  // A bad file on disk: the message names its path and line.
  const std::string path = ::testing::TempDir() + "md_bad.grid";
  {
    std::ofstream f(path);
    f << "0 0 5 2 3 2\n1 2 3\n4 5\n";
  }
  try {
    loadSeabedGrid(path);
    FAIL() << "no exception";
  } catch (const ProblemError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path + ":3: ", 0), 0u) << m;
  }
  std::remove(path.c_str());

  const SeabedGrid g = loadSeabedGrid(std::string(MD_SOURCE_DIR) + "/config/sloping_bay.grid");
  EXPECT_EQ(g.validate(), "");
  EXPECT_EQ(g.nx, 5u);
  EXPECT_EQ(g.ny, 4u);
  // The 100 m contour passes through the origin (documented in the file).
  constexpr double kTol = 1e-12;  // bilinear weights of 1/2 on O(100) depths
  EXPECT_NEAR(g.depthAt(0.0, 0.0), 100.0, kTol);
}
