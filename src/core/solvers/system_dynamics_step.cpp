// One step of a system of lines (SystemDynamics::advanceTo, DESIGN.md section 6): every line
// through the step with its ends on the vessel's path or on the free points, the free points by
// Newmark's trapezoidal rule in a point iteration per group (finite-difference Jacobian, kept
// while the iteration contracts), a failed group restarted from statics alone.
#include <algorithm>
#include <cmath>

#include "system_dynamics_impl.hpp"

namespace mooring_dynamics {
namespace core {

struct SystemDynamics::Impl::Step {
  double dt = 0.0, t1 = 0.0;  ///< step length [s], its end (system time) [s]
  std::vector<std::shared_ptr<const DynamicSolver3D::Saved>> saved;  ///< each line at the step's start
  Eigen::VectorXd X1, V1, A1;          ///< the points at t1 (all points, 3 each): the iterate
  RigidMotion vm;                      ///< the vessel at t1
  std::vector<Restart> restarts;       ///< groups to restart at t1
  std::string abort_why;               ///< why the step cannot be taken
  std::vector<std::size_t> group_of;   ///< group of each line
};

void SystemDynamics::Impl::kinematics(const Step& s, const Eigen::VectorXd& X1, Eigen::VectorXd& V1,
                                      Eigen::VectorXd& A1) const {
  const double dt = s.dt;
  A1 = (X1 - X - dt * V - dt * dt * (0.5 - kBeta) * A) / (kBeta * dt * dt);
  V1 = V + dt * ((1.0 - kGamma) * A + kGamma * A1);
}

std::function<TopState(double)> SystemDynamics::Impl::endMotion(const Step& s, std::size_t i, std::size_t p,
                                                                const Eigen::VectorXd& X1,
                                                                const Eigen::VectorXd& V1) const {
  // A point's motion over the step: position and velocity linear in time from (X, V) at t to
  // (X1, V1) at t1 (a fixed point stays where it is).
  auto pointMotion = [&]() {
    const double t0 = t, dt = s.dt;
    const Eigen::Vector3d x0 = X.segment<3>(static_cast<Eigen::Index>(3 * p)),
                          v0 = V.segment<3>(static_cast<Eigen::Index>(3 * p)),
                          x1 = X1.segment<3>(static_cast<Eigen::Index>(3 * p)),
                          v1 = V1.segment<3>(static_cast<Eigen::Index>(3 * p));
    return [=](double tau) {
      const double w = dt > 0.0 ? std::clamp((tau - t0) / dt, 0.0, 1.0) : 1.0;
      const Eigen::Vector3d x = x0 + w * (x1 - x0), v = v0 + w * (v1 - v0);
      return TopState::prescribed(x.data(), v.data());
    };
  };
  std::function<TopState(double)> f = isVessel(p) ? fairleadMotion(p) : std::function<TopState(double)>(pointMotion());
  const double off = line_t0[i];
  if (off == 0.0) return f;
  return std::function<TopState(double)>([f, off](double tau) { return f(tau + off); });
}

std::vector<std::pair<std::size_t, std::string>> SystemDynamics::Impl::runSet(const Step& s,
                                                                              const std::vector<std::size_t>& all,
                                                                              const Eigen::VectorXd& X1,
                                                                              const Eigen::VectorXd& V1) {
  std::vector<std::size_t> set;
  for (std::size_t i : all)
    if (!retired[i]) set.push_back(i);
  std::vector<StepReport> reports(set.size());
  // Each line writes only its own solver and report.
  pool->parallelFor(set.size(), [&](std::size_t k) {
    const std::size_t i = set[k];
    DynamicSolver3D& line = *lines[i];
    const SystemLine& sl = system.lines[i];
    line.restore(*s.saved[i]);
    line.setTopInput(endMotion(s, i, sl.to, X1, V1));
    if (sl.from != SystemLine::kFreeEnd && (system.points[sl.from].free() || isVessel(sl.from)))
      line.setLowerEndInput(endMotion(s, i, sl.from, X1, V1));
    reports[k] = line.advanceTo(s.t1 - line_t0[i]);
  });
  line_steps += static_cast<long>(set.size());
  std::vector<std::pair<std::size_t, std::string>> failed;
  for (std::size_t k = 0; k < set.size(); ++k) {
    if (reports[k].ok && fail_hook && fail_hook(set[k], s.t1)) {
      reports[k].ok = false;
      reports[k].message = "failure injected (test hook)";
    }
    if (!reports[k].ok && loose(set[k])) {
      // Let go from everything that moves: held where it was, reported, and the step goes on.
      lines[set[k]]->restore(*s.saved[set[k]]);
      retired[set[k]] = 1;
      LineEventRecord r;
      r.t = t;
      r.what = "retired";
      r.line = system.lines[set[k]].name;
      r.cause = "the loose line stopped converging (" + reports[k].message +
                "); it pulls on nothing that moves and is held where it was from here on";
      retired_log.push_back(r);
      continue;
    }
    if (!reports[k].ok) failed.emplace_back(set[k], "line " + system.lines[set[k]].name + ": " + reports[k].message);
  }
  return failed;
}

bool SystemDynamics::Impl::restart(Step& s, std::size_t g, const std::string& reason) {
  if (!restart_failed_groups) {
    s.abort_why = reason;
    return false;
  }
  Restart r;
  std::string why;
  if (!restartGroup(g, s.t1, s.vm.pose, r, why)) {
    s.abort_why = reason + "; restarting its group from statics failed too: " + why;
    return false;
  }
  r.report.reason = reason;
  s.restarts.push_back(std::move(r));
  return true;
}

bool SystemDynamics::Impl::stepGroup(Step& s, std::size_t g, std::string& why) {
  const std::vector<std::size_t>& pts = group_pts[g];
  const int m = static_cast<int>(3 * pts.size());
  Eigen::VectorXd& X1 = s.X1;
  // Run every line with an end at one of `ps` through the step with the points at Xa.
  auto runLines = [&](const std::vector<std::size_t>& ps, const Eigen::VectorXd& Xa, const Eigen::VectorXd& Va) {
    std::vector<char> done(lines.size(), 0);
    std::vector<std::size_t> set;
    for (std::size_t p : ps)
      for (std::size_t i : lines_at[p])
        if (!done[i]) {
          done[i] = 1;
          set.push_back(i);
        }
    const auto failed = runSet(s, set, Xa, Va);
    if (!failed.empty()) why = failed.front().second;
    return failed.empty();
  };
  // Force balance of the group's free points: M a - (pulls + own load).
  double scale = 1.0;
  auto residual = [&](const Eigen::VectorXd& Xa, const Eigen::VectorXd& Va, const Eigen::VectorXd& Aa,
                      Eigen::VectorXd& G) {
    G.resize(m);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const std::size_t p = pts[k];
      double F[3];
      load(p, Xa.data() + 3 * p, Va.data() + 3 * p, s.t1, F);
      scale = std::max({scale, std::abs(F[2])});
      for (std::size_t i : lines_at[p]) {
        // A line pulls its upper point with -top_force and its lower point with anchor_force.
        const StaticResult st = lines[i]->snapshot();
        const bool top = system.lines[i].to == p;
        const double f[3] = {top ? -st.top_force_x : st.anchor_force_x, top ? -st.top_force_y : st.anchor_force_y,
                             top ? -st.top_force_z : st.anchor_force_z};
        for (int c = 0; c < 3; ++c) {
          F[c] += f[c];
          scale = std::max(scale, std::abs(f[c]));
        }
      }
      for (int c = 0; c < 3; ++c)
        G[static_cast<Eigen::Index>(3 * k + c)] = mass(p) * Aa[static_cast<Eigen::Index>(3 * p + c)] - F[c];
    }
  };
  Eigen::VectorXd G;
  if (!runLines(pts, X1, s.V1)) return false;
  residual(X1, s.V1, s.A1, G);
  bool converged = false;
  double g_prev = 0.0;
  Eigen::MatrixXd& Jg = J[g];
  for (int it = 0; it < kMaxPointIterations && !converged; ++it) {
    const double gm = G.cwiseAbs().maxCoeff();
    if (gm < kForceTolerance * scale) {
      converged = true;
      break;
    }
    // Point Jacobian by finite differences, kept across steps while the iteration contracts.
    if (Jg.rows() != m || (it > 0 && gm > 0.25 * g_prev)) {
      Jg.resize(m, m);
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const std::size_t p = pts[k];
        for (int c = 0; c < 3; ++c) {
          Eigen::VectorXd Xp = X1, Vp, Ap, Gp;
          Xp[static_cast<Eigen::Index>(3 * p + c)] += kFdStep;
          kinematics(s, Xp, Vp, Ap);
          if (!runLines({p}, Xp, Vp)) return false;
          residual(Xp, Vp, Ap, Gp);
          // Only the lines at p changed: the other points' rows are unchanged but for M a.
          Jg.col(static_cast<Eigen::Index>(3 * k + c)) = (Gp - G) / kFdStep;
        }
        if (!runLines({p}, X1, s.V1)) return false;  // back to the current iterate
      }
    }
    g_prev = gm;
    const Eigen::VectorXd dX = Jg.fullPivLu().solve(-G);
    for (std::size_t k = 0; k < pts.size(); ++k)
      X1.segment<3>(static_cast<Eigen::Index>(3 * pts[k])) += dX.segment<3>(static_cast<Eigen::Index>(3 * k));
    kinematics(s, X1, s.V1, s.A1);
    if (!runLines(pts, X1, s.V1)) return false;
    residual(X1, s.V1, s.A1, G);
    ++iterations;
  }
  if (!converged && G.cwiseAbs().maxCoeff() >= kForceTolerance * scale) {
    why = "the point iteration did not converge: force residual " + std::to_string(G.cwiseAbs().maxCoeff()) + " N";
    return false;
  }
  return true;
}

