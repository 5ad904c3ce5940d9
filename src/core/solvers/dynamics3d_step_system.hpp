// The 3-D dynamic solver's time step as a Newton system (DynamicStepSystem3D): the box rows of
// every interval and end at the new level in generalized-alpha form (docs/method.md), their
// Jacobian by automatic differentiation, the residual alone in double. Used by dynamics3d.cpp
// (the step, the Jacobian check). Private to src/core/solvers.
#pragma once

#include <algorithm>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "dynamics3d_impl.hpp"
#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/numerics/ad_rows.hpp"
#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

namespace mooring_dynamics {
namespace core {

namespace dynamics3d_detail {
using AD32 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;
using AD16 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
}  // namespace dynamics3d_detail

// ------------------------------------------------------------------------------------------------

// --- One time step as a Newton system ------------------------------------------------------------
//
// Row layout as in statics (10 anchor rows, 16 per interval, 6 top rows): kl = 25, ku = 21.

class DynamicStepSystem3D : public NewtonSystem {
  using AD32 = dynamics3d_detail::AD32;
  using AD16 = dynamics3d_detail::AD16;

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

  /// The rows of intervals [j0, j1) (but a parted one's: partedRows): the residual alone in
  /// double, or with the Jacobian (node terms in S16, the interval's rows in S32), by sharedRows.
  template <class S32>
  void intervalRows(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J, int j0, int j1) const {
    if constexpr (std::is_same_v<S32, double>)
      sharedRows<double, double>(Yv, R, nullptr, j0, j1);
    else
      sharedRows<AD16, S32>(Yv, R, J, j0, j1);
  }

  /// The rows of intervals [j0, j1) (but a parted one's), each on its own: every node term
  /// evaluated in S32 (junctions, a parted line; sharedRows for the rest).
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

  /// What an interval's rows take from one of its nodes: the node's unknowns (S16: seeded on
  /// that node's sixteen), the spatial terms, the inertia rows at the new and the last level.
  template <class S>
  struct NodeRows {
    S y[N];
    NodeTerms<S> terms;
    S in1[kInertiaRows], in0[kInertiaRows];
  };

  /// Node k's rows for an interval of material m: the quantities intervalSpatial and
  /// intervalInertia compute there, in the same operations.
  template <class S>
  void nodeRows(const Eigen::VectorXd& Yv, int k, const Material& m, NodeRows<S>& out) const {
    const auto [am, ak, c1, c0] = weights();
    (void)ak;
    const Environment& env = im_.problem.environment;
    const double* yp = im_.Y.data() + N * k;
    const double* ydp = im_.Yd.data() + N * k;
    S ydw[N], ypc[N];
    for (int q = 0; q < N; ++q) {
      out.y[q] = variable<S>(Yv[N * k + q], N, q);
      const S yd = c1 * (out.y[q] - yp[q]) - c0 * ydp[q];
      ydw[q] = (1.0 - am) * yd + am * ydp[q];  // weighted rate of eq. 30
      ypc[q] = constant<S>(yp[q]);
    }
    const std::size_t kk = static_cast<std::size_t>(k);
    nodeTerms(env, m, out.y, water_[kk], out.terms);
    inertia(env, m, out.y, ydw, out.terms.R, water_[kk], out.in1);
    S Rp[9];
    quat::matrix(ypc + Q0, Rp);
    inertia(env, m, ypc, ydw, Rp, im_.water[kk], out.in0);
  }

  /// A node's value into the interval's scalar: its derivatives in the first (half 0, node j) or
  /// the second sixteen (half 1, node j + 1) of thirty-two. The identity in double.
  static double lift(double v, int) { return v; }
  static AD32 lift(const AD16& v, int half) {
    AD32 out(v.value());
    out.derivatives().setZero();
    out.derivatives().template segment<N>(N * half) = v.derivatives();
    return out;
  }
  template <class S16, class S32>
  static void lift(const NodeRows<S16>& in, int half, NodeRows<S32>& out) {
    for (int q = 0; q < N; ++q) out.y[q] = lift(in.y[q], half);
    for (int q = 0; q < 9; ++q) out.terms.R[q] = lift(in.terms.R[q], half);
    out.terms.T = lift(in.terms.T, half);
    out.terms.p = lift(in.terms.p, half);
    for (int q = 0; q < 3; ++q) out.terms.g[q] = lift(in.terms.g[q], half);
    for (int q = 0; q < kInertiaRows; ++q) {
      out.in1[q] = lift(in.in1[q], half);
      out.in0[q] = lift(in.in0[q], half);
    }
  }

  /// The rows of intervals [j0, j1): a node's terms once for the two intervals it ends where
  /// they share a material (in S16, seeded on its own unknowns), combined per interval in S32
  /// (its derivatives by node j's unknowns, then node j + 1's): the values and derivatives of
  /// intervalRowsAs<S32>, which takes junctions and a parted interval.
  template <class S16, class S32>
  void sharedRows(const Eigen::VectorXd& Yv, Eigen::VectorXd& R, BandedMatrix* J, int j0, int j1) const {
    const double ak = weights().ak;
    NodeRows<S16> rows[2];
    NodeRows<S16> *a = &rows[0], *b = &rows[1];
    NodeRows<S32> la, lb;
    const Material* kept = nullptr;  // the material *a holds node j's rows for (null: none)
    for (int j = j0; j < j1; ++j) {
      const MeshInterval& iv = im_.mesh.intervals[static_cast<std::size_t>(j)];
      if (j == im_.parted || !(iv.h > 0.0)) {
        intervalRowsAs<S32>(Yv, R, J, j, j + 1);
        kept = nullptr;
        continue;
      }
      const Material& m = im_.problem.materials[iv.material];
      if (kept != &m) nodeRows(Yv, j, m, *a);
      nodeRows(Yv, j + 1, m, *b);
      const NodeRows<S32>*na, *nb;
      if constexpr (std::is_same_v<S16, S32>) {
        na = a;
        nb = b;
      } else {
        lift(*a, 0, la);
        lift(*b, 1, lb);
        na = &la;
        nb = &lb;
      }
      S32 r[N], in1[kInertiaRows], in0[kInertiaRows];
      intervalSpatialOf(m, iv.h, na->y, nb->y, na->terms, nb->terms, r);
      intervalInertiaOf(iv.h, na->in1, nb->in1, in1);
      intervalInertiaOf(iv.h, na->in0, nb->in0, in0);
      for (int q = 0; q < kInertiaRows; ++q)
        r[q] = (1.0 - ak) * (in1[q] + r[q]) + ak * (in0[q] + im_.S[kInertiaRows * j + q]);
      scatter(r, N, end_rows_ + N * j, N * j, 2 * N, R, J);
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

}  // namespace core
}  // namespace mooring_dynamics
