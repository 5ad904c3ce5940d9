#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "dynamics3d_impl.hpp"
#include "lumped_line.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/solvers/adaptive_mesh.hpp"
#include "mooring_dynamics/core/solvers/drifting.hpp"
#include "mooring_dynamics/core/solvers/dynamic_run.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/solvers/statics3d.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq3d;

namespace {
using AD32 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;
using AD16 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
}  // namespace

// ------------------------------------------------------------------------------------------------

// --- One time step as a Newton system ------------------------------------------------------------
//
// Row layout as in statics (10 anchor rows, 16 per interval, 6 top rows): kl = 25, ku = 21.

class DynamicStepSystem3D : public NewtonSystem {
 public:
  DynamicStepSystem3D(const DynamicSolver3D::Impl& im, double t_new, double dt, const TopState& top)
      : im_(im), t_(t_new), dt_(dt), top_(top), end_rows_(im.lower->dynamicRows()) {}

  int size() const override { return N * im_.nodes(); }
  // Interval j's rows start at end_rows_ + N j and touch nodes j, j + 1.
  int lowerBandwidth() const override { return end_rows_ + N - 1; }
  int upperBandwidth() const override { return 2 * N - 1 - end_rows_; }
  // Node-by-node block elimination (BandedMatrix::setBlockStructure).
  int blockSize() const override { return N; }
  int leadingRows() const override { return end_rows_; }
  double scale(int i) const override { return im_.chi[i % N]; }
  std::string describe(int i) const override {
    const std::size_t j = static_cast<std::size_t>(i / N);
    std::ostringstream os;
    os << "node " << j << " (s = " << im_.mesh.nodes[j].s << " m) " << varName(i % N);
    return os.str();
  }
  double stepLimit(const Eigen::VectorXd& dY) const override { return stepLimit(dY, 0, size()); }
  double stepLimit(const Eigen::VectorXd& dY, int first, int end) const override {
    constexpr double kMaxQuaternionStep = 0.25;  // about half a radian, as in statics
    double largest = 0.0;
    for (int i = first; i + N <= end; i += N) largest = std::max(largest, dY.segment<4>(i + Q0).norm());
    return largest > kMaxQuaternionStep ? kMaxQuaternionStep / largest : 1.0;
  }
  /// The Newton loop's vector work in the halves of the two-ended elimination (see evaluateAs).
  bool splitsUpdate() const override { return true; }
  void conditionStep(const Eigen::VectorXd& Yv, Eigen::VectorXd& dY) const override {
    conditionStep(Yv, dY, 0, size());
  }
  void conditionStep(const Eigen::VectorXd& Yv, Eigen::VectorXd& dY, int first, int end) const override {
    const Environment& env = im_.problem.environment;
    for (int j = first / N; j < end / N; ++j) {
      const Eigen::Index i = N * j;
      const double w = std::max(im_.mat(j).wet_weight, 0.0);
      const double zb = env.seabedElevation(Yv[i + X], Yv[i + eq3d::Y]);
      const double rest = zb - 1.5 * w / env.seabed.stiffness;
      if (Yv[i + Z] >= zb && Yv[i + Z] + dY[i + Z] < rest) dY[i + Z] = rest - Yv[i + Z];
      // A slack line's strain has almost no restoring force (kSlackJacobianFraction): an update
      // that would take the stretch 1 + eps through zero (where sqrt(1 + eps) and the frame
      // rows lose their meaning) goes a fraction of the way to it instead.
      const double stretch = 1.0 + Yv[i + EPS];
      if (stretch > 0.0 && stretch + dY[i + EPS] < kStretchFloor * stretch)
        dY[i + EPS] = -(1.0 - kStretchFloor) * stretch;
    }
  }
  /// An update keeps at least this fraction of a node's stretch 1 + eps [-].
  static constexpr double kStretchFloor = 0.1;

  /// The residual alone is evaluated in double (for Newton iterations that reuse a Jacobian);
  /// with J, in AutoDiff scalars (AD16 for the end rows, AD32 for the intervals).
  void evaluate(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J) override {
    if (J)
      evaluateAs<AD16, AD32>(Yv, R, J);
    else
      evaluateAs<double, double>(Yv, R, nullptr);
  }

