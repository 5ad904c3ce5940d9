// The assembled 2-D static problem as a NewtonSystem (exposed for tests: Jacobian against
// finite differences, relaxation studies).
#pragma once

#include <memory>
#include <string>

#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

class StaticSystem2D : public NewtonSystem {
 public:
  StaticSystem2D(const Problem& problem, const Mesh& mesh);
  int size() const override;
  // Row layout: the anchor's rows, 6 per interval, the top's rows; interval j's rows start at
  // lower_rows_ + 6 j and touch nodes j and j + 1 (kl = ku = 8 with the anchor's 3 rows).
  int lowerBandwidth() const override { return lower_rows_ + eq2d::N - 1; }
  int upperBandwidth() const override { return 2 * eq2d::N - 1 - lower_rows_; }
  void evaluate(const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) override;
  double scale(int i) const override;
  std::string describe(int i) const override;
  /// No node turns by more than kMaxAngleStep in one iteration.
  double stepLimit(const Eigen::VectorXd& dY) const override;
  /// A node that is off the seabed and would pass below its rest penetration stops there.
  void conditionStep(const Eigen::VectorXd& Y, Eigen::VectorXd& dY) const override;

  /// Apply the static cap F_bot <= w_o of eq. 35 (the paper's model) or the plain spring (default).
  void setSeabedCap(bool capped) { capped_ = capped; }
  /// Largest seabed reaction over wet weight among the nodes of state Y (for the cap check).
  double maxSeabedLoadRatio(const Eigen::VectorXd& Y) const;

 private:
  /// The rows of an end (end_conditions.hpp) at the node whose unknowns start at col0, from row0.
  void endRows(const EndCondition2D& end, int row0, int col0, const Eigen::VectorXd& Y, Eigen::VectorXd& R,
               BandedMatrix* J) const;
  /// The six rows of interval j (eq. 11).
  void intervalRows(int j, const Eigen::VectorXd& Y, Eigen::VectorXd& R, BandedMatrix* J) const;

  bool capped_ = false;
  const Problem& problem_;
  const Mesh& mesh_;
  std::unique_ptr<EndCondition2D> lower_, upper_;  ///< the anchor and the top
  int lower_rows_;                                 ///< rows of the anchor, before the intervals'
  double chi_[6];
};

/// Per-node values and end forces from the Newton state vector.
StaticResult staticResultFromState(const Problem& problem, const Mesh& mesh, const Eigen::VectorXd& Y);

/// Newton options from the static options of a problem.
NewtonOptions newtonOptions(const StaticOptions& options);

}  // namespace core
}  // namespace mooring_dynamics
