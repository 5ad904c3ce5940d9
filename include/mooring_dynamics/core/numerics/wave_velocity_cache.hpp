// Wave kinematics at a line's nodes, cached for the time-domain solvers: WaveField::velocity
// (model/waves.hpp) evaluated point by point with per-component constants and second-order
// expansions about each point's reference, within a bounded error. A numerical device of the
// dynamic solvers, not part of the wave model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

/// Water-particle velocity of a WaveField in the x-z plane (y = 0) at a fixed set of points
/// that move little between evaluations, such as the nodes of a line over the Newton iterations
/// of its time steps. The phase of component i at point x and time t is split as
/// B_i + A_i with A_i = phase_i - omega_i t (cos, sin once per time for all points) and
/// B_i = k_i cos(theta_i) x; the depth factors cosh, sinh of k_i (z + h) / sinh(k_i h) are sums
/// of two exponentials E+-_i = e^{+-k_i (z + o+-_i)}. Per point, cos and sin of B_i and E+-_i are
/// kept at a reference position and carried to (x, z) by the angle-addition formulas and
/// e^{+-k_i dz}, with Taylor series of the small differences; every evaluation moves the
/// reference to its point (computed afresh when |k_i cos(theta_i) dx| or |k_i dz| would exceed
/// kTaylorRadius, and after 512 moves). The value is WaveField::velocity(x, 0, z, t) up
/// to rounding (and to components below its negligible velocity, which the cache may sum), with no transcendental function per component, point and evaluation, and the
/// sum over the components is taken eight components at a time (SIMD where the compiler has it).
/// Within a point's expansion radius of its reference the cache returns the second-order Taylor
/// expansion about it instead (expansionRadius), at the same time or, by default, at a later one:
/// the sums at the reference are then taken afresh at that time, without the Taylor series that
/// carry the reference (a deep node sees only long waves and stays within metres of it for many
/// steps).
class WaveVelocityCache {
 public:
  WaveVelocityCache() = default;
  /// For `points` points of `field` (which must outlive the cache): in the x-z plane (y = 0,
  /// velocity()), or with `horizontal_plane` anywhere (velocity3(); every component must then
  /// travel in the same direction, as those of WaveSpec do; std::invalid_argument otherwise).
  /// With `across_times` false the expansion is used only at the time of the reference's last
  /// sum: the first evaluation of a point at a time is then the exact sum (up to rounding).
  WaveVelocityCache(const WaveField* field, std::size_t points, bool horizontal_plane = false,
                    bool across_times = true);
  bool empty() const { return field_ == nullptr || field_->empty(); }
  /// Time of the following evaluations [s].
  void setTime(double t);
  /// (vx, vz) at point i at (x, 0, z) and the time of setTime [m/s]. (With horizontal_plane, x
  /// is the distance along the direction of travel and vx the horizontal velocity along it.)
  /// Changes only point i's state: calls for different points may run on different threads
  /// (between two setTime calls).
  void velocity(std::size_t i, double x, double z, double& vx, double& vz);
  /// (vx, vy, vz) at point i at (x, y, z) and the time of setTime [m/s]: WaveField::velocity up
  /// to rounding, for a cache built with horizontal_plane (std::logic_error otherwise). The
  /// phases depend on x, y through xi = x cos(theta) + y sin(theta) only, so this is velocity()
  /// at xi with the horizontal velocity split along theta.
  void velocity3(std::size_t i, double x, double y, double z, double& vx, double& vy, double& vz);
  /// The number of components an exact evaluation at elevation z sums (whole lane groups; 0 where
  /// every component is negligible): its cost, for sharing the points between threads.
  std::size_t componentsAt(double z) const;

