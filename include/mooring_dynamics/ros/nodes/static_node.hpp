// ROS node state for static solves: parameters -> problem, the problem's own static case on start,
// and the ~solve_static service. All numerics stay in the core; all message translation is in
// converter.hpp; this class only wires them to topics, services and logs.
//
// Parameters (private namespace):
//   ~problem_file  string  path of a YAML problem file (docs/problem_format.md)
//   ~problem_yaml  string  the problem as YAML text, or a map (e.g. <rosparam command="load" ...>)
//                          exactly one of ~problem_file / ~problem_yaml must be set
//   ~frame_id      string  frame of all positions and forces, default "world"
//   ~marker_scale  double  multiplies the automatic marker sizes, default 1.0
// Publications (latched): ~cable_state (mooring_dynamics/CableState), ~markers
//   (visualization_msgs/MarkerArray). Service: ~solve_static (mooring_dynamics/SolveStatic).
// Full description: docs/ros_interface.md.
#pragma once

#include <optional>
#include <string>

#include <ros/ros.h>

#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/ros/publish/markers.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

/// Reads the problem from ~problem_file or ~problem_yaml of `pnh`. `source` receives a short
/// description for logs ("file /path/x.yaml", "parameter /node/problem_yaml").
/// Throws core::ProblemError for a bad problem and std::runtime_error for bad/missing parameters.
core::Problem loadProblemFromParams(const ros::NodeHandle& pnh, std::string& source);

/// Outcome of one static solve, never throwing.
struct SolveOutcome {
  bool ok = false;              ///< converged and finite
  core::StaticResult result;    ///< filled when the solver ran (also when it did not converge)
  bool solver_ran = false;
  std::string message;          ///< success summary or the reason for failure
};

/// Solve `problem` with the core; catches std::invalid_argument (invalid problem, e.g. a top
/// position out of reach) and any other exception from the solver, and rejects non-finite results.
SolveOutcome solveSafely(const core::Problem& problem);

class StaticNode {
 public:
  /// Reads parameters, loads the problem, advertises topics and the service. Throws
  /// core::ProblemError (bad problem) or std::runtime_error (bad parameters); nothing is
  /// advertised then.
  StaticNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Solves the problem's own static case and publishes it. Returns false (logged with
  /// ROS_ERROR) when it fails; the node still serves ~solve_static then.
  bool start();

  /// ~solve_static handler (public for tests). Always returns true (the call itself succeeded);
  /// the outcome is in res.success / res.message.
  bool onSolveStatic(SolveStatic::Request& req, SolveStatic::Response& res);

  const core::Problem& problem() const { return problem_; }
  /// Last converged state (published), if any.
  const std::optional<core::StaticResult>& lastResult() const { return last_; }
  const std::string& frameId() const { return frame_id_; }

 private:
  void publish(const core::StaticResult& result);

  ros::NodeHandle nh_, pnh_;
  core::Problem problem_;
  std::string source_;
  std::string frame_id_ = "world";
  MarkerOptions marker_options_;
  ros::Publisher state_pub_, marker_pub_;
  ros::ServiceServer solve_srv_;
  std::optional<core::StaticResult> last_;
};

}  // namespace ros_bridge
}  // namespace mooring_dynamics
