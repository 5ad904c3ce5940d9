// The 3-D dynamic solver's state (DynamicSolver3D::Impl), shared by its source files:
// dynamics3d.cpp (the time step as a Newton system, the start, advanceTo, save and restore),
// dynamics3d_events.cpp (line events), dynamics3d_fallback.cpp (the fallback step) and
// dynamics3d_winch.cpp (the winch's payout and haul-in). Private to src/core/solvers.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations3d.hpp"
#include "mooring_dynamics/core/equations/mesh.hpp"
#include "mooring_dynamics/core/model/winch.hpp"
#include "mooring_dynamics/core/numerics/banded_matrix.hpp"
#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"
#include "mooring_dynamics/core/solvers/dynamics3d.hpp"
#include "lumped_line.hpp"

namespace mooring_dynamics {
namespace core {

using namespace eq3d;  // private to the solver's sources, as in them

/// The winch at the top (docs/method.md "Winch"): the top interval's length follows the
/// program's L(t); nodes are added and removed below the top as it grows and shrinks.
struct WinchState {
  bool able = false;       ///< the top takes a winch (its motion prescribed: a position top, a surface buoy)
  WinchProgram program;    ///< empty: the length fixed
  double spacing = 0.0;    ///< nominal top interval h0 [m] (the top segment's spacing)
  double lo = 0.0;         ///< shortest length allowed [m]: min_length or the top segment's shortest
  double hi = std::numeric_limits<double>::infinity();  ///< longest [m]: max_length or none
  double min_length = 0.0, max_length = 0.0;  ///< as given (0: none), for messages
  double shortest = 0.0;   ///< the top segment's start (or last body) + its shortest interval [m]
  double top_start = 0.0;  ///< arclength where the top segment starts [m]
  double base_s = 0.0;     ///< arclength below which no node is removed [m] (the start, or its last body)
  double length = 0.0;     ///< the line's length at the accepted time [m]
  double rate = 0.0;       ///< dL/dt of the step being taken [m/s] (0 between steps, or none)
  bool used = false;       ///< a program was set: the top holds its position by feedback from then on
  Mesh initial_mesh;       ///< the mesh before any program (what a state saved then had)
  double initial_top_length = 0.0;  ///< the top segment's length then [m]
  bool active() const { return able && !program.empty(); }
};

/// What a saved state (DynamicSolver3D::save) keeps of the winch: after a program was set, the
/// mesh it changes, the program and the length; before, nothing (the mesh was the initial one).
struct WinchSaved {
  bool used = false;
  Mesh mesh;
  WinchProgram program;
  double length = 0.0, top_length = 0.0;
};

struct DynamicSolver3D::Impl {
  Problem problem;
  Mesh mesh;
  WaveField waves;
  mutable WaveVelocityCache wave_cache;  ///< wave kinematics at the nodes (WaveVelocityCache)
  CurrentProfile current;  ///< problem.environment.current, components precomputed
  GeneralizedAlpha ga;
  DynamicOptions opt;
  std::function<TopState(double)> top;
  StaticResult statics;
  /// The lower end and the top (end_conditions.hpp): their rows at nodes 0 and n - 1 and the
  /// state they carry between time levels. Anchored, 10 rows at the anchor and 6 at the top; with
  /// a free lower end (towing, drifting) 7 at the end and 9 at the top.
  std::unique_ptr<EndCondition3D> lower, upper;

  double t = 0.0;
  Eigen::VectorXd Y, Yd;        ///< accepted state and rate at time t
  std::vector<Water> water;     ///< water velocity at each node at time t
  Eigen::VectorXd S;            ///< spatial rows 0-5 of each interval at time t
  double chi[N];
  Totals totals;
  BandedMatrix newton_matrix;  ///< Newton matrix reused by every step (solveNewton workspace)
  /// The second thread (dynamics.threads = 2; null with one): assembles and eliminates the
  /// upper half of the line, as in the 2-D solver.
  std::unique_ptr<ForkJoin> fork;
  double factored_dt = 0.0;    ///< step size the factorization in newton_matrix belongs to [s]
  Eigen::VectorXd Yd_prev;     ///< rate before the last accepted step (second-order predictor)
  double last_dt = 0.0;        ///< size of the last accepted step [s]

