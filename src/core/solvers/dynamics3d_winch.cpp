// The winch at the top of a 3-D line (issue 21; docs/method.md "Winch"): the top interval's
// unstretched length is L(t) - s_{n-2}; as it grows past 1.5 spacings a node is added below the
// top, as it shrinks under half a spacing the node below the top is taken out. A new node's state
// is the linear interpolation of its neighbours' (global velocities interpolated, then turned
// into its frame), which keeps the line's mass and its momentum (the trapezoidal sum of the box
// scheme) unchanged; taking a node out keeps the mass and changes the momentum by half the merged
// interval times the node's departure from the linear profile.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dynamics3d_impl.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

/// Node splits and merges, in spacings h0 of the top interval: split above kSplit h0 (leaving
/// h0 below), merge below kMerge h0 (into at most kSplit h0, so the two never chase each other).
constexpr double kSplit = 1.5;
constexpr double kMerge = 0.5;
/// Shortest top interval a step may end on [h0]: a step that hauls in more than the top interval
/// less this is cut (section 4.3), so that the node below the top is taken out in between.
constexpr double kShortestInStep = 0.1;

std::string num(double v) {
  std::ostringstream os;
  os.precision(8);
  os << v;
  return os.str();
}

/// The top interval's length for a line length L [m].
double topInterval(const DynamicSolver3D::Impl& im, double L) {
  return L - im.mesh.nodes[static_cast<std::size_t>(im.nodes() - 2)].s;
}

/// Puts the accepted length back on the mesh: the top node's s and the top interval's h.
void setLength(DynamicSolver3D::Impl& im, double L) {
  const std::size_t n = im.mesh.nodes.size();
  im.mesh.intervals[n - 2].h = topInterval(im, L);
  im.mesh.nodes[n - 1].s = L;
}

/// The state of a node at fraction f from node a to node b (both of N unknowns).
void interpolateNode(const double* ya, const double* yb, double f, double* y) {
  for (int k = 0; k < N; ++k) y[k] = (1.0 - f) * ya[k] + f * yb[k];
  double qb[4] = {yb[Q0], yb[Q0 + 1], yb[Q0 + 2], yb[Q0 + 3]};
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) dot += ya[Q0 + i] * qb[i];
  const double sign = dot < 0.0 ? -1.0 : 1.0;  // q and -q are the same frame
  double norm = 0.0;
  for (int i = 0; i < 4; ++i) {
    y[Q0 + i] = (1.0 - f) * ya[Q0 + i] + f * sign * qb[i];
    norm += y[Q0 + i] * y[Q0 + i];
  }
  for (int i = 0; i < 4; ++i) y[Q0 + i] /= std::sqrt(norm);
  // Global velocity interpolated (momentum), then in the new node's frame.
  double Va[3], Vb[3], V[3], R[9];
  globalVelocity(ya, Va);
  globalVelocity(yb, Vb);
  for (int i = 0; i < 3; ++i) V[i] = (1.0 - f) * Va[i] + f * Vb[i];
  quat::matrix(y + Q0, R);
  quat::toLocal(R, V, y + U1);
}

/// Vector v with N entries inserted before node `at` (holding `node`) or removed at `at`.
void insertNode(Eigen::VectorXd& v, int at, const double* node) {
  Eigen::VectorXd out(v.size() + N);
  out << v.head(N * at), Eigen::Map<const Eigen::VectorXd>(node, N), v.tail(v.size() - N * at);
  v.swap(out);
}
void eraseNode(Eigen::VectorXd& v, int at) {
  Eigen::VectorXd out(v.size() - N);
  out << v.head(N * at), v.tail(v.size() - N * (at + 1));
  v.swap(out);
}

/// Adds a node h0 above node n - 2.
void splitTop(DynamicSolver3D::Impl& im) {
  const int n = im.nodes(), a = n - 2, b = n - 1;
  const double h = im.mesh.intervals[static_cast<std::size_t>(a)].h, h0 = im.winch.spacing;
  const double f = h0 / h;
  double y[N], yd[N];
  interpolateNode(im.Y.data() + N * a, im.Y.data() + N * b, f, y);
  for (int k = 0; k < N; ++k) yd[k] = (1.0 - f) * im.Yd[N * a + k] + f * im.Yd[N * b + k];
  insertNode(im.Y, b, y);
  insertNode(im.Yd, b, yd);
  MeshNode node = im.mesh.nodes[static_cast<std::size_t>(b)];
  node.s = im.mesh.nodes[static_cast<std::size_t>(a)].s + h0;
  im.mesh.nodes.insert(im.mesh.nodes.begin() + b, node);
  MeshInterval upper = im.mesh.intervals[static_cast<std::size_t>(a)];
  im.mesh.intervals[static_cast<std::size_t>(a)].h = h0;
  upper.h = h - h0;
  im.mesh.intervals.insert(im.mesh.intervals.begin() + b, upper);
}

