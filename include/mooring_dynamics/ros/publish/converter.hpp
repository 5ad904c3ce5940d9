// The one place where core structs and ROS messages meet (no node handles, no publishing).
//
// Frames: every position and force is in the node's frame (parameter ~frame_id, REP 103: x east,
// y north, z up, z = 0 at the mean sea surface). With `model: 2d` the core works in the vertical
// x-z plane of that frame, so y is 0 on the way out and must be 0 on the way in; with `model: 3d`
// all three components are used both ways.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/time.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/SystemStatics.h"
#include "mooring_dynamics/VesselStatics.h"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/solvers/system_statics.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// End forces of a line [N] (same conventions as core::StaticResult).
struct EndForces {
  double top_x = 0.0, top_z = 0.0;        ///< force the platform applies to the line's top end [N]
  double anchor_x = 0.0, anchor_z = 0.0;  ///< force the line exerts on the anchor [N]
  double top_y = 0.0, anchor_y = 0.0;     ///< y components [N] (3-D model; 0 from the 2-D solver)
};

/// CableState from per-node values (anchor first). Shared by the static and the dynamic output
/// path: positions and forces with their y (0 from the 2-D solver), min_tension over all nodes,
/// slack when any tension <= 0.
CableState toCableState(const std::vector<core::NodeState>& nodes, const EndForces& forces, bool converged,
                        const std::string& line_name, const std::string& frame_id, const ros::Time& stamp);

/// CableState of a static result.
CableState toCableState(const core::StaticResult& result, const std::string& line_name,
                        const std::string& frame_id, const ros::Time& stamp);

/// Fill a SolveStatic response from a static result: success = summary.converged, message =
/// summary.message, iterations, end forces, positions and tensions (anchor to top).
void toResponse(const core::StaticResult& result, SolveStatic::Response& res);

/// Failed response: success = false, the message, all arrays empty.
void toFailureResponse(const std::string& message, SolveStatic::Response& res);

/// Outcome of translating a SolveStatic request.
struct TopBoundaryRequest {
  bool ok = false;
  core::TopBoundary top;   ///< valid when ok
  std::string error;       ///< when !ok: names the field, its value and the constraint
  std::string summary;     ///< when ok: short description, e.g. "top position (x, z) = (90, 0) m"
};

/// SolveStatic request -> core::TopBoundary. `problem_top` is what PROBLEM_DEFAULT returns.
/// Rejects an unknown mode, NaN/inf components (`top_position.x = nan: must be finite`) and, for
/// `model` TwoD, a non-zero y (the 2-D solver works in the x-z plane); ThreeD takes y as given.
/// Whether the line can reach a requested position is left to the core (core::Problem::validate).
TopBoundaryRequest topBoundaryFromRequest(const SolveStatic::Request& req, const core::TopBoundary& problem_top,
                                          core::Formulation model = core::Formulation::TwoD);

/// Short description of a top boundary for logs and messages: "(x, z) = ..." for TwoD,
/// "(x, y, z) = ..." for ThreeD.
std::string describeTop(const core::TopBoundary& top, core::Formulation model = core::Formulation::TwoD);

// ---------------------------------------------------------------------------------------------
// Moored vessel (docs/ros_interface.md, "Moored vessel"). World = ~frame_id (REP 103); body axes
// per REP 103 (x forward, y left, z up) in the frame vessel.frame.

/// geometry_msgs/Pose -> core::RigidPose: the numbers as they are (quaternion (w, x, y, z) like
/// core::parseVesselMotionTable), neither checked nor normalized (core::VesselLockstep does that).
core::RigidPose toRigidPose(const geometry_msgs::Pose& pose);
geometry_msgs::Pose toPoseMsg(const core::RigidPose& pose);

/// The lines' total wrench on the vessel about its body origin: in the body frame (`body_frame`,
/// what a rigid-body simulator applies) and in the world frame (`world_frame`).
geometry_msgs::WrenchStamped toBodyWrench(const core::VesselWrench& w, const std::string& body_frame,
                                          const ros::Time& stamp);
