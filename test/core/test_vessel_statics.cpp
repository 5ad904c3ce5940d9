// The moored vessel in statics (solvers/vessel_statics): wrench, fairlead placement, the 6 x 6
// stiffness and the offset curve, each checked against sums and rotations done by hand here.
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"
#include "system_test_util.hpp"

using namespace mooring_dynamics::core;
using mooring_dynamics::core::testing_util::fourLegVessel;

namespace {

constexpr double kPi = 3.14159265358979323846;
// [-] relative: the lines' static Newton stops at sigma < 1e-9 (eq. 39); forces of mirrored lines
// then agree to about 1e-8 of a line's tension; 1e-6 leaves room for the seabed contact.
constexpr double kRel = 1e-6;
// [m] a line's top node sits on its prescribed fairlead up to the Newton tolerance.
constexpr double kPositionTol = 1e-6;

/// R = Rz(yaw) Ry(pitch) Rx(roll), written out element by element.
Eigen::Matrix3d rotationByHand(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch),
               cy = std::cos(yaw), sy = std::sin(yaw);
  Eigen::Matrix3d R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

double largestTension(const VesselStaticResult& r) {
  double T = 0.0;
  for (const auto& l : r.system.lines) T = std::max(T, l.topTension());
  return T;
}

}  // namespace

TEST(VesselStatics, SymmetricSpreadAtRestHasNoHorizontalForceNorMoment) {
  const VesselStaticResult r = solveVesselStatic(fourLegVessel(), RigidPose());
  ASSERT_TRUE(r.system.summary.converged) << r.system.summary.message;
  const double T = largestTension(r);
  ASSERT_GT(T, 1e4);
  EXPECT_LT(r.wrench.force_world.z(), -1e4);  // the lines pull the vessel down
  EXPECT_NEAR(r.wrench.force_world.x(), 0.0, kRel * T);
  EXPECT_NEAR(r.wrench.force_world.y(), 0.0, kRel * T);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.wrench.moment_world[c], 0.0, kRel * T * 20.0) << "moment " << c;
  EXPECT_EQ(r.wrench.fairleads.size(), 4u);
}

TEST(VesselStatics, FairleadsMoveWithTheRotationAndTheMomentIsTheHandSum) {
  const double roll = 2.0 * kPi / 180, pitch = -1.0 * kPi / 180, yaw = 10.0 * kPi / 180;
  const Eigen::Vector3d p(3.0, -2.0, 0.5);
  const SystemProblem s = fourLegVessel();
  const VesselStaticResult r = solveVesselStatic(s, RigidPose::fromRollPitchYaw(p, roll, pitch, yaw));
  ASSERT_TRUE(r.system.summary.converged) << r.system.summary.message;
  const Eigen::Matrix3d R = rotationByHand(roll, pitch, yaw);
  Eigen::Vector3d F = Eigen::Vector3d::Zero(), M = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const Eigen::Vector3d arm = R * s.points[s.lines[i].to].body_offset;
    const NodeState& top = r.system.lines[i].nodes.back();
    EXPECT_NEAR((Eigen::Vector3d(top.x, top.y, top.z) - (p + arm)).norm(), 0.0, kPositionTol) << s.lines[i].name;
    const StaticResult& l = r.system.lines[i];
    const Eigen::Vector3d f(-l.top_force_x, -l.top_force_y, -l.top_force_z);
    F += f;
    M += arm.cross(f);
  }
  const double T = largestTension(r);
  EXPECT_NEAR((r.wrench.force_world - F).norm(), 0.0, 1e-9 * T);
  EXPECT_NEAR((r.wrench.moment_world - M).norm(), 0.0, 1e-9 * T * 30.0);
  EXPECT_NEAR((r.wrench.force_body - R.transpose() * F).norm(), 0.0, 1e-9 * T);
  EXPECT_NEAR((r.wrench.moment_body - R.transpose() * M).norm(), 0.0, 1e-9 * T * 30.0);
}