  template <class S16, class S32>
  void evaluateAs(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J) {
    const int n = im_.nodes();
    R.resize(size());
    // The line in two halves, nodes [0, m) and [m, n), as the Newton matrix's two-ended
    // elimination splits it (both on im_.fork when there is one: each thread then assembles
    // and clears the rows it eliminates, writesEveryBlockEntry).
    const int m = BandedMatrix::meetingNode(n);
    im_.wave_cache.setTime(t_);
    water_.resize(static_cast<std::size_t>(n));
    inHalves(im_.fork.get(), m, n, [&](int j0, int j1) {
      for (int j = j0; j < j1; ++j)
        water_[static_cast<std::size_t>(j)] = im_.waterAt(j, Yv[N * j + X], Yv[N * j + eq3d::Y], Yv[N * j + Z]);
    });
    inHalves(im_.fork.get(), m, n - 1, [&](int j0, int j1) {
      const int first = j0 == 0 ? 0 : end_rows_ + N * j0;
      const int last = j1 == n - 1 ? size() : end_rows_ + N * j1;
      if (J) J->setZeroRows(first, last - first);
      if (j0 == 0) endRows<S16>(*im_.lower, 0, 0, Yv, R, J);
      intervalRows<S32>(Yv, R, J, j0, j1);
      if (im_.parted >= j0 && im_.parted < j1) partedRows<S16>(Yv, R, J);
      if (j1 == n - 1) endRows<S16>(*im_.upper, n - 1, end_rows_ + N * (n - 1), Yv, R, J, im_.winch.rate);
    });
  }

  /// The generalized-alpha weights of the step: alpha_m, alpha_k, and the rate's
  /// Yd = c1 (Y - Yp) - c0 Ydp (eq. 26).
  AlphaWeights weights() const {
    const double g = im_.ga.gamma;
    return {im_.ga.alpha_m, im_.ga.alpha_k, 1.0 / (g * dt_), (1.0 - g) / g};
  }

  /// Every entry of a block-structured J is written or cleared (setZeroRows), half by half.
  bool writesEveryBlockEntry() const override { return true; }

  /// The rows of an end (end_conditions.hpp) at `node`, from row0.
  template <class S16>
  void endRows(const EndCondition3D& end, int node, int row0, const Eigen::VectorXd& Yv, Eigen::VectorXd& R,
               BandedMatrix* J, double payout = 0.0) const {
    const int col0 = N * node;
    S16 y[N], r[kMaxEndRows];
    for (int k = 0; k < N; ++k) y[k] = variable<S16>(Yv[col0 + k], N, k);
    DynamicEnd3D c;
    c.t = t_;
    c.input = &top_;
    c.yp = im_.Y.data() + col0;
    c.ydp = im_.Yd.data() + col0;
    c.water = &water_[static_cast<std::size_t>(node)];
    c.w = weights();
    c.payout = payout;
    if (payout != 0.0) c.below = im_.Y.data() + col0 - N;
    c.winch = &end == im_.upper.get() && im_.winch.used;
    end.dynamicResidual(c, y, r);
    scatter(r, end.dynamicRows(), row0, col0, N, R, J);
  }

  /// The rows of the interval the line parted in: its two new ends, the upper end of the lower
  /// part at node j and the lower end of the upper part at node j + 1 (end_conditions.hpp).
  template <class S16>
  void partedRows(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J) const {
    const int j = im_.parted, row = end_rows_ + N * j;
    endRows<S16>(*im_.part_top, j, row, Yv, R, J);
    endRows<S16>(*im_.part_lower, j + 1, row + im_.part_top->dynamicRows(), Yv, R, J);
  }

  /// The rows of intervals [j0, j1) (but a parted one's: partedRows): the residual alone
  /// (double) by residualRows, with the Jacobian by intervalRowsAs.
  template <class S32>
  void intervalRows(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J, int j0, int j1) const {
    if constexpr (std::is_same_v<S32, double>)
      residualRows(Yv, R, j0, j1);
    else
      intervalRowsAs<S32>(Yv, R, J, j0, j1);
  }

