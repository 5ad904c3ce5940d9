// The start of the 2-D dynamic solver: the static solution it starts from (on the adaptive mesh
// of eq. 22 when the options ask, section 3), the top motion of the problem file, where the two
// threads meet, the error scales of eq. 39, and the state at rest with its water and spatial rows.
#include "dynamics2d_impl.hpp"
#include "lumped_line.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "mooring_dynamics/core/solvers/adaptive_mesh.hpp"
#include "mooring_dynamics/core/solvers/dynamic_run.hpp"
#include "mooring_dynamics/core/equations/dynamic_interval.hpp"
#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"
#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

/// Newton state vector (N = 8) from a static result: velocities zero (the line starts at rest).
Eigen::VectorXd stateFromStatic(const StaticResult& r) {
  const std::size_t n = r.nodes.size();
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N * n));
  for (std::size_t j = 0; j < n; ++j) {
    double* y = Y.data() + N * j;
    const NodeState& ns = r.nodes[j];
    y[EPS] = ns.strain;
    y[SN] = ns.shear;
    y[PHI] = ns.angle;
    y[OMEGA] = ns.curvature;
    y[X] = ns.x;
    y[Z] = ns.z;
  }
  return Y;
}

}  // namespace

namespace {

/// The static solution the run starts from (section 3: on the adaptive mesh of eq. 22 when the
/// options ask), into im.mesh and im.statics.
void solveStart(DynamicSolver2D::Impl& im, const Problem& problem) {
  // The dynamic equations have no static cap (eq. 35 caps statics only): start from the
  // equilibrium of the same seabed model so that the start is at rest.
  Problem start = problem;
  start.environment.seabed.static_cap = false;
  im.mesh = buildMesh(problem);
  im.statics = solveStaticOnMesh(start, im.mesh, start.static_options);
  if (im.statics.summary.converged && problem.dynamics.adaptive_mesh) {
    // Section 3: redistribute the nodes by eq. 22 from the uniform-mesh statics, re-solve.
    im.mesh = buildAdaptiveMesh(start, im.mesh, im.statics, problem.dynamics.mesh_weight);
    im.statics = solveStaticOnMesh(start, im.mesh, start.static_options);
  }
  if (!im.statics.summary.converged)
    throw std::runtime_error("the static solution that starts the dynamic run did not converge: " +
                             im.statics.summary.message);
}

/// The top motion of the problem file: the 3-D source projected on the x-z plane, started at
/// the static top (y = 0).
void setTopMotion(DynamicSolver2D::Impl& im, const Problem& problem) {
  const NodeState& topNode = im.statics.nodes.back();
  const TopMotion& tm = problem.dynamics.top_motion;
  constexpr double kStartMismatch = 0.01;  // [m] a position table must start where statics put the top
  std::string bad_motion = planarTopMotionError(tm);
  if (bad_motion.empty()) bad_motion = topMotionStartError(tm, topNode.x, 0.0, topNode.z, kStartMismatch);
  if (!bad_motion.empty()) throw std::invalid_argument(bad_motion);
  im.top = [source = makeTopMotion(tm, topNode.x, 0.0, topNode.z, &im.waves)](double t) {
    const TopState s = source(t);
    TopInput in;
    in.force = s.force;
    in.x = s.x;
    in.z = s.z;
    in.vx = s.vx;
    in.vz = s.vz;
    in.fx = s.fx;
    in.fz = s.fz;
    return in;
  };
}

/// Where the two threads are expected to meet in the node values and in the interval rows.
void balanceThreads(DynamicSolver2D::Impl& im) {
  {
    // In the units of one component's sum (measured on A.2, one thread): a node's water without
    // the sum (the current table's look-ups, three then, the cache's bookkeeping), and its rates and
    // angles. A.2 at 0.1 s, timed on one thread: the water phase took 0.71 s in the upper half
    // against 0.34 s in the lower; split at node 198 of 274 instead of 137, 0.55 and 0.55 s.
    constexpr double kWaterWork = 40.0, kRestWork = 8.0;
    std::vector<double> z(static_cast<std::size_t>(im.nodes()));
    for (int j = 0; j < im.nodes(); ++j) z[static_cast<std::size_t>(j)] = im.Y[N * j + Z];
    im.water_split = balancedWaterSplit(im.wave_cache, z, BandedMatrix::meetingNode(im.nodes()), kWaterWork + kRestWork, 0.0);
  }
  {
    // The Newton matrix's rows of a junction (pin rows with automatic differentiation) in those
    // of an interval of a material. Timed per interval on one thread: about 4 times (A.3 and A.2
    // at 0.1 s: 0.71-0.92 us against 0.18-0.24 us). With two threads the halves of the interval
    // phase came out even at 3 in both (A.3 0.24 / 0.24 s, A.2 0.43-0.49 / 0.48 s; at 3.5 A.3's
    // lower half took 0.24-0.29 s against 0.20-0.22): the halves' other work differs.
    constexpr double kJunctionWork = 3.0;
    std::vector<double> cost;
    for (const MeshInterval& iv : im.mesh.intervals) cost.push_back(iv.h > 0.0 ? 1.0 : kJunctionWork);
    im.interval_split = balancedSplit(cost);
  }
}

/// Error scales chi_m of eq. 39.
void setErrorScales(DynamicSolver2D::Impl& im, const Problem& problem) {
  double Tc = 1.0, stiffest = 0.0;
  for (const auto& ns : im.statics.nodes) Tc = std::max(Tc, std::abs(ns.tension));
  for (const auto& m : problem.materials) stiffest = std::max(stiffest, m.rawTensionSlope(0.0));
  im.chi[EPS] = Tc / stiffest;
  im.chi[SN] = Tc;
  im.chi[U] = im.chi[V] = 1.0;  // [m/s]
  im.chi[PHI] = 1.0;            // [rad]
  im.chi[OMEGA] = 1.0 / std::max(im.mesh.minSpacing(), 1e-3);
  im.chi[X] = im.chi[Z] = 1.0;  // [m]
}

}  // namespace

