// Newton relaxation with adaptive relaxation factor (paper section 6, eqs. 38-41).
// Shared by the static and dynamic solvers: each supplies a NewtonSystem.
#pragma once

#include <string>

#include <Eigen/Core>

#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// A square nonlinear system R(Y) = 0 with a banded Jacobian.
class NewtonSystem {
 public:
  virtual ~NewtonSystem() = default;
  virtual int size() const = 0;
  virtual int lowerBandwidth() const = 0;
  virtual int upperBandwidth() const = 0;
  /// Optional block structure of the Jacobian (BandedMatrix::setBlockStructure): unknowns per
  /// node and rows on the first node only. Default (0, 0): a plain band.
  virtual int blockSize() const { return 0; }
  virtual int leadingRows() const { return 0; }
  /// Residual R(Y); when J is non-null also the Jacobian dR/dY (J is zeroed by the caller,
  /// unless writesEveryBlockEntry()).
  virtual void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) = 0;
  /// True when evaluate() writes every entry of a block-structured J, zeroing those it leaves
  /// (BandedMatrix::setZeroRows): the caller then skips clearing the whole matrix first.
  virtual bool writesEveryBlockEntry() const { return false; }
  /// chi_m of eq. 39 for unknown i: the magnitude of a physically negligible change.
  virtual double scale(int i) const = 0;
  /// Human-readable name of unknown i, e.g. "node 12 (s = 5.50 m) phi".
  virtual std::string describe(int i) const = 0;
  /// Largest fraction of the update dY that may be applied in one iteration, in (0, 1]
  /// (e.g. to keep angles from turning by more than a fraction of a radian). Default 1.
  virtual double stepLimit(const Eigen::VectorXd& dY) const {
    (void)dY;
    return 1.0;
  }
  /// Chance to adjust the update dY at iterate Y before it is applied (e.g. to stop nodes at a
  /// unilateral contact instead of letting them fly through it). Default: unchanged.
  virtual void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const {
    (void)Y;
    (void)dY;
  }
  /// A system whose blocks are nodes can have the vector work of an iteration split at the
  /// Newton matrix's meeting node (BandedMatrix::meetingNode; on its second thread when it has
  /// one): it then returns true and gives stepLimit and conditionStep on a range of whole nodes,
  /// unknowns [first, end), with the whole-vector versions' values. solveNewton calls the range
  /// versions, with [0, size()) when not split; by default they call the whole-vector ones.
  virtual bool splitsUpdate() const { return false; }
  virtual double stepLimit(const Eigen::VectorXd& dY, int first, int end) const {
    (void)first;
    (void)end;
    return stepLimit(dY);
  }
  virtual void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY, int first, int end) const {
    (void)first;
    (void)end;
    conditionStep(Y, dY);
  }
};

struct NewtonOptions {
  double tolerance = 1.0e-9;  ///< stop when sigma (eq. 39) < tolerance
  int max_iterations = 500;
  double mu0 = 1.0;           ///< baseline relaxation factor
  bool adaptive = true;       ///< eqs. 40-41
  double R1 = 1.1;
  double R2 = 1.02;
  /// Modified Newton: keep the factored Jacobian of an earlier iteration, or of the workspace's
  /// last call, and evaluate only the residual, as long as each update shrinks sigma by at
  /// least `reuse_rate`; a slower iteration assembles and factors a fresh Jacobian at the
  /// current iterate and redoes the update. When the iteration even grew and the last update
  /// was made with the kept Jacobian too (one kept from an earlier call can be far off), that
  /// update is undone first; undone updates do not count as iterations. Off by default (plain Newton). The rate trades
  /// assemblies for iterations: on the paper's towed array (A.1) 0.5 took 3737 iterations with
  /// 17 Jacobians (3.9 s), 0.15 2936 with 36 (3.2 s), 0.03 2494 with 136 (3.7 s).
  bool reuse_jacobian = false;
  double reuse_rate = 0.15;
  /// Stop also when the error left after the update, estimated from the contraction
  /// theta = sigma_k / sigma_{k-1} of the last two updates as theta / (1 - theta) sigma_k
  /// (the usual estimate for Newton's method in implicit integrators, Hairer & Wanner IV.8),
  /// is below the tolerance and theta < estimate_max_theta: the iterate is then already as
  /// accurate as the next update would make it, and the iteration that would only confirm it is
  /// saved. With a fresh Jacobian Newton's quadratic contraction makes the estimate an upper
  /// bound; with a kept one (modified Newton) the contraction is linear and the estimate is the
  /// geometric sum of the updates to come, as Hairer & Wanner derive it for their simplified
  /// Newton iteration, taken where the update was applied in full (not relaxed).
  /// Off by default (eq. 39 on the last update only).
  bool estimate_convergence = false;
  double estimate_max_theta = 0.1;
  /// With a kept Jacobian the estimate must be below this fraction of the tolerance. A kept
  /// Jacobian's updates stopped at sigma < tolerance leave about theta (0.02-0.1) of the last
  /// one, far below the tolerance, and the series agreed with plain Newton's to 0.006 N of 9 kN
  /// (A.2, 30 s); stopped on the estimate at the tolerance itself they moved by up to 0.17 N there
  /// and by 3 N over A.2's 600 s. At 0.1: 0.2 N over the 600 s (rms 0.06 N, against some 200 N
  /// between base steps of 0.1 and 0.05 s), and 22 % fewer iterations (21 021 to 16 458).
  /// 0: a kept Jacobian stops on eq. 39 alone.
  double estimate_kept_margin = 0.1;
  /// Halve an update that reverses the one before (cosine of the two, scaled by 1/chi, below
  /// -0.9): Newton cycling between two iterates across a kink, such as a touchdown node in and
  /// out of contact with the seabed. Eq. 40 does not see such a cycle (sigma stays the same)
  /// and lets it run until rounding makes sigma grow; half the update lands between the two.
  /// Off by default (dynamics.damp_two_cycles turns it on for the time steps).
  bool damp_two_cycles = false;
};

/// What solveNewton did with the Jacobian (modified Newton bookkeeping).
struct NewtonWork {
  int assemblies = 0;  ///< Jacobians assembled and factored
  int residuals = 0;   ///< residual-only evaluations (with a kept factorization)
};

/// Assembled Jacobian of `system` at Y against central finite differences of its residual
/// (relative step 1e-6): the largest relative difference max|exact - fd| / max(1, |exact|, |fd|)
/// over all entries, where it occurs, and whether any coupling falls outside the band.
struct JacobianCheck {
  double worst = 0.0;
  int row = -1, column = -1;
  double exact = 0.0, finite_difference = 0.0;
  bool outside_band = false;  ///< a nonzero finite difference outside the declared band
};
JacobianCheck checkJacobian(NewtonSystem& system, const Eigen::VectorXd& Y);

/// Iterate Y^{k+1} = Y^k + mu dY^k (eq. 38) from the initial guess in Y until sigma^k (eq. 39)
/// falls below the tolerance. Y holds the last iterate on return, converged or not.
/// `workspace`, when given, is the Newton matrix reused from call to call (resized when its
/// dimensions do not match the system), so that a time stepper allocates it once. With
/// options.reuse_jacobian a factorization left in it by the previous call is used first: the
/// caller calls workspace->setZero() when the system changed so that it no longer applies
/// (e.g. another time step size). `work`, when given, receives the counts.
SolverSummary solveNewton(NewtonSystem& system, Eigen::VectorXd& Y, const NewtonOptions& options,
                          BandedMatrix* workspace = nullptr, NewtonWork* work = nullptr);

}  // namespace core
}  // namespace mooring_dynamics
