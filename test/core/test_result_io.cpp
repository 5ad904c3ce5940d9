// Result writers: JSON keys and full-precision numbers, CSV shape, text summaries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/result_io.hpp"

using namespace mooring_dynamics::core;

namespace {

StaticResult makeResult(std::size_t n) {
  StaticResult r;
  for (std::size_t i = 0; i < n; ++i) {
    NodeState v;
    v.s = 0.1 * static_cast<double>(i);                 // 0.1 is not exact in binary: tests precision
    v.x = 10.0 * static_cast<double>(i) + 1.0 / 3.0;
    v.z = -100.0 + 20.0 * static_cast<double>(i);
    v.tension = 1000.0 + 123.456789012345 * static_cast<double>(i);
    v.shear = 0.25;
    v.angle = 0.5 * std::atan(1.0);                      // pi/8 rad = 22.5 deg
    v.curvature = 1e-3;
    v.strain = 1.5e-5;
    v.segment = static_cast<int>(i / 3);
    r.nodes.push_back(v);
  }
  r.nodes[1].tension = 500.0;  // minimum
  r.top_force_x = 1234.5;
  r.top_force_z = 6789.25;
  r.anchor_force_x = -1234.5;
  r.anchor_force_z = -42.0;
  r.buoy_draft = 0.75;
  r.summary.converged = true;
  r.summary.iterations = 17;
  r.summary.error = 3.5e-10;
  r.summary.relaxation = 1.0;
  r.summary.message = "converged \"quoted\"\tok";
  return r;
}

Problem makeProblem() {
  Problem p;
  p.name = "test \"line\" \\ 1";
  p.top.type = TopBoundary::Type::Buoy;
  return p;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

/// The numbers of the JSON array under "key": [...].
std::vector<double> jsonArray(const std::string& json, const std::string& key) {
  std::vector<double> out;
  const auto k = json.find("\"" + key + "\": [");
  if (k == std::string::npos) return out;
  const auto b = json.find('[', k) + 1;
  const auto e = json.find(']', b);
  std::stringstream ss(json.substr(b, e - b));
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::strtod(item.c_str(), nullptr));
  return out;
}

}  // namespace

TEST(ResultIo, JsonHasKeysAndFullPrecision) {
  const StaticResult r = makeResult(7);
  std::ostringstream os;
  writeStaticJson(os, makeProblem(), r);
  const std::string j = os.str();

  for (const char* key : {"\"name\"", "\"summary\"", "\"converged\": true", "\"iterations\": 17", "\"error\"",
                          "\"relaxation\"", "\"message\"", "\"top_force\"", "\"anchor_force\"", "\"buoy_draft\"",
                          "\"nodes\"", "\"s\"", "\"x\"", "\"z\"", "\"tension\"", "\"shear\"", "\"angle\"",
                          "\"curvature\"", "\"strain\"", "\"segment\""})
    EXPECT_NE(j.find(key), std::string::npos) << "missing " << key << " in\n" << j;

  // Strings are escaped.
  EXPECT_NE(j.find("\"name\": \"test \\\"line\\\" \\\\ 1\""), std::string::npos) << j;
  EXPECT_NE(j.find("converged \\\"quoted\\\"\\tok"), std::string::npos) << j;
  // Balanced braces and brackets (plausibly well-formed).
  EXPECT_EQ(count(j, "{"), count(j, "}"));
  EXPECT_EQ(count(j, "["), count(j, "]"));

  EXPECT_NE(j.find("\"top_force\": {\"x\": 1234.5, \"z\": 6789.25}"), std::string::npos) << j;
  EXPECT_NE(j.find("\"anchor_force\": {\"x\": -1234.5, \"z\": -42}"), std::string::npos) << j;
  EXPECT_NE(j.find("\"buoy_draft\": 0.75"), std::string::npos) << j;

  // Per-node arrays: n entries each, values round-trip exactly.
  for (const char* key : {"s", "x", "z", "tension", "shear", "angle", "curvature", "strain", "segment"})
    EXPECT_EQ(jsonArray(j, key).size(), r.nodes.size()) << key;
  const auto s = jsonArray(j, "s");
  const auto x = jsonArray(j, "x");
  const auto t = jsonArray(j, "tension");
  const auto seg = jsonArray(j, "segment");
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    EXPECT_EQ(s[i], r.nodes[i].s);  // exact: %.17g round-trips
    EXPECT_EQ(x[i], r.nodes[i].x);
    EXPECT_EQ(t[i], r.nodes[i].tension);
    EXPECT_EQ(seg[i], r.nodes[i].segment);
  }
}

TEST(ResultIo, JsonNonFiniteBecomesNull) {
  StaticResult r = makeResult(2);
  r.summary.error = std::numeric_limits<double>::quiet_NaN();
  r.nodes[0].tension = std::numeric_limits<double>::infinity();
  std::ostringstream os;
  writeStaticJson(os, makeProblem(), r);
  const std::string j = os.str();
  EXPECT_NE(j.find("\"error\": null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"tension\": [null, "), std::string::npos) << j;
  EXPECT_EQ(j.find("nan"), std::string::npos);
  EXPECT_EQ(j.find("inf"), std::string::npos);
}

