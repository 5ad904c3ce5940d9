// Options of the dynamic solver and the prescribed motion of the top end (problem file section
// `dynamics:`). Plain structs; validation names the problem-file key.
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model/gnss.hpp"
#include "mooring_dynamics/core/model/ship_track.hpp"
#include "mooring_dynamics/core/model/time_integration.hpp"
#include "mooring_dynamics/core/model/winch.hpp"

namespace mooring_dynamics {
namespace core {

/// How the top end moves in a dynamic run. Positions are in the problem frame (x east, y north,
/// z up, z = 0 the mean surface); motions are about the static top position unless a table gives
/// absolute positions. The 2-D solver follows only motions in the plane y = 0
/// (planarTopMotionError, top_motion.hpp); makeTopMotion (top_motion.hpp) evaluates them.
struct TopMotion {
  enum class Type {
    Hold,           ///< top held at its static position
    Sinusoid,       ///< x = x0 + ax (sin(2 pi t / T + phase) - sin(phase)), likewise y and z
    PositionTable,  ///< rows (t [s], x, y, z [m]): absolute positions, linear in between
    VelocityTable,  ///< rows (t [s], vx, vy, vz [m/s]): linear in between, integrated from the static top
    ForceTable,     ///< rows (t [s], fx, fy, fz [N]): force applied to the line's top end
    WaveFollower,   ///< the top follows the wave surface vertically (heave), horizontal position held
    ShipTrack       ///< tow point on a ship track (`ship_track`), elevation held at the static top
  };
  Type type = Type::Hold;
  double amplitude_x = 0.0;  ///< Sinusoid [m]
  double amplitude_y = 0.0;  ///< Sinusoid [m]
  double amplitude_z = 0.0;  ///< Sinusoid [m]
  double period = 1.0;       ///< Sinusoid [s]
  double phase = 0.0;        ///< Sinusoid [rad]
  /// One table row: time and the three components of a position [m], velocity [m/s] or force
  /// [N] (per Type). Row{t, x, z} is a row in the x-z plane (y = 0), Row{t, x, y, z} a 3-D row.
  struct Row {
    double t = 0.0;  ///< [s]
    double x = 0.0, y = 0.0, z = 0.0;
    Row() = default;
    Row(double t_, double x_, double z_) : t(t_), x(x_), z(z_) {}
    Row(double t_, double x_, double y_, double z_) : t(t_), x(x_), y(y_), z(z_) {}
  };
  std::vector<Row> table;    ///< tables, t strictly increasing; held constant after the last row
  ShipTrack ship_track;      ///< ShipTrack: speed, initial heading and legs, started at the static top

  /// Velocity BCs (paper eq. 34, default) or positions prescribed directly in the Newton system.
  bool prescribe_position = false;

  /// Empty when valid, else "dynamics.top_motion.<key> = value: constraint".
  std::string validate() const;
};

/// A line event in a dynamic run (`dynamics.events`, issue 21): an end of the line let go, or
/// the line parting. After it the loose ends are free ends that carry no force (docs/method.md,
/// "Line events"); 3-D formulation only.
struct LineEvent {
  enum class Type { Release, Break };
  /// The line's ends: its top (upper end) and its anchor (lower end).
  enum class End { Top, Anchor };
  Type type = Type::Release;
  End end = End::Top;   ///< Release: the end let go
  /// Release, timed Break: the time [s] (>= 0); < 0 when not given (a Break on tension).
  double t = -1.0;
  /// Break: the line parts when a node's tension first exceeds this [N] (0: not given).
  double tension = 0.0;
  /// Break: ... or first reaches its material's `mbl` (`tension: mbl`).
  bool at_mbl = false;
  /// Timed Break: the arclength of the break from the lower end [m]; < 0: at the node with the
  /// largest tension at time t (as a tension-triggered break).
  double s = -1.0;
  /// In a system file: the name of the line (empty in a single-line problem).
  std::string line;

  bool onTension() const { return type == Type::Break && (tension > 0.0 || at_mbl); }
  /// Empty when valid, else "<key>.<field> = value: constraint" with `key` the event's key
  /// (e.g. "dynamics.events[0]").
  std::string validate(const std::string& key) const;
};

/// A line event that happened (what a run reports).
struct LineEventRecord {
  double t = 0.0;           ///< [s]
  /// "released top", "released anchor" or "parted": the line parts between nodes `node` and
  /// `node` + 1 (a break at an end node is that end's release).
  std::string what;
  int node = 0;             ///< the node of the release or, when parted, the lower node of the cut
  double s = 0.0;           ///< its arclength from the lower end [m]
  double tension = 0.0;     ///< the largest tension of the line just before the event [N]
  std::string cause;        ///< "at t = 30 s", "tension 2.1e5 N > 2e5 N at node 12", "released by a service call"
  std::string line;         ///< systems: the line's name
};

/// One line of text for a summary or a diagnostic: "t = 30 s: leg_e released top, largest
/// tension 42335.0 N (at t = 30 s)".
std::string lineEventText(const LineEventRecord& e);

struct DynamicOptions {
  double duration = 0.0;         ///< simulated time [s], > 0 for a dynamic run
  double dt = 0.1;               ///< base time step [s]; also the output grid unless output_interval is set
  double output_interval = 0.0;  ///< time series sampling [s]; 0 = dt; must be a multiple of dt
  double snapshot_interval = 0.0;///< full line snapshots every this many seconds; 0 = none
  std::vector<double> record_s;  ///< arclengths [m] of nodes whose tension and position are recorded

