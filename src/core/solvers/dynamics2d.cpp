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

using AD16 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;
using AD8 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
const char* const kVarNames[N] = {"eps", "Sn", "u", "v", "phi", "Omega3", "x", "z"};

/// The top's input as the end conditions take it (y = 0 in 2-D).
TopState topState(const TopInput& in) {
  TopState s;
  s.force = in.force;
  s.x = in.x;
  s.z = in.z;
  s.vx = in.vx;
  s.vz = in.vz;
  s.fx = in.fx;
  s.fz = in.fz;
  return s;
}

}  // namespace

// --- One time step as a Newton system ----------------------------------------------------------
//
// Row layout: 5 anchor rows, 8 rows per interval, 3 top rows; 8 unknowns per node. Interval j
// touches nodes j and j + 1, so the half-bandwidths are kl = 12, ku = 10.

class DynamicStepSystem : public NewtonSystem {
 public:
  DynamicStepSystem(const DynamicSolver2D::Impl& im, double t_new, double dt, const TopInput& top)
      : im_(im), t_(t_new), dt_(dt), input_(topState(top)), end_rows_(im.lower->dynamicRows()) {}

  int size() const override { return N * im_.nodes(); }
  // Interval j's rows start at end_rows_ + N j and touch nodes j, j + 1 (kl = 12, ku = 10).
  int lowerBandwidth() const override { return end_rows_ + N - 1; }
  int upperBandwidth() const override { return 2 * N - 1 - end_rows_; }
  // Node-by-node elimination of the same matrix (every row couples node j and j + 1 only).
  int blockSize() const override { return N; }
  int leadingRows() const override { return end_rows_; }
  double scale(int i) const override { return im_.chi[i % N]; }
  std::string describe(int i) const override {
    const std::size_t j = static_cast<std::size_t>(i / N);
    std::ostringstream os;
    os << "node " << j << " (s = " << im_.mesh.nodes[j].s << " m) " << kVarNames[i % N];
    return os.str();
  }
  double stepLimit(const Eigen::VectorXd& dY) const override { return stepLimit(dY, 0, size()); }
  double stepLimit(const Eigen::VectorXd& dY, int first, int end) const override {
    constexpr double kMaxAngleStep = 0.5;  // [rad], as in statics
    double largest = 0.0;
    for (int i = first + PHI; i < end; i += N) largest = std::max(largest, std::abs(dY[i]));
    return largest > kMaxAngleStep ? kMaxAngleStep / largest : 1.0;
  }

  /// The Newton loop's vector work in the halves of the two-ended elimination (see evaluate).
  bool splitsUpdate() const override { return true; }