TEST(VesselStatics, YawedSpreadTurnsBack) {
  const SystemProblem s = fourLegVessel();
  for (double deg : {5.0, -5.0}) {
    const VesselStaticResult r = solveVesselStatic(s, RigidPose::fromRollPitchYaw({0, 0, 0}, 0, 0, deg * kPi / 180));
    ASSERT_TRUE(r.system.summary.converged);
    EXPECT_LT(r.wrench.moment_body.z() * deg, 0.0) << "yaw " << deg << " deg: Mz " << r.wrench.moment_body.z();
  }
  // Surged forward: pulled back.
  const VesselStaticResult r = solveVesselStatic(s, RigidPose::fromRollPitchYaw({8, 0, 0}, 0, 0, 0));
  EXPECT_LT(r.wrench.force_body.x(), 0.0);
}

TEST(VesselStatics, StiffnessIsSymmetricWhereNoLoadTermEntersAndPositiveInSurgeSwayHeaveYaw) {
  const StiffnessResult k = mooringStiffness(fourLegVessel(), RigidPose());
  ASSERT_TRUE(k.converged) << k.message;
  for (int d : {0, 1, 2, 5}) EXPECT_GT(k.K(d, d), 0.0) << "K(" << d << "," << d << ") = " << k.K(d, d);
  // Surge, sway, heave, yaw: the moment of the (vertical) resultant does not change with these
  // rotations' partners, so K is symmetric there. Roll and pitch couple with the vertical pull
  // through the load term dF_body/dtheta = -e_theta x F (a follower load): not symmetric.
  // [-] 1e-4 of the geometric mean of the diagonal: central differences' O(h^2) error.
  constexpr double kSymTol = 1e-4;
  const int dofs[4] = {0, 1, 2, 5};
  for (int a : dofs)
    for (int b : dofs)
      EXPECT_NEAR(k.K(a, b), k.K(b, a), kSymTol * std::sqrt(k.K(a, a) * k.K(b, b))) << a << "," << b;
  // Double symmetry of the layout: surge does not couple with sway or yaw.
  EXPECT_NEAR(k.K(0, 1), 0.0, kSymTol * std::sqrt(k.K(0, 0) * k.K(1, 1)));
  EXPECT_NEAR(k.K(0, 5), 0.0, kSymTol * std::sqrt(k.K(0, 0) * k.K(5, 5)));
  // The antisymmetric part is the follower-load term alone: turning the body by dtheta about y
  // turns the (world-fixed) resultant F in the body frame by -e_y x F, so dFx/dtheta_y gains -Fz
  // and K(surge, pitch) - K(pitch, surge) = Fz; likewise K(sway, roll) - K(roll, sway) = -Fz.
  // [-] 1e-3 of Fz: the two entries are each ~Fz and come from differences of wrenches of ~Fz over
  // a 0.1 deg turn, whose O(h^2) truncation is measured at 3e-4 of Fz for this mooring.
  constexpr double kLoadTermTol = 1e-3;
  const double Fz = k.at.wrench.force_body.z();
  EXPECT_NEAR(k.K(0, 4) - k.K(4, 0), Fz, kLoadTermTol * std::abs(Fz));
  EXPECT_NEAR(k.K(1, 3) - k.K(3, 1), -Fz, kLoadTermTol * std::abs(Fz));
  // The fairlead rectangle is longer than wide: stiffer in yaw per radian than sway per metre x 1 m.
  EXPECT_GT(k.K(5, 5), k.K(1, 1));
}

