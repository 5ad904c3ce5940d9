#include "mooring_dynamics/core/numerics/newton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "mooring_dynamics/core/numerics/fork_join.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

/// The sum over unknowns [first, end) of (1/chi_m) |dY_jm| (eq. 39), and its largest term and
/// where (the first of them); inv_chi holds 1 / chi_m of every unknown.
struct UpdateSum {
  double sum = 0.0, largest = -1.0;
  int worst = 0;
  double dot = 0.0, norm2 = 0.0, prev2 = 0.0;  ///< against the previous update (scaled by 1/chi)
};
UpdateSum scaledUpdateSum(const Eigen::VectorXd& inv_chi, const Eigen::VectorXd& dY, int first, int end,
                          const Eigen::VectorXd* prev) {
  UpdateSum u;
  u.worst = first;
  for (int i = first; i < end; ++i) {
    const double term = std::abs(dY[i]) * inv_chi[i];
    u.sum += term;
    if (term > u.largest) {
      u.largest = term;
      u.worst = i;
    }
  }
  if (prev)
    for (int i = first; i < end; ++i) {
      const double a = dY[i] * inv_chi[i], b = (*prev)[i] * inv_chi[i];
      u.dot += a * b;
      u.norm2 += a * a;
      u.prev2 += b * b;
    }
  return u;
}

/// MD_NEWTON_TRACE set: every update (sigma, relaxation, applied factor, largest update and
/// whether the Jacobian was kept) and how each call ended, on stderr. A diagnosis aid: with
/// several lines on threads their lines interleave; trace one thread.
bool tracing() {
  static const bool on = std::getenv("MD_NEWTON_TRACE") != nullptr;
  return on;
}

bool allFinite(const Eigen::VectorXd& v, int first, int end) { return v.segment(first, end - first).allFinite(); }

/// The vector work of an iteration over the unknowns [0, split) and [split, n): each part on
/// the thread whose rows it is (the Newton matrix's fork, or one after the other without one);
/// without a split (split = 0) over [0, n) only. f(first, end, part) with part 0 or 1.
template <class F>
void inParts(ForkJoin* fork, int split, int n, const F& f) {
  if (split == 0) {
    f(0, n, 0);
    return;
  }
  runBoth(fork, [&] { f(0, split, 0); }, [&] { f(split, n, 1); });
}

/// Newton's method with relaxation on a NewtonSystem (section 6): assemble, factor, solve for
/// the update, measure it (eq. 39), relax (eqs. 40-41), update (eq. 38), check convergence. With
/// options.reuse_jacobian, modified Newton: a factorization is kept while it contracts fast
/// enough.
class NewtonIteration {
 public:
  NewtonIteration(NewtonSystem& system, Eigen::VectorXd& Y, const NewtonOptions& options, BandedMatrix* workspace,
                  NewtonWork* work)
      : system_(system), Y_(Y), o_(options), work_(work), n_(system.size()), J_(workspace ? *workspace : local_),
        mu_(options.mu0) {
    prepareMatrix();
    R_.resize(n_);
    dY_.resize(n_);
    inv_chi_.resize(n_);
    for (int i = 0; i < n_; ++i) inv_chi_[i] = 1.0 / system_.scale(i);
    // The vector work split as the elimination splits the nodes (eq. 39's sum in two parts then,
    // with one thread or two), so that each half stays with the thread that assembles it.
    const int nb = system_.blockSize();
    split_ = system_.splitsUpdate() && J_.blockRow(0) && nb > 0 ? nb * BandedMatrix::meetingNode(n_ / nb) : 0;
    fork_ = J_.parallel();
    // Modified Newton: start from a factorization kept in the workspace (setBlockStructure leaves
    // it when the structure is unchanged); otherwise, and whenever the kept one converges too
    // slowly, assemble afresh.
    fresh_ = !(o_.reuse_jacobian && J_.factorized());
    mu_before_ = mu_;
    dY_prev_.resize(o_.damp_two_cycles ? n_ : 0);
  }

