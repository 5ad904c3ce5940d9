// Line events of the 3-D dynamic solver (issue 21; docs/method.md "Line events"): an end let go,
// a line parting at a node, at a time or when a node's tension first exceeds a limit or its mbl;
// each logged (DynamicSolver3D::eventLog). The rows of a released end or a parted interval
// change: the kept factorization is dropped (rowsChanged).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "dynamics3d_impl.hpp"

namespace mooring_dynamics {
namespace core {

std::string fmtNum(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

namespace {

double nodeTension(const DynamicSolver3D::Impl& im, int j) { return im.mat(j).tension(im.Y[N * j + EPS]); }

/// The node of largest tension now.
int largestTensionNode(const DynamicSolver3D::Impl& im) {
  int best = 0;
  for (int j = 1; j < im.nodes(); ++j)
    if (nodeTension(im, j) > nodeTension(im, best)) best = j;
  return best;
}

void logEvent(DynamicSolver3D::Impl& im, const std::string& what, int node, const std::string& cause) {
  LineEventRecord r;
  r.t = im.t;
  r.what = what;
  r.node = node;
  r.s = im.mesh.nodes[static_cast<std::size_t>(node)].s;
  r.tension = nodeTension(im, largestTensionNode(im));
  r.cause = cause;
  im.event_log.push_back(r);
}

}  // namespace

void releaseEnd(DynamicSolver3D::Impl& im, LineEvent::End end, const std::string& cause) {
  const int n = im.nodes();
  if (end == LineEvent::End::Top) {
    if (im.upper_kept) throw std::logic_error("release: the line's top is let go already");
    logEvent(im, "released top", n - 1, cause);
    im.winch.program = WinchProgram();  // the line is off the winch
    const int rows = im.upper->dynamicRows();
    im.upper_kept = std::move(im.upper);
    im.upper = makeReleasedUpperEnd3D(im.mat(n - 1), rows);
  } else {
    if (im.lower_kept || im.problem.lower_end == Problem::LowerEnd::Free)
      throw std::logic_error("release: the line's lower end is free already");
    logEvent(im, "released anchor", 0, cause);
    const int rows = im.lower->dynamicRows();
    im.lower_kept = std::move(im.lower);
    im.lower = makeReleasedLowerEnd3D(im.mat(0), rows);
  }
  rowsChanged(im);
}

/// The line parts at node k: in the interval beside it (not a junction) toward the higher
/// tension; at an end node, that end is let go.
void partAt(DynamicSolver3D::Impl& im, int k, const std::string& cause) {
  const int n = im.nodes();
  if (im.parted >= 0) throw std::logic_error("break: the line has parted already");
  if (k < 0 || k >= n) throw std::out_of_range("break: node " + std::to_string(k) + " is not on the line");
  if (k == n - 1 && !im.upper_kept) return releaseEnd(im, LineEvent::End::Top, cause);
  if (k == 0 && !im.lower_kept && im.problem.lower_end != Problem::LowerEnd::Free)
    return releaseEnd(im, LineEvent::End::Anchor, cause);
  auto usable = [&im, n](int j) { return j >= 0 && j + 1 < n && im.mesh.intervals[static_cast<std::size_t>(j)].h > 0.0; };
  int j = -1;
  if (usable(k - 1) && usable(k))
    j = nodeTension(im, k - 1) > nodeTension(im, k + 1) ? k - 1 : k;
  else
    j = usable(k) ? k : k - 1;
  if (!usable(j)) throw std::logic_error("break: no interval beside node " + std::to_string(k) + " can part");
  logEvent(im, "parted", j, cause);
  im.parted = j;
  if (j >= n - 3) im.winch.program = WinchProgram();  // parted at the winch: it stops
  im.part_top = makeReleasedUpperEnd3D(im.mat(j), N - im.lower->dynamicRows());
  im.part_lower = makeReleasedLowerEnd3D(im.mat(j + 1), N - im.upper->dynamicRows());
  rowsChanged(im);
}

void applyEvent(DynamicSolver3D::Impl& im, std::size_t i, const std::string& cause) {
  const LineEvent& e = im.events[i];
  im.event_done[i] = 1;
  if (e.type == LineEvent::Type::Release) return releaseEnd(im, e.end, cause);
  int k = largestTensionNode(im);
  if (e.s >= 0.0) {
    k = 0;
    for (int j = 1; j < im.nodes(); ++j)
      if (std::abs(im.mesh.nodes[static_cast<std::size_t>(j)].s - e.s) <
          std::abs(im.mesh.nodes[static_cast<std::size_t>(k)].s - e.s))
        k = j;
  }
  partAt(im, k, cause);
}

/// After an accepted step: a break on tension whose limit a node's tension exceeds happens now,
/// at the node where the tension is the largest fraction of its limit.
void breakOnTension(DynamicSolver3D::Impl& im) {
  for (std::size_t i = 0; i < im.events.size(); ++i) {
    const LineEvent& e = im.events[i];
    if (im.event_done[i] || !e.onTension()) continue;
    int worst = -1;
    double worst_ratio = 1.0, limit = 0.0;
    for (int j = 0; j < im.nodes(); ++j) {
      const double lim = e.at_mbl ? im.mat(j).mbl : e.tension;
      if (!(lim > 0.0)) continue;
      const double ratio = nodeTension(im, j) / lim;
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = j;
        limit = lim;
      }
    }
    if (worst < 0) continue;
    im.event_done[i] = 1;
    partAt(im, worst, "tension " + fmtNum(nodeTension(im, worst)) + " N > " + (e.at_mbl ? "mbl " : "") +
                          fmtNum(limit) + " N at node " + std::to_string(worst));
  }
}

/// The first timed event that has not happened (-1: none).
int nextTimedEvent(const DynamicSolver3D::Impl& im) {
  int next = -1;
  for (std::size_t i = 0; i < im.events.size(); ++i) {
    if (im.event_done[i] || !(im.events[i].t >= 0.0)) continue;
    if (next < 0 || im.events[i].t < im.events[static_cast<std::size_t>(next)].t) next = static_cast<int>(i);
  }
  return next;
}

void DynamicSolver3D::releaseEnd(LineEvent::End end, const std::string& cause) {
  core::releaseEnd(*impl_, end, cause);
}
void DynamicSolver3D::partAt(int node, const std::string& cause) { core::partAt(*impl_, node, cause); }
const std::vector<LineEventRecord>& DynamicSolver3D::eventLog() const { return impl_->event_log; }
bool DynamicSolver3D::endReleased(LineEvent::End end) const {
  return end == LineEvent::End::Top ? impl_->upper_kept != nullptr : impl_->lower_kept != nullptr;
}

}  // namespace core
}  // namespace mooring_dynamics
