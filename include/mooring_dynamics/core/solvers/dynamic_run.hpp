// Parts of a dynamic run shared by the 2-D and 3-D solvers: adaptive time stepping (paper
// section 4.3) around a solver's single step, and a whole run of problem.dynamics on the output
// grid. Templates over the solver type (DynamicSolver2D, DynamicSolver3D).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "mooring_dynamics/core/solvers/dynamics2d.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/top_motion.hpp"
#include "mooring_dynamics/core/numerics/newton.hpp"

namespace mooring_dynamics {
namespace core {

/// Newton options of one time step from the problem's dynamics options (section 6 per step).
inline NewtonOptions stepNewtonOptions(const DynamicOptions& o) {
  NewtonOptions no;
  no.tolerance = o.tolerance;
  no.max_iterations = o.max_iterations;
  no.mu0 = o.relaxation;
  no.adaptive = o.adaptive_relaxation;
  no.reuse_jacobian = o.jacobian_reuse;  // modified Newton (dynamics.jacobian_reuse)
  no.reuse_rate = o.jacobian_reuse_rate;
  // Stop on the estimated error left (NewtonOptions::estimate_convergence): on the shipped A.3
  // and A.2 runs this saves 16-24 % of the iterations and moves the top tension by 0.4 N and
  // 0.005 N rms, against some 200 N between base steps of 0.1 and 0.05 s.
  no.estimate_convergence = true;
  // With a kept Jacobian the estimate leaves up to a tenth of the tolerance at each step; a scheme
  // that does not damp the highest frequencies (box, spectral radius 1 at infinity) keeps what
  // each step leaves, and on A.2 at 0.1 s box then took 34 001 iterations and 2 cuts instead of
  // 29 325 and 1: there the kept Jacobian stops on eq. 39 alone.
  constexpr double kUndampedRadius = 1.0 - 1e-9;
  if (!(o.scheme.spectralRadius(1e12) < kUndampedRadius)) no.estimate_kept_margin = 0.0;
  no.damp_two_cycles = o.damp_two_cycles;  // dynamics.damp_two_cycles
  return no;
}

/// Whether two step sizes are the same for a kept factorization or extrapolation: equal up to the
/// rounding of t_end - t when a step lands on an output sample (dt = 0.1 s gives steps that
/// differ from 0.1 in the last bits).
inline bool sameStepSize(double a, double b) {
  constexpr double kRelative = 1e-9;
  return std::abs(a - b) <= kRelative * std::max(std::abs(a), std::abs(b));
}

/// The top's path between two samples as the lockstep drivers and position tables give it: the
/// position linear from (x0, y0, z0) at t0 to (x1, y1, z1) at t1 > t0, held outside, and the
/// velocity the segment's slope at every tau (also at its ends). The 2-D form drops y.
inline TopState segmentTopState(double tau, double t0, double x0, double y0, double z0, double t1, double x1, double y1,
                                double z1) {
  const double span = t1 - t0;
  TopState in;
  const double w = std::clamp((tau - t0) / span, 0.0, 1.0);
  in.x = x0 + w * (x1 - x0);
  in.y = y0 + w * (y1 - y0);
  in.z = z0 + w * (z1 - z0);
  in.vx = (x1 - x0) / span;
  in.vy = (y1 - y0) / span;
  in.vz = (z1 - z0) / span;
  return in;
}
inline TopInput segmentTopInput(double tau, double t0, double x0, double z0, double t1, double x1, double z1) {
  const double span = t1 - t0;
  TopInput in;
  const double w = std::clamp((tau - t0) / span, 0.0, 1.0);
  in.x = x0 + w * (x1 - x0);
  in.z = z0 + w * (z1 - z0);
  in.vx = (x1 - x0) / span;
  in.vz = (z1 - z0) / span;
  return in;
}

namespace detail {
/// Section 4.3: try a step; on failure cut it by 10 and take ten sub-steps, recursively, down to
/// `max_levels` cuts. `t` is the solver's time, which try_step advances on success.
template <class TryStep, class OnCut>
bool stepWithCuts(double& t, double dt, int level, int max_levels, StepReport& rep, TryStep& try_step,
                  OnCut& on_cut) {
  if (try_step(dt, rep)) return true;
  if (level >= max_levels) {
    rep.message = "adaptive time stepping exhausted at " + std::to_string(level) + " cuts (dt = " +
                  std::to_string(dt) + " s): " + rep.message;
    return false;
  }
  ++rep.cuts;
  on_cut();
  const double t0 = t;
  for (int k = 1; k <= 10; ++k) {
    const double target = t0 + dt * k / 10.0;
    if (!stepWithCuts(t, target - t, level + 1, max_levels, rep, try_step, on_cut)) return false;
  }
  return true;
}
}  // namespace detail

/// A solver without a fallback step: a step that fails at the smallest size stops the run.
struct NoFallback {
  int levels(int max_levels) const { return max_levels; }
  bool operator()(double, StepReport&) const { return false; }
};

/// Advance the solver time `t` to t_end in base steps `base` (the last one shortened to land on
/// t_end), each with adaptive cutting. try_step(dt, report) -> bool takes one step of dt from the
/// accepted state; on_cut() counts a cut. A base step that fails at `max_levels` cuts goes to
/// fallback(dt_left, report) -> bool for the rest of the base step (the 3-D solver's lumped-mass
/// step); fallback.levels(max_levels) says how many cuts a base step gets before that (fewer
/// than max_levels when the fallback is there, none right after a fallback step, and -1 for a
/// base step that goes to the fallback without an implicit try). On failure the report says why and t stays at the last converged time.
template <class TryStep, class OnCut, class Fallback = NoFallback>
StepReport advanceWithCuts(double& t, double base, int max_levels, double t_end, TryStep try_step, OnCut on_cut,
                           Fallback fallback = Fallback()) {
  StepReport rep;
  const double eps = 1e-9 * base;
  if (t_end < t - eps) {
    rep.ok = false;
    rep.message = "advanceTo: t_end = " + std::to_string(t_end) + " s is before the current time " +
                  std::to_string(t) + " s";
    return rep;
  }
  while (t < t_end - eps) {
    const double dt = std::min(base, t_end - t);
    const double t_base_end = t + dt;
    const int levels = fallback.levels(max_levels);
    if (levels < 0 || !detail::stepWithCuts(t, dt, 0, levels, rep, try_step, on_cut)) {
      if (!fallback(t_base_end - t, rep)) {
        rep.ok = false;
        return rep;
      }
      t = t_base_end;
    }
  }
  t = std::max(t, t_end);
  return rep;
}

/// Run problem.dynamics with `Solver` from its static solution: samples on the output grid (plus
/// the end time when the duration is not a whole multiple of it), recorded nodes, snapshots.
/// `progress(t, duration)` is called after every output sample when given.
/// Relative shortfall of the last sample's time below dynamics.duration that still counts as the
/// end: the sample times are k * dout, exact to a few ulps, far inside 1e-9.
inline constexpr double kEndTimeTolerance = 1e-9;

namespace detail {

/// What a run records: the output samples of the top, the anchor and the recorded nodes (the
/// nodes nearest to dynamics.record_s), and the snapshots of the whole line.
template <class Solver>
class SeriesRecorder {
 public:
  SeriesRecorder(const Solver& solver, const Problem& problem, double dout, DynamicSeries& out)
      : solver_(solver), problem_(problem), out_(out) {
    const DynamicOptions& opt = problem.dynamics;
    findRecordedNodes();
    out.record_s.clear();
    for (std::size_t i : rec_) out.record_s.push_back(s_[i]);
    out.node_tension.assign(rec_.size(), {});
    out.node_x.assign(rec_.size(), {});
    out.node_y.assign(rec_.size(), {});
    out.node_z.assign(rec_.size(), {});
    snap_every_ = opt.snapshot_interval > 0.0
                      ? std::max(1L, static_cast<long>(std::llround(opt.snapshot_interval / dout)))
                      : 0;
  }