  SolverSummary run() {
    while (k_ < o_.max_iterations) {
      const bool assembled = fresh_;
      assemble(assembled);
      if (!negateResidual()) {
        if (!assembled && last_kept_) {  // a kept Jacobian's update went bad: back, and assemble
          undoLastUpdate();
          fresh_ = true;
          continue;
        }
        return fail("residual is not finite at iteration " + std::to_string(k_));
      }
      if (fresh_ && !factor()) return summary_;
      UpdateSum sums[2];
      double limit[2] = {1.0, 1.0};
      if (!solveUpdate(sums, limit)) {
        if (!assembled) {  // a kept factorization gone bad: try a fresh one at this iterate
          fresh_ = true;
          continue;
        }
        return fail("Newton update is not finite at iteration " + std::to_string(k_));
      }
      // Error measure (eq. 39). (Without a split sums[1] is empty: sum 0, largest -1.)
      const double sigma = (sums[0].sum + sums[1].sum) / static_cast<double>(n_);
      worst_ = sums[1].largest > sums[0].largest ? sums[1].worst : sums[0].worst;
      if (o_.reuse_jacobian && !assembled && k_ > 0 && sigma > o_.reuse_rate * sigma_prev_) {
        // The kept Jacobian no longer contracts fast enough: assemble afresh and redo the update.
        // When it made the last update too and the iteration grew (a Jacobian kept from an
        // earlier call can be far off), that update is suspect: redo it from the iterate before.
        if (last_kept_ && sigma > sigma_prev_) undoLastUpdate();
        fresh_ = true;
        continue;
      }
      relax(sigma, assembled);
      const double applied = relaxationApplied(sums, limit);
      trace(sigma, applied, assembled);
      update(applied);
      if (converged(sigma, assembled, applied)) return finish();
    }
    return notConverged();
  }

 private:
  /// The Newton matrix of the system's size, bandwidths and block structure.
  void prepareMatrix() {
    if (J_.size() != n_ || J_.lower() != system_.lowerBandwidth() || J_.upper() != system_.upperBandwidth()) {
      ForkJoin* const fork = J_.parallel();  // (the workspace's threads stay with it)
      J_ = BandedMatrix(n_, system_.lowerBandwidth(), system_.upperBandwidth());
      J_.setParallel(fork);
    }
    J_.setBlockStructure(system_.blockSize(), system_.leadingRows());
  }

  /// The residual at the current iterate, with the Jacobian when `jacobian`.
  void assemble(bool jacobian) {
    if (jacobian) {
      if (J_.blockRow(0) && system_.writesEveryBlockEntry()) J_.beginAssembly();
      else J_.setZero();
      system_.evaluate(Y_, R_, &J_);
      ++counts_.assemblies;
    } else {
      system_.evaluate(Y_, R_, nullptr);
      ++counts_.residuals;
    }
  }

  /// dY = -R here already (the factorization does not need it); false when R is not finite.
  bool negateResidual() {
    bool finite[2] = {true, true};
    inParts(fork_, split_, n_, [&](int first, int end, int part) {
      finite[part] = allFinite(R_, first, end);
      dY_.segment(first, end - first) = -R_.segment(first, end - first);
    });
    return finite[0] && finite[1];
  }

  /// Factor the Newton matrix; false (the summary says which unknown) when it is singular.
  bool factor() {
    const int info = J_.factorize();
    if (info != 0) {
      fail("singular Newton matrix at iteration " + std::to_string(k_) + ", unknown " + system_.describe(info - 1));
      return false;
    }
    fresh_ = !o_.reuse_jacobian;  // plain Newton assembles at every iterate
    return true;
  }

  /// The Newton update dY = -J^{-1} R, conditioned by the system, its sum of eq. 39 and the
  /// system's step limit, by parts; false when it is not finite.
  bool solveUpdate(UpdateSum* sums, double* limit) {
    J_.solve(dY_);
    bool finite[2] = {true, true};
    inParts(fork_, split_, n_, [&](int first, int end, int part) {
      finite[part] = allFinite(dY_, first, end);
      if (!finite[part]) return;
      system_.conditionStep(Y_, dY_, first, end);  // (the whole vector when not split)
      sums[part] = scaledUpdateSum(inv_chi_, dY_, first, end, have_prev_ ? &dY_prev_ : nullptr);
      limit[part] = system_.stepLimit(dY_, first, end);
    });
    return finite[0] && finite[1];
  }

