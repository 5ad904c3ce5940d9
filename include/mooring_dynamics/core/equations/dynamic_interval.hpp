// One half-grid interval (h > 0) of a generalized-alpha time step of the 2-D dynamic equations,
// in double with a hand-coded Jacobian: the same rows as DynamicStepSystem built from the
// templates of equations2d_dynamic.hpp with automatic differentiation (eqs. 1-6 and 42 times h,
// eq. 11; mass matrix of eq. 8 averaged between the levels with the alpha_k weights, eq. 30 with
// 31 as read in docs/method.md), at a fraction of the cost. test_dynamic_interval checks value
// and Jacobian against the AutoDiff templates; test_dynamics2d checks the assembled Jacobian
// against finite differences.
#pragma once

#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"

namespace mooring_dynamics {
namespace core {
namespace eq2dyn {

/// A node's state with the cosine and sine of its inclination and the water at it.
struct NodeView {
  const double* y = nullptr;  ///< N unknowns
  double c = 1.0, s = 0.0;    ///< cos(phi), sin(phi)
  const Water* w = nullptr;
};

/// Weights of one step: r = (1 - ak) [I(Y, Yd~) + S(Y)] + ak [I(Yp, Yd~) + S(Yp)] in rows 0-5,
/// r = S(Y) in rows 6-7, with the weighted rate Yd~ = (1 - am) Yd + am Ydp whose derivative
/// along its own unknown is wr = (1 - am) / (gamma dt) (eqs. 26, 30).
struct StepWeights {
  double ak = 0.0;
  double wr = 0.0;
};

/// The terms of one node in the rows of the intervals on either side of it: distributed load
/// (eqs. 1-2, 35-36) and inertia rows M(Y) Yd~ (eq. 8, rows 0-3) at the new level and at the
/// previous one, with their gradients along the node's unknowns. A node between two intervals of
/// the same material enters both with the same terms, computed once (DynamicStepSystem).
struct NodeTerms {
  double f1 = 0.0, f2 = 0.0;       ///< load along t, n per unit length [N/m]
  double df1[N] = {}, df2[N] = {};  ///< their gradients (with the Jacobian only)
  double I[4] = {}, Ip[4] = {};     ///< inertia rows at the new and the previous level [N/m, -]
  double dI[4][N] = {}, dIp[4][N] = {};  ///< their gradients (with the Jacobian only)
};

/// Distributed load (f1, f2) per unit length at a node of material m [N/m] (eqs. 1-2, 35-36):
/// the value of NodeTerms::f1, f2 without the gradients.
void nodeLoadValue(const Environment& env, const Material& m, const NodeView& nv, double& f1, double& f2);

/// Spatial rows sp[0..7] of interval (a, b) of length h > 0 and material m, K dY/ds + F times h
/// (eqs. 1-6, 42 on the half grid, eq. 11), from its nodes' loads (nodeLoadValue).
void intervalSpatialRows(const Material& m, double h, const NodeView& a, const NodeView& b, double f1a, double f2a,
                         double f1b, double f2b, double* sp);

/// The terms of a node of material m: its state now and at the previous level, and its weighted
/// rate yd (weight wts.wr along its own unknown). Gradients only when `jacobian` is true.
void nodeStepTerms(const Environment& env, const Material& m, const NodeView& now, const NodeView& prev,
                   const double* yd, const StepWeights& wts, bool jacobian, NodeTerms& out);

/// Rows R[0..7] of interval (a, b) of length h > 0 and material m from its nodes' terms (ta, tb,
/// computed by nodeStepTerms with the same material, and with the Jacobian when J is non-null),
/// the previous level's spatial rows Sprev[0..7]; J as below.
void intervalStepRows(const Material& m, double h, const NodeView& a, const NodeView& b, const NodeTerms& ta,
                      const NodeTerms& tb, const StepWeights& wts, const double* Sprev, double* R, double (*J)[2 * N]);

/// Rows R[0..7] of interval (a, b) of length h > 0 and material m at the new level (a, b), the
/// previous level (pa, pb) with its spatial rows Sprev[0..7], and the weighted rates yda, ydb.
/// When J is non-null, J[q][k] = dR[q] / dY_k with k < N the unknowns of node a and k >= N those
/// of node b (all 8 x 16 entries written). The wave velocity's dependence on the node position
/// is left out, as in the AutoDiff version (a quasi-Newton term, docs/method.md).
void intervalStepRows(const Environment& env, const Material& m, double h, const NodeView& a, const NodeView& b,
                      const NodeView& pa, const NodeView& pb, const double* yda, const double* ydb,
                      const StepWeights& wts, const double* Sprev, double* R, double (*J)[2 * N]);

}  // namespace eq2dyn
}  // namespace core
}  // namespace mooring_dynamics