/// Node n - 2 can go: it lies above the winch's base, between two intervals of one material
/// that the line has not parted in.
bool canMerge(const DynamicSolver3D::Impl& im) {
  const int n = im.nodes();
  if (n < 3) return false;
  const MeshInterval& below = im.mesh.intervals[static_cast<std::size_t>(n - 3)];
  const MeshInterval& top = im.mesh.intervals[static_cast<std::size_t>(n - 2)];
  constexpr double kBaseTolerance = 1e-9;  // [m] the base node itself stays
  return im.mesh.nodes[static_cast<std::size_t>(n - 2)].s > im.winch.base_s + kBaseTolerance && below.h > 0.0 &&
         below.material == top.material && im.parted != n - 3;
}

/// Takes out node n - 2: the interval below it grows by the top interval.
void mergeTop(DynamicSolver3D::Impl& im) {
  const int n = im.nodes(), m = n - 2;
  im.mesh.intervals[static_cast<std::size_t>(m - 1)].h += im.mesh.intervals[static_cast<std::size_t>(m)].h;
  im.mesh.intervals.erase(im.mesh.intervals.begin() + m);
  im.mesh.nodes.erase(im.mesh.nodes.begin() + m);
  eraseNode(im.Y, m);
  eraseNode(im.Yd, m);
}

}  // namespace

void winchSetUp(DynamicSolver3D::Impl& im) {
  const Problem& p = im.problem;
  WinchState& w = im.winch;
  const bool free_below = p.lower_end == Problem::LowerEnd::Free;
  w.able = (p.top.type == TopBoundary::Type::Position ||
            (p.top.type == TopBoundary::Type::Buoy && !free_below)) &&
           im.nodes() >= 2 && im.mesh.intervals.back().h > 0.0;
  if (!w.able) return;
  const Segment& top = p.segments.back();
  const double L = im.mesh.nodes.back().s;
  w.top_start = L - top.length;
  w.base_s = winchBase(p.segments);
  w.shortest = w.base_s + kWinchShortestTopFraction * top.spacing;
  w.spacing = im.mesh.intervals.back().h;
  const Winch& f = p.dynamics.winch;
  w.min_length = f.given ? f.min_length : 0.0;
  w.max_length = f.given ? f.max_length : 0.0;
  w.lo = std::max(w.min_length, w.shortest);
  w.hi = w.max_length > 0.0 ? w.max_length : std::numeric_limits<double>::infinity();
  w.length = L;
  w.initial_mesh = im.mesh;
  w.initial_top_length = top.length;
  if (f.given) w.program = f.program(L);
  w.used = f.given;
}

WinchSaved winchSave(const DynamicSolver3D::Impl& im) {
  WinchSaved s;
  s.used = im.winch.used;
  if (!s.used) return s;  // nothing changed the mesh yet
  s.mesh = im.mesh;
  s.program = im.winch.program;
  s.length = im.winch.length;
  s.top_length = im.problem.segments.back().length;
  return s;
}

void winchRestore(DynamicSolver3D::Impl& im, const WinchSaved& s) {
  WinchState& w = im.winch;
  if (!s.used && !w.used) return;  // the mesh never changed in between
  const std::size_t before = im.mesh.nodes.size();
  if (s.used) {
    im.mesh = s.mesh;
    w.program = s.program;
    w.length = s.length;
    im.problem.segments.back().length = s.top_length;
  } else {  // saved before any program: the initial mesh and length
    im.mesh = w.initial_mesh;
    w.program = WinchProgram();
    w.length = im.mesh.nodes.back().s;
    im.problem.segments.back().length = w.initial_top_length;
  }
  w.used = s.used;
  w.rate = 0.0;
  if (im.mesh.nodes.size() != before) {
    im.wave_cache = WaveVelocityCache(&im.waves, im.mesh.nodes.size(), true);
    rowsChanged(im);
  }
}