  GeneralizedAlpha scheme = GeneralizedAlpha::fromLambdaInf(-0.5);  ///< section 4, default lambda_inf = -0.5
  std::string scheme_name = "lambda_inf=-0.5";                       ///< for reports

  int max_cut_levels = 4;        ///< adaptive time stepping: dt / 10^level down to 1e-4 dt (4.3)
  double tolerance = 1.0e-6;     ///< Newton tolerance on sigma (eq. 39) per step
  int max_iterations = 30;       ///< Newton iterations per step before the step is cut
  double relaxation = 1.0;       ///< mu0 of the per-step Newton iteration
  bool adaptive_relaxation = true;
  /// Modified Newton: keep a step's factored Jacobian for later iterations and steps of the
  /// same size while each update shrinks fast enough (NewtonOptions::reuse_rate). Same
  /// tolerance, fewer assemblies; off by default, worth it on smooth problems (a tow), not where
  /// contact events make the Jacobian jump (it changed where the 2-D chain mooring cut steps).
  /// The step predictor then extrapolates the rate's change too (docs/method.md).
  bool jacobian_reuse = false;
  /// With jacobian_reuse: the kept Jacobian stays while each update shrinks sigma (eq. 39) to at
  /// most this fraction of the one before (NewtonOptions::reuse_rate), in (0, 1). It trades
  /// assemblies for iterations: 0.15 (the default) suits a smooth tow, whose few Jacobians are
  /// cheap beside its iterations; a moored line in a storm, whose Jacobian (an automatic-
  /// differentiation assembly and a block LU) costs some fifteen iterations and goes stale
  /// within a step or two, runs faster at 0.5 (docs/performance.md, "Storms").
  double jacobian_reuse_rate = 0.15;
  /// Halve a Newton update that undoes the one before (NewtonOptions::damp_two_cycles): a
  /// touchdown node cycling in and out of contact. Same tolerance, fewer iterations where the
  /// line lands on the seabed (A.3: 11 744 -> 11 144); off by default, so that the paper cases'
  /// published runs stay as they are (the box method's step cuts move with any change).
  bool damp_two_cycles = false;
  /// A base step that the implicit scheme cannot take at max_cut_levels cuts is taken by the
  /// 3-D solver's explicit lumped-mass step of the line (docs/method.md "Slack and snap: the
  /// fallback step"), counted in the summaries; false: such a step stops the run, as the paper's
  /// method alone does. The 2-D solver has none.
  bool fallback = true;
  /// Cuts a base step gets before what is left of it goes to the fallback step, in [0, 8]
  /// (capped at max_cut_levels), or kFallbackAfterCutsAuto (the default, when the file does not
  /// say): 1 for a line with a material that carries no compression (chain, rope, wire: the
  /// lines that go slack and snap), 4 (= max_cut_levels) for others. 4: only steps the implicit
  /// scheme cannot take at all, so a run that goes through without the fallback is unchanged bit
  /// for bit. 0-1: slack-and-snap steps go to the fallback at once or after one cut; the deeper
  /// cuts cost many failed Newton iterations, and the tiny steps they end in give snap loads
  /// several times too large (docs/problem_format.md).
  static constexpr int kFallbackAfterCutsAuto = -1;
  int fallback_after_cuts = kFallbackAfterCutsAuto;

  /// Threads of the 2-D and 3-D dynamic solvers, 1 or 2: with 2 a second thread assembles and
  /// eliminates the upper half of the line in every Newton iteration (the Newton matrix's
  /// two-ended elimination, BandedMatrix::factorize). The results are the same bit for bit.
  /// Systems (SystemDynamics) refuse 2.
  int threads = 1;

  bool adaptive_mesh = false;    ///< section 3, eqs. 15-24
  double mesh_weight = 20.0;     ///< c_w of eq. 15

  TopMotion top_motion;
  /// A real ship track (`dynamics.gnss`): GNSS fixes and headings drive the top or the vessel.
  GnssOptions gnss;
  /// Releases and breaks (`dynamics.events`), in the order given.
  std::vector<LineEvent> events;
  /// A winch at the top paying the line out or hauling it in (`dynamics.winch`; given = false:
  /// none, the length fixed).
  Winch winch;

  std::string validate() const;
};

}  // namespace core
}  // namespace mooring_dynamics
