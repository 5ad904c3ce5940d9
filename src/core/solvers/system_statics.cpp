#include "mooring_dynamics/core/solvers/system_statics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/solvers/solvers.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

// --- Statics -------------------------------------------------------------------------------------

namespace {

/// Load of a free point itself [N]: a surface buoy's buoyancy, current drag and wind
/// (eq3d::buoyForce), or a body's net buoyancy and its drag on the current (the full relative
/// velocity, as a sphere: no line tangent is defined at a junction of several lines).
void pointLoad(const SystemProblem& s, const SystemPoint& pt, const double* X, double* F) {
  F[0] = F[1] = F[2] = 0.0;
  if (pt.type == SystemPoint::Type::Buoy) {
    eq3d::buoyForce(s.environment, pt.buoy, X[2], F);
  } else if (pt.type == SystemPoint::Type::Body) {
    const Body& b = s.bodies[pt.body];
    double ux, uy;
    s.environment.currentAt(X[2], ux, uy);
    const double q = 0.5 * s.environment.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.isotropicCd();
    const double U = std::hypot(ux, uy);
    F[0] = q * U * ux;
    F[1] = q * U * uy;
    F[2] = -b.wet_weight;
  }
}

struct Evaluation {
  std::vector<StaticResult> lines;
  bool ok = true;
  std::string message;
};

/// The statics of a system: Newton with backtracking on the force balance of the free points,
/// each line solved on its own for every trial position of its ends (section 5.1's outer
/// iteration, generalized to points joined by several lines).
class SystemStaticSolver {
 public:
  SystemStaticSolver(const SystemProblem& s, const SystemSolveOptions& o)
      : s_(s), o_(o), np_(s.points.size()), nl_(s.lines.size()), at_(np_), shortest_(np_, 1e300) {
    for (std::size_t p = 0; p < np_; ++p)
      if (s_.points[p].free()) free_pts_.push_back(p);
    for (std::size_t i = 0; i < nl_; ++i) {
      const SystemLine& l = s_.lines[i];
      double L = 0.0;
      for (const Segment& g : l.segments) L += g.length;
      at_[l.to].push_back(i);
      shortest_[l.to] = std::min(shortest_[l.to], L);
      if (l.from != SystemLine::kFreeEnd) {
        at_[l.from].push_back(i);
        shortest_[l.from] = std::min(shortest_[l.from], L);
      }
    }
    m_ = static_cast<int>(3 * free_pts_.size());
  }

  SystemStaticResult solve() {
    SystemStaticResult out;
    std::vector<double> X = initialPositions();
    Evaluation ev;
    evaluateAll(X, ev);
    if (!ev.ok) {
      out.summary.message = "the lines do not solve at the initial point positions: " + ev.message +
                            " (give free points a `position` guess)";
      out.lines = ev.lines;
      return out;
    }
    Eigen::VectorXd G;
    residual(X, ev.lines, G);
    const int it = iterate(X, ev, G, out);
    summarize(it, G, out);
    out.lines = ev.lines;
    pointResults(X, ev, out);
    return out;
  }

 private:
  /// Initial positions: fixed points as given; a free point without a guess at the mean of the
  /// fixed points it is joined to (of all fixed points if none), a buoy at the surface.
  std::vector<double> initialPositions() const {
    std::vector<double> X(3 * np_);
    for (std::size_t p = 0; p < np_; ++p) {
      X[3 * p] = s_.points[p].x;
      X[3 * p + 1] = s_.points[p].y;
      X[3 * p + 2] = s_.points[p].z;
    }
    for (std::size_t p : free_pts_) {
      const SystemPoint& pt = s_.points[p];
      if (pt.position_given) continue;
      double sx = 0, sy = 0, sz = 0;
      int k = 0;
      auto add = [&](std::size_t q) {
        if (s_.points[q].free()) return;
        sx += s_.points[q].x;
        sy += s_.points[q].y;
        sz += s_.points[q].z;
        ++k;
      };
      for (std::size_t i : at_[p]) {
        add(s_.lines[i].to);
        if (s_.lines[i].from != SystemLine::kFreeEnd) add(s_.lines[i].from);
      }
      if (k == 0)
        for (std::size_t q = 0; q < np_; ++q) add(q);
      X[3 * p] = sx / k;
      X[3 * p + 1] = sy / k;
      X[3 * p + 2] = pt.type == SystemPoint::Type::Buoy ? -0.5 * pt.buoy.totalHeight() : sz / k;
    }
    return X;
  }

