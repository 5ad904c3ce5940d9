// Problem description for the cable solver: materials, inline bodies, the line from anchor to
// top, the environment and the top boundary condition. Plain structs, no ROS, no YAML.
//
// Frame (REP 103): x east, y north, z up; z = 0 is the mean sea surface. The 2-D solver works in
// the vertical x-z plane through the anchor. All quantities SI.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/model/dynamics_options.hpp"
#include "mooring_dynamics/core/model/limits.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

/// Strain over which a line that carries no compression goes from slack to taut [-]: the law is
/// rounded over |eps_raw| < kSlackStrain / 2 around its zero (see Material::compression), so that
/// its slope is continuous and Newton stays well posed. 1e-6 is far below any working strain
/// (a chain at 1 % of its breaking load has strain ~1e-4); the band in tension, EA kSlackStrain,
/// is 64 N for the A.3 chain, whose grounded end rests at 260 N: a wider band (1e-5, 640 N)
/// reached into that chain's working range and its dynamic run lost Newton convergence there.
constexpr double kSlackStrain = 1.0e-6;

/// Slope of the slack law that Newton's Jacobian sees where the law itself is flat, as a
/// fraction of the law's slope at zero strain [-]. A slack stretch has T = 0 whatever its strain,
/// so its strain has no restoring force: the box scheme's odd-even mode of the strain (nodal
/// strains alternating about their mean, which the coordinate rows of eq. 42 do not see) is then
/// singular, and a wholly slack line cannot be solved. The Jacobian keeps this small slope there;
/// the residual, hence the converged state and its tensions, keeps the exact law (T = 0).
constexpr double kSlackJacobianFraction = 1.0e-3;

/// The rounded ramp max(T, 0) of a line without compression: T when T >= b / 2, 0 when
/// T <= -b / 2, (T + b / 2)^2 / (2 b) between (value and slope continuous), band b > 0 [N].
/// Never negative; at most b / 8 above max(T, 0). `Tv` is the value of T (T itself may be an
/// automatic-differentiation scalar, whose derivative is kept at least kSlackJacobianFraction
/// times that of T: the slope Newton sees, see above).
template <class S>
S slackRamp(const S& T, double Tv, double b) {
  if (Tv >= 0.5 * b) return T;
  const double u = Tv + 0.5 * b;
  if (u <= 0.0) return kSlackJacobianFraction * (T - Tv);  // value 0
  if (u <= kSlackJacobianFraction * b) return u * u / (2.0 * b) + kSlackJacobianFraction * (T - Tv);
  const S uS = T + 0.5 * b;
  return uS * uS / (2.0 * b);
}
inline double slackRamp(double T, double Tv, double b) {
  (void)Tv;
  if (T >= 0.5 * b) return T;
  if (T <= -0.5 * b) return 0.0;
  const double u = T + 0.5 * b;
  return u * u / (2.0 * b);
}

/// Axial constitutive law T(eps): linear (EA) or a piecewise-linear tension-strain table.
/// By default (`compression: true`) the law holds below zero strain too, as WHOI Cable's (the
/// paper's eq. 9); `compression: false` (ropes and chains that must never push) makes it
/// slackRamp of the linear or table law, rounded over kSlackStrain. Not the default because the
/// box scheme cannot yet run every wholly slack stretch through (docs/method.md, "Slack lines").
struct Material {
  std::string name;
  double EA = 0.0;                        ///< axial stiffness [N]; used when the table is empty
  std::vector<std::pair<double, double>> tension_strain;  ///< (strain [-], tension [N]), strain increasing
  double EI = 0.0;                        ///< bending stiffness [N m^2], > 0
  double GJ = 0.0;                        ///< torsional stiffness [N m^2] (3-D only)
  double mass = 0.0;                      ///< mass per unstretched length [kg/m]
  double added_mass = 0.0;                ///< normal added mass per unstretched length [kg/m]
  double wet_weight = 0.0;                ///< weight in water per unstretched length [N/m]; < 0 is buoyant
  double diameter = 0.0;                  ///< hydrodynamic diameter [m]
  double cdn = 0.0;                       ///< normal drag coefficient [-]
  double cdt = 0.0;                       ///< tangential drag coefficient [-]
  double max_strain = 0.2;                ///< strain beyond which the law is not trusted [-]
  double mbl = 0.0;                       ///< minimum breaking load [N]; 0 = not given
  /// What the line is (YAML `type`): chain, rope, wire, rod, pipe or umbilical; "" not given.
  /// It sets the default of `compression` (materialCarriesCompression).
  std::string kind;
  bool compression = true;                ///< the law holds below zero strain too (else slackRamp)
  /// Coulomb friction coefficients on the seabed, along the line and across it [-], times the
  /// seabed reaction (docs/method.md, "Seabed friction"); 0 = frictionless (the default).
  double mu_axial = 0.0;
  double mu_lateral = 0.0;