  /// As in statics: a node off the seabed that would pass below its rest penetration stops there
  /// (Newton sees no foundation under it and would otherwise cycle through the contact).
  void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const override {
    conditionStep(Y, dY, 0, size());
  }
  void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY, int first, int end) const override {
    const Environment& env = im_.problem.environment;
    for (int j = first / N; j < end / N; ++j) {
      const Eigen::Index iz = N * j + Z;
      const double w = std::max(im_.mat(j).wet_weight, 0.0);
      const double rest = env.seabedElevation(Y[iz - 1]) - 1.5 * w / env.seabed.stiffness;
      // Only a node out of contact is stopped; one already on the bottom may go deeper.
      const double zb = env.seabedElevation(Y[iz - 1]);
      if (Y[iz] >= zb && Y[iz] + dY[iz] < rest) dY[iz] = rest - Y[iz];
    }
  }

  void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override {
    const int n = im_.nodes();
    R.resize(size());
    endRows(*im_.lower, 0, 0, Y, R, J);  // the anchor (eq. 34)
    // The line in two halves, nodes [0, m) and [m, n), as the Newton matrix's two-ended
    // elimination splits it (both on im_.fork when there is one: each thread then assembles
    // the rows it eliminates).
    const int m = BandedMatrix::meetingNode(n);
    nodeValues(Y, m);
    intervalRows(Y, R, J, m);
    endRows(*im_.upper, end_rows_ + N * (n - 1), N * (n - 1), Y, R, J);  // the top (eq. 34)
  }

  /// alpha_m, alpha_k of the scheme and the rate of eq. 26, Yd = c1 (Y - Yp) - c0 Ydp.
  AlphaWeights weights() const {
    const GeneralizedAlpha& ga = im_.ga;
    const double g = ga.gamma;
    return {ga.alpha_m, ga.alpha_k, 1.0 / (g * dt_), (1.0 - g) / g};
  }

  /// Water at every node, weighted rates (eq. 30) and cos, sin of the inclination at iterate Y.
  /// Shared out as the threads go (sharedHalves), from the static shape's guess: every node's
  /// values are its own, whichever thread computes them.
  void nodeValues(const Eigen::VectorXd& Y, int m) {
    const int n = im_.nodes();
    const AlphaWeights w = weights();
    const double am = w.am, c1 = w.c1, c0 = w.c0;
    const Eigen::VectorXd& Yp = im_.Y;
    const Eigen::VectorXd& Ydp = im_.Yd;
    im_.wave_cache.setTime(t_);
    water_.resize(static_cast<std::size_t>(n));
    ydw_.resize(Y.size());
    c_.resize(static_cast<std::size_t>(n));
    s_.resize(static_cast<std::size_t>(n));
    sharedHalves(im_.fork.get(), m == 0 ? 0 : im_.water_split, n, [&](int j0, int j1, bool) {
      for (int j = j0; j < j1; ++j) water_[static_cast<std::size_t>(j)] = im_.waterAt(j, Y[N * j + X], Y[N * j + Z]);
      for (int j = j0; j < j1; ++j) {
        const std::size_t a = static_cast<std::size_t>(j);
        for (int k = N * j; k < N * (j + 1); ++k)
          ydw_[k] = (1.0 - am) * (c1 * (Y[k] - Yp[k]) - c0 * Ydp[k]) + am * Ydp[k];
        sinCos(Y[N * j + PHI], s_[a], c_[a]);
      }
    });
  }

  /// Every interval's rows (eq. 30 on eq. 11), shared out from interval_split (sharedHalves).
  void intervalRows(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J, int m) {
    const int n = im_.nodes();
    im_.node_terms.resize(static_cast<std::size_t>(n));
    terms_material_.assign(static_cast<std::size_t>(n), -1);  // none computed yet
    sharedHalves(im_.fork.get(), m == 0 ? 0 : im_.interval_split, n - 1,
                 [&](int j0, int j1, bool continued) { intervalPiece(Y, R, J, j0, j1, continued); });
  }

  /// The terms of node j0 of a piece of sharedHalves, when j0 > 0: also the piece below's (its last
  /// interval's upper node), so a piece computes them in a place of its own, unless it continues
  /// its thread's previous piece, which left them in im_.node_terms.
  struct PieceTerms {
    int own_node = -1;  ///< the node whose terms are the piece's own (-1: none)
    NodeTerms terms;
    long material = -1;  ///< the material they were computed with (-1: none)
  };

  /// Intervals [j0, j1), a piece of sharedHalves.
  void intervalPiece(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J, int j0, int j1, bool continued) {
    const AlphaWeights w = weights();
    const StepWeights wts{w.ak, (1.0 - w.am) * w.c1};
    PieceTerms own;
    own.own_node = j0 > 0 && !continued ? j0 : -1;
    double Jl[N][2 * N];
    for (int j = j0; j < j1; ++j) {
      const MeshInterval& iv = im_.mesh.intervals[static_cast<std::size_t>(j)];
      if (iv.h > 0.0)
        cableRows(j, iv, Y, R, J, wts, own, Jl);
      else
        junctionRowsInto(j, iv, Y, R, J, w);
    }
  }

  /// The terms of `node` (nodeStepTerms) for interval iv, computed once for the intervals of one
  /// material the node belongs to.
  const NodeTerms& termsOf(std::size_t node, const NodeView& now, const MeshInterval& iv, const StepWeights& wts,
                           bool jacobian, PieceTerms& own) {
    const bool is_own = node == static_cast<std::size_t>(own.own_node);
    long& material = is_own ? own.material : terms_material_[node];
    NodeTerms& t = is_own ? own.terms : im_.node_terms[node];
    if (material != static_cast<long>(iv.material)) {
      const NodeView prev{im_.Y.data() + N * node, im_.cos_phi[node], im_.sin_phi[node], &im_.water[node]};
      nodeStepTerms(im_.problem.environment, im_.problem.materials[iv.material], now, prev, ydw_.data() + N * node,
                    wts, jacobian, t);
      material = static_cast<long>(iv.material);
    }
    return t;
  }

  /// Interval j's rows with the hand-coded Jacobian (dynamic_interval.hpp), from the terms of its
  /// nodes; Jl: scratch rows when J has no block structure.
  void cableRows(int j, const MeshInterval& iv, const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J,
                 const StepWeights& wts, PieceTerms& own, double (&Jl)[N][2 * N]) {
    const int row = end_rows_ + N * j;
    const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
    const NodeView na{Y.data() + N * j, c_[a], s_[a], &water_[a]};
    const NodeView nb{Y.data() + N * (j + 1), c_[b], s_[b], &water_[b]};
    const NodeTerms& ta = termsOf(a, na, iv, wts, J != nullptr, own);
    const NodeTerms& tb = termsOf(b, nb, iv, wts, J != nullptr, own);
    // With the block structure the interval's 8 rows of 16 entries are contiguous in J.
    double(*Jrows)[2 * N] = J && J->blockRow(row) ? reinterpret_cast<double(*)[2 * N]>(J->blockRow(row)) : Jl;
    intervalStepRows(im_.problem.materials[iv.material], iv.h, na, nb, ta, tb, wts, im_.S.data() + N * j,
                     R.data() + row, J ? Jrows : nullptr);
    if (J && Jrows == Jl)
      for (int q = 0; q < N; ++q)
        for (int k = 0; k < 2 * N; ++k) J->at(row + q, N * j + k) = Jl[q][k];
  }

  /// Junction (pin) rows of interval j: few, left to automatic differentiation; in double when
  /// only the residual is asked for.
  void junctionRowsInto(int j, const MeshInterval& iv, const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J,
                        const AlphaWeights& w) const {
    const int row = end_rows_ + N * j;
    if (!J) {
      junctionRows(j, iv, Y, w.c1, w.c0, R.data() + row);
      return;
    }
    AD16 r[N];
    junctionRows(j, iv, Y, w.c1, w.c0, r);
    // With the block structure the 8 rows of 16 entries are written whole (a zero as +0, as
    // clearing the rows would leave it), else the non-zero entries after clearing.
    double* const rows = J->blockRow(row);
    if (!rows) J->setZeroRows(row, N);
    for (int q = 0; q < N; ++q) {
      R[row + q] = r[q].value();
      for (int k = 0; k < 2 * N; ++k) {
        const double d = r[q].derivatives().size() ? r[q].derivatives()[k] : 0.0;
        if (rows) rows[2 * N * q + k] = d != 0.0 ? d : 0.0;
        else if (d != 0.0) J->at(row + q, N * j + k) = d;
      }
    }
  }

  /// The rows of an end (end_conditions.hpp) at the node whose unknowns start at col0, from row0.
  void endRows(const EndCondition2D& end, int row0, int col0, const Eigen::VectorXd& Y, Eigen::VectorXd& R,
               BandedMatrix* J) const {
    const int rows = end.dynamicRows();
    AD8 y[N], r[kMaxEndRows];
    for (int k = 0; k < N; ++k) y[k] = AD8(Y[col0 + k], N, k);
    if (J) J->setZeroRows(row0, rows);
    end.dynamicResidual(input_, y, r);
    scatter(r, rows, row0, col0, N, R, J);
  }

  /// Rows r[0..7] of junction interval j at iterate Y, in scalar type S (AD16 for the
  /// Jacobian, double for the residual alone); c1, c0: the rate of eq. 26, Yd = c1 (Y - Yp) - c0 Ydp.
  template <class S>
  void junctionRows(int j, const MeshInterval& iv, const Eigen::VectorXd& Y, double c1, double c0, S* r) const {
    const Eigen::VectorXd& Yp = im_.Y;
    const Eigen::VectorXd& Ydp = im_.Yd;
    const double am = im_.ga.alpha_m, ak = im_.ga.alpha_k;
    S y[2 * N], ydw[2 * N], yp[2 * N];
    for (int k = 0; k < 2 * N; ++k) {
      if constexpr (std::is_same_v<S, double>) y[k] = Y[N * j + k];
      else y[k] = S(Y[N * j + k], 2 * N, k);
    }
    // The inertia of the bodies (junctionInertia) reads node a's u, v, phi at both levels and
    // their weighted rates only: the other entries of yp and ydw are left unset.
    for (const int k : {U, V, PHI}) {
      const int idx = N * j + k;
      if constexpr (std::is_same_v<S, double>) {
        yp[k] = Yp[idx];
      } else {
        yp[k] = S(Yp[idx]);
        yp[k].derivatives().setZero(2 * N);
      }
      const S yd = c1 * (y[k] - Yp[idx]) - c0 * Ydp[idx];
      ydw[k] = (1.0 - am) * yd + am * Ydp[idx];  // weighted rate of eq. 30
    }
    const Water& wa = water_[static_cast<std::size_t>(j)];
    // cos, sin of the angles of nodes a and b (now) and of node a (at the previous level) from
    // the nodes' tables, with the derivatives cos() and sin() give them (angleOf,
    // equations2d_dynamic.hpp; test_dynamic_interval checks the bits).
    const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
    const auto angle = [](const S& phi, double c, double s) -> Angle<S> {
      if constexpr (std::is_same_v<S, double>) {
        (void)phi;
        return {c, s};
      } else {
        return {S(c, phi.derivatives() * (-s)), S(s, phi.derivatives() * c)};
      }
    };
    const Angle<S> aa = angle(y[PHI], c_[a], s_[a]), ab = angle(y[N + PHI], c_[b], s_[b]);
    const Angle<S> ap = angle(yp[PHI], im_.cos_phi[a], im_.sin_phi[a]);
    S sp[N], in1[N], in0[N];
    junctionForces(im_.problem, iv, im_.mat(j), im_.mat(j + 1), y, y + N, aa, ab, wa, sp);
    junctionInertia(im_.problem, iv, y, aa, ydw, in1);
    junctionInertia(im_.problem, iv, yp, ap, ydw, in0);
    junctionConstraints(y, y + N, aa, ab, sp);
    constexpr int kJunctionWeighted = 2;  // the force balance; the constraints hold at the new level
    for (int q = 0; q < N; ++q) {
      if (q < kJunctionWeighted)
        // Eq. 30 with the mass matrix averaged between the levels (eq. 31) by alpha_k, not the
        // printed alpha_m: the weighted rate approximates dY/dt at the alpha_k level, and with
        // alpha_m weights a state-dependent M costs second order (measured slope 1.6 for
        // lambda_inf = -0.5 on a cable, 2.0 with alpha_k; test_dynamics2d).
        r[q] = (1.0 - ak) * in1[q] + ak * in0[q] + (1.0 - ak) * sp[q] + ak * im_.S[N * j + q];
      else
        r[q] = sp[q];  // constraints at the new time level
    }
  }

  /// Interval rows write all their entries (intervalStepRows), the others are zeroed first.
  bool writesEveryBlockEntry() const override { return true; }

  const std::vector<Water>& water() const { return water_; }

 private:
  const DynamicSolver2D::Impl& im_;
  double t_, dt_;
  TopState input_;   ///< the top's prescribed motion or force at t_
  int end_rows_;     ///< rows of the anchor, before the intervals'
  mutable std::vector<Water> water_;
  std::vector<double> c_, s_;     ///< cos, sin of phi at the current iterate
  Eigen::VectorXd ydw_;           ///< weighted rates (eq. 30) at the current iterate
  std::vector<long> terms_material_;  ///< the material each node's terms were computed with (-1: none)
};

