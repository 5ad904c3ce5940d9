// The two ends of a line as small types behind one interface (issue 23): the rows an end adds to
// the Newton system at its node (paper eqs. 33-34, sections 5.1-5.2) in statics and dynamics,
// and the state an end carries from one time level to the next. The solvers hold "the lower end"
// and "the upper end" and call them without knowing which kind they hold; a new kind of end is
// one new class here and one case in its factory (docs/architecture.md, "A new end condition").
//
// An end only computes residual rows on its own node's unknowns, in double or in automatic-
// differentiation scalars; the solver copies them into its residual vector and, from the AD
// derivatives, into the end's block of the Jacobian (this layer knows no matrix). The rows are the
// arithmetic the solvers had inline, operation for operation, so that results stay bit-identical.
//
// Row counts, node unknowns and the row order at each end:
//   2-D statics (eq2d, 6 unknowns):   anchor 3 rows, top 3 rows (moment free + 2 conditions)
//   2-D dynamics (eq2dyn, 8):         anchor 5 rows, top 3 rows
//   3-D statics (eq3d, 16):           lower end 10 rows, top 6 rows
//   3-D dynamics (eq3d, 16):          anchored lower end 10 rows, top 6; a free lower end 7 rows
//                                     and its top (tow point or drifting buoy) 9 rows; released
//                                     ends the rows of the end they replace
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "mooring_dynamics/core/equations/equations2d.hpp"
#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"

namespace mooring_dynamics {
namespace core {

// Position feedback of a driven top (docs/method.md, "Top boundary"): the velocity of eq. 34 with
// the position error fed back over this many BASE steps (a cut step must not raise the gain, or
// an offset becomes a huge velocity). The fallback step pulls an offset top back at the same rate.
inline constexpr double kPositionFeedbackSteps = 5.0;

/// Gain of the position feedback [1/s]: 1 / (kPositionFeedbackSteps dt) when the problem asks for
/// it (dynamics.top_motion.prescribe: position), else 0.
inline double feedbackGain(const Problem& p) {
  return p.dynamics.top_motion.prescribe_position ? 1.0 / (kPositionFeedbackSteps * p.dynamics.dt) : 0.0;
}

/// The most rows any end adds (the 3-D anchor's ten): the size of a solver's row buffer.
constexpr int kMaxEndRows = 10;

// --- 2-D ---------------------------------------------------------------------------------------

/// One end of a 2-D line (the paper's equations: the line in the x-z plane).
class EndCondition2D {
 public:
  using ADs = Eigen::AutoDiffScalar<Eigen::Matrix<double, eq2d::N, 1>>;    ///< statics' unknowns
  using ADd = Eigen::AutoDiffScalar<Eigen::Matrix<double, eq2dyn::N, 1>>;  ///< dynamics' unknowns

  virtual ~EndCondition2D() = default;
  /// A short name for messages and tests ("anchor", "force top", ...).
  virtual const char* name() const = 0;

  /// Static rows (eq. 33, section 5.1) on the node's unknowns y (eq2d::Var): staticRows() of r.
  virtual int staticRows() const = 0;
  virtual void staticResidual(const ADs* y, ADs* r) const = 0;

  /// Dynamic rows (eq. 34) on the node's unknowns y (eq2dyn::Var) at the new time level, with the
  /// top's prescribed motion or force `in` at that time (unused at the anchor).
  virtual int dynamicRows() const = 0;
  virtual void dynamicResidual(const TopState& in, const ADd* y, ADd* r) const = 0;

