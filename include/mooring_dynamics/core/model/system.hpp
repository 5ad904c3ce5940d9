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
//
// A moored vessel (a rigid body with a full pose) is a system whose `vessel` points are its
// fairleads: fixed in the body frame, placed in the world by the vessel's pose (placeVessel).
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model/hull_slow_motion.hpp"
#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"
#include "mooring_dynamics/core/model/rao.hpp"
#include "mooring_dynamics/core/model/wave_drift.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"

namespace mooring_dynamics {
namespace core {

/// A connection point of a system. Positions in the problem (world) frame [m].
struct SystemPoint {
  enum class Type {
    Anchor,  ///< fixed on (or above) the seabed
    Fixed,   ///< fixed anywhere in the world
    Buoy,    ///< a free surface buoy (SurfaceBuoy: its draft, current drag and wind balance the lines)
    Body,    ///< a free submerged body (net buoyancy or weight, drag), e.g. a junction float or clump
    Vessel   ///< a fairlead: fixed to the vessel at `body_offset` in its body frame, moves with its pose
  };
  std::string name;
  Type type = Type::Anchor;
  /// World position: fixed, the initial guess of a free point, or (Vessel) the fairlead where
  /// the vessel's pose puts it (SystemProblem::placeVessel keeps it so).
  double x = 0.0, y = 0.0, z = 0.0;
  Eigen::Vector3d body_offset = Eigen::Vector3d::Zero();  ///< Vessel: fairlead in the body frame [m]
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

/// The rigid body the `vessel` points are fixed to (a ship, a spar or disk buoy, a platform).
struct Vessel {
  bool present = false;            ///< the file has a `vessel:` section
  std::string frame = "base_link"; ///< name of its body frame (tf, REP 105 style)
  RigidPose pose;                  ///< reference pose (statics, the start of a dynamic run), world frame
  /// `vessel.motion_table`: CSV of the vessel's pose in time for `cable_sim dynamic` (t, x, y, z,
  /// qx, qy, qz, qw; world frame), path resolved against the problem file's folder; "" = none.
  std::string motion_table;
  /// `vessel.sea_state` given: the vessel moves about `pose` in the sea of environment.waves (which
  /// the file's vessel.sea_state sets, so that the lines see the same waves) by its RAOs
  /// (SeaStateMotion); `raos` and `rao_table` say how and hold the table read.
  bool sea_state = false;
  RaoSource raos;
  RaoTable rao_table;
  /// `vessel.low_frequency` given: the hull's slow surge, sway and yaw move under the lines'
  /// wrench and `slow.mean_force` (HullSlowMotion), in still water or under the sea state's motion.
  bool low_frequency = false;
  HullSlowMotionOptions slow;
  /// `vessel.low_frequency.wave_drift` given: the mean and slowly varying wave drift of the sea
  /// state on the slow motion (WaveDrift), from the coefficients read into `drift_table` (SI).
  bool wave_drift = false;
  WaveDriftSource drift;
  RaoTable drift_table;
};

struct SystemProblem {
  std::string name;
  Formulation formulation = Formulation::ThreeD;
  Environment environment;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<SystemPoint> points;
  std::vector<SystemLine> lines;
  Vessel vessel;
  StaticOptions static_options;  ///< for every line's solve
  /// `dynamics:` of the file (duration, dt, scheme, tolerances; no top motion: the free points
  /// move by themselves) for SystemDynamics / `cable_sim dynamic`.
  DynamicOptions dynamics;
  ResourceLimits limits;  ///< `limits:` of the file (limits.hpp), for all lines together

  /// Empty when consistent, else a message naming the field, value and constraint: unknown
  /// points, a line from a point to itself, unused points, a graph in several pieces, no anchor
  /// or fixed point, and the single-line checks of every line.
  std::string validate() const;
  /// The single-line problem of line i with its ends at the given positions of its points.
  Problem lineProblem(std::size_t i, const std::vector<double>& xyz) const;
  /// Sets vessel.pose and puts every `vessel` point where that pose takes its body offset.
  void placeVessel(const RigidPose& pose);
  /// True when some point is a `vessel` point.
  bool hasVesselPoints() const;
};

}  // namespace core
}  // namespace mooring_dynamics
