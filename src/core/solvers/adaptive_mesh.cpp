#include "mooring_dynamics/core/solvers/adaptive_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mooring_dynamics {
namespace core {

namespace {

// Old-mesh arclengths must reproduce [0, L] to this fraction of L.
constexpr double kEndTol = 1e-9;
// Bisection stops when |s(q = L) - L| is below this fraction of L (a few ulps of L times the
// rounding accumulated over the RK4 sum) or when the bracket cannot shrink any further.
constexpr double kShotTol = 1e-13;
constexpr int kMaxBisections = 200;
// Cap on the RK4 substeps of one shot (reached only for old pieces with intervals far below their
// mean, e.g. re-adapting an adapted mesh with a large c_w, or for a very large c_w).
constexpr double kMaxSubstepsPerShot = 4.0e6;
// A piece whose largest |dOmega3| is below this fraction of the line's largest is left uniform.
constexpr double kPieceNoiseFloor = 1e-6;

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("adaptive mesh: " + what); }

/// Unnormalised curvature gradient |dOmega3/ds| of the old piece at the knots `at`.
void gradientKnots(const std::vector<double>& s, const std::vector<double>& omega, GradientEstimate est,
                   std::vector<double>& at, std::vector<double>& g) {
  at.clear();
  g.clear();
  if (est == GradientEstimate::HalfGrid && s.size() >= 3) {
    // Differences of the half-grid curvatures (Omega_k + Omega_{k+1}) / 2 between neighbouring
    // interval midpoints: |Omega_{k+1} - Omega_{k-1}| / (s_{k+1} - s_{k-1}) at node k.
    for (std::size_t k = 1; k + 1 < s.size(); ++k) {
      at.push_back(s[k]);
      g.push_back(std::abs(omega[k + 1] - omega[k - 1]) / (s[k + 1] - s[k - 1]));
    }
    return;
  }
  // Eq. 21: |Omega_{k+1} - Omega_k| / (s_{k+1} - s_k) at the midpoint of interval k.
  for (std::size_t k = 0; k + 1 < s.size(); ++k) {
    at.push_back(0.5 * (s[k] + s[k + 1]));
    g.push_back(std::abs(omega[k + 1] - omega[k]) / (s[k + 1] - s[k]));
  }
}

/// Normalised curvature gradient Omega'_s (eq. 21): linear between its knots, constant beyond them.
class CurvatureGradient {
 public:
  /// Returns false when the largest gradient is zero (uniform curvature).
  bool build(const std::vector<double>& s, const std::vector<double>& omega, GradientEstimate est) {
    gradientKnots(s, omega, est, knots_, g_);
    double gmax = 0.0;
    for (double g : g_) gmax = std::max(gmax, g);
    if (!(gmax > 0.0)) return false;
    for (double& g : g_) g /= gmax;
    return true;
  }

  /// Omega'_s(x); successive calls at nearby x (as along a shot) cost O(1).
  double operator()(double x) const {
    if (x <= knots_.front()) return g_.front();
    if (x >= knots_.back()) return g_.back();
    // Interval [knots_[k], knots_[k + 1]) holding x, walked to from the previous call's.
    std::size_t k = std::min(hint_, knots_.size() - 2);
    while (x < knots_[k]) --k;
    while (x >= knots_[k + 1]) ++k;
    hint_ = k;
    const double t = (x - knots_[k]) / (knots_[k + 1] - knots_[k]);
    return g_[k] + t * (g_[k + 1] - g_[k]);
  }

