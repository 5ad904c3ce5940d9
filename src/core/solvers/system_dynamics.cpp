#include "mooring_dynamics/core/solvers/system_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "system_dynamics_impl.hpp"

namespace mooring_dynamics {
namespace core {

SystemDynamics::SystemDynamics(const SystemProblem& system, const DynamicOptions& options, int threads)
    : impl_(std::make_unique<Impl>()) {
  Impl& im = *impl_;
  const std::string e = system.validate();
  if (!e.empty()) throw std::invalid_argument(e);
  const std::string eo = options.validate();
  if (!eo.empty()) throw std::invalid_argument(eo);
  if (options.threads != 1)  // (a second thread per line would have them compete for the cores)
    throw std::invalid_argument("dynamics.threads = " + std::to_string(options.threads) +
                                ": the lines of a system run on one thread (must be 1)");
  if (threads < 1) throw std::invalid_argument("threads = " + std::to_string(threads) + ": must be >= 1");
  im.system = system;
  im.system.formulation = Formulation::ThreeD;  // the lines run on the 3-D solver
  im.system.placeVessel(system.vessel.pose);
  im.vessel_pose = im.system.vessel.pose;
  const RigidPose start = im.vessel_pose;
  im.vessel_motion = [start](double) { return RigidSegment::hold(start).at(0.0); };
  im.pool = std::make_unique<ThreadPool>(threads);
  im.opt = options;
  im.statics = solveSystemStatic(im.system);
  if (!im.statics.summary.converged)
    throw std::runtime_error("the system's statics that start the run did not converge: " +
                             im.statics.summary.message);
  const std::size_t np = system.points.size();
  im.X.resize(static_cast<Eigen::Index>(3 * np));
  for (std::size_t p = 0; p < np; ++p) {
    im.X[3 * p] = im.statics.points[p].x;
    im.X[3 * p + 1] = im.statics.points[p].y;
    im.X[3 * p + 2] = im.statics.points[p].z;
    if (system.points[p].free()) im.free_pts.push_back(p);
  }
  im.V = Eigen::VectorXd::Zero(im.X.size());
  im.A = Eigen::VectorXd::Zero(im.X.size());
  im.forces.resize(np);
  im.lines_at.resize(np);
  std::vector<double> xyz(im.X.data(), im.X.data() + im.X.size());
  for (std::size_t i = 0; i < system.lines.size(); ++i) {
    im.lines.push_back(std::make_unique<DynamicSolver3D>(im.lineDynamicProblem(im.system, i, xyz)));
    im.lines_at[system.lines[i].to].push_back(i);
    if (system.lines[i].from != SystemLine::kFreeEnd) im.lines_at[system.lines[i].from].push_back(i);
    const SystemLine& l = system.lines[i];
    const bool at_free = system.points[l.to].free() || (l.from != SystemLine::kFreeEnd && system.points[l.from].free());
    if (!at_free && (im.isVessel(l.to) || im.isVessel(l.from))) im.vessel_lines.push_back(i);
  }
  im.line_t0.assign(system.lines.size(), 0.0);
  im.retired.assign(system.lines.size(), 0);
  // Groups: lines joined through free points (union-find over the lines at each free point).
  std::vector<std::size_t> root(system.lines.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = i;
  auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (std::size_t p : im.free_pts)
    for (std::size_t i : im.lines_at[p]) {
      const std::size_t a = find(i), b = find(im.lines_at[p].front());
      if (a != b) root[std::max(a, b)] = std::min(a, b);
    }
  std::vector<std::size_t> group_of_root(system.lines.size(), SystemLine::kFreeEnd);
  for (std::size_t i = 0; i < system.lines.size(); ++i) {
    const std::size_t r = find(i);
    if (group_of_root[r] == SystemLine::kFreeEnd) {
      group_of_root[r] = im.groups.size();
      im.groups.emplace_back();
      im.group_pts.emplace_back();
    }
    im.groups[group_of_root[r]].push_back(i);
  }
  for (std::size_t p : im.free_pts) im.group_pts[group_of_root[find(im.lines_at[p].front())]].push_back(p);
  im.J.resize(im.groups.size());
}

const std::vector<LineGroupRestart>& SystemDynamics::lastRestarts() const { return impl_->restarts; }
const std::vector<std::vector<std::size_t>>& SystemDynamics::lineGroups() const { return impl_->groups; }
void SystemDynamics::setFailureInjection(std::function<bool(std::size_t, double)> fail) {
  impl_->fail_hook = std::move(fail);
}
void SystemDynamics::setRestartFailedGroups(bool restart) { impl_->restart_failed_groups = restart; }

void SystemDynamics::setVesselMotion(std::function<RigidMotion(double)> motion) {
  if (!motion) throw std::invalid_argument("setVesselMotion: empty motion");
  impl_->vessel_motion = std::move(motion);
}

const RigidPose& SystemDynamics::vesselPose() const { return impl_->vessel_pose; }
int SystemDynamics::threads() const { return impl_->pool->threads(); }

VesselWrench SystemDynamics::vesselWrench() const {
  std::vector<StaticResult> lines;
  for (const auto& l : impl_->lines) lines.push_back(l->snapshot());
  return core::vesselWrench(impl_->system, impl_->vessel_pose, lines);
}

SystemDynamics::~SystemDynamics() = default;

void SystemDynamics::setPointForce(std::size_t point, std::function<std::array<double, 3>(double)> force) {
  if (point >= impl_->forces.size()) throw std::out_of_range("setPointForce: no point " + std::to_string(point));
  impl_->forces[point] = std::move(force);
}

double SystemDynamics::time() const { return impl_->t; }
const SystemStaticResult& SystemDynamics::initialStatic() const { return impl_->statics; }
long SystemDynamics::pointIterations() const { return impl_->iterations; }
long SystemDynamics::lineSteps() const { return impl_->line_steps; }
long SystemDynamics::lineFallbackSteps(std::size_t i) const {
  const long before = i < impl_->fallback_before.size() ? impl_->fallback_before[i] : 0;
  return before + impl_->lines.at(i)->totals().fallback_steps;
}
DynamicSolver3D::Totals SystemDynamics::lineTotals(std::size_t i) const { return impl_->lines.at(i)->totals(); }
StaticResult SystemDynamics::line(std::size_t i) const { return impl_->lines.at(i)->snapshot(); }

std::array<double, 3> SystemDynamics::pointVelocity(std::size_t p) const {
  return {impl_->V[3 * p], impl_->V[3 * p + 1], impl_->V[3 * p + 2]};
}

void SystemDynamics::releaseLineEnd(std::size_t line, LineEvent::End end, const std::string& cause) {
  impl_->lines.at(line)->releaseEnd(end, cause);
}

std::string SystemDynamics::commandLineWinch(std::size_t line, double rate, double target) {
  return impl_->lines.at(line)->commandWinch(rate, target);
}
double SystemDynamics::lineLength(std::size_t line) const { return impl_->lines.at(line)->lineLength(); }
double SystemDynamics::lineWinchRate(std::size_t line) const { return impl_->lines.at(line)->winchRate(); }

std::vector<LineEventRecord> SystemDynamics::lineEvents() const {
  const Impl& im = *impl_;
  std::vector<LineEventRecord> out;
  for (std::size_t i = 0; i < im.lines.size(); ++i)
    for (LineEventRecord r : im.lines[i]->eventLog()) {
      r.t += im.line_t0[i];
      r.line = im.system.lines[i].name;
      out.push_back(r);
    }
  out.insert(out.end(), im.retired_log.begin(), im.retired_log.end());
  std::stable_sort(out.begin(), out.end(), [](const LineEventRecord& a, const LineEventRecord& b) { return a.t < b.t; });
  return out;
}

std::vector<SystemPointResult> SystemDynamics::points() const {
  const Impl& im = *impl_;
  std::vector<SystemPointResult> out;
  for (std::size_t p = 0; p < im.system.points.size(); ++p) {
    SystemPointResult r;
    r.name = im.system.points[p].name;
    r.x = im.X[3 * p];
    r.y = im.X[3 * p + 1];
    r.z = im.X[3 * p + 2];
    for (std::size_t i = 0; i < im.system.lines.size(); ++i) {
      const SystemLine& l = im.system.lines[i];
      const bool top = l.to == p, bottom = l.from == p;
      if (!top && !bottom) continue;
      const StaticResult s = im.lines[i]->snapshot();
      r.fx += top ? -s.top_force_x : s.anchor_force_x;
      r.fy += top ? -s.top_force_y : s.anchor_force_y;
      r.fz += top ? -s.top_force_z : s.anchor_force_z;
    }
    if (im.system.points[p].type == SystemPoint::Type::Buoy) r.buoy_draft = -r.z;
    out.push_back(r);
  }
  return out;
}

bool SystemDynamics::advanceTo(double t_end, std::string* message) {
  Impl& im = *impl_;
  im.restarts.clear();
  const double eps = 1e-9 * im.opt.dt;
  while (im.t < t_end - eps)
    if (!im.step(t_end, message)) return false;
  im.t = std::max(im.t, t_end);
  return true;
}

}  // namespace core
}  // namespace mooring_dynamics