  /// The rows of intervals [j0, j1) (but a parted one's), each on its own.
  template <class S32>
  void intervalRowsAs(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J, int j0, int j1) const {
    const auto [am, ak, c1, c0] = weights();
    const Environment& env = im_.problem.environment;
    const Eigen::VectorXd &Yp = im_.Y, &Ydp = im_.Yd;
    for (int j = j0; j < j1; ++j) {
      if (j == im_.parted) continue;
      const MeshInterval& iv = im_.mesh.intervals[static_cast<std::size_t>(j)];
      const int row = end_rows_ + N * j;
      S32 y[2 * N], ydw[2 * N], yp[2 * N];
      for (int k = 0; k < 2 * N; ++k) {
        const int idx = N * j + k;
        y[k] = variable<S32>(Yv[idx], 2 * N, k);
        const S32 yd = c1 * (y[k] - Yp[idx]) - c0 * Ydp[idx];
        ydw[k] = (1.0 - am) * yd + am * Ydp[idx];  // weighted rate of eq. 30
        yp[k] = constant<S32>(Yp[idx]);
      }
      const Water& wa = water_[static_cast<std::size_t>(j)];
      const Water& wb = water_[static_cast<std::size_t>(j) + 1];
      const Water& wpa = im_.water[static_cast<std::size_t>(j)];
      const Water& wpb = im_.water[static_cast<std::size_t>(j) + 1];
      S32 r[N], in1[kInertiaRows], in0[kInertiaRows];
      int weighted;
      if (iv.h > 0.0) {
        const Material& m = im_.problem.materials[iv.material];
        intervalSpatial(env, m, iv.h, y, y + N, wa, wb, r);
        // Mass matrix at both levels averaged by alpha_k (docs/method.md: not eq. 31's alpha_m).
        intervalInertia(env, m, iv.h, y, y + N, ydw, ydw + N, wa, wb, in1);
        intervalInertia(env, m, iv.h, yp, yp + N, ydw, ydw + N, wpa, wpb, in0);
        weighted = kInertiaRows;
      } else {
        junctionForces(im_.problem, iv, im_.mat(j), im_.mat(j + 1), y, y + N, wa, r);
        junctionConstraints(im_.mat(j), im_.mat(j + 1), y, y + N, r);
        junctionInertia(im_.problem, iv, y, ydw, in1);
        junctionInertia(im_.problem, iv, yp, ydw, in0);
        weighted = 3;
      }
      for (int q = 0; q < weighted; ++q)
        r[q] = (1.0 - ak) * (in1[q] + r[q]) + ak * (in0[q] + im_.S[kInertiaRows * j + q]);
      scatter(r, N, row, N * j, 2 * N, R, J);
    }
  }

  /// What an interval's residual rows take from one of its nodes (intervalRows in double):
  /// the spatial terms, the weighted rate, the inertia rows at the new and the last level.
  struct NodeRows {
    NodeTerms<double> terms;
    double ydw[N], in1[kInertiaRows], in0[kInertiaRows];
  };

  /// Node k's rows for an interval of material m: the quantities intervalSpatial and
  /// intervalInertia compute there, in the same operations.
  void nodeRows(const Eigen::VectorXd& Yv, int k, const Material& m, NodeRows& out) const {
    const auto [am, ak, c1, c0] = weights();
    (void)ak;
    const Environment& env = im_.problem.environment;
    const double* y = Yv.data() + N * k;
    const double* yp = im_.Y.data() + N * k;
    const double* ydp = im_.Yd.data() + N * k;
    for (int q = 0; q < N; ++q) {
      const double yd = c1 * (y[q] - yp[q]) - c0 * ydp[q];
      out.ydw[q] = (1.0 - am) * yd + am * ydp[q];  // weighted rate of eq. 30
    }
    const std::size_t kk = static_cast<std::size_t>(k);
    nodeTerms(env, m, y, water_[kk], out.terms);
    inertia(env, m, y, out.ydw, out.terms.R, water_[kk], out.in1);
    double Rp[9];
    quat::matrix(yp + Q0, Rp);
    inertia(env, m, yp, out.ydw, Rp, im_.water[kk], out.in0);
  }