  /// Effective tension T(eps) [N] and its slope dT/deps [N] as Newton's Jacobian takes it: the
  /// true slope, but at least kSlackJacobianFraction of the law's where a slack law is flat.
  double tension(double eps) const;
  double tensionSlope(double eps) const;
  /// Inverse law: strain at tension T [-]. Without compression, T <= 0 gives the strain where
  /// the rounded law reaches zero.
  double strainAt(double T) const;
  /// The law as given (linear or table), without the slack ramp, and its slope [N].
  double rawTension(double eps) const;
  double rawTensionSlope(double eps) const;
  /// Width in tension of the slack ramp, kSlackStrain times the law's slope at zero strain [N].
  double slackBand() const;
};

/// The material kinds of the YAML key `type`, and whether each carries compression unless the
/// file says otherwise: chain, rope and wire do not (they cannot push: their tension is >= 0
/// exactly); rod, pipe and umbilical do (the law through zero, with bending), and so does a
/// material of no given type (WHOI Cable's law, the paper's eq. 9).
const std::vector<std::string>& materialKinds();
bool materialCarriesCompression(const std::string& kind);

/// A point body on the line: float, clump weight or instrument.
struct Body {
  std::string name;
  double mass = 0.0;         ///< [kg]
  double added_mass = 0.0;   ///< [kg]
  double wet_weight = 0.0;   ///< weight in water [N]; negative is buoyant
  double diameter = 0.0;     ///< diameter of the sphere with the same projected area [m]
  /// Drag law. Sphere (YAML `cd`): 1/2 rho Cd A |r| r on the water velocity r relative to the
  /// body, A = pi d^2 / 4, whatever the line's direction. LineAligned (YAML `cdn` and `cdt`, for
  /// elongated bodies): the relative velocity split along the line's tangent (cdt) and across it
  /// (cdn), each component with its own coefficient (the convention of WHOI Cable).
  enum class Drag { Sphere, LineAligned };
  Drag drag = Drag::LineAligned;
  double cd = 0.0;           ///< Sphere: drag coefficient [-]
  double cdn = 0.0;          ///< LineAligned: drag coefficient normal to the line [-]
  double cdt = 0.0;          ///< LineAligned: drag coefficient along the line [-]

  /// The coefficient of a point where no line tangent is defined (a junction of the lines of a
  /// system): cd for a sphere, cdn for a line-aligned body [-].
  double isotropicCd() const { return drag == Drag::Sphere ? cd : cdn; }
};

/// A body placed on a segment at a distance from the segment's lower end.
struct BodyPlacement {
  std::size_t body = 0;  ///< index into Problem::bodies
  double at = 0.0;       ///< unstretched arclength from the segment's lower end [m], 0 <= at <= length
};

/// A uniform cable segment. Segments are listed from the anchor to the top.
struct Segment {
  std::size_t material = 0;            ///< index into Problem::materials
  double length = 0.0;                 ///< unstretched length [m]
  double spacing = 1.0;                ///< target node spacing [m]; the segment gets ceil(length/spacing) intervals
  std::vector<BodyPlacement> bodies;   ///< inline bodies on this segment
};

/// One point of a current profile table.
struct CurrentPoint {
  double depth = 0.0;          ///< depth below the mean surface [m], >= 0
  double speed = 0.0;          ///< [m/s], >= 0
  double direction = 0.0;      ///< direction the water flows toward, counterclockwise from +x (east) [rad]
};

