#include "mooring_dynamics/core/solvers/statics3d.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/solvers/drifting.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/solvers/initial_guess.hpp"
#include "mooring_dynamics/core/solvers/static_system.hpp"
#include "mooring_dynamics/core/solvers/statics2d.hpp"
#include "mooring_dynamics/core/solvers/towing.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq3d;

namespace {
using AD32 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;
using AD16 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

/// Water velocity of the steady current at a node (statics: no waves).
Water currentAt(const Environment& env, double z) {
  Water w;
  env.currentAt(z, w.w[0], w.w[1]);
  env.currentGradientAt(z, w.dw_dz[0], w.dw_dz[1]);
  w.z = z;
  return w;
}

}  // namespace

// --- StaticSystem3D ------------------------------------------------------------------------------

StaticSystem3D::StaticSystem3D(const Problem& problem, const Mesh& mesh, const double* q_ref)
    : problem_(problem),
      mesh_(mesh),
      lower_(makeLowerEnd3D(problem, problem.materials[mesh.nodes.front().material])),
      upper_(makeUpperEnd3D(problem, problem.materials[mesh.nodes.back().material])),
      lower_rows_(lower_->staticRows()) {
  for (int i = 0; i < 4; ++i) q_ref_[i] = q_ref[i];
  double Tc = std::abs(totalWetWeight(problem, mesh));
  Tc = std::max(Tc, upper_->characteristicForce());  // a force top's force
  Tc = std::max(Tc, 1.0);
  double stiffest = 0.0;
  for (const auto& m : problem.materials) stiffest = std::max(stiffest, m.rawTensionSlope(0.0));
  const double L = problem.totalLength();
  // chi_m of eq. 39, as in 2-D.
  chi_[EPS] = Tc / stiffest;
  chi_[S2] = chi_[S3] = Tc;
  chi_[U1] = chi_[U2] = chi_[U3] = 1.0;                         // [m/s]
  chi_[O1] = chi_[O2] = chi_[O3] = 1.0 / std::max(mesh.minSpacing(), 1e-3);
  chi_[Q0] = chi_[Q1] = chi_[Q2] = chi_[Q3] = 1.0;              // about 2 rad
  chi_[X] = chi_[Y] = chi_[Z] = L;
}

int StaticSystem3D::size() const { return N * static_cast<int>(mesh_.nodes.size()); }

double StaticSystem3D::scale(int i) const { return chi_[i % N]; }

std::string StaticSystem3D::describe(int i) const {
  const std::size_t j = static_cast<std::size_t>(i / N);
  std::ostringstream os;
  os << "node " << j << " (s = " << mesh_.nodes[j].s << " m) " << varName(i % N);
  return os.str();
}

void StaticSystem3D::evaluate(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J) {
  const int n = static_cast<int>(mesh_.nodes.size());
  R.resize(size());
  std::vector<Water> water(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) water[static_cast<std::size_t>(j)] = currentAt(problem_.environment, Yv[N * j + Z]);
  // The lower end (anchor or free end), sixteen rows per interval (eq. 11), the top (eq. 33 /
  // section 5.1 in 3-D).
  endRows(*lower_, 0, 0, water.front(), Yv, R, J);
  for (int j = 0; j + 1 < n; ++j) intervalRows(j, water, Yv, R, J);
  endRows(*upper_, lower_rows_ + N * (n - 1), N * (n - 1), water.back(), Yv, R, J);
}

void StaticSystem3D::endRows(const EndCondition3D& end, int row0, int col0, const Water& water,
                             const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J) const {
  AD16 y[N], r[kMaxEndRows];
  for (int k = 0; k < N; ++k) y[k] = AD16(Yv[col0 + k], N, k);
  end.staticResidual(StaticEnd3D{&water, q_ref_}, y, r);
  scatter(r, end.staticRows(), row0, col0, N, R, J);
}