  // Line events (issue 21; docs/method.md "Line events").
  std::vector<LineEvent> events;        ///< problem.dynamics.events
  std::vector<char> event_done;         ///< per event: it happened
  std::vector<LineEventRecord> event_log;
  std::unique_ptr<EndCondition3D> lower_kept, upper_kept;  ///< an end before its release (null: held)
  /// The interval the line parted in (-1: in one piece) and its rows: a released upper end at
  /// its lower node, a released lower end at its upper node (end_conditions.hpp).
  int parted = -1;
  std::unique_ptr<EndCondition3D> part_top, part_lower;

  WinchState winch;  ///< the winch at the top (dynamics3d_winch.cpp)

  /// The anchor's path when it moves (setLowerEndInput; empty: fixed), for the fallback step.
  std::function<TopState(double)> lower_path;
  /// The last step was a fallback step (dynamics3d_fallback.cpp): a base step that fails now
  /// falls back at once, without the cuts of section 4.3.
  bool in_fallback = false;
  /// Time [s] of the fallback steps in a row taken without trying the implicit step first
  /// (stayInFallback).
  double fallback_skipped_time = 0.0;
  /// Base steps still to go to the fallback without an implicit try after a retry failed
  /// (lumped::kRetryWait).
  int retry_wait = 0;
  /// How long [s] a slack line stays in the fallback without an implicit try before one is made
  /// (lumped::staySlack): kMaxSkippedTime, doubled after each such try that fails.
  double skipped_cap = lumped::kMaxSkippedTime;
  /// The reference lengths of the last fallback step's intervals (lumped::Line::ref), which the
  /// next one keeps while the line stays in the fallback.
  std::vector<double> fallback_ref;

  int nodes() const { return static_cast<int>(mesh.nodes.size()); }
  const Material& mat(int j) const { return problem.materials[mesh.nodes[static_cast<std::size_t>(j)].material]; }

  /// Water at node j, at (x, y, z) and the time last given to wave_cache.setTime.
  Water waterAt(int j, double x, double y, double z) const {
    Water w;
    current.at(z, w.w[0], w.w[1]);
    current.gradientAt(z, w.dw_dz[0], w.dw_dz[1]);
    w.z = z;
    if (!wave_cache.empty() && z <= 0.0) {
      double vx, vy, vz;
      wave_cache.velocity3(static_cast<std::size_t>(j), x, y, z, vx, vy, vz);  // WaveField::velocity
      w.w[0] += vx;
      w.w[1] += vy;
      w.w[2] += vz;
    }
    return w;
  }

  void waterField(const Eigen::VectorXd& y, double time, std::vector<Water>& out) const {
    out.resize(static_cast<std::size_t>(nodes()));
    wave_cache.setTime(time);
    for (int j = 0; j < nodes(); ++j)
      out[static_cast<std::size_t>(j)] = waterAt(j, y[N * j + X], y[N * j + eq3d::Y], y[N * j + Z]);
  }

  /// Rows 0-5 of the spatial part of every interval at state y (double): the rows that eq. 30
  /// weights between the time levels.
  void spatialRows(const Eigen::VectorXd& y, const std::vector<Water>& w, Eigen::VectorXd& out) const {
    const int n = nodes();
    out.setZero(kInertiaRows * (n - 1));
    for (int j = 0; j + 1 < n; ++j) {
      if (j == parted) continue;  // a parted interval's rows are not weighted in time
      const MeshInterval& iv = mesh.intervals[static_cast<std::size_t>(j)];
      const double* ya = y.data() + N * j;
      double r[N];
      if (iv.h > 0.0)
        intervalSpatial(problem.environment, problem.materials[iv.material], iv.h, ya, ya + N,
                        w[static_cast<std::size_t>(j)], w[static_cast<std::size_t>(j) + 1], r);
      else
        junctionForces(problem, iv, mat(j), mat(j + 1), ya, ya + N, w[static_cast<std::size_t>(j)], r);
      const int rows = iv.h > 0.0 ? kInertiaRows : 3;
      for (int q = 0; q < rows; ++q) out[kInertiaRows * j + q] = r[q];
    }
  }

