#include "mooring_dynamics/core/solvers/statics2d.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/solvers/initial_guess.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/solvers/static_system.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq2d;

// --- StaticSystem2D ----------------------------------------------------------------------------
//
// Row layout: 3 anchor rows, 6 rows per interval, 3 top rows; columns: 6 unknowns per node.
// Interval j touches nodes j and j + 1, so the Newton matrix has half-bandwidths kl = ku = 8.

namespace {
using AD12 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;
using AD6 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
const char* const kVarNames[N] = {"eps", "Sn", "phi", "Omega3", "x", "z"};
}  // namespace

StaticSystem2D::StaticSystem2D(const Problem& problem, const Mesh& mesh)
    : problem_(problem),
      mesh_(mesh),
      lower_(makeLowerEnd2D(problem)),
      upper_(makeUpperEnd2D(problem, problem.materials[mesh.nodes.back().material])),
      lower_rows_(lower_->staticRows()) {
  // Characteristic magnitudes for the error measure (chi_m of eq. 39).
  double Tc = std::abs(totalWetWeight(problem, mesh));
  Tc = std::max(Tc, upper_->characteristicForce());  // a force top's force
  Tc = std::max(Tc, 1.0);
  double stiffest = 0.0;
  for (const auto& m : problem.materials) stiffest = std::max(stiffest, m.rawTensionSlope(0.0));
  const double L = problem.totalLength();
  chi_[EPS] = Tc / stiffest;  // strain giving the characteristic tension on the stiffest material
  chi_[SN] = Tc;
  chi_[PHI] = 1.0;
  chi_[OMEGA] = 1.0 / std::max(mesh.minSpacing(), 1e-3);
  chi_[X] = L;
  chi_[Z] = L;
}

int StaticSystem2D::size() const { return N * static_cast<int>(mesh_.nodes.size()); }

double StaticSystem2D::scale(int i) const { return chi_[i % N]; }

std::string StaticSystem2D::describe(int i) const {
  const std::size_t j = static_cast<std::size_t>(i / N);
  std::ostringstream os;
  os << "node " << j << " (s = " << mesh_.nodes[j].s << " m) " << kVarNames[i % N];
  return os.str();
}

void StaticSystem2D::evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) {
  const int n = static_cast<int>(mesh_.nodes.size());
  R.resize(size());
  endRows(*lower_, 0, 0, Y, R, J);  // the anchor (eq. 33)
  for (int j = 0; j + 1 < n; ++j) intervalRows(j, Y, R, J);
  endRows(*upper_, lower_rows_ + N * (n - 1), N * (n - 1), Y, R, J);  // the top (eq. 33, section 5.1)
}

void StaticSystem2D::endRows(const EndCondition2D& end, int row0, int col0, const Eigen::VectorXd& Y,
                             Eigen::VectorXd& R, BandedMatrix* J) const {
  AD6 y[N], r[kMaxEndRows];
  for (int k = 0; k < N; ++k) y[k] = AD6(Y[col0 + k], N, k);
  end.staticResidual(y, r);
  scatter(r, end.staticRows(), row0, col0, N, R, J);
}

void StaticSystem2D::intervalRows(int j, const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) const {
  // One block of six rows per half-grid interval (eq. 11).
  const MeshInterval& iv = mesh_.intervals[static_cast<std::size_t>(j)];
  const Material& ma = problem_.materials[mesh_.nodes[static_cast<std::size_t>(j)].material];
  const Material& mb = problem_.materials[mesh_.nodes[static_cast<std::size_t>(j) + 1].material];
  const int row = lower_rows_ + N * j;
  if (J) {
    AD12 y[2 * N], r[N];
    for (int k = 0; k < 2 * N; ++k) y[k] = AD12(Y[N * j + k], 2 * N, k);
    intervalResidual(problem_, iv, ma, mb, y, y + N, r, capped_);
    for (int q = 0; q < N; ++q) {
      R[row + q] = r[q].value();
      for (int k = 0; k < 2 * N; ++k) J->at(row + q, N * j + k) = r[q].derivatives()[k];
    }
  } else {
    double r[N];
    intervalResidual(problem_, iv, ma, mb, Y.data() + N * j, Y.data() + N * (j + 1), r, capped_);
    for (int q = 0; q < N; ++q) R[row + q] = r[q];
  }
}