void StaticSystem3D::intervalRows(int j, const std::vector<Water>& water, const Eigen::VectorXd& Yv,
                                  Eigen::VectorXd& R, BandedMatrix* J) const {
  // Sixteen rows per half-grid interval (eq. 11), or a pin junction.
  const Environment& env = problem_.environment;
  const MeshInterval& iv = mesh_.intervals[static_cast<std::size_t>(j)];
  const Material& ma = problem_.materials[mesh_.nodes[static_cast<std::size_t>(j)].material];
  const Material& mb = problem_.materials[mesh_.nodes[static_cast<std::size_t>(j) + 1].material];
  const Water& wa = water[static_cast<std::size_t>(j)];
  const Water& wb = water[static_cast<std::size_t>(j) + 1];
  const int row = lower_rows_ + N * j;
  if (J) {
    AD32 y[2 * N], r[N];
    for (int k = 0; k < 2 * N; ++k) y[k] = AD32(Yv[N * j + k], 2 * N, k);
    if (iv.h > 0.0) {
      intervalSpatial(env, problem_.materials[iv.material], iv.h, y, y + N, wa, wb, r);
      addStaticSeabedFriction(env, problem_.materials[iv.material], iv.h, y, y + N, r);
    } else {
      junctionForces(problem_, iv, ma, mb, y, y + N, wa, r);
      junctionConstraints(ma, mb, y, y + N, r);
    }
    scatter(r, N, row, N * j, 2 * N, R, J);
  } else {
    double r[N];
    const double* ya = Yv.data() + N * j;
    if (iv.h > 0.0) {
      intervalSpatial(env, problem_.materials[iv.material], iv.h, ya, ya + N, wa, wb, r);
      addStaticSeabedFriction(env, problem_.materials[iv.material], iv.h, ya, ya + N, r);
    } else {
      junctionForces(problem_, iv, ma, mb, ya, ya + N, wa, r);
      junctionConstraints(ma, mb, ya, ya + N, r);
    }
    for (int q = 0; q < N; ++q) R[row + q] = r[q];
  }
}

double StaticSystem3D::stepLimit(const Eigen::VectorXd& dY) const {
  // A change of the Euler parameters by 0.25 is a turn of about half a radian: the largest turn
  // Newton's linearization of the rotation is trusted with (as the 2-D 0.5 rad).
  constexpr double kMaxQuaternionStep = 0.25;
  double largest = 0.0;
  for (Eigen::Index i = 0; i + N <= dY.size(); i += N)
    largest = std::max(largest, dY.segment<4>(i + Q0).norm());
  return largest > kMaxQuaternionStep ? kMaxQuaternionStep / largest : 1.0;
}

void StaticSystem3D::conditionStep(const Eigen::VectorXd& Yv, Eigen::VectorXd& dY) const {
  // As in 2-D: Newton sees no seabed under a node above it and may throw it far below.
  const Environment& env = problem_.environment;
  for (std::size_t j = 0; j < mesh_.nodes.size(); ++j) {
    const Eigen::Index i = static_cast<Eigen::Index>(N * j);
    const double w = std::max(problem_.materials[mesh_.nodes[j].material].wet_weight, 0.0);
    const double zb = env.seabedElevation(Yv[i + X], Yv[i + Y]);
    const double rest = zb - 1.5 * w / env.seabed.stiffness;
    if (Yv[i + Z] >= zb && Yv[i + Z] + dY[i + Z] < rest) dY[i + Z] = rest - Yv[i + Z];
  }
}

// --- Initial guess -------------------------------------------------------------------------------

double initialGuessAzimuth(const Problem& p) {
  const TopBoundary& tb = p.top;
  constexpr double kNone = 1e-9;  // [m] or [N]: no horizontal direction to follow
  if (tb.type == TopBoundary::Type::Position) {
    const double dx = tb.x - p.anchor_x, dy = tb.y - p.anchor_y;
    if (std::hypot(dx, dy) > kNone) return std::atan2(dy, dx);
  } else if (tb.type == TopBoundary::Type::Force) {
    if (std::hypot(tb.fx, tb.fy) > kNone) return std::atan2(tb.fy, tb.fx);
  }
  double ux, uy;
  p.environment.currentAt(0.0, ux, uy);
  if (std::hypot(ux, uy) > kNone) return std::atan2(uy, ux);
  if (p.environment.wind_speed > 0.0) return p.environment.wind_direction;
  return 0.0;
}