  /// Largest phase difference or exponent carried by the Taylor series [rad]: the terms left
  /// out (beyond u^11) are below 0.2^12 / 12! ~ 9e-18.
  static constexpr double kTaylorRadius = 0.2;
  /// Below this largest argument the series stop at u^7 (left out: 0.02^8 / 8! ~ 6e-19) [rad].
  static constexpr double kShortTaylorRadius = 0.02;
  /// Bound on the error of the expanded velocity (see linearRadius) [m/s]: far below the drag
  /// velocities of a cable and below the dynamic solver's Newton tolerance on velocities.
  static constexpr double kLinearTolerance = 1e-7;
  /// Distance [m] from a point's last exact evaluation at the same time within which velocity()
  /// returns the second-order Taylor expansion about it (both points inside the water column,
  /// below the surface): the Newton iterations of a time step move a node by millimetres, and
  /// the sum over the components is then taken once per step instead of once per iteration.
  /// Each derivative of a component brings a factor of at most k_i (|k_i cos(theta_i)| <= k_i,
  /// the depth factors are at most coth(k_i h)), so along any unit direction the third
  /// derivatives are below 2^{3/2} G3 with G3 = sum_i a_i omega_i k_i^3 coth(k_i h), and the
  /// remainder over a distance d below 2^{3/2} G3 d^3 / 6 <= kLinearTolerance.
  double linearRadius() const { return lin_radius_; }
  /// The radius [m] about point i's reference (its last exact evaluation) within which velocity()
  /// returns the second-order expansion; 0 before the first exact evaluation and for a point
  /// outside the water column. As linearRadius, with the components point i sums and their
  /// depth factors there: 2^{3/2} G3_i e^{k_n r} r^3 / 6 <= kLinearTolerance with
  /// G3_i = sum_i a_i omega_i k_i^3 (depth factor at the reference), k_n the largest k_i summed
  /// (the growth of the depth factors over r); at most kMaxExpansionRadius. The sums take the
  /// components seen up to kMaxExpansionRadius above the reference, so that those left out stay
  /// below the negligible velocity (1e-12 m/s each) wherever the expansion is used.
  double expansionRadius(std::size_t i) const;
  static constexpr double kMaxExpansionRadius = 5.0;  ///< [m]: ~1e-7 m/s at 800 m in the A.2 storm

  /// Layout of the component sums' data: components in groups of kGroup (the SIMD width of
  /// the sums), each group a block of rows of kGroup values, so that a sum streams through two
  /// arrays (the constants and the point's state) instead of one per quantity. Constants per
  /// group (kCoefGroup values): k, k cos(theta), cos and sin of A, the six coefficients of vx and
  /// the six of vz, and a omega k^3 times the depth factors' denominator (G3 of
  /// expansionRadius); state per point and group (kStateGroup values): cos and sin of B, E+, E-.
  static constexpr std::size_t kGroup = 8;
  enum CoefRow : std::size_t {
    kRowK, kRowKx, kRowCosA, kRowSinA, kRowCx, kRowCz = kRowCx + 6, kRowG3 = kRowCz + 6, kCoefRows
  };
  enum StateRow : std::size_t { kRowCosB, kRowSinB, kRowEp, kRowEm, kStateRows };
  static constexpr std::size_t kCoefGroup = kCoefRows * kGroup;
  static constexpr std::size_t kStateGroup = kStateRows * kGroup;