DynamicSolver2D::~DynamicSolver2D() = default;

void DynamicSolver2D::setTopInput(std::function<TopInput(double)> source) { impl_->top = std::move(source); }

double DynamicSolver2D::time() const { return impl_->t; }
const StaticResult& DynamicSolver2D::initialStatic() const { return impl_->statics; }
DynamicSolver2D::Totals DynamicSolver2D::totals() const { return impl_->totals; }
int DynamicSolver2D::threads() const { return impl_->fork ? 2 : 1; }

std::vector<double> DynamicSolver2D::nodeArclengths() const {
  std::vector<double> s;
  for (const auto& n : impl_->mesh.nodes) s.push_back(n.s);
  return s;
}

StaticResult DynamicSolver2D::snapshot() const {
  const Impl& im = *impl_;
  StaticResult res;
  const int n = im.nodes();
  res.nodes.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double* y = im.Y.data() + N * j;
    NodeState& ns = res.nodes[static_cast<std::size_t>(j)];
    ns.s = im.mesh.nodes[static_cast<std::size_t>(j)].s;
    ns.x = y[X];
    ns.z = y[Z];
    ns.tension = im.mat(j).tension(y[EPS]);
    ns.shear = y[SN];
    ns.angle = y[PHI];
    ns.curvature = y[OMEGA];
    ns.strain = y[EPS];
    ns.segment = static_cast<int>(im.mesh.nodes[static_cast<std::size_t>(j)].segment);
  }
  internalForce(im.mat(n - 1), im.Y.data() + N * (n - 1), res.top_force_x, res.top_force_z);
  internalForce(im.mat(0), im.Y.data(), res.anchor_force_x, res.anchor_force_z);
  res.summary.converged = true;
  return res;
}