  /// Sample k, at time t.
  void record(double t, long k) {
    const StaticResult r = solver_.snapshot();
    if (r.nodes.size() != s_.size()) findRecordedNodes();  // a winch added or took out nodes
    out_.t.push_back(t);
    out_.top_tension.push_back(r.nodes.back().tension);
    out_.anchor_tension.push_back(r.nodes.front().tension);
    out_.top_x.push_back(r.nodes.back().x);
    out_.top_y.push_back(r.nodes.back().y);
    out_.top_z.push_back(r.nodes.back().z);
    out_.peak.add(problem_.materials, problem_.segments, r.nodes, t);
    if constexpr (!std::is_same_v<Solver, DynamicSolver2D>)
      if (problem_.dynamics.winch.given) out_.line_length.push_back(solver_.lineLength());
    for (std::size_t i = 0; i < rec_.size(); ++i) {
      out_.node_tension[i].push_back(r.nodes[rec_[i]].tension);
      out_.node_x[i].push_back(r.nodes[rec_[i]].x);
      out_.node_y[i].push_back(r.nodes[rec_[i]].y);
      out_.node_z[i].push_back(r.nodes[rec_[i]].z);
    }
    if (snap_every_ > 0 && k % snap_every_ == 0) {
      out_.snapshots.push_back(r);
      out_.snapshot_t.push_back(t);
    }
  }