geometry_msgs::WrenchStamped toWorldWrench(const core::VesselWrench& w, const std::string& world_frame,
                                           const ros::Time& stamp);
/// One line's force on the vessel at its fairlead, world frame; torque = (fairlead - body origin)
/// x force, the line's share of the moment about the body origin (the shares of all lines sum to
/// toWorldWrench's torque up to rounding).
geometry_msgs::WrenchStamped toFairleadWrench(const core::FairleadForce& f, const core::RigidPose& vessel,
                                              const std::string& world_frame, const ros::Time& stamp);
/// tf frame of a fairlead: at its world position, oriented as the vessel.
geometry_msgs::TransformStamped fairleadTransform(const core::FairleadForce& f, const core::RigidPose& vessel,
                                                  const std::string& world_frame, const std::string& child,
                                                  const ros::Time& stamp);
/// tf transform world -> body frame of the vessel at `pose`.
geometry_msgs::TransformStamped vesselTransform(const core::RigidPose& pose, const std::string& world_frame,
                                                const std::string& body_frame, const ros::Time& stamp);

/// A VesselStatics request translated for the core.
struct VesselStaticsRequest {
  bool ok = false;
  std::string error;            ///< when !ok: names the field, its value and the constraint
  core::RigidPose pose;         ///< the file's pose (use_file_pose) or the request's, normalized
  bool want_stiffness = false;
  bool has_offset = false;      ///< an offset curve was asked for
  core::VesselDof dof = core::VesselDof::Surge;
  bool angular = false;         ///< dof is roll, pitch or yaw (offsets in rad for the core, deg in messages)
  std::vector<double> offsets;  ///< [m] or [rad], -range .. +range in offset_steps
  std::string summary;          ///< e.g. "pose (x, y, z) = (1, 0, 0) m, yaw 0 deg"
};

/// [-] Largest offset_steps a VesselStatics request may ask for (each one a static solve of every line).
constexpr std::uint32_t kMaxOffsetSteps = 1001;

/// Checks a VesselStatics request: a finite pose with a unit quaternion (core::kUnitQuaternionTolerance;
/// unless use_file_pose), offset_dof empty or a DOF name, offset_range > 0 and finite (< 90 deg
/// for an angle), 2 <= offset_steps <= kMaxOffsetSteps.
VesselStaticsRequest vesselStaticsFromRequest(const VesselStatics::Request& req, const core::RigidPose& file_pose);

/// Fills a VesselStatics response: wrenches and the lines' top tensions of `at`, the stiffness
/// (when given) and the offset curve (when given; offsets in deg for an angular DOF). success =
/// every solve converged; message says which did not.
void toVesselStaticsResponse(const core::SystemProblem& system, const core::VesselStaticResult& at,
                             const core::StiffnessResult* stiffness, const std::vector<core::OffsetPoint>* curve,
                             const VesselStaticsRequest& request, VesselStatics::Response& res);

/// Fills a SystemStatics response from a system's static result: every point (position, the
/// lines' pull), every line (top and minimum tension), in the file's order; success = converged.
/// `reinitialised` is left false (the dynamic node sets it).
void toSystemStaticsResponse(const core::SystemProblem& system, const core::SystemStaticResult& r,
                             SystemStatics::Response& res);

/// "%.6g" formatting that prints nan/inf as such (for messages).
std::string formatNumber(double v);

/// The monitor's statuses as one DiagnosticArray stamped `stamp`: the run's status named
/// "mooring_dynamics: <node> <run_name>" and one "mooring_dynamics: <node> line <line>" per line.
diagnostic_msgs::DiagnosticArray toDiagnostics(const std::vector<VesselMonitor::Status>& statuses,
                                               const std::string& node, const std::string& run_name,
                                               const std::string& hardware_id, const ros::Time& stamp);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