namespace {

/// One attempted step of size dt from the accepted state; on success the state advances.
bool tryStep(DynamicSolver2D::Impl& im, double dt, StepReport& rep) {
  const double t_new = im.t + dt;
  // The top's motion at t_new (on this thread: a user's source may not be thread-safe) while the
  // second thread, if any, takes the wave phases at t_new (WaveVelocityCache::setTime; the step's
  // first evaluation would otherwise compute them alone, with the second thread waiting).
  TopInput top;
  if (im.fork && !im.wave_cache.empty())
    runBoth(im.fork.get(), [&] { top = im.top(t_new); }, [&] { im.wave_cache.setTime(t_new); });
  else
    top = im.top(t_new);
  DynamicStepSystem sys(im, t_new, dt, top);
  // Predictor: constant rate; with modified Newton the rate's change over the last step of the
  // same size is extrapolated too (as in 3-D), which starts the kept Jacobian's linear
  // iteration closer (A.2 at 0.1 s: 22 543 -> 21 021 iterations). Plain Newton keeps the
  // constant rate: its first update is not set by the predictor (docs/validation.md).
  Eigen::VectorXd Y = im.Y + dt * im.Yd;
  if (im.opt.jacobian_reuse && sameStepSize(im.last_dt, dt) && im.Yd_prev.size() == im.Yd.size())
    Y += 0.5 * dt * (im.Yd - im.Yd_prev);
  // Back from a fallback step: a few iterations say whether the implicit step holds again.
  const NewtonOptions no =
      im.in_fallback ? lumped::retryNewtonOptions(stepNewtonOptions(im.opt)) : stepNewtonOptions(im.opt);
  // A kept factorization (modified Newton) belongs to one step size.
  if (!sameStepSize(dt, im.factored_dt)) im.newton_matrix.setZero();
  NewtonWork work;
  const SolverSummary s = solveNewton(sys, Y, no, &im.newton_matrix, &work);
  im.factored_dt = dt;
  rep.newton_iterations += s.iterations;
  im.totals.newton_iterations += s.iterations;
  im.totals.jacobians += work.assemblies;
  if (!s.converged) {
    lumped::countFailedTry(im, 0);
    im.newton_matrix.setZero();  // factored at an iterate that did not converge
    std::ostringstream os;
    os << "t = " << t_new << " s (dt = " << dt << " s): " << s.message;
    rep.message = os.str();
    return false;
  }
  if (const std::string off = topOffItsPath(im, Y, t_new); !off.empty()) {
    ++im.totals.top_off_path;
    im.newton_matrix.setZero();
    std::ostringstream os;
    os << "t = " << t_new << " s (dt = " << dt << " s): " << off;
    rep.message = os.str();
    return false;
  }
  // Accept: rates from eq. 26, water and spatial rows at the new level.
  const double g = im.ga.gamma;
  im.Yd_prev = im.Yd;
  im.last_dt = dt;
  im.Yd = (Y - im.Y) / (g * dt) - ((1.0 - g) / g) * im.Yd;
  im.Y = Y;
  im.t = t_new;
  im.water = sys.water();
  im.spatialRows(im.Y, im.water, im.S, im.cos_phi, im.sin_phi);
  im.in_fallback = false;
  im.skipped_cap = lumped::kMaxSkippedTime;
  ++rep.steps;
  ++im.totals.steps;
  rep.smallest_dt = rep.smallest_dt > 0.0 ? std::min(rep.smallest_dt, dt) : dt;
  return true;
}

}  // namespace