void SystemDynamics::Impl::commitRestarts(Step& s) {
  for (Restart& r : s.restarts) {
    const std::vector<std::size_t>& gl = groups[r.group];
    for (std::size_t k = 0; k < gl.size(); ++k) {
      if (fallback_before.size() < lines.size()) fallback_before.resize(lines.size(), 0);
      fallback_before[gl[k]] += lines[gl[k]]->totals().fallback_steps;
      lines[gl[k]] = std::move(r.lines[k]);
      line_t0[gl[k]] = s.t1;
    }
    const std::vector<std::size_t>& gp = group_pts[r.group];
    for (std::size_t k = 0; k < gp.size(); ++k) {
      s.X1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])) = r.points[k];
      s.V1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])).setZero();
      s.A1.segment<3>(static_cast<Eigen::Index>(3 * gp[k])).setZero();
    }
    J[r.group].resize(0, 0);
    restarts.push_back(r.report);
  }
}

bool SystemDynamics::Impl::step(double t_end, std::string* message) {
  Step s;
  s.dt = std::min(opt.dt, t_end - t);
  s.t1 = t + s.dt;
  for (const auto& l : lines) s.saved.push_back(l->save());
  // Predictor: constant acceleration.
  s.X1 = X + s.dt * V + 0.5 * s.dt * s.dt * A;
  kinematics(s, s.X1, s.V1, s.A1);
  s.vm = vessel_motion(s.t1);
  s.group_of.resize(lines.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t i : groups[g]) s.group_of[i] = g;

  // The lines on the vessel that touch no free point (each a group of its own): once per step,
  // side by side; a failed one restarts alone.
  bool ok = true;
  for (const auto& f : runSet(s, vessel_lines, s.X1, s.V1)) ok = ok && restart(s, s.group_of[f.first], f.second);
  // Each group with free points: its own point iteration (so that its bits do not depend on the
  // other groups), its lines side by side.
  for (std::size_t g = 0; g < groups.size() && ok; ++g) {
    if (group_pts[g].empty()) continue;
    std::string why;
    if (!stepGroup(s, g, why)) ok = restart(s, g, why);
  }
  if (!ok) {
    // A failed group not restarted, or its statics failed too: the whole step is undone (the replacements are dropped).
    for (std::size_t i = 0; i < lines.size(); ++i) lines[i]->restore(*s.saved[i]);
    if (message) *message = "t = " + std::to_string(s.t1) + " s: " + s.abort_why;
    return false;
  }
  commitRestarts(s);
  // The vessel's points are where its motion puts them (the Newmark values above are only
  // meaningful for the free points).
  for (std::size_t p = 0; p < system.points.size(); ++p) {
    if (!isVessel(p)) continue;
    const Eigen::Vector3d r = system.points[p].body_offset;
    s.X1.segment<3>(static_cast<Eigen::Index>(3 * p)) = s.vm.pose.apply(r);
    s.V1.segment<3>(static_cast<Eigen::Index>(3 * p)) = s.vm.pointVelocity(r);
    s.A1.segment<3>(static_cast<Eigen::Index>(3 * p)).setZero();
  }
  vessel_pose = s.vm.pose;
  X = s.X1;
  V = s.V1;
  A = s.A1;
  t = s.t1;
  return true;
}

}  // namespace core
}  // namespace mooring_dynamics
