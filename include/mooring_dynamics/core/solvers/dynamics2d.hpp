// 2-D dynamic solver: paper eqs. 1-10 on the half-grid box scheme, generalized-alpha in time
// (section 4) with averaged coefficient matrices (31-32), adaptive time stepping (4.3), started
// from the static solution. Positions are part of the Newton unknowns (N = 8 per node).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/utilization.hpp"

namespace mooring_dynamics {
namespace core {

/// Kinematics or force of the top end at one instant, in the problem frame.
struct TopInput {
  bool force = false;        ///< true: (fx, fz) is applied; false: position and velocity prescribed
  double x = 0.0, z = 0.0;   ///< [m]
  double vx = 0.0, vz = 0.0; ///< [m/s]
  double fx = 0.0, fz = 0.0; ///< [N]
};

/// What one call to advanceTo did.
struct StepReport {
  bool ok = true;
  int steps = 0;             ///< accepted (sub)steps
  int cuts = 0;              ///< times a step was cut by 10 (section 4.3)
  int newton_iterations = 0; ///< summed over accepted and failed attempts
  double smallest_dt = 0.0;  ///< [s]
  /// Steps the implicit scheme could not take, taken by the solver's fallback (3-D: the
  /// lumped-mass step, docs/method.md "Slack and snap: the fallback step"), included in steps.
  int fallback_steps = 0;
  std::string message;       ///< on failure: time, node and variable that would not converge
};

class DynamicSolver2D {
 public:
  /// Builds the mesh (adaptive if the options ask), solves statics and starts from it.
  /// Throws std::invalid_argument for an invalid problem and std::runtime_error when the static
  /// start does not converge.
  explicit DynamicSolver2D(const Problem& problem);
  ~DynamicSolver2D();
  DynamicSolver2D(const DynamicSolver2D&) = delete;
  DynamicSolver2D& operator=(const DynamicSolver2D&) = delete;

  /// Replace the top motion of the problem file, e.g. by a live source (ROS). Called with the
  /// time [s]; must be defined for every t >= time().
  void setTopInput(std::function<TopInput(double)> source);

  /// Advance to t_end >= time() in base steps (the last one shortened to land on t_end), cutting
  /// a step that does not converge (4.3). On failure the state stays at the last converged time.
  StepReport advanceTo(double t_end);

  double time() const;
  const StaticResult& initialStatic() const;
  /// Current per-node values and end forces (same layout as the static result).
  StaticResult snapshot() const;
  /// Unstretched arclength of every node [m] (after adaptive meshing).
  std::vector<double> nodeArclengths() const;

  /// Diagnostic: largest relative difference between the assembled Jacobian of a step of size dt
  /// from the current state (at the predictor) and central finite differences of its residual
  /// (checkJacobian, newton.hpp); 1 when a coupling falls outside the band.
  double jacobianFiniteDifferenceError(double dt) const;

  struct Totals {
    long steps = 0, cuts = 0, newton_iterations = 0;
    long jacobians = 0;  ///< Jacobians assembled and factored (3-D solver; 0 from the 2-D one)
    long fallback_steps = 0;     ///< steps taken by the fallback (3-D solver; included in steps)
    long fallback_substeps = 0;  ///< the fallback's explicit sub-steps
    long fallback_retries = 0;   ///< implicit base steps tried and failed right after a fallback step
    /// Implicit tries that did not converge (every step size; fallback_retries among them), and
    /// the Jacobians they assembled (3-D solver; included in jacobians).
    long failed_tries = 0, failed_jacobians = 0;
    /// Converged implicit steps refused because the top node had left the top's path (a folded
    /// top interval; docs/method.md "Slack and snap"); a cut step or the fallback took them.
    long top_off_path = 0;
  };
  Totals totals() const;
  /// Threads the solver runs on: dynamics.threads, but 1 for a line of fewer than
  /// kMinNodesForTwoThreads nodes (the second thread costs more than it takes off there).
  int threads() const;
  /// Nodes from which a second thread pays on a 2-D line (scripts/threads_bench, 2-core host:
  /// 50 and 100 nodes 2.2 and 1.7 times slower on two threads, A.3's 170 nodes 1.15 times
  /// slower, 200 nodes 0.79, 274 (A.2) 0.87, 500-1000 0.87, 2000 0.50).
  static constexpr int kMinNodesForTwoThreads = 200;

  struct Impl;  ///< solver state (opaque; defined in dynamics2d.cpp)

 private:
  std::unique_ptr<Impl> impl_;
};

/// Time series of a whole dynamic run on the output grid.
struct DynamicSeries {
  std::vector<double> t;                        ///< [s]
  std::vector<double> top_tension;              ///< [N]
  std::vector<double> anchor_tension;           ///< [N]
  std::vector<double> top_x, top_z;             ///< [m]
  std::vector<double> top_y;                    ///< [m] (0 in 2-D)
  std::vector<double> record_s;                 ///< recorded node arclengths [m] (nearest nodes)
  std::vector<std::vector<double>> node_tension;///< [record][sample] [N]
  std::vector<std::vector<double>> node_x, node_z;  ///< [record][sample] [m]
  std::vector<std::vector<double>> node_y;          ///< [record][sample] [m] (3-D runs; 0 in 2-D)
  std::vector<StaticResult> snapshots;          ///< full line at snapshot times
  std::vector<double> snapshot_t;               ///< [s]
  StaticResult initial_static;
  /// Largest tension along the line over the output samples, and its utilization (Material::mbl).
  TensionPeak peak;
  bool completed = false;
  std::string message;                          ///< failure message when not completed
  std::vector<LineEventRecord> events;          ///< line events that happened (3-D runs)
  /// The line's unstretched length at each sample [m], when a winch pays it out or hauls it in
  /// (dynamics.winch; empty otherwise).
  std::vector<double> line_length;
  long steps = 0, cuts = 0, newton_iterations = 0;
  long jacobians = 0;  ///< Jacobians assembled (3-D; 0 from the 2-D solver, one per iteration)
  /// Base-step remainders taken by the fallback step (3-D; docs/method.md "Slack and snap") and
  /// the explicit sub-steps they took.
  long fallback_steps = 0, fallback_substeps = 0;
  long top_off_path = 0;  ///< converged implicit steps refused: the top node off its path (3-D)
  int threads = 1;        ///< threads the solver ran on (DynamicSolver2D::threads)
  double wall_seconds = 0.0;
};

/// Run problem.dynamics from the static solution. `progress(t, duration)` is called after every
/// output sample when given.
DynamicSeries runDynamic(const Problem& problem,
                         const std::function<void(double, double)>& progress = nullptr);

}  // namespace core
}  // namespace mooring_dynamics