 private:
  /// The nodes nearest to dynamics.record_s (by unstretched arclength, which a winch leaves on
  /// the nodes below its top interval).
  void findRecordedNodes() {
    s_ = solver_.nodeArclengths();
    rec_.clear();
    for (double want : problem_.dynamics.record_s) {
      std::size_t best = 0;
      for (std::size_t j = 1; j < s_.size(); ++j)
        if (std::abs(s_[j] - want) < std::abs(s_[best] - want)) best = j;
      rec_.push_back(best);
    }
  }

  const Solver& solver_;
  const Problem& problem_;
  DynamicSeries& out_;
  std::vector<double> s_;         ///< the nodes' arclengths when rec_ was found [m]
  std::vector<std::size_t> rec_;  ///< the recorded nodes
  long snap_every_ = 0;           ///< a snapshot every this many samples (0: none)
};

/// Advances the solver to the sample times. A position table is followed as the lockstep node
/// follows its samples: row by row, the top on the segment from the previous row (the first from
/// the static top) to the next, advanced to every row time; the same samples through the node
/// give the same bits.
template <class Solver>
class RowFollower {
 public:
  RowFollower(Solver& solver, const TopMotion& tm)
      : solver_(solver),
        rows_(tm.table),
        by_rows_(tm.type == TopMotion::Type::PositionTable && !tm.table.empty()),
        seg_p_{solver.initialStatic().nodes.back().x, solver.initialStatic().nodes.back().y,
               solver.initialStatic().nodes.back().z} {
    while (by_rows_ && next_row_ < rows_.size() && !(rows_[next_row_].t > 0.0)) ++next_row_;  // the start row
  }

  /// Advance to t, row by row when following a table (the rows' times are step ends).
  StepReport advance(double t) {
    StepReport rep;
    while (by_rows_ && next_row_ < rows_.size() && rows_[next_row_].t <= t) {
      setSegment();
      rep = solver_.advanceTo(rows_[next_row_].t);
      if (!rep.ok) return rep;
      seg_t_ = rows_[next_row_].t;
      seg_p_[0] = rows_[next_row_].x;
      seg_p_[1] = rows_[next_row_].y;
      seg_p_[2] = rows_[next_row_].z;
      ++next_row_;
    }
    if (by_rows_ && next_row_ < rows_.size()) setSegment();
    if (by_rows_ && next_row_ >= rows_.size()) holdAtLastRow();
    return solver_.time() < t ? solver_.advanceTo(t) : rep;
  }

