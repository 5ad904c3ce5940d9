// A winch at the top of a line (`dynamics.winch`, issue 21; docs/method.md "Winch"): it pays the
// line out or hauls it in, so that the line's unstretched length L(t) [m] follows a constant rate
// or a table. The length is the whole line's, anchor (or free lower end) to the top; the winch
// takes in and gives out the top segment only. Plain structs; validation names the file key.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

/// The line's unstretched length as a function of time: piecewise linear through knots
/// (t_k, L_k), L_0 before the first knot, and after the last one L_last + rate_after (t - t_last).
/// What a winch does from the file's `dynamics.winch` or from a command (WinchProgram::toward).
struct WinchProgram {
  std::vector<double> t, length;  ///< knots: t strictly increasing [s], lengths [m]
  double rate_after = 0.0;        ///< [m/s] after the last knot (+ pays out)

  bool empty() const { return t.empty(); }
  /// L(t) [m].
  double lengthAt(double time) const;
  /// dL/dt [m/s] on the piece that ends at `time` (the rate of the step that ends there).
  double rateAt(double time) const;
  /// From (t0, L0): at speed |rate| to `target` [m] and held there, or (target NaN) at `rate` for
  /// ever.
  static WinchProgram toward(double t0, double L0, double rate, double target);
};

/// `dynamics.winch` of a problem file.
struct Winch {
  bool given = false;
  /// Constant rate [m/s]: > 0 pays out, < 0 hauls in, from t = 0 (exclusive with `table`).
  double rate = 0.0;
  /// Rows (t [s], L [m]): the line's length, linear in between, held after the last row. The
  /// first row's length is the file's line length (the run starts from its statics).
  std::vector<std::vector<double>> table;
  /// Limits of the length [m]: a program or command that would pass one is an error, never a
  /// clamp. 0: no limit given (the top segment still bounds a haul-in, validateWinchOnLine).
  double min_length = 0.0;
  double max_length = 0.0;
  /// In a system file: the line the winch pays out (empty in a single-line problem).
  std::string line;

  /// Empty when valid on its own, else "<key>.<field> = value: constraint".
  std::string validate(const std::string& key) const;
  /// The program of the file from the line's length L0 at t = 0.
  WinchProgram program(double L0) const;
};

/// The shortest top segment a winch may leave, as a fraction of the segment's mesh spacing: the
/// top interval's stiffness EA / h grows without bound as it shrinks.
constexpr double kWinchShortestTopFraction = 0.5;

/// Checks of a winch against its line: `top_start` the arclength where the top segment starts,
/// `spacing` its mesh spacing, `L0` the line's length [m]; the table's first length is L0 (within
/// 1 mm); over [0, duration] L(t) stays within the limits and above top_start +
/// kWinchShortestTopFraction spacing. Empty when valid.
std::string validateWinchOnLine(const Winch& w, const std::string& key, double L0, double top_start, double spacing,
                                double duration);

/// Where a program first leaves [lo, hi] in [t0, t1] ([m], [s]): the time, or NaN when never.
double winchLimitCrossing(const WinchProgram& p, double lo, double hi, double t0, double t1);

}  // namespace core
}  // namespace mooring_dynamics
