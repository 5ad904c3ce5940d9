// A moored vessel in statics (DESIGN.md section 6): the wrench its lines put on the body at a
// pose, the 6 x 6 mooring stiffness by central differences of that wrench, and the offset curve
// (wrench and the most loaded line against an offset in surge, sway, heave, roll, pitch or yaw).
//
// Frames: world per REP 103 (x east, y north, z up, z = 0 at the mean surface); body per REP 103
// body axes (x forward, y left, z up). Moments are about the body origin. The wrench is given in
// both frames; the stiffness and the offset curve use body axes: the vessel is displaced along
// (or rotated about) its own axes, and the wrench is read in its own frame.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"

namespace mooring_dynamics {
namespace core {

/// What one line does to the vessel at its fairlead.
struct FairleadForce {
  std::size_t line = 0;                                       ///< index into SystemProblem::lines
  std::size_t point = 0;                                      ///< the vessel point it hangs from
  Eigen::Vector3d position = Eigen::Vector3d::Zero();         ///< fairlead, world [m]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();            ///< on the vessel, world [N]
};

/// Total force and moment of the lines on the vessel, about its body origin.
struct VesselWrench {
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();   ///< [N]
  Eigen::Vector3d moment_world = Eigen::Vector3d::Zero();  ///< [N m]
  Eigen::Vector3d force_body = Eigen::Vector3d::Zero();    ///< the same force in the body frame [N]
  Eigen::Vector3d moment_body = Eigen::Vector3d::Zero();   ///< [N m]
  std::vector<FairleadForce> fairleads;                    ///< per line at a vessel point, in line order
  /// (force_body, moment_body) as one 6-vector: surge, sway, heave, roll, pitch, yaw.
  Eigen::Matrix<double, 6, 1> body6() const;
};

/// The wrench of the lines' states `lines` (SystemProblem::lines order) on a vessel at `pose`:
/// F = sum F_i, M = sum (R r_i) x F_i, summed in line order (the same bits whatever computed the
/// lines). A line pulls its upper point with -top_force and its lower point with anchor_force.
VesselWrench vesselWrench(const SystemProblem& system, const RigidPose& pose, const std::vector<StaticResult>& lines);

struct VesselStaticResult {
  SystemStaticResult system;
  VesselWrench wrench;
  RigidPose pose;
};

/// Statics of the system with the vessel held at `pose`. Throws std::invalid_argument for an
/// invalid system or pose; non-convergence is in system.summary.
VesselStaticResult solveVesselStatic(SystemProblem system, const RigidPose& pose, const SystemSolveOptions& options = {});

/// Degrees of freedom of the vessel, body axes.
enum class VesselDof { Surge = 0, Sway, Heave, Roll, Pitch, Yaw };
/// "surge", ..., "yaw"; VesselDof from its name (false when unknown).
const char* toString(VesselDof dof);
bool parseVesselDof(const std::string& name, VesselDof& dof);
/// `pose` moved by `amount` along (m) or about (rad) the body axis of `dof`.
RigidPose offsetPose(const RigidPose& pose, VesselDof dof, double amount);

struct StiffnessOptions {
  /// [m] translation step of the central differences: large enough that the lines' static
  /// tolerance (sigma < 1e-9 of eq. 39) is far below the wrench change, small enough that the
  /// O(step^2) curvature error stays below 1e-3 of the stiffness of a catenary mooring.
  double translation_step = 0.1;
  /// [rad] rotation step (0.1 degree), by the same reasoning for fairleads tens of metres off.
  double rotation_step = 1.745329251994e-3;
  SystemSolveOptions solve;
  /// Empty when valid, else the field, value and constraint.
  std::string validate() const;
};

struct StiffnessResult {
  /// K(i, j) = -d wrench_i / d offset_j [N/m, N, N m/rad], body axes, (surge .. yaw) both ways.
  Eigen::Matrix<double, 6, 6> K = Eigen::Matrix<double, 6, 6>::Zero();
  VesselStaticResult at;   ///< the statics at the pose itself
  bool converged = false;  ///< every one of the 13 static solves converged
  std::string message;     ///< which solve failed, when one did
};

/// The 6 x 6 mooring stiffness at `pose`: 12 static solves at +-step along each DOF.
StiffnessResult mooringStiffness(const SystemProblem& system, const RigidPose& pose, const StiffnessOptions& options = {});

/// One point of an offset curve.
struct OffsetPoint {
  double offset = 0.0;                                              ///< [m] or [rad]
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();  ///< body axes [N, N m]
  double max_tension = 0.0;                                          ///< largest tension of any line [N]
  std::string max_tension_line;                                      ///< the line that has it
  bool converged = false;
  std::string message;
};

/// The wrench and the most loaded line at each offset (from `pose`, along/about `dof`).
std::vector<OffsetPoint> offsetCurve(const SystemProblem& system, const RigidPose& pose, VesselDof dof,
                                     const std::vector<double>& offsets, const SystemSolveOptions& options = {});

}  // namespace core
}  // namespace mooring_dynamics