  /// Adaptive relaxation (eqs. 40-41) and the bookkeeping of the iteration before.
  void relax(double sigma, bool assembled) {
    if (o_.adaptive && k_ > 0) {
      if (sigma > sigma_prev_) mu_ /= o_.R1;
      else mu_ *= o_.R2;
      mu_ = std::clamp(mu_, o_.mu0 / 1000.0, o_.mu0);
    }
    sigma_before_ = sigma_prev_;
    mu_before_ = mu_;
    if (o_.reuse_jacobian) last_kept_ = !assembled;
    sigma_prev_ = sigma;
  }

  /// MD_NEWTON_TRACE (tracing()): one line per update.
  void trace(double sigma, double applied, bool assembled) const {
    if (tracing())
      std::fprintf(stderr, "newton %d sigma %.3e mu %.3e applied %.3e worst %s dY %.3e%s\n", k_, sigma, mu_, applied,
                   system_.describe(worst_).c_str(), dY_[worst_], assembled ? "" : " (kept Jacobian)");
  }

  /// The factor the update is applied with: mu within the step limits, halved on a two-cycle.
  double relaxationApplied(const UpdateSum* sums, const double* limit) const {
    double applied = std::min(mu_, std::min(limit[0], limit[1]));
    if (have_prev_) {
      // An update that undoes the one before (cosine of the scaled updates below
      // -kTwoCycleCosine, and at least kTwoCycleRatio of its length: a shrinking alternation
      // is convergence) is a two-cycle across a kink, a touchdown node in and out of contact:
      // half of it lands between the two iterates. (Eq. 40 sees no growth there: sigma stays.)
      constexpr double kTwoCycleCosine = 0.9, kTwoCycleRatio = 0.5;
      const double dot = sums[0].dot + sums[1].dot;
      const double now2 = sums[0].norm2 + sums[1].norm2, before2 = sums[0].prev2 + sums[1].prev2;
      if (dot < -kTwoCycleCosine * std::sqrt(now2 * before2) && now2 > kTwoCycleRatio * kTwoCycleRatio * before2)
        applied *= 0.5;
    }
    return applied;
  }

  /// Y += applied dY (eq. 38), keeping the iterate before for modified Newton.
  void update(double applied) {
    if (o_.reuse_jacobian) Y_before_.resize(n_);
    inParts(fork_, split_, n_, [&](int first, int end, int) {
      if (o_.reuse_jacobian) Y_before_.segment(first, end - first) = Y_.segment(first, end - first);
      Y_.segment(first, end - first) += applied * dY_.segment(first, end - first);  // eq. 38
    });
    if (o_.damp_two_cycles) {
      dY_prev_.swap(dY_);  // (dY is rewritten from -R in the next iteration)
      have_prev_ = true;
    }
  }

  /// After update k, made with a fresh Jacobian (`assembled`) or a kept one and applied with the
  /// factor `applied`: sigma below the tolerance, or the contraction's estimate of the remaining
  /// error below it.
  bool converged(double sigma, bool assembled, double applied) {
    ++k_;
    summary_.iterations = k_;
    summary_.error = sigma;
    summary_.relaxation = mu_;
    const double theta = k_ > 1 ? sigma / sigma_before_ : 1.0;  // sigma_before: the update before
    // A fresh Jacobian contracts quadratically: the estimate bounds the error left. A kept one
    // contracts linearly: the estimate is the sum of the updates to come, where the update was
    // applied in full (a relaxed one leaves 1 - applied of itself undone), held to a margin
    // below the tolerance (estimate_kept_margin).
    const double margin = assembled ? 1.0 : o_.estimate_kept_margin;
    const bool full_or_fresh = assembled || applied == 1.0;
    const bool estimated = o_.estimate_convergence && full_or_fresh && k_ > 1 && theta < o_.estimate_max_theta &&
                           theta / (1.0 - theta) * sigma < margin * o_.tolerance;
    return sigma < o_.tolerance || estimated;
  }

  /// Back to the iterate before the last update (made with a kept Jacobian).
  void undoLastUpdate() {
    Y_ = Y_before_;
    sigma_prev_ = sigma_before_;
    mu_ = mu_before_;
    --k_;
    last_kept_ = false;
    have_prev_ = false;
  }

  SolverSummary finish() {
    summary_.converged = true;
    traceEnd();
    std::ostringstream os;
    os << "converged in " << summary_.iterations << " iterations (sigma = " << summary_.error << ")";
    summary_.message = os.str();
    if (work_) *work_ = counts_;
    return summary_;
  }