TEST(VesselStatics, OffsetCurveIsTheSingleLineStaticsSummedByHand) {
  const SystemProblem s = fourLegVessel();
  const std::vector<double> offsets = {-6.0, 0.0, 6.0};
  const std::vector<OffsetPoint> curve = offsetCurve(s, RigidPose(), VesselDof::Surge, offsets);
  ASSERT_EQ(curve.size(), 3u);
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    ASSERT_TRUE(curve[k].converged) << curve[k].message;
    double Fx = 0.0, Tmax = 0.0;
    for (std::size_t i = 0; i < s.lines.size(); ++i) {
      // The line alone: a single-line 3-D problem with its top held at the moved fairlead.
      Problem p;
      p.formulation = Formulation::ThreeD;
      p.environment = s.environment;
      p.materials = s.materials;
      p.segments = s.lines[i].segments;
      const SystemPoint& a = s.points[s.lines[i].from];
      p.anchor_x = a.x;
      p.anchor_y = a.y;
      p.anchor_z = a.z;
      const Eigen::Vector3d f = s.points[s.lines[i].to].body_offset + Eigen::Vector3d(offsets[k], 0, 0);
      p.top.type = TopBoundary::Type::Position;
      p.top.x = f.x();
      p.top.y = f.y();
      p.top.z = f.z();
      const StaticResult r = solveStatic3D(p);
      ASSERT_TRUE(r.summary.converged);
      Fx -= r.top_force_x;
      Tmax = std::max(Tmax, r.topTension());
    }
    EXPECT_NEAR(curve[k].wrench[0], Fx, kRel * Tmax) << "offset " << offsets[k];
    EXPECT_NEAR(curve[k].max_tension, Tmax, kRel * Tmax);
  }
  // Restoring: the force opposes the offset, and grows with it.
  EXPECT_GT(curve[0].wrench[0], 0.0);
  EXPECT_LT(curve[2].wrench[0], 0.0);
  EXPECT_GT(curve[2].max_tension, curve[1].max_tension);
}

TEST(VesselStatics, DofNamesAndOffsets) {
  VesselDof d;
  ASSERT_TRUE(parseVesselDof("yaw", d));
  EXPECT_EQ(d, VesselDof::Yaw);
  EXPECT_FALSE(parseVesselDof("twist", d));
  // Sway of a yawed vessel moves it along its own y axis.
  const RigidPose p = offsetPose(RigidPose::fromRollPitchYaw({0, 0, 0}, 0, 0, kPi / 2), VesselDof::Sway, 2.0);
  EXPECT_NEAR((p.position - Eigen::Vector3d(-2.0, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(VesselStatics, VesselFileLoadsLinesFairleadsAndPose) {
  const std::string yaml = R"(
model: 3d
environment: {depth: 100}
materials:
  chain: {EA: 5.0e8, EI: 10, GJ: 1, mass: 40, wet_weight: 300, diameter: 0.08, cdn: 2.4, cdt: 1.15}
vessel:
  frame: hull
  pose: {position: [1, 2, 0], yaw_deg: 90}
  lines:
    - {name: fwd, fairlead: [20, 0, -5], anchor: [1, 272, -100], segments: [{material: chain, length: 300, spacing: 5}]}
    - {name: aft, fairlead: [-20, 0, -5], anchor: [1, -268, -100], segments: [{material: chain, length: 300, spacing: 5}]}
)";
  const SystemProblem s = loadSystemFromString(yaml);
  EXPECT_TRUE(isSystemText(yaml));
  EXPECT_EQ(s.vessel.frame, "hull");
  ASSERT_EQ(s.lines.size(), 2u);
  ASSERT_EQ(s.points.size(), 4u);
  const SystemPoint& f = s.points[s.lines[0].to];
  EXPECT_EQ(f.type, SystemPoint::Type::Vessel);
  EXPECT_EQ(f.name, "fwd/fairlead");
  // Yawed 90 deg: 20 m forward is 20 m north of the origin at (1, 2).
  EXPECT_NEAR(f.x, 1.0, 1e-12);
  EXPECT_NEAR(f.y, 22.0, 1e-12);
  EXPECT_NEAR(f.z, -5.0, 1e-12);
  // Errors name the key.
  const auto error = [](const std::string& text) {
    try {
      loadSystemFromString(text);
    } catch (const ProblemError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  std::string bad = yaml;
  bad.replace(bad.find("yaw_deg: 90"), 11, "orientation: {x: 0, y: 0, z: 0.5, w: 0.5}");
  EXPECT_NE(error(bad).find("vessel.pose"), std::string::npos) << error(bad);
  bad = yaml;
  bad.replace(bad.find("name: aft"), 9, "name: fwd");
  EXPECT_NE(error(bad).find("duplicate line name"), std::string::npos) << error(bad);
  bad = yaml;
  bad.replace(bad.find("fairlead: [-20, 0, -5]"), 22, "fairlead: [-20, 0]");
  EXPECT_NE(error(bad).find("vessel.lines[1].fairlead"), std::string::npos) << error(bad);
}
