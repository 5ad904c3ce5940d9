// Systems of several lines (issue 6; paper: "multi-leg and branched array systems"): points
// (anchors, fixed points, free surface buoys, free submerged bodies) joined by lines, each line a
// single-line problem of model.hpp between two points (or from a free end up to a point).
//
// Statics by partitioned Newton: the unknowns are the positions of the free points; for given
// positions every line is solved on its own (its own banded Newton system, cost linear in its
// node count), and the residual is the force balance of every free point (the lines' pulls plus
// the point's own buoyancy, weight and drag). The point Jacobian (3 x 3 blocks per pair of
// points joined by a line) is built by finite differences, one perturbation of each point
// coordinate re-solving only the lines at that point. The outer system has 3 unknowns per free
// point, so the whole solve stays linear in the number of nodes: the paper's outer iteration of
// section 5.1 ("consecutively better guesses") made a Newton iteration.
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model.hpp"
#include "mooring_dynamics/core/result.hpp"

namespace mooring_dynamics {
namespace core {

/// A connection point of a system. Positions in the problem frame [m].
struct SystemPoint {
  enum class Type {
    Anchor,  ///< fixed on (or above) the seabed
    Fixed,   ///< fixed anywhere, e.g. a vessel's fairlead
    Buoy,    ///< a free surface buoy (SurfaceBuoy: its draft, current drag and wind balance the lines)
    Body     ///< a free submerged body (net buoyancy or weight, drag), e.g. a junction float or clump
  };
  std::string name;
  Type type = Type::Anchor;
  double x = 0.0, y = 0.0, z = 0.0;  ///< fixed position, or the initial guess of a free point
  bool position_given = false;       ///< free points: x, y, z is a user guess
  SurfaceBuoy buoy;                  ///< Buoy
  std::size_t body = static_cast<std::size_t>(-1);  ///< Body: index into SystemProblem::bodies
  bool free() const { return type == Type::Buoy || type == Type::Body; }
};

/// A line of a system, from its lower end (node 0: the `from` point or a free end) to its upper
/// end (the `to` point).
struct SystemLine {
  std::string name;
  std::vector<Segment> segments;  ///< from the lower end up (indices into SystemProblem materials/bodies)
  static constexpr std::size_t kFreeEnd = static_cast<std::size_t>(-1);
  std::size_t from = kFreeEnd;    ///< point index of the lower end, or kFreeEnd
  std::size_t to = 0;             ///< point index of the upper end
  std::size_t end_body = Problem::kNoBody;  ///< free lower end: body hanging there, or kNoBody
};

struct SystemProblem {
  std::string name;
  Formulation formulation = Formulation::ThreeD;
  Environment environment;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<SystemPoint> points;
  std::vector<SystemLine> lines;
  StaticOptions static_options;  ///< for every line's solve
  /// `dynamics:` of the file (duration, dt, scheme, tolerances; no top motion: the free points
  /// move by themselves) for SystemDynamics / `cable_sim dynamic`.
  DynamicOptions dynamics;

  /// Empty when consistent, else a message naming the field, value and constraint: unknown
  /// points, a line from a point to itself, unused points, a graph in several pieces, no anchor
  /// or fixed point, and the single-line checks of every line.
  std::string validate() const;
  /// The single-line problem of line i with its ends at the given positions of its points.
  Problem lineProblem(std::size_t i, const std::vector<double>& xyz) const;
};

/// Options of the outer (point) iteration.
struct SystemSolveOptions {
  int max_iterations = 50;
  double force_tolerance = 1e-6;  ///< stop when every point's force residual < this times the largest line tension
  double fd_step = 1e-4;          ///< finite-difference step of a point coordinate [m]
  double max_move = 0.1;          ///< largest move of a point per iteration, as a fraction of its shortest line
};

struct SystemPointResult {
  std::string name;
  double x = 0.0, y = 0.0, z = 0.0;  ///< [m]
  /// Sum of the lines' pulls on the point [N] (for a fixed point or anchor: what it must resist).
  double fx = 0.0, fy = 0.0, fz = 0.0;
  double residual = 0.0;             ///< free points: |force balance| at the solution [N]
  double buoy_draft = 0.0;           ///< Buoy: draft [m]
};

struct SystemStaticResult {
  std::vector<StaticResult> lines;   ///< per line, in SystemProblem::lines order
  std::vector<SystemPointResult> points;
  SolverSummary summary;             ///< of the outer iteration (iterations, largest residual [N], message)
};

/// Solve the statics of a system. Throws std::invalid_argument when the system is invalid.
SystemStaticResult solveSystemStatic(const SystemProblem& system, const SystemSolveOptions& options = {});

}  // namespace core
}  // namespace mooring_dynamics
