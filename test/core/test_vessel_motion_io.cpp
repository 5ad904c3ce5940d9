#include "mooring_dynamics/core/io/vessel_motion_io.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "mooring_dynamics/core/io/problem_io.hpp"

using namespace mooring_dynamics::core;

namespace {
std::string error(const std::string& text) {
  try {
    parseVesselMotionTable(text, "m.csv");
  } catch (const ProblemError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(VesselMotionTable, ReadsRowsSkipsHeaderAndComments) {
  const auto rows = parseVesselMotionTable("# a comment\nt,x,y,z,qx,qy,qz,qw\n0,1,2,3,0,0,0,1\n0.5,1.5,2,3,0,0,0.7071067811865476,0.7071067811865476\n", "m.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].t, 0.5);
  EXPECT_EQ(rows[1].pose.position.x(), 1.5);
  // Yawed 90 deg: the body's x axis points north.
  EXPECT_NEAR((rows[1].pose.orientation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(VesselMotionTable, ErrorsNameTheRowColumnAndValue) {
  EXPECT_NE(error("0,1,2,3,0,0,0,1\n0.1,1,abc,3,0,0,0,1\n").find("m.csv:2: column y = \"abc\""), std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,1\n").find("7 values, expected 8"), std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,0,1\n0,1,2,3,0,0,0,1\n").find("must be after"), std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,0,2\n").find("norm"), std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,0,nan\n").find("not a finite number"), std::string::npos);
  EXPECT_NE(error("# nothing\n").find("no rows"), std::string::npos);
}

TEST(VesselMotionTable, VelocityColumnsAreTheBodyTwist) {
  // 14 columns: the body-frame twist (vx, vy, vz, wx, wy, wz) as nav_msgs/Odometry's.
  const auto rows = parseVesselMotionTable(
      "t,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz\n0,1,2,3,0,0,0,1,0.5,-0.25,0.125,0.01,-0.02,0.03\n", "m.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].has_twist);
  EXPECT_EQ(rows[0].twist.linear, Eigen::Vector3d(0.5, -0.25, 0.125));
  EXPECT_EQ(rows[0].twist.angular, Eigen::Vector3d(0.01, -0.02, 0.03));
  EXPECT_FALSE(parseVesselMotionTable("0,1,2,3,0,0,0,1\n", "m.csv")[0].has_twist);
  // Widths: 8 or 14, the same in every row; the column of a bad value is named.
  EXPECT_NE(error("0,1,2,3,0,0,0,1,0.5,0,0\n").find("11 values, expected 8"), std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,0,1\n0.1,1,2,3,0,0,0,1,0,0,0,0,0,0\n").find("m.csv:2: 14 values, the first row 8"),
            std::string::npos);
  EXPECT_NE(error("0,1,2,3,0,0,0,1,0,0,0,0,x,0\n").find("column wy = \"x\""), std::string::npos);
}