StepReport DynamicSolver2D::advanceTo(double t_end) {
  Impl& im = *impl_;
  // Base steps with the adaptive cutting of section 4.3 (dynamic_run.hpp). The fallback
  // (dynamics2d_fallback.cpp) takes what is left of a base step that fails at
  // dynamics.fallback_after_cuts cuts, as in 3-D: right after a fallback step a failed base step
  // goes to it at once, and while the line is still slack (stayInFallback) without an implicit try.
  struct Fallback {
    Impl* im;
    int levels(int max_levels) const {
      if (!im->opt.fallback || !fallbackUnavailable(*im).empty()) return max_levels;
      if (lumped::waitAfterFailedRetry(*im) || stayInFallback(*im)) return -1;
      return im->in_fallback ? 0 : std::min(max_levels, im->opt.fallback_after_cuts);
    }
    bool operator()(double dt, StepReport& rep) const {
      if (!im->opt.fallback) return false;
      const bool skipped = stayInFallback(*im);
      if (!fallbackStep(*im, dt, rep)) return false;
      im->fallback_skipped_time = skipped ? im->fallback_skipped_time + dt : 0.0;
      return true;
    }
  };
  return advanceWithCuts(
      im.t, im.opt.dt, im.opt.max_cut_levels, t_end, [&im](double dt, StepReport& rep) { return tryStep(im, dt, rep); },
      [&im]() { ++im.totals.cuts; }, Fallback{&im});
}

double DynamicSolver2D::jacobianFiniteDifferenceError(double dt) const {
  const Impl& im = *impl_;
  DynamicStepSystem sys(im, im.t + dt, dt, im.top(im.t + dt));
  const JacobianCheck c = checkJacobian(sys, im.Y + dt * im.Yd);
  return c.outside_band ? 1.0 : c.worst;
}

// ------------------------------------------------------------------------------------------------

DynamicSeries runDynamic(const Problem& problem, const std::function<void(double, double)>& progress) {
  return runDynamicWith<DynamicSolver2D>(problem, progress);
}

}  // namespace core
}  // namespace mooring_dynamics
