// The 2-D dynamic solver's state (DynamicSolver2D::Impl), shared by its source files:
// dynamics2d.cpp (the time step), dynamics2d_start.cpp (the start) and dynamics2d_fallback.cpp (the
// fallback step). Private to src/core/solvers.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/dynamic_interval.hpp"
#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/time_integration.hpp"
#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"
#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "lumped_line.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq2dyn;  // private to the solver's sources, as in them

struct DynamicSolver2D::Impl {
  Problem problem;
  Mesh mesh;
  WaveField waves;
  mutable WaveVelocityCache wave_cache;  ///< wave kinematics at the nodes (cos, sin reused)
  CurrentProfile current;                ///< problem.environment.current, components precomputed
  /// Workspace of DynamicStepSystem::evaluate: each node's terms (nodeStepTerms), kept between
  /// steps so that a step does not allocate them.
  mutable std::vector<NodeTerms> node_terms;
  GeneralizedAlpha ga;
  DynamicOptions opt;
  std::function<TopInput(double)> top;
  StaticResult statics;
  /// The anchor and the top (end_conditions.hpp): their rows at nodes 0 and n - 1.
  std::unique_ptr<EndCondition2D> lower, upper;

  // Accepted state at time t.
  double t = 0.0;
  Eigen::VectorXd Y, Yd;
  Eigen::VectorXd Yd_prev;      ///< rate before the last accepted step (second-order predictor)
  double last_dt = 0.0;         ///< size of the last accepted step [s]
  std::vector<Water> water;     ///< water velocity at each node at time t
  Eigen::VectorXd S;            ///< spatial rows of each interval at time t (8 per interval)
  std::vector<double> cos_phi, sin_phi;  ///< of each node's inclination at time t

  double chi[N];
  Totals totals;
  /// The last step was a fallback step (dynamics2d_fallback.cpp): a base step that fails now
  /// goes to the fallback at once, and the first implicit try gets few iterations.
  bool in_fallback = false;
  /// Time [s] of the fallback steps in a row taken without trying the implicit step first
  /// (stayInFallback).
  double fallback_skipped_time = 0.0;
  /// Base steps still to go to the fallback without an implicit try after a retry failed
  /// (lumped::kRetryWait).
  int retry_wait = 0;
  /// How long [s] a slack line stays in the fallback without an implicit try before one is made
  /// (lumped::staySlack): kMaxSkippedTime, doubled after each such try that fails.
  double skipped_cap = lumped::kMaxSkippedTime;
  /// The reference lengths of the last fallback step's intervals (lumped::Line::ref), which the
  /// next one keeps while the line stays in the fallback.
  std::vector<double> fallback_ref;
  BandedMatrix newton_matrix;  ///< Newton matrix reused by every step (solveNewton workspace)
  /// The second thread (dynamics.threads = 2; null with one): assembles and eliminates the
  /// upper half of the line (inHalves, BandedMatrix::setParallel).
  std::unique_ptr<ForkJoin> fork;
  double factored_dt = 0.0;    ///< step size the factorization in newton_matrix belongs to [s]

  int nodes() const { return static_cast<int>(mesh.nodes.size()); }

  /// core::inHalves on this solver's fork (the second thread, if any).
  template <class F>
  void inHalves(int m, int end, const F& f) const {
    core::inHalves(fork.get(), m, end, f);
  }
  /// Where the threads are expected to meet in the nodes' water values (set from the static
  /// shape, balancedWaterSplit): sharedHalves starts from it and moves the meeting with the
  /// threads' speed, so that a node's wave references stay with one thread but near it.
  int water_split = 0;
  /// Where the threads are expected to meet in the interval rows (evaluate; set from the mesh,
  /// balancedSplit with kJunctionWork; sharedHalves starts from it): a junction's rows
  /// (automatic differentiation) cost several intervals', and junctions gather where bodies sit,
  /// near the top of a mooring. The rows between the meeting and the Newton matrix's meeting
  /// node are assembled by one thread and eliminated by the other (1 KB an interval). No result
  /// depends on it: every interval's rows are computed alike on either thread.
  int interval_split = 0;
  const Material& mat(int j) const { return problem.materials[mesh.nodes[static_cast<std::size_t>(j)].material]; }

