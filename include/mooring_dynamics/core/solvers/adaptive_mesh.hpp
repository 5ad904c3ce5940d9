// Adaptive spatial mesh (paper section 3, eqs. 15-24, after Eggleton 1971): given a static
// solution on a uniform mesh, redistribute the nodes of every piece of line so that they crowd
// where the curvature Omega3 changes fast, keeping the node count.
//
// Within a piece of length L the mesh control function f(s) = c_w Omega3(s) + s (eq. 16) is
// equidistributed by the variational solution (eq. 22)
//     ds/dq = beta / (c_w Omega'_s(s) + 1),   s(0) = 0, s(L) = L,   q in [0, L],
// where Omega'_s in [0, 1] is the normalised curvature gradient (eq. 21) and the constant beta lies
// in [1, 1 + c_w] (eqs. 23-24). beta is found by shooting with RK4 over n_nodes - 1 equal steps of
// q and bisection on the end error s(q = L) - L; the ends of the steps are the new nodes. Each
// step is made of equal RK4 substeps that advance s by at most one old interval (see
// adaptive_mesh.cpp); the substep count is fixed before the bisection.
//
// Omega'_s(s): gradient magnitudes |dOmega3/ds| estimated at knots on the old piece (see
// GradientEstimate), divided by their maximum over the piece, interpolated linearly between the
// knots and constant beyond the outermost ones. The right-hand side of eq. 22 is then continuous,
// so RK4 keeps its accuracy wherever its steps fall relative to the old nodes.
//
// Pure functions: nothing here solves. The intended sequence (paper section 3, last paragraph) is
//     uniform = buildMesh(p); s0 = solveStaticOnMesh(p, uniform, o);
//     adapted = buildAdaptiveMesh(p, uniform, s0, c_w); s1 = solveStaticOnMesh(p, adapted, o);
#pragma once

#include <vector>

#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// How |dOmega3/ds| is estimated from the nodal curvatures of the old piece (both are eq. 21's
/// normalised gradient up to the choice of difference; they agree to O(h) on smooth curvature).
enum class GradientEstimate {
  /// Differences of the half-grid curvatures (Omega3_k + Omega3_{k+1}) / 2 of neighbouring old
  /// intervals, i.e. |Omega3_{k+1} - Omega3_{k-1}| / (s_{k+1} - s_{k-1}), knots at the interior old
  /// nodes. Blind to the odd-even nodal mode of the box scheme on low-EI line (paper eq. 13),
  /// which otherwise dominates eq. 21 on grounded chain and draws the nodes away from touchdown.
  /// Default.
  HalfGrid,
  /// Eq. 21 as printed: |Omega3_{k+1} - Omega3_k| / (s_{k+1} - s_k) per old interval, knots at
  /// the old interval midpoints (on a uniform mesh the division by the spacing cancels in the
  /// normalisation).
  Nodal,
};

/// Outcome of the shooting for one piece (eqs. 22-24).
struct EggletonMesh {
  std::vector<double> s;     ///< new node arclengths: s.front() == 0, s.back() == L, increasing [m]
  double beta = 1.0;         ///< the constant of eq. 22, in [1, 1 + c_w] [-]
  double end_error = 0.0;    ///< s(q = L) - L of the accepted shot, before the last node is set to L [m]
  int bisections = 0;        ///< bisection steps taken (0: uniform curvature or c_w == 0, uniform mesh)
};

/// Eqs. 21-24 on one piece. `s` (increasing, s.front() == 0, s.back() == L to 1e-9 L) and `omega`
/// are the old node arclengths and curvatures Omega3 [1/m]; c_w >= 0 is the curvature weight and
/// n_nodes >= 2 the number of new nodes. A zero gradient estimate everywhere (uniform curvature)
/// or c_w == 0 gives the uniform mesh. Throws std::invalid_argument on inconsistent input.
EggletonMesh eggletonMesh(const std::vector<double>& s, const std::vector<double>& omega, double L, double c_w,
                          int n_nodes, GradientEstimate estimate = GradientEstimate::HalfGrid);

/// The node arclengths of eggletonMesh(...).s.
std::vector<double> eggletonNodePositions(const std::vector<double>& s, const std::vector<double>& omega, double L,
                                          double c_w, int n_nodes,
                                          GradientEstimate estimate = GradientEstimate::HalfGrid);

/// The mesh `uniform` (from buildMesh(problem)) with the nodes of every piece (maximal run of
/// intervals with h > 0 between junctions and ends) redistributed by eggletonMesh, using the
/// curvature of `statics` (solved on `uniform`: statics.nodes[j] belongs to uniform.nodes[j]).
/// Node count, junctions, materials, segments and bodies are kept; a piece's end nodes keep their
/// arclengths. Omega'_s is normalised per piece; a piece whose largest gradient is below 1e-6 of
/// the largest over the whole line (solver noise on a straight stretch, not a feature) keeps its
/// nodes. Throws std::invalid_argument when c_w < 0, or when `uniform` does not span the problem's
/// line or `statics` was not solved on it.
Mesh buildAdaptiveMesh(const Problem& problem, const Mesh& uniform, const StaticResult& statics, double c_w,
                       GradientEstimate estimate = GradientEstimate::HalfGrid);

}  // namespace core
}  // namespace mooring_dynamics