/// A current table (Environment::current) with its velocity components computed once: at() and
/// gradientAt() are Environment::currentAt and currentGradientAt, bit for bit, without a cosine
/// and sine per table point and call (the dynamic solvers ask at every node and iteration).
class CurrentProfile {
 public:
  CurrentProfile() = default;
  explicit CurrentProfile(const std::vector<CurrentPoint>& table);
  /// Current velocity (east, north) [m/s] at elevation z [m].
  void at(double z, double& ux, double& uy) const;
  /// Its vertical gradient d(ux, uy)/dz [1/s].
  void gradientAt(double z, double& dux_dz, double& duy_dz) const;
  /// at(z) and the east components at z + dz and z - dz [m/s] (dz > 0 [m]) with one search of
  /// the table: the same values bit for bit as three calls of at().
  void atAndAround(double z, double dz, double& ux, double& uy, double& ux_above, double& ux_below) const;
  std::size_t size() const { return depth_.size(); }
  /// The table's depth [m] and velocity components [m/s] at point i.
  double depth(std::size_t i) const { return depth_[i]; }
  void comp(std::size_t i, double& cx, double& cy) const {
    cx = ux_[i];
    cy = uy_[i];
  }

 private:
  std::vector<double> depth_, ux_, uy_;  ///< table depths [m] and velocity components [m/s]
};

/// Bathymetry on a regular grid in x (east) and y (north), bilinear between the grid points and
/// held at the edge values outside (problem file `environment.seabed.grid_file`).
struct SeabedGrid {
  double x0 = 0.0, y0 = 0.0;   ///< position of the first grid point, the south-west corner [m]
  double dx = 1.0, dy = 1.0;   ///< grid spacing in x and y [m], > 0
  std::size_t nx = 0, ny = 0;  ///< number of grid points in x and y, >= 2 each; 0 = no grid
  /// Depths below the mean surface [m], > 0 (positive down), stored row by row in y with x
  /// varying fastest: depths[iy * nx + ix] is the depth at (x0 + ix dx, y0 + iy dy). The first
  /// row is the southern edge y = y0 (the file order of the grid file format).
  std::vector<double> depths;
  std::string source;          ///< file the grid was read from, for messages; "" when built in code

  bool empty() const { return depths.empty(); }
  /// Depth [m] at grid point (ix, iy), unchecked.
  double at(std::size_t ix, std::size_t iy) const { return depths[iy * nx + ix]; }
  /// Bilinear depth [m] at (x, y) [m]; outside the grid the coordinates are clamped to the edges.
  /// Needs a valid grid (validate() empty).
  double depthAt(double x, double y) const;
  /// Gradient of depthAt [-]: d(depth)/dx and d(depth)/dy. In a direction where the point is
  /// clamped (outside the grid, or on its edge) that component is 0; on an inner grid line the
  /// cell on the east (north) side is used.
  void depthGradient(double x, double y, double& dd_dx, double& dd_dy) const;
  /// Empty when valid, else "environment.seabed.grid.<field> = value: constraint".
  std::string validate() const;
};

/// Seabed: elastic foundation (paper section 5.3).
struct Seabed {
  double stiffness = 1.0e5;    ///< k, force per unit line length per metre of penetration [N/m^2]
  double damping = 0.0;        ///< b, dashpot per unit line length [N s/m^2] (dynamics)
  /// Static cap of eq. 35: the reaction on a stretch of line never exceeds its wet weight w_o.
  /// Off by default: a capped seabed cannot carry a concentrated reaction (a ridge under a taut
  /// line, a clump weight on the bottom), which then sinks in without end (docs/method.md).
  bool static_cap = false;
  /// Optional bottom profile (x [m], depth [m]) with x increasing; empty means flat at Environment::depth.
  std::vector<std::pair<double, double>> profile;
  /// Optional bathymetry grid varying in x and y; when given it replaces the flat depth (the
  /// profile and the grid are exclusive).
  SeabedGrid grid;
};