namespace {

/// The problem seen in the vertical plane through the anchor at azimuth psi, as a 2-D problem:
/// anchor at x' = 0, horizontal loads projected on the plane, the seabed sampled along it.
Problem planarProjection(const Problem& p, double psi) {
  Problem q = p;
  q.formulation = Formulation::TwoD;
  q.dynamics.events.clear();  // a static first guess: the 3-D run's events are not its business
  const double c = std::cos(psi), s = std::sin(psi);
  const bool identity = psi == 0.0 && p.anchor_y == 0.0;
  if (!identity) {
    q.anchor_x = 0.0;
    q.anchor_y = 0.0;
    const double L = p.totalLength();
    Environment& e = q.environment;
    if (!p.environment.flatSeabed()) {
      constexpr int kSamples = 400;
      e.seabed.grid = SeabedGrid{};
      e.seabed.profile.clear();
      for (int k = 0; k <= kSamples; ++k) {
        const double xp = -0.25 * L + 1.5 * L * k / kSamples;
        e.seabed.profile.emplace_back(
            xp, -p.environment.seabedElevation(p.anchor_x + xp * c, p.anchor_y + xp * s));
      }
    }
    for (CurrentPoint& cp : e.current) cp.direction -= psi;
    e.wind_direction -= psi;
    if (p.top.type == TopBoundary::Type::Position) {
      q.top.x = (p.top.x - p.anchor_x) * c + (p.top.y - p.anchor_y) * s;
      q.top.y = 0.0;
    }
    if (p.top.type == TopBoundary::Type::Force) {
      q.top.fx = p.top.fx * c + p.top.fy * s;
      q.top.fy = 0.0;
    }
  }
  if (p.top.type == TopBoundary::Type::Body) {
    // A subsurface buoy: for the guess, a force top of its net buoyancy and its drag in the
    // current at the depth it would float at (anchor plus line length, at most the surface).
    const Body& b = p.bodies[p.top.body];
    double ux, uy;
    p.environment.currentAt(std::min(0.0, p.anchor_z + p.totalLength()), ux, uy);
    const double U = ux * c + uy * s;
    q.top.type = TopBoundary::Type::Force;
    q.top.fx = 0.5 * p.environment.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.isotropicCd() * U * std::abs(U);
    q.top.fz = -b.wet_weight;
    q.formulation = Formulation::TwoD;
  }
  q.top.y = 0.0;
  q.top.fy = 0.0;
  return q;
}

}  // namespace

Eigen::VectorXd planarInitialGuess3D(const Problem& problem, const Mesh& mesh, double psi) {
  const Problem planar = planarProjection(problem, psi);
  StaticOptions o = planar.static_options;
  const StaticResult r2 = solveStaticOnMesh(planar, mesh, o);  // last iterate if not converged
  const std::size_t n = mesh.nodes.size();
  Eigen::VectorXd Yv = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N * n));
  const bool identity = psi == 0.0 && problem.anchor_y == 0.0;
  const double c = std::cos(psi), s = std::sin(psi);
  for (std::size_t j = 0; j < n; ++j) {
    const NodeState& ns = r2.nodes[j];
    double* y = Yv.data() + N * j;
    y[EPS] = ns.strain;
    y[S2] = ns.shear;
    y[O3] = ns.curvature;
    quat::planarFrame(psi, ns.angle, y + Q0);
    if (identity) {
      y[X] = ns.x;
      y[Y] = 0.0;
    } else {
      y[X] = problem.anchor_x + ns.x * c;
      y[Y] = problem.anchor_y + ns.x * s;
    }
    y[Z] = ns.z;
  }
  return Yv;
}