double StaticSystem2D::stepLimit(const Eigen::VectorXd& dY) const {
  // Newton's linearization of the rotation terms (sin, cos of phi) is trusted up to about half a
  // radian; a larger predicted turn is scaled down with the whole update.
  constexpr double kMaxAngleStep = 0.5;  // [rad]
  double largest = 0.0;
  for (Eigen::Index i = PHI; i < dY.size(); i += N) largest = std::max(largest, std::abs(dY[i]));
  return largest > kMaxAngleStep ? kMaxAngleStep / largest : 1.0;
}

void StaticSystem2D::conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const {
  // Newton sees no seabed under a node that is above it, and may send it far below, where the
  // stiff foundation throws it back up: the iteration then oscillates through the contact.
  const Environment& env = problem_.environment;
  for (std::size_t j = 0; j < mesh_.nodes.size(); ++j) {
    const Eigen::Index iz = static_cast<Eigen::Index>(N * j + Z);
    const double w = std::max(problem_.materials[mesh_.nodes[j].material].wet_weight, 0.0);
    const double rest = env.seabedElevation(Y[iz - 1]) - 1.5 * w / env.seabed.stiffness;  // resting penetration
    // Only a node out of contact is stopped; one already on the bottom may go deeper, except
    // under the static cap, where nothing pushes a node back up from below its resting depth.
    const double from = capped_ ? rest : env.seabedElevation(Y[iz - 1]);
    if (Y[iz] >= from && Y[iz] + dY[iz] < rest) dY[iz] = rest - Y[iz];
  }
}

double StaticSystem2D::maxSeabedLoadRatio(const Eigen::VectorXd& Y) const {
  double ratio = 0.0;
  for (std::size_t j = 0; j < mesh_.intervals.size(); ++j) {
    const MeshInterval& iv = mesh_.intervals[j];
    const Material& m = problem_.materials[iv.material];
    if (iv.h <= 0.0 || m.wet_weight <= 0.0) continue;
    double Fa, Fb;
    seabedForces(problem_.environment, m, Y.data() + N * j, Y.data() + N * (j + 1), false, Fa, Fb);
    ratio = std::max(ratio, 0.5 * (Fa + Fb) / m.wet_weight);
  }
  return ratio;
}

// --- Result extraction ---------------------------------------------------------------------------

StaticResult staticResultFromState(const Problem& problem, const Mesh& mesh, const Eigen::VectorXd& Y) {
  StaticResult res;
  const std::size_t n = mesh.nodes.size();
  res.nodes.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double* y = Y.data() + N * j;
    const Material& m = problem.materials[mesh.nodes[j].material];
    NodeState& ns = res.nodes[j];
    ns.s = mesh.nodes[j].s;
    ns.x = y[X];
    ns.z = y[Z];
    ns.tension = m.tension(y[EPS]);
    ns.shear = y[SN];
    ns.angle = y[PHI];
    ns.curvature = y[OMEGA];
    ns.strain = y[EPS];
    ns.segment = static_cast<int>(mesh.nodes[j].segment);
  }
  internalForce(problem.materials[mesh.nodes.back().material], Y.data() + N * (n - 1), res.top_force_x,
                res.top_force_z);
  internalForce(problem.materials[mesh.nodes.front().material], Y.data(), res.anchor_force_x, res.anchor_force_z);
  if (problem.top.type == TopBoundary::Type::Buoy) res.buoy_draft = -res.nodes.back().z;
  return res;
}

NewtonOptions newtonOptions(const StaticOptions& o) {
  NewtonOptions n;
  n.tolerance = o.tolerance;
  n.max_iterations = o.max_iterations;
  n.mu0 = o.relaxation;
  n.adaptive = o.adaptive_relaxation;
  n.R1 = o.R1;
  n.R2 = o.R2;
  return n;
}

// --- Driver --------------------------------------------------------------------------------------

StaticResult solveStatic(const Problem& problem) { return solveStatic(problem, problem.static_options); }

StaticResult solveStatic(const Problem& problem, const StaticOptions& options) {
  std::string err = problem.validate();
  if (err.empty()) err = options.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  return solveStaticOnMesh(problem, buildMesh(problem), options);
}