bool winchBeginStep(DynamicSolver3D::Impl& im, double t_new, std::string& message) {
  WinchState& w = im.winch;
  if (!w.active()) return true;
  const double L = w.program.lengthAt(t_new);
  constexpr double kLimitRounding = 1e-12;  // relative: a program that ends on a limit stays inside
  if (L > w.hi * (1.0 + kLimitRounding) || L < w.lo * (1.0 - kLimitRounding)) {
    const bool above = L > w.hi;
    message = "t = " + num(t_new) + " s: the winch's length " + num(L) + " m passes " +
              (above ? "max_length = " + num(w.hi)
                     : (w.lo > w.shortest ? "min_length = " : "the shortest top segment, ") + num(w.lo)) +
              " m";
    return false;
  }
  if (!(topInterval(im, L) > kShortestInStep * w.spacing)) {
    message = "t = " + num(t_new) + " s: the winch takes in more than the top interval in one step (length " +
              num(L) + " m)";
    return false;
  }
  setLength(im, L);
  w.rate = (L - w.length) / (t_new - im.t);  // the step's mean dL/dt (a table's corner may fall inside it)
  return true;
}

void winchUndoStep(DynamicSolver3D::Impl& im) {
  WinchState& w = im.winch;
  if (!w.active()) return;
  setLength(im, w.length);
  w.rate = 0.0;
}

bool winchRemesh(DynamicSolver3D::Impl& im) {
  WinchState& w = im.winch;
  if (!w.active()) return false;
  w.length = im.mesh.nodes.back().s;
  w.rate = 0.0;
  im.problem.segments.back().length = w.length - w.top_start;  // what snapshots and summaries read
  bool changed = false;
  for (;;) {
    const double h = im.mesh.intervals.back().h;
    if (h > kSplit * w.spacing) {
      splitTop(im);
    } else if (h < kMerge * w.spacing && canMerge(im)) {
      mergeTop(im);
    } else {
      break;
    }
    changed = true;
  }
  if (!changed) return false;
  im.wave_cache = WaveVelocityCache(&im.waves, im.mesh.nodes.size(), true);
  im.waterField(im.Y, im.t, im.water);
  im.spatialRows(im.Y, im.water, im.S);
  im.acceptEndLevels(im.Y, im.water, im.t);
  im.Yd_prev.resize(0);  // the predictor's rate history belongs to the old nodes
  rowsChanged(im);
  return true;
}

std::string DynamicSolver3D::commandWinch(double rate, double target) {
  Impl& im = *impl_;
  WinchState& w = im.winch;
  if (!w.able)
    throw std::invalid_argument(std::string("winch: the line's top (") + im.upper->name() +
                                ") takes no winch; it needs a top whose motion is prescribed (a position top or a "
                                "surface buoy over an anchor)");
  if (im.upper_kept || im.parted >= im.nodes() - 3)
    throw std::invalid_argument("winch: the line is off the winch (its top let go or parted at it)");
  if (!std::isfinite(rate)) throw std::invalid_argument("winch rate = " + num(rate) + ": must be a finite rate [m/s]");
  const double L = lineLength();
  auto limits = [&w]() {
    return "[" + num(w.lo) + ", " + (std::isinf(w.hi) ? std::string("inf") : num(w.hi)) + "] m (min_length " +
           num(w.min_length) + ", max_length " + (w.max_length > 0.0 ? num(w.max_length) : std::string("none")) +
           ", the top segment's shortest " + num(w.shortest) + " m)";
  };
  if (!std::isnan(target)) {
    if (!(std::isfinite(target) && target >= w.lo && target <= w.hi))
      throw std::invalid_argument("winch target length = " + num(target) + " m: outside " + limits());
    if (rate == 0.0 && target != L)
      throw std::invalid_argument("winch rate = 0 m/s: going to a target length needs a speed |rate| > 0");
    w.used = true;
    w.program = WinchProgram::toward(im.t, L, rate, target);
    return "to " + num(target) + " m at " + num(std::abs(rate)) + " m/s, there at t = " + num(w.program.t.back()) + " s";
  }
  const double limit = rate > 0.0 ? w.hi : w.lo;
  if (rate == 0.0 || std::isinf(limit)) {
    w.used = true;
    w.program = WinchProgram::toward(im.t, L, rate, std::numeric_limits<double>::quiet_NaN());
    return rate == 0.0 ? "stopped at " + num(L) + " m" : "paying out at " + num(rate) + " m/s (no max_length)";
  }
  if ((rate > 0.0 && L >= limit) || (rate < 0.0 && L <= limit))
    throw std::invalid_argument("winch rate = " + num(rate) + " m/s: the line is at its limit already, " + num(L) +
                                " m of " + limits());
  w.used = true;
  w.program = WinchProgram::toward(im.t, L, rate, limit);
  return std::string(rate > 0.0 ? "paying out" : "hauling in") + " at " + num(std::abs(rate)) + " m/s; stops at " +
         (rate > 0.0 ? "max_length " : (w.lo > w.shortest ? "min_length " : "the top segment's shortest ")) +
         num(limit) + " m at t = " + num(w.program.t.back()) + " s";
}

}  // namespace core
}  // namespace mooring_dynamics
