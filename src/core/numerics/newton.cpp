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

}  // namespace

SolverSummary solveNewton(NewtonSystem& system, Eigen::VectorXd& Y, const NewtonOptions& options,
                          BandedMatrix* workspace, NewtonWork* work) {
  SolverSummary summary;
  const int n = system.size();
  BandedMatrix local;
  BandedMatrix& J = workspace ? *workspace : local;
  if (J.size() != n || J.lower() != system.lowerBandwidth() || J.upper() != system.upperBandwidth()) {
    ForkJoin* const fork = J.parallel();  // (the workspace's threads stay with it)
    J = BandedMatrix(n, system.lowerBandwidth(), system.upperBandwidth());
    J.setParallel(fork);
  }
  J.setBlockStructure(system.blockSize(), system.leadingRows());
  Eigen::VectorXd R(n), dY(n), inv_chi(n);
  for (int i = 0; i < n; ++i) inv_chi[i] = 1.0 / system.scale(i);
  // The vector work split as the elimination splits the nodes (eq. 39's sum in two parts then,
  // with one thread or two), so that each half stays with the thread that assembles it.
  const int nb = system.blockSize();
  const int split = system.splitsUpdate() && J.blockRow(0) && nb > 0 ? nb * BandedMatrix::meetingNode(n / nb) : 0;
  ForkJoin* const fork = J.parallel();
  bool finite[2] = {true, true};
  double mu = options.mu0;
  double sigma_prev = 0.0;
  int worst = 0;
  NewtonWork counts;
  // Modified Newton: start from a factorization kept in the workspace (setBlockStructure leaves
  // it when the structure is unchanged); otherwise, and whenever the kept one converges too
  // slowly, assemble afresh.
  bool fresh = !(options.reuse_jacobian && J.factorized());

  // Modified Newton bookkeeping: the iterate before the last update and the state of the
  // iteration there, to go back to when that update was made with a kept Jacobian that turns
  // out not to contract (the update itself may then have gone the wrong way).
  Eigen::VectorXd Y_before;
  double sigma_before = 0.0, mu_before = mu;
  bool last_kept = false;
  int k = 0;  // accepted updates
  // Two-cycle damping: the update before (its direction), when there is one to compare with.
  Eigen::VectorXd dY_prev(options.damp_two_cycles ? n : 0);
  bool have_prev = false;
  auto undoLastUpdate = [&]() {
    Y = Y_before;
    sigma_prev = sigma_before;
    mu = mu_before;
    --k;
    last_kept = false;
    have_prev = false;
  };
  while (k < options.max_iterations) {
    const bool assembled = fresh;
    if (fresh) {
      // Assemble residual and Jacobian at the current iterate.
      if (J.blockRow(0) && system.writesEveryBlockEntry()) J.beginAssembly();
      else J.setZero();
      system.evaluate(Y, R, &J);
      ++counts.assemblies;
    } else {
      system.evaluate(Y, R, nullptr);
      ++counts.residuals;
    }
    // dY = -R here already (the factorization does not need it), with the finiteness check.
    inParts(fork, split, n, [&](int first, int end, int part) {
      finite[part] = allFinite(R, first, end);
      dY.segment(first, end - first) = -R.segment(first, end - first);
    });
    if (!(finite[0] && finite[1])) {
      if (!assembled && last_kept) {  // a kept Jacobian's update went bad: back, and assemble
        undoLastUpdate();
        fresh = true;
        continue;
      }
      summary.iterations = k;
      summary.message = "residual is not finite at iteration " + std::to_string(k);
      if (work) *work = counts;
      return summary;
    }
    if (fresh) {
      // Factor and solve for the Newton update dY = -J^{-1} R.
      const int info = J.factorize();
      if (info != 0) {
        summary.iterations = k;
        summary.message = "singular Newton matrix at iteration " + std::to_string(k) + ", unknown " +
                          system.describe(info - 1);
        if (work) *work = counts;
        return summary;
      }
      fresh = !options.reuse_jacobian;  // plain Newton assembles at every iterate
    }
    J.solve(dY);
    // Finiteness, the system's conditioning of the update, eq. 39's sum and the step limit.
    UpdateSum sums[2];
    double limit[2] = {1.0, 1.0};
    inParts(fork, split, n, [&](int first, int end, int part) {
      finite[part] = allFinite(dY, first, end);
      if (!finite[part]) return;
      system.conditionStep(Y, dY, first, end);  // (the whole vector when not split)
      sums[part] = scaledUpdateSum(inv_chi, dY, first, end, have_prev ? &dY_prev : nullptr);
      limit[part] = system.stepLimit(dY, first, end);
    });
    if (!(finite[0] && finite[1])) {
      if (!assembled) {  // a kept factorization gone bad: try a fresh one at this iterate
        fresh = true;
        continue;
      }
      summary.iterations = k;
      summary.message = "Newton update is not finite at iteration " + std::to_string(k);
      if (work) *work = counts;
      return summary;
    }
    // Error measure and adaptive relaxation (eqs. 39-41).
    // (Without a split sums[1] is empty: sum 0, largest -1.)
    const double sigma = (sums[0].sum + sums[1].sum) / static_cast<double>(n);
    worst = sums[1].largest > sums[0].largest ? sums[1].worst : sums[0].worst;
    if (options.reuse_jacobian && !assembled && k > 0 && sigma > options.reuse_rate * sigma_prev) {
      // The kept Jacobian no longer contracts fast enough: assemble afresh and redo the update.
      // When it made the last update too and the iteration grew (a Jacobian kept from an
      // earlier call can be far off), that update is suspect: redo it from the iterate before.
      if (last_kept && sigma > sigma_prev) undoLastUpdate();
      fresh = true;
      continue;
    }
    if (options.adaptive && k > 0) {
      if (sigma > sigma_prev) mu /= options.R1;
      else mu *= options.R2;
      mu = std::clamp(mu, options.mu0 / 1000.0, options.mu0);
    }
    sigma_before = sigma_prev;
    mu_before = mu;
    if (options.reuse_jacobian) last_kept = !assembled;
    sigma_prev = sigma;
    if (std::getenv("MD_NEWTON_TRACE"))
      std::fprintf(stderr, "newton %d sigma %.3e mu %.3e worst %s dY %.3e%s\n", k, sigma, mu,
                   system.describe(worst).c_str(), dY[worst], assembled ? "" : " (kept Jacobian)");
    double applied = std::min(mu, std::min(limit[0], limit[1]));
    if (have_prev) {
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

    if (options.reuse_jacobian) Y_before.resize(n);
    inParts(fork, split, n, [&](int first, int end, int) {
      if (options.reuse_jacobian) Y_before.segment(first, end - first) = Y.segment(first, end - first);
      Y.segment(first, end - first) += applied * dY.segment(first, end - first);  // eq. 38
    });
    if (options.damp_two_cycles) {
      dY_prev.swap(dY);  // (dY is rewritten from -R in the next iteration)
      have_prev = true;
    }
    ++k;
    summary.iterations = k;
    summary.error = sigma;
    summary.relaxation = mu;
    const double theta = k > 1 ? sigma / sigma_before : 1.0;  // sigma_before: the update before
    // (Updates with a fresh Jacobian only: Newton's quadratic contraction makes the estimate
    // an upper bound, the linear one of a kept Jacobian does not.)
    const bool estimated = options.estimate_convergence && assembled && k > 1 && theta < options.estimate_max_theta &&
                           theta / (1.0 - theta) * sigma < options.tolerance;
    if (sigma < options.tolerance || estimated) {
      summary.converged = true;
      std::ostringstream os;
      os << "converged in " << summary.iterations << " iterations (sigma = " << sigma << ")";
      summary.message = os.str();
      if (work) *work = counts;
      return summary;
    }
  }
  if (work) *work = counts;
  std::ostringstream os;
  os << "did not converge in " << options.max_iterations << " iterations: sigma = " << summary.error
     << " (tolerance " << options.tolerance << "), relaxation " << mu << "; largest update at "
     << system.describe(worst);
  summary.message = os.str();
  return summary;
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