  SolverSummary fail(const std::string& message) {
    summary_.iterations = k_;
    traceEnd();
    summary_.message = message;
    if (work_) *work_ = counts_;
    return summary_;
  }

  SolverSummary notConverged() {
    traceEnd();
    if (work_) *work_ = counts_;
    std::ostringstream os;
    os << "did not converge in " << o_.max_iterations << " iterations: sigma = " << summary_.error
       << " (tolerance " << o_.tolerance << "), relaxation " << mu_ << "; largest update at "
       << system_.describe(worst_);
    summary_.message = os.str();
    return summary_;
  }

  /// MD_NEWTON_TRACE (tracing()): how the call ended, after its iterations' lines.
  void traceEnd() const {
    if (tracing())
      std::fprintf(stderr, "newton end %s iterations %d of %d jacobians %d\n",
                   summary_.converged ? "converged" : "failed", k_, o_.max_iterations, counts_.assemblies);
  }

  NewtonSystem& system_;
  Eigen::VectorXd& Y_;
  const NewtonOptions& o_;
  NewtonWork* work_;
  const int n_;
  BandedMatrix local_;  ///< the Newton matrix when the caller gives no workspace
  BandedMatrix& J_;
  Eigen::VectorXd R_, dY_, inv_chi_;
  int split_ = 0;  ///< first unknown of the second part of the vector work (0: one part)
  ForkJoin* fork_ = nullptr;
  SolverSummary summary_;
  NewtonWork counts_;
  double mu_;
  double sigma_prev_ = 0.0;
  int worst_ = 0;
  bool fresh_ = true;  ///< assemble and factor at the next iterate
  // Modified Newton bookkeeping: the iterate before the last update and the state of the
  // iteration there, to go back to when that update was made with a kept Jacobian that turns
  // out not to contract (the update itself may then have gone the wrong way).
  Eigen::VectorXd Y_before_;
  double sigma_before_ = 0.0, mu_before_ = 0.0;
  bool last_kept_ = false;
  int k_ = 0;  ///< accepted updates
  // Two-cycle damping: the update before (its direction), when there is one to compare with.
  Eigen::VectorXd dY_prev_;
  bool have_prev_ = false;
};

}  // namespace

SolverSummary solveNewton(NewtonSystem& system, Eigen::VectorXd& Y, const NewtonOptions& options,
                          BandedMatrix* workspace, NewtonWork* work) {
  return NewtonIteration(system, Y, options, workspace, work).run();
}

JacobianCheck checkJacobian(NewtonSystem& system, const Eigen::VectorXd& Y) {
  JacobianCheck out;
  const int n = system.size();
  BandedMatrix J(n, system.lowerBandwidth(), system.upperBandwidth());
  J.setBlockStructure(system.blockSize(), system.leadingRows());
  if (J.blockRow(0) && system.writesEveryBlockEntry()) {
    // As solveNewton leaves it (stale), but with NaN: an entry evaluate() fails to write shows.
    J.beginAssembly();
    const int w = 2 * system.blockSize();
    for (int i = 0; i < n; ++i) std::fill(J.blockRow(i), J.blockRow(i) + w, std::nan(""));
  }
  Eigen::VectorXd R(n), Rp(n), Rm(n);
  system.evaluate(Y, R, &J);
  for (int c = 0; c < n; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(Y[c]));
    Eigen::VectorXd Yp = Y, Ym = Y;
    Yp[c] += h;
    Ym[c] -= h;
    system.evaluate(Yp, Rp, nullptr);
    system.evaluate(Ym, Rm, nullptr);
    for (int r = 0; r < n; ++r) {
      const double fd = (Rp[r] - Rm[r]) / (2.0 * h);
      if (!J.inBand(r, c)) {
        if (fd != 0.0) out.outside_band = true;
        continue;
      }
      const double ex = J.get(r, c);
      const double e = std::isfinite(ex) ? std::abs(fd - ex) / std::max({1.0, std::abs(fd), std::abs(ex)})
                                         : std::numeric_limits<double>::infinity();
      if (e > out.worst) {
        out.worst = e;
        out.row = r;
        out.column = c;
        out.exact = ex;
        out.finite_difference = fd;
      }
    }
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