  /// intervalRows in double (the residual alone, for Newton iterations that keep a Jacobian):
  /// a node's terms once for the two intervals it ends where they share a material, the same
  /// values as the generic rows bit for bit; junctions and a parted interval as there.
  void residualRows(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, int j0, int j1) const {
    const double ak = weights().ak;
    NodeRows rows[2];
    NodeRows *a = &rows[0], *b = &rows[1];
    const Material* kept = nullptr;  // the material *a holds node j's rows for (null: none)
    for (int j = j0; j < j1; ++j) {
      const MeshInterval& iv = im_.mesh.intervals[static_cast<std::size_t>(j)];
      if (j == im_.parted || !(iv.h > 0.0)) {
        intervalRowsAs<double>(Yv, R, nullptr, j, j + 1);
        kept = nullptr;
        continue;
      }
      const Material& m = im_.problem.materials[iv.material];
      if (kept != &m) nodeRows(Yv, j, m, *a);
      nodeRows(Yv, j + 1, m, *b);
      double r[N], in1[kInertiaRows], in0[kInertiaRows];
      intervalSpatialOf(m, iv.h, Yv.data() + N * j, Yv.data() + N * (j + 1), a->terms, b->terms, r);
      intervalInertiaOf(iv.h, a->in1, b->in1, in1);
      intervalInertiaOf(iv.h, a->in0, b->in0, in0);
      for (int q = 0; q < kInertiaRows; ++q)
        r[q] = (1.0 - ak) * (in1[q] + r[q]) + ak * (in0[q] + im_.S[kInertiaRows * j + q]);
      const int row = end_rows_ + N * j;
      for (int q = 0; q < N; ++q) R[row + q] = r[q];
      std::swap(a, b);
      kept = &m;
    }
  }

  const std::vector<Water>& water() const { return water_; }

 private:
  const DynamicSolver3D::Impl& im_;
  double t_, dt_;
  TopState top_;
  int end_rows_;  ///< rows of the lower end, before the intervals'

  mutable std::vector<Water> water_;
};

// ------------------------------------------------------------------------------------------------