DynamicSolver2D::DynamicSolver2D(const Problem& problem) : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  const std::string err = problem.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  // Its mesh is fixed: a winch would be ignored. runDynamicModel runs such a problem on the 3-D
  // equations in its plane.
  if (problem.dynamics.winch.given)
    throw std::invalid_argument("dynamics.winch: the 2-D solver's mesh is fixed; a 2-D problem with a winch runs on "
                                "the 3-D equations in its plane (cable_sim dynamic does so; the line node needs "
                                "model: 3d)");
  im.problem = problem;
  im.opt = problem.dynamics;
  im.ga = problem.dynamics.scheme;
  solveStart(im, problem);
  if (im.opt.fallback_after_cuts == DynamicOptions::kFallbackAfterCutsAuto) {
    // (DynamicOptions::fallback_after_cuts) 1 where the line can go slack and snap, as in 3-D.
    bool slack_law = false;
    for (int j = 0; j < im.nodes(); ++j) slack_law = slack_law || !im.mat(j).compression;
    im.opt.fallback_after_cuts = slack_law ? 1 : 4;
  }
  im.lower = makeLowerEnd2D(im.problem);
  im.upper = makeUpperEnd2D(im.problem, im.mat(im.nodes() - 1));
  if (problem.environment.waves.type != WaveSpec::Type::None)
    im.waves = WaveField(problem.environment.waves, problem.environment.depth, problem.environment.gravity);
  im.wave_cache = WaveVelocityCache(&im.waves, im.mesh.nodes.size());
  im.current = CurrentProfile(problem.environment.current);
  // The second thread takes the upper half of every iteration, on lines long enough for it to pay.
  if (im.opt.threads > 1 && im.nodes() >= DynamicSolver2D::kMinNodesForTwoThreads) {
    im.fork = std::make_unique<ForkJoin>();
    im.newton_matrix.setParallel(im.fork.get());
  }
  setTopMotion(im, problem);

  // The start: the static shape at rest, with its water and spatial rows (the first step's
  // previous level).
  im.t = 0.0;
  im.Y = stateFromStatic(im.statics);
  im.Yd = Eigen::VectorXd::Zero(im.Y.size());
  im.waterField(im.Y, 0.0, im.water);
  im.spatialRows(im.Y, im.water, im.S, im.cos_phi, im.sin_phi);
  balanceThreads(im);
  setErrorScales(im, problem);
}

}  // namespace core
}  // namespace mooring_dynamics
