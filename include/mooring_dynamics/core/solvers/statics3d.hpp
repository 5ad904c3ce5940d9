// 3-D static solver: the equations of equations3d.hpp without time derivatives on the half-grid
// box scheme (section 3), Newton relaxation with adaptive relaxation (section 6), seabed as an
// elastic foundation (5.3) with depth varying in x and y. Shares the mesh, the Newton solver and
// the banded LU with the 2-D solver; the initial guess is the 2-D solution in the vertical plane
// through the anchor toward the top, turned into that plane.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// The assembled 3-D static problem as a NewtonSystem (exposed for tests).
/// Row layout: the lower end's 10 rows, 16 rows per interval, the top's 6 rows; 16 unknowns per
/// node (eq3d::Var). Interval j couples nodes j and j + 1: half-bandwidths kl = 25, ku = 21.
class StaticSystem3D : public NewtonSystem {
 public:
  /// q_ref: the frame the anchor's twist is measured from (the initial guess's anchor frame).
  StaticSystem3D(const Problem& problem, const Mesh& mesh, const double* q_ref);
  int size() const override;
  int lowerBandwidth() const override { return lower_rows_ + eq3d::N - 1; }
  int upperBandwidth() const override { return 2 * eq3d::N - 1 - lower_rows_; }
  int blockSize() const override { return eq3d::N; }  // node-by-node block elimination
  int leadingRows() const override { return lower_rows_; }
  void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override;
  double scale(int i) const override;
  std::string describe(int i) const override;
  /// No frame turns by more than about half a radian in one iteration.
  double stepLimit(const Eigen::VectorXd& dY) const override;
  /// A node that is off the seabed and would pass below its rest penetration stops there.
  void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const override;

 private:
  /// The rows of an end (end_conditions.hpp) at the node whose unknowns start at col0, from row0.
  void endRows(const EndCondition3D& end, int row0, int col0, const eq3d::Water& water, const Eigen::VectorXd& Y,
               Eigen::VectorXd& R, BandedMatrix* J) const;
  /// The sixteen rows of interval j (eq. 11) or of a pin junction.
  void intervalRows(int j, const std::vector<eq3d::Water>& water, const Eigen::VectorXd& Y, Eigen::VectorXd& R,
                    BandedMatrix* J) const;

  const Problem& problem_;
  const Mesh& mesh_;
  std::unique_ptr<EndCondition3D> lower_, upper_;  ///< the anchor or free end, and the top
  int lower_rows_;                                 ///< rows of the lower end, before the intervals'
  double q_ref_[4];
  double chi_[16];
};

/// A converged (or last) 3-D static state: the Newton vector (16 per node) and its result.
struct StaticState3D {
  Eigen::VectorXd Y;
  StaticResult result;
};

/// Solve the 3-D static equilibrium of `problem` (any Formulation; the 3-D equations are used).
/// Throws std::invalid_argument when the problem is invalid; non-convergence is in the summary.
StaticResult solveStatic3D(const Problem& problem);
StaticResult solveStatic3D(const Problem& problem, const StaticOptions& options);
/// Same on a given mesh, returning the Newton state too (the start of a 3-D dynamic run).
StaticState3D solveStatic3DOnMesh(const Problem& problem, const Mesh& mesh, const StaticOptions& options);

/// Initial guess (16 per node): the 2-D solution in the vertical plane through the anchor at
/// azimuth `psi` [rad], turned into that plane; velocities zero.
Eigen::VectorXd planarInitialGuess3D(const Problem& problem, const Mesh& mesh, double psi);

/// Per-node values and end forces from a 3-D Newton state.
StaticResult staticResult3DFromState(const Problem& problem, const Mesh& mesh, const Eigen::VectorXd& Y);

/// Azimuth [rad] of the vertical plane the initial guess lies in: toward the top position, along
/// the top force, or down the surface current (then the wind) for a buoy; 0 when undefined.
double initialGuessAzimuth(const Problem& problem);

}  // namespace core
}  // namespace mooring_dynamics