  /// The statics of line i with its ends at the points Xv; false (why set) when it fails.
  bool solveLine(std::size_t i, const std::vector<double>& Xv, StaticResult& out, std::string& why) const {
    try {
      out = solveStaticModel(s_.lineProblem(i, Xv));
    } catch (const std::invalid_argument& e) {
      why = "line " + s_.lines[i].name + ": " + e.what();
      return false;
    }
    if (!out.summary.converged) {
      why = "line " + s_.lines[i].name + ": " + out.summary.message;
      return false;
    }
    return true;
  }

  void evaluateAll(const std::vector<double>& Xv, Evaluation& ev) const {
    ev.lines.assign(nl_, StaticResult{});
    ev.ok = true;
    for (std::size_t i = 0; i < nl_ && ev.ok; ++i) ev.ok = solveLine(i, Xv, ev.lines[i], ev.message);
  }

  /// Force on point p [N]: the pulls of its lines plus its own load.
  void pointForce(std::size_t p, const std::vector<double>& Xv, const std::vector<StaticResult>& res, double* F) const {
    pointLoad(s_, s_.points[p], Xv.data() + 3 * p, F);
    for (std::size_t i : at_[p]) {
      const StaticResult& r = res[i];
      if (s_.lines[i].to == p) {  // the line pulls its upper point with -top_force
        F[0] -= r.top_force_x;
        F[1] -= r.top_force_y;
        F[2] -= r.top_force_z;
      } else {  // and its lower point with anchor_force
        F[0] += r.anchor_force_x;
        F[1] += r.anchor_force_y;
        F[2] += r.anchor_force_z;
      }
    }
  }

  /// The force balance G of every free point (3 each).
  void residual(const std::vector<double>& Xv, const std::vector<StaticResult>& res, Eigen::VectorXd& G) const {
    G.resize(m_);
    for (std::size_t k = 0; k < free_pts_.size(); ++k) {
      double F[3];
      pointForce(free_pts_[k], Xv, res, F);
      for (int c = 0; c < 3; ++c) G[static_cast<Eigen::Index>(3 * k + c)] = F[c];
    }
  }

  /// The largest tension of the lines [N] (at least 1): the force the tolerance refers to.
  static double scaleOf(const std::vector<StaticResult>& res) {
    double T = 1.0;
    for (const auto& r : res)
      for (const auto& n : r.nodes) T = std::max(T, std::abs(n.tension));
    return T;
  }

  /// Newton iterations on G from X; returns their number. Stops converged, at the limit, or with
  /// out.summary.message saying why.
  int iterate(std::vector<double>& X, Evaluation& ev, Eigen::VectorXd& G, SystemStaticResult& out) const {
    int it = 0;
    for (; it < o_.max_iterations; ++it) {
      const double tol = o_.force_tolerance * scaleOf(ev.lines);
      if (std::getenv("MD_SYSTEM_TRACE")) trace(it, X, G, tol);
      if (m_ == 0 || G.cwiseAbs().maxCoeff() < tol) {
        out.summary.converged = true;
        break;
      }
      Eigen::MatrixXd J;
      if (!pointJacobian(X, ev, G, J)) {
        out.summary.message = "a line did not solve while differentiating: " + ev.message;
        break;
      }
      const Eigen::VectorXd dX = J.fullPivLu().solve(-G);
      if (!backtrack(dX, X, ev, G)) {
        out.summary.message = "no step reduced the force residual (a line would not solve along it)";
        break;
      }
    }
    return it;
  }

  void trace(int it, const std::vector<double>& X, const Eigen::VectorXd& G, double tol) const {
    std::fprintf(stderr, "system %d |G| %.3e tol %.3e", it, m_ ? G.cwiseAbs().maxCoeff() : 0.0, tol);
    for (std::size_t p : free_pts_) std::fprintf(stderr, "  %s (%.3f %.3f %.3f)", s_.points[p].name.c_str(), X[3 * p], X[3 * p + 1], X[3 * p + 2]);
    std::fprintf(stderr, "\n");
  }