  /// Water at node j, at (x, z) and the time last given to wave_cache.setTime.
  Water waterAt(int j, double x, double z) const {
    Water w;
    double ux, uy;
    w.z = z;
    if (current.size() > 1) {
      // Slope of the piecewise-linear profile (exact inside a table interval), as in statics.
      constexpr double kDz = 1e-6;  // [m]
      double up, um;
      current.atAndAround(z, kDz, ux, uy, up, um);
      w.dwx_dz = (up - um) / (2.0 * kDz);
    } else {
      current.at(z, ux, uy);
    }
    w.wx = ux;
    if (!wave_cache.empty() && z <= 0.0) {
      double vx, vz;
      wave_cache.velocity(static_cast<std::size_t>(j), x, z, vx, vz);  // WaveField::velocity(x, 0, z, t)
      w.wx += vx;
      w.wz += vz;
    }
    return w;
  }

  void waterField(const Eigen::VectorXd& y, double time, std::vector<Water>& out) const {
    out.resize(static_cast<std::size_t>(nodes()));
    wave_cache.setTime(time);
    for (int j = 0; j < nodes(); ++j) out[static_cast<std::size_t>(j)] = waterAt(j, y[N * j + X], y[N * j + Z]);
  }

  /// Spatial rows of every interval at the accepted state y (double), and cos, sin of every
  /// node's inclination there (the next step's previous level). In the halves of the Newton
  /// iteration (the angles at the meeting node, the intervals at interval_split), on both
  /// threads when there are two.
  void spatialRows(const Eigen::VectorXd& y, const std::vector<Water>& w, Eigen::VectorXd& out, std::vector<double>& c,
                   std::vector<double>& s) const {
    const int n = nodes();
    out.setZero(N * (n - 1));
    c.resize(static_cast<std::size_t>(n));
    s.resize(static_cast<std::size_t>(n));
    auto angles = [&](int j0, int j1) {
      for (int j = j0; j < j1; ++j) sinCos(y[N * j + PHI], s[static_cast<std::size_t>(j)], c[static_cast<std::size_t>(j)]);
    };
    // Intervals [j0, j1), each node's load once for the intervals of one material it belongs to
    // (a half's first node computes its own: the same value as the other half's last).
    auto intervals = [&](int j0, int j1) {
      double f1b = 0.0, f2b = 0.0;
      long load_material = -1;  // that of the load of node j kept from the interval before
      for (int j = j0; j < j1; ++j) {
        const MeshInterval& iv = mesh.intervals[static_cast<std::size_t>(j)];
        const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
        const double* ya = y.data() + N * j;
        const double* yb = ya + N;
        double* r = out.data() + N * j;
        if (iv.h > 0.0) {
          const Material& m = problem.materials[iv.material];
          const NodeView na{ya, c[a], s[a], &w[a]}, nb{yb, c[b], s[b], &w[b]};
          double f1a = f1b, f2a = f2b;
          if (load_material != static_cast<long>(iv.material)) nodeLoadValue(problem.environment, m, na, f1a, f2a);
          nodeLoadValue(problem.environment, m, nb, f1b, f2b);
          load_material = static_cast<long>(iv.material);
          intervalSpatialRows(m, iv.h, na, nb, f1a, f2a, f1b, f2b, r);
        } else {
          junctionForces(problem, iv, mat(j), mat(j + 1), ya, yb, w[a], r);
          load_material = -1;
        }
      }
    };
    const int m = BandedMatrix::meetingNode(n);
    inHalves(m, n, angles);  // (the intervals need both halves' angles)
    inHalves(m == 0 ? 0 : interval_split, n - 1, intervals);
  }
};

// The fallback step (dynamics2d_fallback.cpp; docs/method.md "Slack and snap: the fallback step").
/// Why a converged implicit step ending at t_new with unknowns Yv is not the line's motion ("" when
/// it is): the top node off the path of a top held there by position feedback.
std::string topOffItsPath(const DynamicSolver2D::Impl& im, const Eigen::VectorXd& Yv, double t_new);
/// Why the line cannot fall back ("" when it can): only a line from an anchor to a top whose
/// motion is prescribed falls back in 2-D.
std::string fallbackUnavailable(const DynamicSolver2D::Impl& im);
/// Take a step of dt from the accepted state with the explicit lumped-mass model of the line
/// (lumped_line.hpp) in its plane; false (the reason appended to rep.message) when it cannot.
bool fallbackStep(DynamicSolver2D::Impl& im, double dt, StepReport& rep);
/// After a fallback step: whether the next base step goes to the fallback at once (as in 3-D).
bool stayInFallback(const DynamicSolver2D::Impl& im);

}  // namespace core
}  // namespace mooring_dynamics