  /// The parts of the end rows that eq. 30 weights in time, at state y and time `time`.
  void acceptEndLevels(const Eigen::VectorXd& y, const std::vector<Water>& w, double time) {
    const int n = nodes();
    lower->acceptLevel(y.data(), w.front(), time, top);
    upper->acceptLevel(y.data() + N * (n - 1), w[static_cast<std::size_t>(n - 1)], time, top);
  }
};


/// The rows changed (an event, a node added or removed): the kept factorization no longer applies.
void rowsChanged(DynamicSolver3D::Impl& im);

// The fallback step (dynamics3d_fallback.cpp; docs/method.md "Slack and snap: the fallback step").
/// Why a converged implicit step ending at t_new with unknowns Yv is not the line's motion ("" when
/// it is): the top node off the path of a top held there by position feedback, when the fallback
/// can take the step instead.
std::string topOffItsPath(const DynamicSolver3D::Impl& im, const Eigen::VectorXd& Yv, double t_new);
/// Why the line cannot fall back over a step ending at t_new ("" when it can).
std::string fallbackUnavailable(const DynamicSolver3D::Impl& im, double t_new);
/// Take a step of dt from the accepted state with the explicit lumped-mass model of the line;
/// false (the reason appended to rep.message) when it cannot.
bool fallbackStep(DynamicSolver3D::Impl& im, double dt, StepReport& rep);
/// After a fallback step: whether the next base step goes to the fallback at once, without an
/// implicit try (the line is still slack: some node of a material without compression shorter
/// than its unstretched length, and for less than skipped_cap in a row; lumped::staySlack).
bool stayInFallback(const DynamicSolver3D::Impl& im);

// Line events (dynamics3d_events.cpp; docs/method.md "Line events").
/// v to 6 significant digits, as the solver's messages write times and tensions.
std::string fmtNum(double v);
/// Let go the lower or upper end now (its rows become a free end's), logged with `cause`.
void releaseEnd(DynamicSolver3D::Impl& im, LineEvent::End end, const std::string& cause);
/// Part the line at node k now (the interval above it carries no force), logged with `cause`.
void partAt(DynamicSolver3D::Impl& im, int k, const std::string& cause);
/// Let dynamics.events[i] happen now.
void applyEvent(DynamicSolver3D::Impl& im, std::size_t i, const std::string& cause);
/// After an accepted step: the events on tension whose limit a node now exceeds happen.
void breakOnTension(DynamicSolver3D::Impl& im);
/// The first timed event that has not happened (-1: none).
int nextTimedEvent(const DynamicSolver3D::Impl& im);

// The winch (dynamics3d_winch.cpp).
/// Set up from the problem after the statics (the mesh final).
void winchSetUp(DynamicSolver3D::Impl& im);
/// Before a step to t_new: the top interval's length at t_new and the payout rate; false (and
/// why in `message`) when the program leaves its limits there. The mesh changes only by the
/// top node's s and interval's h, which winchUndoStep puts back.
bool winchBeginStep(DynamicSolver3D::Impl& im, double t_new, std::string& message);
void winchUndoStep(DynamicSolver3D::Impl& im);
/// After an accepted step: split the top interval where it has grown past 1.5 spacings, merge it
/// into the one below where it has shrunk under half of one; returns whether nodes changed.
bool winchRemesh(DynamicSolver3D::Impl& im);
/// The winch's part of save() and restore(): a restore puts back the mesh (and the arrays'
/// caches for its node count) that go with the saved Y.
WinchSaved winchSave(const DynamicSolver3D::Impl& im);
void winchRestore(DynamicSolver3D::Impl& im, const WinchSaved& s);

}  // namespace core
}  // namespace mooring_dynamics