 private:
  std::vector<double> knots_, g_;
  mutable std::size_t hint_ = 0;
};

/// One RK4 shot of eq. 22 from s(0) = 0 over n - 1 steps of dq = L / (n - 1), each made of
/// `sub` equal RK4 substeps; fills `out` with s at the end of every step.
void shoot(const CurvatureGradient& g, double c_w, double beta, double L, int n, int sub, std::vector<double>& out) {
  out.assign(static_cast<std::size_t>(n), 0.0);
  const double dq = L / (n - 1) / sub;
  const auto f = [&](double s) { return beta / (c_w * g(s) + 1.0); };
  double s = 0.0;
  for (int i = 1; i < n; ++i) {
    for (int k = 0; k < sub; ++k) {
      const double k1 = f(s);
      const double k2 = f(s + 0.5 * dq * k1);
      const double k3 = f(s + 0.5 * dq * k2);
      const double k4 = f(s + dq * k3);
      s += dq / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    out[static_cast<std::size_t>(i)] = s;
  }
}

std::vector<double> uniformPositions(double L, int n) {
  std::vector<double> s(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) s[static_cast<std::size_t>(i)] = L * i / (n - 1);
  s.back() = L;
  return s;
}

}  // namespace

EggletonMesh eggletonMesh(const std::vector<double>& s, const std::vector<double>& omega, double L, double c_w,
                          int n_nodes, GradientEstimate estimate) {
  if (!(L > 0.0) || !std::isfinite(L)) fail("piece length L = " + std::to_string(L) + " must be positive");
  if (!(c_w >= 0.0) || !std::isfinite(c_w)) fail("curvature weight c_w = " + std::to_string(c_w) + " must be >= 0");
  if (n_nodes < 2) fail("n_nodes = " + std::to_string(n_nodes) + " must be >= 2");
  if (s.size() < 2 || s.size() != omega.size()) {
    std::ostringstream os;
    os << "need at least two old nodes with one curvature each (s: " << s.size() << ", omega: " << omega.size()
       << ")";
    fail(os.str());
  }
  if (std::abs(s.front()) > kEndTol * L || std::abs(s.back() - L) > kEndTol * L) {
    std::ostringstream os;
    os << "old nodes span [" << s.front() << ", " << s.back() << "], not [0, L = " << L << "]";
    fail(os.str());
  }
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!std::isfinite(omega[k])) fail("curvature at old node " + std::to_string(k) + " is not finite");
    if (k > 0 && !(s[k] > s[k - 1])) fail("old node arclengths not increasing at node " + std::to_string(k));
  }

  EggletonMesh out;
  CurvatureGradient g;
  if (c_w == 0.0 || !g.build(s, omega, estimate)) {
    out.s = uniformPositions(L, n_nodes);
    return out;
  }
  // Every RK4 increment is a convex combination of values of eq. 22's right-hand side, which lies
  // in [beta / (1 + c_w), beta]: beta = 1 undershoots L and beta = 1 + c_w overshoots it.
  double lo = 1.0, hi = 1.0 + c_w;
  double h_min = s.back();
  for (std::size_t k = 1; k < s.size(); ++k) h_min = std::min(h_min, s[k] - s[k - 1]);
  // RK4 substeps: a step may advance s by up to (1 + c_w) dq, across many old intervals where the
  // right-hand side of eq. 22 jumps by up to a factor 1 + c_w; a full step there is inaccurate and
  // makes s(q = L) so steep a function of beta that bisection stalls. Each substep advances s by
  // at most one old interval. The count is fixed before the bisection (independent of beta), so
  // that s(q = L) stays a continuous function of beta.
  const double step_max = (1.0 + c_w) * L / (n_nodes - 1);
  const double wanted = std::ceil(step_max / h_min - 1e-9);
  const int sub = static_cast<int>(std::max(1.0, std::min(wanted, std::floor(kMaxSubstepsPerShot / (n_nodes - 1)))));
  while (out.bisections < kMaxBisections) {
    ++out.bisections;
    out.beta = 0.5 * (lo + hi);
    shoot(g, c_w, out.beta, L, n_nodes, sub, out.s);
    out.end_error = out.s.back() - L;
    if (std::abs(out.end_error) <= kShotTol * L || !(out.beta > lo && out.beta < hi)) break;
    (out.end_error < 0.0 ? lo : hi) = out.beta;
  }
  // Close the remaining end error by scaling (keeps the nodes increasing whatever its size).
  const double scale = L / out.s.back();
  for (double& x : out.s) x *= scale;
  out.s.back() = L;
  return out;
}