 private:
  /// The top on the segment from the last row passed to the next.
  void setSegment() {
    const TopMotion::Row r = rows_[next_row_];
    const double t0 = seg_t_, x0 = seg_p_[0], y0 = seg_p_[1], z0 = seg_p_[2];
    if constexpr (std::is_same_v<Solver, DynamicSolver2D>)
      solver_.setTopInput([=](double tau) { return segmentTopInput(tau, t0, x0, z0, r.t, r.x, r.z); });
    else
      solver_.setTopInput([=](double tau) { return segmentTopState(tau, t0, x0, y0, z0, r.t, r.x, r.y, r.z); });
  }
  /// After the last row: held there, at rest.
  void holdAtLastRow() {
    const double x = seg_p_[0], y = seg_p_[1], z = seg_p_[2], t_last = seg_t_;
    if constexpr (std::is_same_v<Solver, DynamicSolver2D>)
      solver_.setTopInput([=](double) { return segmentTopInput(t_last + 1.0, t_last, x, z, t_last + 1.0, x, z); });
    else
      solver_.setTopInput([=](double) { return segmentTopState(t_last + 1.0, t_last, x, y, z, t_last + 1.0, x, y, z); });
  }

  Solver& solver_;
  const std::vector<TopMotion::Row>& rows_;
  const bool by_rows_;
  std::size_t next_row_ = 0;
  double seg_t_ = 0.0;  ///< time of the last row passed [s]
  double seg_p_[3];     ///< its position (the static top before the first) [m]
};

}  // namespace detail

template <class Solver>
DynamicSeries runDynamicWith(const Problem& problem, const std::function<void(double, double)>& progress) {
  const auto wall0 = std::chrono::steady_clock::now();
  DynamicSeries out;
  const DynamicOptions& opt = problem.dynamics;
  if (!(opt.duration > 0.0))
    throw std::invalid_argument("dynamics.duration = " + std::to_string(opt.duration) +
                                ": must be > 0 for a dynamic run");
  Solver solver(problem);
  out.initial_static = solver.initialStatic();
  const double dout = opt.output_interval > 0.0 ? opt.output_interval : opt.dt;
  const long samples = static_cast<long>(std::floor(opt.duration / dout + 1e-9));
  detail::SeriesRecorder<Solver> recorder(solver, problem, dout, out);
  recorder.record(0.0, 0);
  out.completed = true;
  detail::RowFollower<Solver> follower(solver, opt.top_motion);
  const bool partial_end = opt.duration - samples * dout > 1e-9 * dout;
  for (long k = 1; k <= samples + (partial_end ? 1 : 0); ++k) {
    const double t = k <= samples ? k * dout : opt.duration;
    const StepReport rep = follower.advance(t);
    if (!rep.ok) {
      out.completed = false;
      out.message = rep.message;
      break;
    }
    recorder.record(t, k);
    if (progress) progress(t, opt.duration);
  }
  // Whatever the loop did, a run that did not reach its end time is not complete (an output grid
  // that rounds to nothing, a step lost in the time's rounding).
  if (out.completed && !(out.t.back() >= opt.duration * (1.0 - kEndTimeTolerance))) {
    out.completed = false;
    out.message = "reached t = " + std::to_string(out.t.back()) + " s of dynamics.duration = " +
                  std::to_string(opt.duration) + " s";
  }
  if constexpr (!std::is_same_v<Solver, DynamicSolver2D>) out.events = solver.eventLog();
  const auto tot = solver.totals();
  out.steps = tot.steps;
  out.cuts = tot.cuts;
  out.newton_iterations = tot.newton_iterations;
  out.jacobians = tot.jacobians;
  out.fallback_steps = tot.fallback_steps;
  out.fallback_substeps = tot.fallback_substeps;
  out.top_off_path = tot.top_off_path;
  out.threads = solver.threads();
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