 private:
  struct Component;  ///< one component's constants before sorting (wave_velocity_cache.cpp)
  /// The field's components' constants (k, kx, omega, phase, depth factors), in increasing skip
  /// depth (the order of the tables).
  std::vector<Component> sortedComponents() const;
  /// The per-component tables and the kernel's constants (coef_) of the sorted components.
  void fillTables(const std::vector<Component>& comps);
  /// Empty per-point state for `points` points.
  void allocatePoints(std::size_t points);
  std::size_t seenAt(double zc) const;  ///< components summed at a clamped, relevant elevation
  /// expansionRadius from G3 at the reference and the largest k summed.
  static double expansionRadiusFor(double g3, double k_n);
  const WaveField* field_ = nullptr;
  bool plane_ = false;                  ///< points anywhere: tables along the direction of travel
  bool across_times_ = true;            ///< expansions at later times too (constructor)
  double direction_ = 0.0, cos_dir_ = 1.0, sin_dir_ = 0.0;  ///< that direction theta [rad]
  std::size_t nc_ = 0;                  ///< components
  std::size_t np_ = 0;                  ///< components padded to a multiple of 8 (zero terms)
  double t_ = 0.0;
  bool have_time_ = false;
  double ramp_ = 1.0;
  double kx_max_ = 0.0, k_max_ = 0.0;   ///< max_i |k_i cos(theta_i)|, max_i k_i [rad/m]
  std::vector<double> kx_upto_, k_upto_;  ///< the same maxima over components [0, i] [rad/m]
  /// Per component, in increasing skip depth (the components a point at elevation z sees are
  /// a prefix; below z_skip a deep component's velocity is under 1e-12 m/s): k, k cos(theta),
  /// the offsets o+- of the exponentials, and the coefficients of the six sums of vx (value,
  /// d/dx, d/dz, d2/dx2, d2/dxdz, d2/dz2) and of vz, which fold in a omega, cos(theta), the
  /// powers of k and kx and the depth factors' denominator.
  std::vector<double> k_, kx_, op_, om_, z_skip_, omega_, phase_;
  /// The constants (and cos, sin of A_i at the current time) by group: CoefRow, coefData().
  std::vector<double> coef_;
  /// Per point: the reference position (NaN until first used) and, per component, cos and sin
  /// of B_i and E+, E- there, valid for the first valid_ components; moves_ counts the moves
  /// of the reference by the Taylor factors since it was last computed afresh.
  std::vector<double> x_ref_, z_ref_;
  std::vector<std::size_t> valid_;
  std::vector<int> moves_;
  std::vector<double> state_;  ///< StateRow, by point then group: stateData()
  /// coef_ and state_ start kAlignSlack values early: their data from the first 64-byte
  /// boundary on (whole cache lines per row; the vectors' own alignment is 16 bytes).
  static constexpr std::size_t kAlignSlack = 8;
  static double* aligned(std::vector<double>& v) {
    const auto a = reinterpret_cast<std::uintptr_t>(v.data());
    return v.data() + ((64 - a % 64) % 64) / sizeof(double);
  }
  double* coefData() { return aligned(coef_); }
  double* stateData() { return aligned(state_); }
  static std::size_t coefIndex(std::size_t i, std::size_t row) { return i / kGroup * kCoefGroup + row * kGroup + i % kGroup; }
  static std::size_t stateIndex(std::size_t i, std::size_t row) { return i / kGroup * kStateGroup + row * kGroup + i % kGroup; }
  /// Each point's reference inside the water column (its last exact evaluation): position, the
  /// expansion radius there and the components summed, and the time of the sums below: the
  /// velocity with its first and second derivatives at the reference, for vx then vz the value,
  /// d/dx, d/dz, d2/dx2, d2/dxdz, d2/dz2 [m/s, 1/s, 1/(m s)].
  struct Exact {
    double t = 0.0, x = 0.0, z = 0.0;
    double radius = 0.0;         ///< expansionRadius [m]
    std::size_t components = 0;  ///< summed at the reference (whole groups)
    double vx[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double vz[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    bool valid = false;
    /// vx, vz from the twelve sums (vx's six, then vz's) times the sea's ramp factor.
    void setSums(const double* sums, double ramp) {
      for (int q = 0; q < 6; ++q) {
        vx[q] = sums[q] * ramp;
        vz[q] = sums[6 + q] * ramp;
      }
    }
  };
  std::vector<Exact> exact_;
  double lin_radius_ = 0.0;             ///< linearRadius() [m]
};

/// Where two threads should split the water velocities of points 0 .. n - 1 at elevations z
/// (a line's nodes, top last) so that their work is equal: the first thread takes points [0, w)
/// and `rest_work` per point of [0, meeting) besides, the second [w, n) and the rest of
/// [meeting, n). A point's water costs `water_work` plus the components it sums
/// (componentsAt), in the units of one component's sum. Without a sea: meeting. The nodes near
/// the surface sum all the components and the deep ones only the long waves, so the upper half
/// of a deep line would otherwise do most of the sums.
int balancedWaterSplit(const WaveVelocityCache& cache, const std::vector<double>& z, int meeting, double water_work,
                       double rest_work);

}  // namespace core
}  // namespace mooring_dynamics