namespace {

/// A towed line starts from the steady tow at the tow point's initial velocity (section 7.1:
/// "steady tow, then the manoeuvre"): statics in the frame moving with it (start.top.tow_v),
/// then every node given that velocity V0, which is a steady state of the dynamic equations.
void steadyTowStart(const Problem& problem, Problem& start, double* V0) {
  const TopState s0 = makeTopMotion(problem.dynamics.top_motion, problem.top.x, problem.top.y, problem.top.z,
                                    nullptr)(0.0);
  constexpr double kVelocityMismatch = 1e-6;  // [m/s]
  const bool given = problem.top.tow_vx != 0.0 || problem.top.tow_vy != 0.0;
  if (given && std::hypot(problem.top.tow_vx - s0.vx, problem.top.tow_vy - s0.vy) > kVelocityMismatch)
    throw std::invalid_argument("top.tow_velocity = (" + std::to_string(problem.top.tow_vx) + ", " +
                                std::to_string(problem.top.tow_vy) + ") m/s: differs from the top motion's velocity at "
                                "t = 0, (" + std::to_string(s0.vx) + ", " + std::to_string(s0.vy) +
                                ") m/s; leave it out to start from the motion's");
  start.top.tow_vx = V0[0] = s0.vx;
  start.top.tow_vy = V0[1] = s0.vy;
}

/// The static solution the run starts from, on im.mesh (section 3: the adaptive mesh of eq. 22
/// when the options ask).
StaticState3D solveStart(DynamicSolver3D::Impl& im, const Problem& problem, const Problem& start) {
  StaticState3D st = solveStatic3DOnMesh(start, im.mesh, start.static_options);
  if (st.result.summary.converged && problem.dynamics.adaptive_mesh) {
    // Section 3: redistribute the nodes by eq. 22. The curvature fed to eq. 21 is the magnitude
    // of the bending curvature (Omega2, Omega3) with the sign of Omega3, which is the 2-D
    // Omega3 for a planar line.
    StaticResult shape = st.result;
    for (auto& ns : shape.nodes)
      ns.curvature = std::copysign(std::hypot(ns.curvature, ns.curvature_b), ns.curvature);
    im.mesh = buildAdaptiveMesh(start, im.mesh, shape, problem.dynamics.mesh_weight);
    st = solveStatic3DOnMesh(start, im.mesh, start.static_options);
  }
  if (!st.result.summary.converged)
    throw std::runtime_error("the 3-D static solution that starts the dynamic run did not converge: " +
                             st.result.summary.message);
  return st;
}

/// The top motion of the problem file, started at the static top.
void setTopMotion(DynamicSolver3D::Impl& im, const Problem& problem) {
  const NodeState& topNode = im.statics.nodes.back();
  const TopMotion& tm = problem.dynamics.top_motion;
  constexpr double kStartMismatch = 0.01;  // [m] a position table must start where statics put the top
  const std::string bad = topMotionStartError(tm, topNode.x, topNode.y, topNode.z, kStartMismatch);
  if (!bad.empty()) throw std::invalid_argument(bad);
  im.top = makeTopMotion(tm, topNode.x, topNode.y, topNode.z, &im.waves);
}

/// The start state from the statics Y: at rest, or every node moving at V0 (a tow or a drift).
void startState(DynamicSolver3D::Impl& im, const Eigen::VectorXd& Y, bool moving, bool drifter, const double* V0) {
  im.t = 0.0;
  im.Y = Y;
  if (moving) {
    for (int j = 0; j < im.nodes(); ++j) {
      double* y = im.Y.data() + N * j;
      double R[9];
      quat::matrix(y + Q0, R);
      quat::toLocal(R, V0, y + U1);
    }
  }
  im.Yd = Eigen::VectorXd::Zero(im.Y.size());
  if (drifter) {
    // The drifter's top kinematics integrate the position rate: start it at V_d (every node
    // moves so), else the first step loses (1 - gamma) dt V_d of the drift.
    for (int j = 0; j < im.nodes(); ++j)
      for (int i = 0; i < 3; ++i) im.Yd[N * j + X + i] = V0[i];
  }
}

/// Error scales chi_m of eq. 39, as in 2-D.
void setErrorScales(DynamicSolver3D::Impl& im, const Problem& problem) {
  double Tc = 1.0, stiffest = 0.0;
  for (const auto& ns : im.statics.nodes) Tc = std::max(Tc, std::abs(ns.tension));
  for (const auto& m : problem.materials) stiffest = std::max(stiffest, m.rawTensionSlope(0.0));
  im.chi[EPS] = Tc / stiffest;
  im.chi[S2] = im.chi[S3] = Tc;
  im.chi[U1] = im.chi[U2] = im.chi[U3] = 1.0;  // [m/s]
  im.chi[O1] = im.chi[O2] = im.chi[O3] = 1.0 / std::max(im.mesh.minSpacing(), 1e-3);
  im.chi[Q0] = im.chi[Q1] = im.chi[Q2] = im.chi[Q3] = 1.0;
  im.chi[X] = im.chi[eq3d::Y] = im.chi[Z] = 1.0;  // [m]
}

}  // namespace

DynamicSolver3D::DynamicSolver3D(const Problem& problem) : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  const std::string err = problem.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  im.problem = problem;
  im.opt = problem.dynamics;
  im.ga = problem.dynamics.scheme;
  im.mesh = buildMesh(problem);
  if (im.opt.fallback_after_cuts == DynamicOptions::kFallbackAfterCutsAuto) {
    // (DynamicOptions::fallback_after_cuts) 1 where the line can go slack and snap.
    bool slack_law = false;
    for (int j = 0; j < im.nodes(); ++j) slack_law = slack_law || !im.mat(j).compression;
    im.opt.fallback_after_cuts = slack_law ? 1 : 4;
  }
  // A towed line starts from its steady tow, a drifter from its steady drift: the statics find
  // the drift velocity V_d, and every node moves at it.
  const bool drifter = isDrifter(problem);
  const bool towed = problem.lower_end == Problem::LowerEnd::Free && !drifter;
  Problem start = problem;
  double V0[3] = {0.0, 0.0, 0.0};
  if (towed) steadyTowStart(problem, start, V0);
  const StaticState3D st = solveStart(im, problem, start);
  im.statics = st.result;
  im.lower = makeLowerEnd3D(im.problem, im.mat(0));
  im.upper = makeUpperEnd3D(im.problem, im.mat(im.nodes() - 1));
  if (drifter) {
    V0[0] = st.result.drift_vx;
    V0[1] = st.result.drift_vy;
  }
  if (problem.environment.waves.type != WaveSpec::Type::None)
    im.waves = WaveField(problem.environment.waves, problem.environment.depth, problem.environment.gravity);
  im.wave_cache = WaveVelocityCache(&im.waves, im.mesh.nodes.size(), true);
  im.current = CurrentProfile(problem.environment.current);
  if (im.opt.threads > 1) {  // the second thread: the upper half of every iteration
    im.fork = std::make_unique<ForkJoin>();
    im.newton_matrix.setParallel(im.fork.get());
  }
  setTopMotion(im, problem);
  im.events = problem.dynamics.events;
  im.event_done.assign(im.events.size(), 0);
  startState(im, st.Y, towed || drifter, drifter, V0);
  im.waterField(im.Y, 0.0, im.water);
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, 0.0);
  setErrorScales(im, problem);
  winchSetUp(im);
}