// --- Result --------------------------------------------------------------------------------------

StaticResult staticResult3DFromState(const Problem& problem, const Mesh& mesh, const Eigen::VectorXd& Yv) {
  StaticResult res;
  const std::size_t n = mesh.nodes.size();
  res.nodes.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double* y = Yv.data() + N * j;
    const Material& m = problem.materials[mesh.nodes[j].material];
    double R[9];
    quat::matrix(y + Q0, R);
    NodeState& ns = res.nodes[j];
    ns.s = mesh.nodes[j].s;
    ns.x = y[X];
    ns.y = y[Y];
    ns.z = y[Z];
    ns.tension = m.tension(y[EPS]);
    ns.shear = y[S2];
    ns.shear_b = y[S3];
    ns.angle = std::atan2(std::hypot(R[0], R[3]), R[6]);
    ns.azimuth = std::atan2(R[3], R[0]);
    ns.curvature = y[O3];
    ns.curvature_b = y[O2];
    ns.twist = y[O1];
    ns.strain = y[EPS];
    ns.segment = static_cast<int>(mesh.nodes[j].segment);
  }
  double F[3];
  internalForce(problem.materials[mesh.nodes.back().material], Yv.data() + N * (n - 1), F);
  res.top_force_x = F[0];
  res.top_force_y = F[1];
  res.top_force_z = F[2];
  internalForce(problem.materials[mesh.nodes.front().material], Yv.data(), F);
  res.anchor_force_x = F[0];
  res.anchor_force_y = F[1];
  res.anchor_force_z = F[2];
  if (problem.top.type == TopBoundary::Type::Buoy) res.buoy_draft = -res.nodes.back().z;
  return res;
}

// --- Driver --------------------------------------------------------------------------------------

StaticResult solveStatic3D(const Problem& problem) { return solveStatic3D(problem, problem.static_options); }

StaticResult solveStatic3D(const Problem& problem, const StaticOptions& options) {
  std::string err = problem.validate();
  if (err.empty()) err = options.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  return solveStatic3DOnMesh(problem, buildMesh(problem), options).result;
}

StaticState3D solveStatic3DOnMesh(const Problem& problem, const Mesh& mesh, const StaticOptions& options) {
  std::string err = problem.validate();
  if (err.empty()) err = options.validate();
  if (err.empty() && problem.environment.seabed.static_cap)
    err = "environment.seabed.static_cap = true: the capped seabed of eq. 35 is a 2-D option "
          "(model: 2d); the 3-D model uses the plain elastic foundation";
  if (!err.empty()) throw std::invalid_argument(err);

  StaticState3D out;
  if (isDrifter(problem)) {
    out = solveDriftStatic3D(problem, mesh, options);
  } else {
    // A towed line is solved in the frame moving with the tow point: the current relative to it.
    Problem solved = problem;
    const bool towed = problem.lower_end == Problem::LowerEnd::Free;
    if (towed) solved.environment = relativeEnvironment(problem.environment, problem.top.tow_vx, problem.top.tow_vy);
    out.Y = towed ? towedInitialGuess3D(solved, mesh) : planarInitialGuess3D(problem, mesh, initialGuessAzimuth(problem));
    const double q_ref[4] = {out.Y[Q0], out.Y[Q1], out.Y[Q2], out.Y[Q3]};
    StaticSystem3D system(solved, mesh, q_ref);
    const SolverSummary summary = solveNewton(system, out.Y, newtonOptions(options));
    out.result = staticResult3DFromState(problem, mesh, out.Y);
    out.result.summary = summary;
  }
  if (problem.top.type == TopBoundary::Type::Buoy && out.result.buoy_draft >= problem.top.buoy.totalHeight()) {
    out.result.summary.converged = false;
    out.result.summary.message += "; the surface buoy is fully submerged (draft " +
                                  std::to_string(out.result.buoy_draft) + " m >= height " +
                                  std::to_string(problem.top.buoy.totalHeight()) +
                                  " m): its buoyancy cannot carry the line";
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