struct Environment {
  double water_density = 1025.0;  ///< rho_w [kg/m^3]
  double air_density = 1.225;     ///< [kg/m^3]
  double gravity = 9.81;          ///< g [m/s^2]
  double depth = 100.0;           ///< water depth for a flat seabed [m]; always the depth of the wave dispersion relation
  Seabed seabed;
  std::vector<CurrentPoint> current;  ///< profile, depth increasing; empty means no current
  double wind_speed = 0.0;            ///< at the buoy [m/s]
  double wind_direction = 0.0;        ///< direction the wind blows toward, counterclockwise from +x [rad]
  WaveSpec waves;                     ///< surface waves (dynamics); none by default

  /// Seabed elevation z_bot(x, y) [m] (negative below the surface): the grid if there is one,
  /// else the x profile, else flat at -depth.
  double seabedElevation(double x, double y) const;
  /// Its gradient dz_bot/dx, dz_bot/dy [-] (0 where the grid or profile is held at an edge value).
  void seabedGradient(double x, double y, double& dzdx, double& dzdy) const;
  /// The 2-D solver's section y = 0: seabedElevation(x, 0) and its slope dz_bot/dx [-].
  double seabedElevation(double x) const;
  double seabedSlope(double x) const;
  /// Neither a grid nor a profile: the seabed is flat at -depth (and its gradient zero).
  bool flatSeabed() const { return seabed.grid.empty() && seabed.profile.empty(); }
  /// Current velocity (east, north) [m/s] at elevation z [m] (z <= 0 in water).
  void currentAt(double z, double& ux, double& uy) const;
  /// Vertical gradient d(ux, uy)/dz [1/s] of currentAt at elevation z [m]: the slope of the
  /// piecewise-linear profile (for Jacobians). Zero above the first and below the last point,
  /// above the surface and for a uniform or absent current. A depth d = -z exactly on a table
  /// point takes the slope of the interval above it (the interval currentAt interpolates in),
  /// and the first point itself belongs to the constant part above it.
  void currentGradientAt(double z, double& dux_dz, double& duy_dz) const;
};

/// A surface buoy at the top of the line (paper 5.1): its draft balances the line.
struct SurfaceBuoy {
  enum class Shape { Sphere, Cylinder };  ///< cylinder: vertical axis
  Shape shape = Shape::Sphere;
  double diameter = 1.0;   ///< [m]
  double height = 1.0;     ///< cylinder height [m]; a sphere's is its diameter
  double mass = 0.0;       ///< [kg]
  double added_mass = 0.0; ///< [kg] (dynamics)
  double cd = 1.0;         ///< drag coefficient of the submerged part [-]
  double wind_area = 0.0;  ///< projected area above water [m^2]
  double wind_cd = 1.0;    ///< drag coefficient in air [-]

  double totalHeight() const { return shape == Shape::Sphere ? diameter : height; }
  /// Submerged volume [m^3] and its derivative [m^2] at draft d [m] (clamped to [0, height]).
  double submergedVolume(double d) const;
  double submergedVolumeSlope(double d) const;
  /// Submerged projected area seen by a horizontal current [m^2] and its derivative [m] at draft d.
  double submergedArea(double d) const;
  double submergedAreaSlope(double d) const;
};

/// What holds the top end of the line in statics.
struct TopBoundary {
  /// Body: a subsurface buoy (or any point body) at the top, held by nothing but the line: its
  /// net buoyancy, drag and (in dynamics) inertia balance the line's pull (3-D model).
  enum class Type { Force, Position, Buoy, Body };
  Type type = Type::Position;
  double fx = 0.0, fz = 0.0;   ///< Force: force applied to the line's top end by the platform [N]
  double fy = 0.0;             ///< Force, y component [N] (3-D model only; 0 in 2-D)
  double x = 0.0, z = 0.0;     ///< Position: top end position in the problem frame [m]
  double y = 0.0;              ///< Position, y component [m] (3-D model only; 0 in 2-D)
  /// Position with a free lower end (towing): the top moves steadily at this horizontal velocity
  /// [m/s] and statics solve the steady tow in the frame moving with it, i.e. with the water
  /// velocity relative to the top (current minus this velocity). YAML `top.tow_velocity`.
  double tow_vx = 0.0, tow_vy = 0.0;
  SurfaceBuoy buoy;            ///< Buoy: the buoy that floats at the top
  std::size_t body = static_cast<std::size_t>(-1);  ///< Body: index into Problem::bodies
};