DynamicSolver3D::~DynamicSolver3D() = default;

void DynamicSolver3D::setTopInput(std::function<TopState(double)> source) { impl_->top = std::move(source); }
void DynamicSolver3D::setLowerEndInput(std::function<TopState(double)> source) {
  Impl& im = *impl_;
  if (im.problem.lower_end == Problem::LowerEnd::Free)
    throw std::invalid_argument("setLowerEndInput: the line's lower end is free; it has no anchor to move");
  std::unique_ptr<EndCondition3D>& held = im.lower_kept ? im.lower_kept : im.lower;  // a released anchor stays so
  im.lower_path = source;
  held = source ? makeMovingAnchor3D(im.problem, std::move(source)) : makeLowerEnd3D(im.problem, im.mat(0));
}
double DynamicSolver3D::time() const { return impl_->t; }
double DynamicSolver3D::lineLength() const { return impl_->mesh.nodes.back().s; }
bool DynamicSolver3D::hasWinch() const { return impl_->winch.able; }
double DynamicSolver3D::winchRate() const {
  const WinchState& w = impl_->winch;
  constexpr double kAfter = 1e-9;  // [s] the rate of the piece that starts now
  return w.active() ? w.program.rateAt(impl_->t + kAfter) : 0.0;
}
const StaticResult& DynamicSolver3D::initialStatic() const { return impl_->statics; }
DynamicSolver3D::Totals DynamicSolver3D::totals() const { return impl_->totals; }
int DynamicSolver3D::threads() const { return impl_->fork ? 2 : 1; }

std::vector<double> DynamicSolver3D::nodeArclengths() const {
  std::vector<double> s;
  for (const auto& n : impl_->mesh.nodes) s.push_back(n.s);
  return s;
}

StaticResult DynamicSolver3D::snapshot() const {
  StaticResult r = staticResult3DFromState(impl_->problem, impl_->mesh, impl_->Y);
  r.summary.converged = true;
  return r;
}

void rowsChanged(DynamicSolver3D::Impl& im) {
  im.newton_matrix.setZero();
  im.factored_dt = 0.0;
}