StaticResult solveStaticOnMesh(const Problem& problem, const Mesh& mesh, const StaticOptions& options) {
  std::string err = problem.validate();
  if (err.empty()) err = options.validate();
  if (err.empty() && (mesh.nodes.size() < 2 || mesh.intervals.size() + 1 != mesh.nodes.size() ||
                      std::abs(mesh.nodes.back().s - problem.totalLength()) > 1e-9 * problem.totalLength()))
    err = "mesh: " + std::to_string(mesh.nodes.size()) + " nodes and " + std::to_string(mesh.intervals.size()) +
          " intervals do not describe the problem's line of " + std::to_string(problem.totalLength()) + " m";
  if (!err.empty()) throw std::invalid_argument(err);

  // Initial guess: a generalized catenary (default) or a straight line.
  const Shot shot = catenaryShot(problem, mesh);
  Eigen::VectorXd Y = options.initial_guess == StaticOptions::InitialGuess::StraightLine
                          ? straightLineState(problem, mesh)
                          : stateFromShot(mesh, shot);
  // Stage 0 (static friction on a line without compression): first with the law through zero,
  // whose tension keeps its slope at and below zero strain. Where the friction uses up the pull
  // the grounded line is slack; an iterate with negative strain there sees neither a friction
  // nor a tension slope (the slack ramp and the friction step are both flat below zero), and
  // Newton on the no-compression law from the catenary guess cycled (docs/method.md, "Seabed
  // friction"). Stage 1 then starts from that solution, which differs only where the tension is
  // within the slack ramp.
  int stage0 = 0;
  Problem eased = problem;
  bool ease = false;
  for (Material& m : eased.materials)
    if (m.mu_axial > 0.0 && !m.compression) ease = m.compression = true;
  if (ease) {
    StaticSystem2D pre(eased, mesh);
    pre.setSeabedCap(false);
    Eigen::VectorXd Y0 = Y;
    const SolverSummary s0 = solveNewton(pre, Y0, newtonOptions(options));
    if (s0.converged) {
      Y = Y0;
      stage0 = s0.iterations;
    }
  }
  StaticSystem2D system(problem, mesh);
  // Stage 1: the seabed as a plain spring: smooth equations, Newton converges quadratically.
  system.setSeabedCap(false);
  SolverSummary summary = solveNewton(system, Y, newtonOptions(options));
  if (stage0 > 0) {
    summary.iterations += stage0;
    summary.message += "; started from the solution with compression (static friction on a line without it), " +
                       std::to_string(summary.iterations) + " iterations in all";
  }
  // Stage 2 (seabed.static_cap): the paper's capped foundation, started from the smooth solution,
  // when some stretch of line carries more than its wet weight. The cap's value enters the
  // residual; its Jacobian keeps the spring's slope (a capped stretch has none, and the box
  // scheme's odd-even mode along grounded line would then have no stiffness at all).
  if (problem.environment.seabed.static_cap && summary.converged && system.maxSeabedLoadRatio(Y) > 1.0) {
    system.setSeabedCap(true);
    const int stage1 = summary.iterations;
    summary = solveNewton(system, Y, newtonOptions(options));
    summary.iterations += stage1;
    summary.message += " with the seabed cap, " + std::to_string(summary.iterations) + " iterations in all";
  }
  if (!summary.converged && problem.top.type == TopBoundary::Type::Position && !shot.ok) {
    summary.message += "; hint: no catenary with positive horizontal tension reaches the top position "
                       "(the top may be too close to the anchor, leaving slack line on a frictionless seabed)";
  }

  StaticResult res = staticResultFromState(problem, mesh, Y);
  res.summary = summary;
  if (problem.top.type == TopBoundary::Type::Buoy && res.buoy_draft >= problem.top.buoy.totalHeight()) {
    res.summary.converged = false;
    res.summary.message += "; the surface buoy is fully submerged (draft " + std::to_string(res.buoy_draft) +
                           " m >= height " + std::to_string(problem.top.buoy.totalHeight()) +
                           " m): its buoyancy cannot carry the line";
  }
  return res;
}

}  // namespace core
}  // namespace mooring_dynamics