TEST(ResultIo, CsvHasHeaderAndOneRowPerNode) {
  const StaticResult r = makeResult(7);
  std::ostringstream os;
  writeStaticCsv(os, r);
  const std::string c = os.str();
  EXPECT_EQ(c.rfind("node,s,x,z,tension,shear,angle_deg,curvature,strain,segment\n", 0), 0u);
  EXPECT_EQ(count(c, "\n"), r.nodes.size() + 1);
  std::istringstream is(c);
  std::string line;
  std::getline(is, line);
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    ASSERT_TRUE(std::getline(is, line));
    std::vector<std::string> f;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    ASSERT_EQ(f.size(), 10u) << line;
    EXPECT_EQ(std::stoul(f[0]), i);
    EXPECT_EQ(std::strtod(f[1].c_str(), nullptr), r.nodes[i].s);
    EXPECT_EQ(std::strtod(f[4].c_str(), nullptr), r.nodes[i].tension);
    EXPECT_NEAR(std::strtod(f[6].c_str(), nullptr), 22.5, 1e-12);  // degrees in the CSV
    EXPECT_EQ(std::stoi(f[9]), r.nodes[i].segment);
  }
}

TEST(ResultIo, CsvEmptyResultIsHeaderOnly) {
  std::ostringstream os;
  writeStaticCsv(os, StaticResult{});
  EXPECT_EQ(count(os.str(), "\n"), 1u);
}

TEST(ResultIo, SummaryTextGivesMaxTensionAndUtilization) {
  // 7 nodes in segments 0, 0, 0, 1, 1, 1, 2; tensions 1000 + 123.456789012345 i: the largest at
  // the top (node 6, s = 0.6 m), 1740.7 N. Segment 2's material has MBL 2000 N: utilization 0.870.
  const StaticResult r = makeResult(7);
  Problem p = makeProblem();
  p.materials.resize(2);
  p.materials[1].name = "wire";
  p.materials[1].mbl = 2000.0;
  p.segments.resize(3);
  p.segments[2].material = 1;
  const std::string s = staticSummaryText(p, r);
  EXPECT_NE(s.find("max tension    1740.7 N at s = 0.60 m; utilization 0.870 of mbl 2000.0 N (wire)"),
            std::string::npos)
      << s;
  p.materials[1].mbl = 0.0;
  EXPECT_NE(staticSummaryText(p, r).find("utilization: no mbl given"), std::string::npos);
}

TEST(ResultIo, SummaryText) {
  const StaticResult r = makeResult(7);
  const std::string s = staticSummaryText(makeProblem(), r);
  EXPECT_NE(s.find("converged"), std::string::npos) << s;
  EXPECT_EQ(s.find("NOT converged"), std::string::npos) << s;
  EXPECT_NE(s.find("17 iterations"), std::string::npos) << s;
  EXPECT_NE(s.find("top tension"), std::string::npos) << s;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", r.topTension());
  EXPECT_NE(s.find(buf), std::string::npos) << s;
  EXPECT_NE(s.find("1234.5"), std::string::npos) << s;    // top force x
  EXPECT_NE(s.find("6789.2"), std::string::npos) << s;    // top force z (rounded to 0.1 N)
  EXPECT_NE(s.find("-42.0"), std::string::npos) << s;     // anchor force z
  EXPECT_NE(s.find("min tension"), std::string::npos) << s;
  EXPECT_NE(s.find("500.0"), std::string::npos) << s;
  EXPECT_NE(s.find("node 1"), std::string::npos) << s;
  EXPECT_NE(s.find("buoy draft"), std::string::npos) << s;
  EXPECT_LE(count(s, "\n"), 8u);

  StaticResult bad = r;
  bad.summary.converged = false;
  bad.summary.message = "max iterations reached";
  const std::string b = staticSummaryText(makeProblem(), bad);
  EXPECT_NE(b.find("NOT converged"), std::string::npos) << b;
  EXPECT_NE(b.find("max iterations reached"), std::string::npos) << b;
  const Problem empty;  // a named object: Problem{} trips GCC 12's -Wmaybe-uninitialized (false positive)
  EXPECT_NO_THROW(staticSummaryText(empty, StaticResult{}));
}

TEST(ResultIo, TableTextStrideKeepsFirstAndLast) {
  const StaticResult r = makeResult(7);
  const std::string all = staticTableText(r);
  EXPECT_NE(all.find("node"), std::string::npos);
  EXPECT_NE(all.find("s [m]"), std::string::npos);
  EXPECT_NE(all.find("tension [N]"), std::string::npos);
  EXPECT_EQ(count(all, "\n"), 1u + 7u);
  // All lines have the same width (aligned columns).
  std::istringstream is(all);
  std::string line;
  std::size_t width = 0;
  while (std::getline(is, line)) {
    if (!width) width = line.size();
    EXPECT_EQ(line.size(), width) << line;
  }
  const std::string strided = staticTableText(r, 4);  // nodes 0, 4 and the last (6)
  EXPECT_EQ(count(strided, "\n"), 1u + 3u) << strided;
  EXPECT_EQ(count(staticTableText(r, 0), "\n"), 1u + 7u);  // stride 0 treated as 1
}
