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
    const double q = 0.5 * s.environment.water_density * 0.25 * eq2d::kPi * b.diameter * b.diameter * b.cdn;
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

}  // namespace

SystemStaticResult solveSystemStatic(const SystemProblem& s, const SystemSolveOptions& o) {
  const std::string err = s.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  const std::size_t np = s.points.size(), nl = s.lines.size();

  // Free points and the lines at each point.
  std::vector<std::size_t> free_pts;
  std::vector<int> slot(np, -1);
  for (std::size_t p = 0; p < np; ++p)
    if (s.points[p].free()) {
      slot[p] = static_cast<int>(free_pts.size());
      free_pts.push_back(p);
    }
  std::vector<std::vector<std::size_t>> at(np);
  std::vector<double> shortest(np, 1e300);
  for (std::size_t i = 0; i < nl; ++i) {
    const SystemLine& l = s.lines[i];
    double L = 0.0;
    for (const Segment& g : l.segments) L += g.length;
    at[l.to].push_back(i);
    shortest[l.to] = std::min(shortest[l.to], L);
    if (l.from != SystemLine::kFreeEnd) {
      at[l.from].push_back(i);
      shortest[l.from] = std::min(shortest[l.from], L);
    }
  }

  // Initial positions: fixed points as given; a free point without a guess at the mean of the
  // fixed points it is joined to (of all fixed points if none), a buoy at the surface.
  std::vector<double> X(3 * np);
  for (std::size_t p = 0; p < np; ++p) {
    X[3 * p] = s.points[p].x;
    X[3 * p + 1] = s.points[p].y;
    X[3 * p + 2] = s.points[p].z;
  }
  for (std::size_t p : free_pts) {
    const SystemPoint& pt = s.points[p];
    if (pt.position_given) continue;
    double sx = 0, sy = 0, sz = 0;
    int k = 0;
    auto add = [&](std::size_t q) {
      if (s.points[q].free()) return;
      sx += s.points[q].x;
      sy += s.points[q].y;
      sz += s.points[q].z;
      ++k;
    };
    for (std::size_t i : at[p]) {
      add(s.lines[i].to);
      if (s.lines[i].from != SystemLine::kFreeEnd) add(s.lines[i].from);
    }
    if (k == 0)
      for (std::size_t q = 0; q < np; ++q) add(q);
    X[3 * p] = sx / k;
    X[3 * p + 1] = sy / k;
    X[3 * p + 2] = pt.type == SystemPoint::Type::Buoy ? -0.5 * pt.buoy.totalHeight() : sz / k;
  }

  auto solveLine = [&](std::size_t i, const std::vector<double>& Xv, StaticResult& out, std::string& why) {
    try {
      out = solveStaticModel(s.lineProblem(i, Xv));
    } catch (const std::invalid_argument& e) {
      why = "line " + s.lines[i].name + ": " + e.what();
      return false;
    }
    if (!out.summary.converged) {
      why = "line " + s.lines[i].name + ": " + out.summary.message;
      return false;
    }
    return true;
  };
  auto evaluateAll = [&](const std::vector<double>& Xv, Evaluation& ev) {
    ev.lines.assign(nl, StaticResult{});
    ev.ok = true;
    for (std::size_t i = 0; i < nl && ev.ok; ++i) ev.ok = solveLine(i, Xv, ev.lines[i], ev.message);
  };
  // Force on point p [N]: the pulls of its lines plus its own load.
  auto pointForce = [&](std::size_t p, const std::vector<double>& Xv, const std::vector<StaticResult>& res,
                        double* F) {
    pointLoad(s, s.points[p], Xv.data() + 3 * p, F);
    for (std::size_t i : at[p]) {
      const StaticResult& r = res[i];
      if (s.lines[i].to == p) {  // the line pulls its upper point with -top_force
        F[0] -= r.top_force_x;
        F[1] -= r.top_force_y;
        F[2] -= r.top_force_z;
      } else {  // and its lower point with anchor_force
        F[0] += r.anchor_force_x;
        F[1] += r.anchor_force_y;
        F[2] += r.anchor_force_z;
      }
    }
  };
  const int m = static_cast<int>(3 * free_pts.size());
  auto residual = [&](const std::vector<double>& Xv, const std::vector<StaticResult>& res, Eigen::VectorXd& G) {
    G.resize(m);
    for (std::size_t k = 0; k < free_pts.size(); ++k) {
      double F[3];
      pointForce(free_pts[k], Xv, res, F);
      for (int c = 0; c < 3; ++c) G[static_cast<Eigen::Index>(3 * k + c)] = F[c];
    }
  };
  auto scaleOf = [&](const std::vector<StaticResult>& res) {
    double T = 1.0;
    for (const auto& r : res)
      for (const auto& n : r.nodes) T = std::max(T, std::abs(n.tension));
    return T;
  };

  SystemStaticResult out;
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
  int it = 0;
  for (; it < o.max_iterations; ++it) {
    const double tol = o.force_tolerance * scaleOf(ev.lines);
    if (std::getenv("MD_SYSTEM_TRACE")) {
      std::fprintf(stderr, "system %d |G| %.3e tol %.3e", it, m ? G.cwiseAbs().maxCoeff() : 0.0, tol);
      for (std::size_t p : free_pts) std::fprintf(stderr, "  %s (%.3f %.3f %.3f)", s.points[p].name.c_str(), X[3 * p], X[3 * p + 1], X[3 * p + 2]);
      std::fprintf(stderr, "\n");
    }
    if (m == 0 || G.cwiseAbs().maxCoeff() < tol) {
      out.summary.converged = true;
      break;
    }
    // Point Jacobian by finite differences: perturbing point p re-solves only its lines, and
    // changes only the balance of the points those lines join.
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, m);
    bool jac_ok = true;
    for (std::size_t k = 0; k < free_pts.size() && jac_ok; ++k) {
      const std::size_t p = free_pts[k];
      for (int c = 0; c < 3 && jac_ok; ++c) {
        if (c == 1 && s.formulation == Formulation::TwoD) {
          // A 2-D system stays in the plane y = 0: y is not an unknown (its residual is 0).
          J(static_cast<Eigen::Index>(3 * k + 1), static_cast<Eigen::Index>(3 * k + 1)) = 1.0;
          continue;
        }
        std::vector<double> Xp = X;
        Xp[3 * p + c] += o.fd_step;
        std::vector<StaticResult> res = ev.lines;
        for (std::size_t i : at[p]) jac_ok = jac_ok && solveLine(i, Xp, res[i], ev.message);
        if (!jac_ok) break;
        Eigen::VectorXd Gp;
        residual(Xp, res, Gp);
        J.col(static_cast<Eigen::Index>(3 * k + c)) = (Gp - G) / o.fd_step;
      }
    }
    if (!jac_ok) {
      out.summary.message = "a line did not solve while differentiating: " + ev.message;
      break;
    }
    Eigen::VectorXd dX = J.fullPivLu().solve(-G);
    // No point moves by more than a fraction of its shortest line in one iteration.
    double scale = 1.0;
    for (std::size_t k = 0; k < free_pts.size(); ++k) {
      const double move = dX.segment<3>(static_cast<Eigen::Index>(3 * k)).norm();
      const double limit = o.max_move * shortest[free_pts[k]];
      if (move > limit) scale = std::min(scale, limit / move);
    }
    // Backtracking on the largest force residual.
    bool accepted = false;
    for (int half = 0; half < 12 && !accepted; ++half, scale *= 0.5) {
      std::vector<double> Xt = X;
      for (std::size_t k = 0; k < free_pts.size(); ++k)
        for (int c = 0; c < 3; ++c) Xt[3 * free_pts[k] + c] += scale * dX[static_cast<Eigen::Index>(3 * k + c)];
      Evaluation et;
      evaluateAll(Xt, et);
      if (!et.ok) continue;
      Eigen::VectorXd Gt;
      residual(Xt, et.lines, Gt);
      if (Gt.cwiseAbs().maxCoeff() < G.cwiseAbs().maxCoeff() || half == 11) {
        X = Xt;
        ev = std::move(et);
        G = Gt;
        accepted = true;
      }
    }
    if (!accepted) {
      out.summary.message = "no step reduced the force residual (a line would not solve along it)";
      break;
    }
  }
  out.summary.iterations = it;
  out.summary.error = m ? G.cwiseAbs().maxCoeff() : 0.0;
  if (out.summary.converged) {
    out.summary.message = "converged in " + std::to_string(it) + " point iterations (largest force residual " +
                          fmt(out.summary.error) + " N)";
  } else if (out.summary.message.empty()) {
    out.summary.message = "did not converge in " + std::to_string(o.max_iterations) +
                          " point iterations: largest force residual " + fmt(out.summary.error) + " N";
  }
  out.lines = ev.lines;
  for (std::size_t p = 0; p < np; ++p) {
    SystemPointResult pr;
    pr.name = s.points[p].name;
    pr.x = X[3 * p];
    pr.y = X[3 * p + 1];
    pr.z = X[3 * p + 2];
    double F[3];
    pointForce(p, X, ev.lines, F);
    double load[3];
    pointLoad(s, s.points[p], X.data() + 3 * p, load);
    pr.fx = F[0] - load[0];  // the lines' pulls alone
    pr.fy = F[1] - load[1];
    pr.fz = F[2] - load[2];
    if (s.points[p].free()) pr.residual = std::sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    if (s.points[p].type == SystemPoint::Type::Buoy) pr.buoy_draft = -pr.z;
    out.points.push_back(pr);
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