namespace {

void addReport(StepReport& total, const StepReport& rep) {
  total.ok = rep.ok;
  total.steps += rep.steps;
  total.cuts += rep.cuts;
  total.newton_iterations += rep.newton_iterations;
  total.fallback_steps += rep.fallback_steps;
  if (rep.smallest_dt > 0.0)
    total.smallest_dt = total.smallest_dt > 0.0 ? std::min(total.smallest_dt, rep.smallest_dt) : rep.smallest_dt;
  total.message = rep.message;
}


/// One attempted step of size dt from the accepted state; on success the state advances.
bool tryStep(DynamicSolver3D::Impl& im, double dt, StepReport& rep) {
  const double t_new = im.t + dt;
  if (!winchBeginStep(im, t_new, rep.message)) return false;
  DynamicStepSystem3D sys(im, t_new, dt, im.top(t_new));
  // Predictor: constant rate; with modified Newton (smooth problems) the rate's change over the
  // last step of the same size is extrapolated too, which starts the iteration closer.
  Eigen::VectorXd Yv = im.Y + dt * im.Yd;
  if (im.opt.jacobian_reuse && sameStepSize(im.last_dt, dt) && im.Yd_prev.size() == im.Yd.size())
    Yv += 0.5 * dt * (im.Yd - im.Yd_prev);
  // A predicted stretch 1 + eps below kStretchFloor of the last one (a slack stretch whose strain
  // rate carries no restoring force) starts from the last strain instead.
  for (int i = 0; i + N <= static_cast<int>(Yv.size()); i += N)
    if (1.0 + Yv[i + EPS] < DynamicStepSystem3D::kStretchFloor * (1.0 + im.Y[i + EPS])) Yv[i + EPS] = im.Y[i + EPS];
  // A kept factorization belongs to one step size (the matrix holds 1 / (gamma dt)).
  if (!sameStepSize(dt, im.factored_dt)) im.newton_matrix.setZero();
  NewtonOptions no = stepNewtonOptions(im.opt);
  // Back from a fallback step: a few iterations say whether the implicit step holds again.
  if (im.in_fallback) no.max_iterations = std::min(no.max_iterations, lumped::kRetryIterations);
  NewtonWork work;
  const SolverSummary s = solveNewton(sys, Yv, no, &im.newton_matrix, &work);
  im.factored_dt = dt;
  rep.newton_iterations += s.iterations;
  im.totals.newton_iterations += s.iterations;
  im.totals.jacobians += work.assemblies;
  if (!s.converged) {
    if (im.in_fallback) ++im.totals.fallback_retries;
    winchUndoStep(im);
    im.newton_matrix.setZero();  // factored at an iterate that did not converge
    std::ostringstream os;
    os << "t = " << t_new << " s (dt = " << dt << " s): " << s.message;
    rep.message = os.str();
    return false;
  }
  if (const std::string off = topOffItsPath(im, Yv, t_new); !off.empty()) {
    ++im.totals.top_off_path;
    im.newton_matrix.setZero();
    rep.message = "t = " + fmtNum(t_new) + " s (dt = " + fmtNum(dt) + " s): " + off;
    return false;
  }
  const double g = im.ga.gamma;
  im.Yd_prev = im.Yd;
  im.last_dt = dt;
  im.Yd = (Yv - im.Y) / (g * dt) - ((1.0 - g) / g) * im.Yd;  // eq. 26
  im.Y = Yv;
  im.t = t_new;
  im.water = sys.water();
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, im.t);
  winchRemesh(im);
  breakOnTension(im);
  im.in_fallback = false;
  ++rep.steps;
  ++im.totals.steps;
  rep.smallest_dt = rep.smallest_dt > 0.0 ? std::min(rep.smallest_dt, dt) : dt;
  return true;
}

}  // namespace

StepReport DynamicSolver3D::advanceTo(double t_end) {
  Impl& im = *impl_;
  // The fallback (dynamics3d_fallback.cpp) takes what is left of a base step that fails at
  // dynamics.fallback_after_cuts cuts; right after a fallback step a failed base step goes to it
  // at once, and while the line is still folded (stayInFallback) the base step goes to it
  // without an implicit try.
  struct Fallback {
    Impl* im;
    int levels(int max_levels) const {
      // A line the fallback cannot take (a buoy, body or force top; the winch running) keeps every
      // cut level, as without the fallback.
      if (!im->opt.fallback || !fallbackUnavailable(*im, im->t + im->opt.dt).empty()) return max_levels;
      if (stayInFallback(*im)) return -1;
      return im->in_fallback ? 0 : std::min(max_levels, im->opt.fallback_after_cuts);
    }
    bool operator()(double dt, StepReport& rep) const {
      if (!im->opt.fallback) return false;
      const bool skipped = stayInFallback(*im);
      if (!fallbackStep(*im, dt, rep)) return false;
      im->fallback_skipped_time = skipped ? im->fallback_skipped_time + dt : 0.0;
      breakOnTension(*im);
      return true;
    }
  };
  auto run = [&im](double t1) {
    return advanceWithCuts(
        im.t, im.opt.dt, im.opt.max_cut_levels, t1, [&im](double dt, StepReport& rep) { return tryStep(im, dt, rep); },
        [&im]() { ++im.totals.cuts; }, Fallback{&im});
  };
  // Timed events up to t_end: advance to each, then let it happen (a break on tension happens
  // inside tryStep, after the step in which its limit is first exceeded).
  const double eps = 1e-9 * im.opt.dt;
  StepReport total;
  for (int i = nextTimedEvent(im); i >= 0 && im.events[static_cast<std::size_t>(i)].t <= t_end + eps;
       i = nextTimedEvent(im)) {
    const double te = im.events[static_cast<std::size_t>(i)].t;
    if (te > im.t + eps) {
      addReport(total, run(te));
      if (!total.ok) return total;
    }
    applyEvent(im, static_cast<std::size_t>(i), "at t = " + fmtNum(te) + " s");
  }
  addReport(total, run(t_end));
  return total;
}