  /// A force the end prescribes [N] (0 when none): with the line's weight, the scale of the
  /// forces in the error measure (chi_m of eq. 39).
  virtual double characteristicForce() const { return 0.0; }
};

/// The lower end of a 2-D line: the anchor (a free lower end needs the 3-D model).
std::unique_ptr<EndCondition2D> makeLowerEnd2D(const Problem& problem);
/// The top of a 2-D line from problem.top: a position, force, surface-buoy or subsurface-body top
/// in statics, each driven by the top motion (velocity, position feedback or force) in dynamics.
/// `top_material`: the material of the top node (outlives the end).
std::unique_ptr<EndCondition2D> makeUpperEnd2D(const Problem& problem, const Material& top_material);

// --- 3-D ---------------------------------------------------------------------------------------

/// What a 3-D end's static rows read besides its node's unknowns.
struct StaticEnd3D {
  const eq3d::Water* water = nullptr;  ///< the steady current at the node
  const double* q_ref = nullptr;       ///< frame the lower end's twist is measured from (4 values)
};

/// The generalized-alpha weights of a step: alpha_m, alpha_k and the rate of eq. 26,
/// Yd = c1 (Y - Yp) - c0 Ydp.
struct AlphaWeights {
  double am = 0.0, ak = 0.0, c1 = 0.0, c0 = 0.0;
};

/// What a 3-D end's dynamic rows read besides its node's unknowns at the iterate.
struct DynamicEnd3D {
  double t = 0.0;                      ///< the new time level [s]
  const TopState* input = nullptr;     ///< the top's prescribed motion or force at t
  const double* yp = nullptr;          ///< the node's unknowns at the previous level (16)
  const double* ydp = nullptr;         ///< their rates at the previous level (16)
  const eq3d::Water* water = nullptr;  ///< water at the node at the iterate
  AlphaWeights w;
  /// A winch's payout rate dL/dt at a top [m/s] (+ pays out; docs/method.md "Winch"): the line
  /// runs through the top, so its material there moves at the top's velocity less
  /// dL/dt (1 + eps) along the tangent. 0 without a winch.
  double payout = 0.0;
  /// With a payout: the unknowns of the node below the top at the previous level (16), whose
  /// (1 + eps) e1 enters the top interval's mean (1 + eps) e1, the direction the coordinates row
  /// (eq. 42) moves the top along as the interval grows.
  const double* below = nullptr;
  /// A winch has run at this top: a top driven by its velocity holds its position by the
  /// feedback of `prescribe: position` (the moving top interval lags it by O(dL/dt dt)).
  bool winch = false;
};

/// One end of a 3-D line.
class EndCondition3D {
 public:
  using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, eq3d::N, 1>>;

  virtual ~EndCondition3D() = default;
  virtual const char* name() const = 0;

  /// Static rows on the node's unknowns y (eq3d::Var): staticRows() of r.
  virtual int staticRows() const = 0;
  virtual void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const = 0;

  /// Dynamic rows at the new time level: dynamicRows() of r, in double (the residual alone) or
  /// in AD scalars (with the Jacobian block).
  virtual int dynamicRows() const = 0;
  virtual void dynamicResidual(const DynamicEnd3D& c, const double* y, double* r) const = 0;
  virtual void dynamicResidual(const DynamicEnd3D& c, const AD* y, AD* r) const = 0;

  /// A force the end prescribes [N] (0 when none), as in 2-D.
  virtual double characteristicForce() const { return 0.0; }

  /// An end with a balance weighted in time (eq. 30: a free end's body, a top body, a drifting
  /// buoy) keeps the spatial part of it at the accepted level: taken here from the node's
  /// unknowns y and water w at time t, with the top's input `top` (called only by an end that
  /// needs it). The others keep nothing.
  virtual void acceptLevel(const double* y, const eq3d::Water& w, double t,
                           const std::function<TopState(double)>& top) {
    (void)y, (void)w, (void)t, (void)top;
  }
  /// That state, for a solver's save and restore (empty for an end without one).
  virtual std::vector<double> state() const { return {}; }
  virtual void setState(const std::vector<double>& s) { (void)s; }
};

/// The lower end of a 3-D line: the anchor, or a free end (towing, drifting) with its body.
/// `end_material`: the material of node 0 (outlives the end).
std::unique_ptr<EndCondition3D> makeLowerEnd3D(const Problem& problem, const Material& end_material);
/// An anchor that moves (a line below a free point or a vessel of a system): its velocity and
/// position prescribed by `motion` in dynamics, the anchor's rows in statics.
std::unique_ptr<EndCondition3D> makeMovingAnchor3D(const Problem& problem, std::function<TopState(double)> motion);
/// The top of a 3-D line: a position, force or surface-buoy top (driven by the top motion in
/// dynamics), a subsurface body, a tow point (over a free lower end) or a drifting buoy.
std::unique_ptr<EndCondition3D> makeUpperEnd3D(const Problem& problem, const Material& top_material);

/// Released ends (line events, docs/method.md "Line events"): an end let go, or the two new ends
/// of a line that parts. A free end carries no force: the internal force is zero at the new
/// level, and the end is moment free. A part of a line needs one node whose position follows
/// its velocity (dx/dt = V) when neither of its ends holds a position; the row count says where
/// those three rows go, so that every part keeps N rows per node (the band of the Newton matrix
/// does not change):
///   upper end: `rows` 6 (moment free, F = 0) or 9 (and dx/dt = V);
///   lower end: `rows` 10 (F = 0, the lower end's gauge, dx/dt = V) or 7 (without dx/dt = V).
/// A released end replaces an end of the same row count; a parted interval holds an upper end
/// of 16 - r rows at its lower node and a lower end of 16 - u rows at its upper node, r and u
/// being the line's lower- and upper-end rows. Dynamics only (the static rows exist for
/// completeness; statics of a let-go line are not defined).
std::unique_ptr<EndCondition3D> makeReleasedUpperEnd3D(const Material& top_material, int rows);
std::unique_ptr<EndCondition3D> makeReleasedLowerEnd3D(const Material& end_material, int rows);

}  // namespace core
}  // namespace mooring_dynamics