  /// Point Jacobian dG/dX by finite differences: perturbing point p re-solves only its lines, and
  /// changes only the balance of the points those lines join. False when a line fails.
  bool pointJacobian(const std::vector<double>& X, Evaluation& ev, const Eigen::VectorXd& G, Eigen::MatrixXd& J) const {
    J = Eigen::MatrixXd::Zero(m_, m_);
    bool jac_ok = true;
    for (std::size_t k = 0; k < free_pts_.size() && jac_ok; ++k) {
      const std::size_t p = free_pts_[k];
      for (int c = 0; c < 3 && jac_ok; ++c) {
        if (c == 1 && s_.formulation == Formulation::TwoD) {
          // A 2-D system stays in the plane y = 0: y is not an unknown (its residual is 0).
          J(static_cast<Eigen::Index>(3 * k + 1), static_cast<Eigen::Index>(3 * k + 1)) = 1.0;
          continue;
        }
        std::vector<double> Xp = X;
        Xp[3 * p + c] += o_.fd_step;
        std::vector<StaticResult> res = ev.lines;
        for (std::size_t i : at_[p]) jac_ok = jac_ok && solveLine(i, Xp, res[i], ev.message);
        if (!jac_ok) break;
        Eigen::VectorXd Gp;
        residual(Xp, res, Gp);
        J.col(static_cast<Eigen::Index>(3 * k + c)) = (Gp - G) / o_.fd_step;
      }
    }
    return jac_ok;
  }

  /// The update dX, no point moving by more than max_move of its shortest line, halved until the
  /// largest force residual falls (the last halving is taken regardless). False when no trial
  /// could be evaluated.
  bool backtrack(const Eigen::VectorXd& dX, std::vector<double>& X, Evaluation& ev, Eigen::VectorXd& G) const {
    double scale = 1.0;
    for (std::size_t k = 0; k < free_pts_.size(); ++k) {
      const double move = dX.segment<3>(static_cast<Eigen::Index>(3 * k)).norm();
      const double limit = o_.max_move * shortest_[free_pts_[k]];
      if (move > limit) scale = std::min(scale, limit / move);
    }
    constexpr int kHalvings = 12;
    for (int half = 0; half < kHalvings; ++half, scale *= 0.5) {
      std::vector<double> Xt = X;
      for (std::size_t k = 0; k < free_pts_.size(); ++k)
        for (int c = 0; c < 3; ++c) Xt[3 * free_pts_[k] + c] += scale * dX[static_cast<Eigen::Index>(3 * k + c)];
      Evaluation et;
      evaluateAll(Xt, et);
      if (!et.ok) continue;
      Eigen::VectorXd Gt;
      residual(Xt, et.lines, Gt);
      if (Gt.cwiseAbs().maxCoeff() < G.cwiseAbs().maxCoeff() || half == kHalvings - 1) {
        X = Xt;
        ev = std::move(et);
        G = Gt;
        return true;
      }
    }
    return false;
  }

  void summarize(int it, const Eigen::VectorXd& G, SystemStaticResult& out) const {
    out.summary.iterations = it;
    out.summary.error = m_ ? G.cwiseAbs().maxCoeff() : 0.0;
    if (out.summary.converged) {
      out.summary.message = "converged in " + std::to_string(it) + " point iterations (largest force residual " +
                            fmt(out.summary.error) + " N)";
    } else if (out.summary.message.empty()) {
      out.summary.message = "did not converge in " + std::to_string(o_.max_iterations) +
                            " point iterations: largest force residual " + fmt(out.summary.error) + " N";
    }
  }

  /// Every point's position, the lines' pull on it and, for a free point, its force residual.
  void pointResults(const std::vector<double>& X, const Evaluation& ev, SystemStaticResult& out) const {
    for (std::size_t p = 0; p < np_; ++p) {
      SystemPointResult pr;
      pr.name = s_.points[p].name;
      pr.x = X[3 * p];
      pr.y = X[3 * p + 1];
      pr.z = X[3 * p + 2];
      double F[3];
      pointForce(p, X, ev.lines, F);
      double load[3];
      pointLoad(s_, s_.points[p], X.data() + 3 * p, load);
      pr.fx = F[0] - load[0];  // the lines' pulls alone
      pr.fy = F[1] - load[1];
      pr.fz = F[2] - load[2];
      if (s_.points[p].free()) pr.residual = std::sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
      if (s_.points[p].type == SystemPoint::Type::Buoy) pr.buoy_draft = -pr.z;
      out.points.push_back(pr);
    }
  }

  const SystemProblem& s_;
  const SystemSolveOptions& o_;
  const std::size_t np_, nl_;
  std::vector<std::size_t> free_pts_;         ///< the free points
  std::vector<std::vector<std::size_t>> at_;  ///< the lines with an end at each point
  std::vector<double> shortest_;              ///< the shortest line at each point [m]
  int m_ = 0;                                 ///< unknowns: 3 per free point
};

}  // namespace

SystemStaticResult solveSystemStatic(const SystemProblem& s, const SystemSolveOptions& o) {
  const std::string err = s.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  return SystemStaticSolver(s, o).solve();
}

}  // namespace core
}  // namespace mooring_dynamics