double DynamicSolver3D::jacobianFiniteDifferenceError(double dt) const {
  const Impl& im = *impl_;
  DynamicStepSystem3D sys(im, im.t + dt, dt, im.top(im.t + dt));
  const JacobianCheck c = checkJacobian(sys, im.Y + dt * im.Yd);
  return c.outside_band ? 1.0 : c.worst;
}

struct DynamicSolver3D::Saved {
  double t = 0.0;
  Eigen::VectorXd Y, Yd, Yd_prev, S;
  std::vector<Water> water;
  std::vector<double> lower_state, upper_state;  ///< of the ends (EndCondition3D::state)
  // Line events: which had happened (a step re-run from here undoes the later ones).
  std::vector<char> event_done;
  std::size_t log_size = 0;
  bool lower_released = false, upper_released = false;
  int parted = -1;
  double last_dt = 0.0;
  bool in_fallback = false;
  double fallback_skipped_time = 0.0;
  std::vector<double> fallback_ref;
  Totals totals;
  WinchSaved winch;  ///< the mesh a winch changes, its program and length
};

std::shared_ptr<const DynamicSolver3D::Saved> DynamicSolver3D::save() const {
  const Impl& im = *impl_;
  auto s = std::make_shared<Saved>();
  s->t = im.t;
  s->Y = im.Y;
  s->Yd = im.Yd;
  s->Yd_prev = im.Yd_prev;
  s->S = im.S;
  s->water = im.water;
  s->lower_state = im.lower->state();
  s->upper_state = im.upper->state();
  s->event_done = im.event_done;
  s->log_size = im.event_log.size();
  s->lower_released = im.lower_kept != nullptr;
  s->upper_released = im.upper_kept != nullptr;
  s->parted = im.parted;
  s->last_dt = im.last_dt;
  s->in_fallback = im.in_fallback;
  s->fallback_skipped_time = im.fallback_skipped_time;
  s->fallback_ref = im.fallback_ref;
  s->totals = im.totals;
  s->winch = winchSave(im);
  return s;
}

void DynamicSolver3D::restore(const Saved& s) {
  Impl& im = *impl_;
  im.t = s.t;
  im.Y = s.Y;
  im.Yd = s.Yd;
  im.Yd_prev = s.Yd_prev;
  im.S = s.S;
  im.water = s.water;
  if (s.lower_released != (im.lower_kept != nullptr) || s.upper_released != (im.upper_kept != nullptr) ||
      s.parted != im.parted)
    rowsChanged(im);
  if (!s.lower_released && im.lower_kept) im.lower = std::move(im.lower_kept);
  if (!s.upper_released && im.upper_kept) im.upper = std::move(im.upper_kept);
  im.parted = s.parted;
  im.event_done = s.event_done;
  im.event_log.resize(s.log_size);
  im.lower->setState(s.lower_state);
  im.upper->setState(s.upper_state);
  im.last_dt = s.last_dt;
  im.in_fallback = s.in_fallback;
  im.fallback_skipped_time = s.fallback_skipped_time;
  im.fallback_ref = s.fallback_ref;
  im.totals = s.totals;
  winchRestore(im, s.winch);
  // A kept factorization (modified Newton) stays: it is still a Jacobian of this step size.
}

DynamicSeries runDynamic3D(const Problem& problem, const std::function<void(double, double)>& progress) {
  return runDynamicWith<DynamicSolver3D>(problem, progress);
}

}  // namespace core
}  // namespace mooring_dynamics