std::vector<double> eggletonNodePositions(const std::vector<double>& s, const std::vector<double>& omega, double L,
                                          double c_w, int n_nodes, GradientEstimate estimate) {
  return eggletonMesh(s, omega, L, c_w, n_nodes, estimate).s;
}

Mesh buildAdaptiveMesh(const Problem& problem, const Mesh& uniform, const StaticResult& statics, double c_w,
                       GradientEstimate estimate) {
  if (!(c_w >= 0.0) || !std::isfinite(c_w)) fail("curvature weight c_w = " + std::to_string(c_w) + " must be >= 0");
  const std::size_t n = uniform.nodes.size();
  if (n < 2 || uniform.intervals.size() + 1 != n) fail("the uniform mesh is malformed");
  const double total = uniform.nodes.back().s;
  const double tol = kEndTol * std::max(total, 1.0);
  if (std::abs(total - problem.totalLength()) > tol) {
    std::ostringstream os;
    os << "the mesh spans " << total << " m but the problem's line is " << problem.totalLength() << " m long";
    fail(os.str());
  }
  if (statics.nodes.size() != n) {
    std::ostringstream os;
    os << "the static result has " << statics.nodes.size() << " nodes, the mesh " << n
       << " (solve the statics on this mesh)";
    fail(os.str());
  }
  for (std::size_t j = 0; j < n; ++j)
    if (std::abs(statics.nodes[j].s - uniform.nodes[j].s) > tol)
      fail("static result node " + std::to_string(j) + " is not at the mesh's arclength (solve on this mesh)");

  // The pieces: maximal runs of intervals with h > 0, nodes a..b.
  struct Piece {
    std::size_t a, b;
    std::vector<double> s, omega;
    double max_gradient;
  };
  std::vector<Piece> pieces;
  double line_max = 0.0;
  for (std::size_t a = 0; a + 1 < n;) {
    if (!(uniform.intervals[a].h > 0.0)) {
      ++a;
      continue;
    }
    std::size_t b = a + 1;
    while (b + 1 < n && uniform.intervals[b].h > 0.0) ++b;
    Piece piece{a, b, {}, {}, 0.0};
    for (std::size_t j = a; j <= b; ++j) {
      piece.s.push_back(uniform.nodes[j].s - uniform.nodes[a].s);
      piece.omega.push_back(statics.nodes[j].curvature);
    }
    std::vector<double> at, g;
    gradientKnots(piece.s, piece.omega, estimate, at, g);
    for (double v : g) piece.max_gradient = std::max(piece.max_gradient, v);
    line_max = std::max(line_max, piece.max_gradient);
    pieces.push_back(std::move(piece));
    a = b;
  }

  Mesh mesh = uniform;
  if (!(line_max > 0.0) || c_w == 0.0) return mesh;
  for (const Piece& piece : pieces) {
    const std::size_t a = piece.a, b = piece.b;
    if (b - a < 2 || !(piece.max_gradient > kPieceNoiseFloor * line_max)) continue;
    const double s0 = uniform.nodes[a].s;
    const std::vector<double> snew =
        eggletonNodePositions(piece.s, piece.omega, piece.s.back(), c_w, static_cast<int>(b - a + 1), estimate);
    for (std::size_t j = a + 1; j < b; ++j) mesh.nodes[j].s = s0 + snew[j - a];
    for (std::size_t j = a; j < b; ++j) mesh.intervals[j].h = mesh.nodes[j + 1].s - mesh.nodes[j].s;
  }
  return mesh;
}

}  // namespace core
}  // namespace mooring_dynamics