/// Numerical options of the static solver (Newton relaxation, paper section 6).
struct StaticOptions {
  double tolerance = 1.0e-9;      ///< convergence when the scaled update sigma (eq. 39) falls below this [-]
  int max_iterations = 500;       ///< Newton iterations before giving up
  double relaxation = 1.0;        ///< mu0, the baseline relaxation factor, in (0, 1]
  bool adaptive_relaxation = true;///< eqs. 40-41; false keeps mu = mu0 throughout
  double R1 = 1.1;                ///< mu divided by R1 when sigma grows (eq. 40), > R2
  double R2 = 1.02;               ///< mu multiplied by R2 when sigma shrinks (eq. 41), > 1
  /// Starting shape of the Newton iteration: a generalized elastic catenary found by shooting
  /// (robust, default) or a straight line from the anchor toward the top (a poor start, useful to
  /// exercise the relaxation).
  enum class InitialGuess { Catenary, StraightLine };
  InitialGuess initial_guess = InitialGuess::Catenary;

  /// Empty when valid, else a message naming the field, its value and the constraint.
  std::string validate() const;
};

/// Which equations solve the problem: the 2-D equations of the paper (eqs. 1-6, the line in the
/// vertical x-z plane, N = 6) or the 3-D equations (DESIGN.md section 3, N = 13 with Euler
/// parameters; any geometry). Problem file key `model: 2d | 3d`.
enum class Formulation { TwoD, ThreeD };

/// A complete single-line problem.
struct Problem {
  std::string name;
  Formulation formulation = Formulation::TwoD;
  Environment environment;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<Segment> segments;  ///< anchor to top
  /// The lower end (node 0): held by the anchor, or free (a towed line, a drogue) with an
  /// optional body hanging there. YAML `free_end:` instead of `anchor:`. 3-D model only.
  enum class LowerEnd { Anchor, Free };
  LowerEnd lower_end = LowerEnd::Anchor;
  static constexpr std::size_t kNoBody = static_cast<std::size_t>(-1);
  std::size_t end_body = kNoBody;  ///< index into bodies of the body at a free lower end (tow body), or kNoBody
  double anchor_x = 0.0;          ///< anchor position [m]
  double anchor_y = 0.0;          ///< [m] (3-D model only; 0 in 2-D)
  double anchor_z = -100.0;       ///< [m]
  TopBoundary top;
  StaticOptions static_options;
  DynamicOptions dynamics;        ///< problem-file section `dynamics:`
  ResourceLimits limits;          ///< problem-file section `limits:` (limits.hpp)

  double totalLength() const;
  /// Empty when the problem is consistent, else a message naming the field, value and constraint.
  std::string validate() const;
  /// The part of validate() on derived sizes: node and step counts and the memory estimate
  /// against `limits` (limits.hpp); the CLI calls it again after its overrides.
  std::string validateResources() const;
};

/// The checks of one line event against its line (dynamics.events[i], `key` its key): `s`
/// within the line, an `mbl` to break at, an anchor that is not free already. `line` names the
/// line in messages ("the line", "line leg_e"). Empty when valid.
/// Where the part of a line a winch can take in starts [m from the lower end]: the top segment's
/// start, or its last inline body.
double winchBase(const std::vector<Segment>& segments);
/// The checks of a winch against the line `segments` (validateWinchOnLine with the line's length,
/// winchBase and the top segment's spacing). Empty when valid.
std::string validateWinchOnSegments(const Winch& w, const std::string& key, const std::vector<Segment>& segments,
                                    double duration);

std::string validateEventOnLine(const LineEvent& ev, const std::string& key, const std::string& line,
                                const std::vector<Segment>& segments, const std::vector<Material>& materials,
                                bool lower_end_free);

}  // namespace core
}  // namespace mooring_dynamics
