// Second-order wave drift on a moored hull (issue "Design storms"; problem file
// `vessel.low_frequency.wave_drift`): the mean drift force of each wave component from a table of
// drift coefficients (WAMIT `.8`/`.9` or CSV, read by core/io/rao_io.hpp), and the slowly varying
// drift by Newman's approximation, on surge, sway and yaw of the hull's slow motion.
//
// With D_i the drift coefficient of component i (force per square metre of wave amplitude, at
// its frequency and its heading relative to the hull), a_i its amplitude and
// theta_i(t) = omega_i t - k_i . x_ref - phase_i its phase at the hull's reference point:
//
//   mean:    F = sum_i a_i^2 D_i                                   (the drift of each component)
//   Newman:  F(t) = Re{ P(t) conj(Q(t)) },  P = sum_i a_i sqrt|D_i| e^{i theta_i},
//                                            Q = sum_i a_i sgn(D_i) sqrt|D_i| e^{i theta_i}
//
// i.e. the difference-frequency double sum sum_ij a_i a_j T_ij cos(theta_i - theta_j) with
// Newman's off-diagonal T_ij = sgn(D_j) sqrt(|D_i| |D_j|) (the geometric mean, exact on the
// diagonal; Newman 1974, Faltinsen "Sea loads on ships and offshore structures" ch. 5). Its
// average over time is the mean drift; the sum-frequency part of the square is left out. Both
// scale with the square of the sea's start-up ramp. Frames: (X, Y) along the hull's slow body
// axes, N about the vertical.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/rao.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

/// Where a hull's drift coefficients come from (problem file `vessel.low_frequency.wave_drift`).
struct WaveDriftSource {
  RaoSource table;      ///< file, format (WAMIT .8/.9 or CSV), ulen, extend, symmetry
  bool newman = true;   ///< slowly varying drift by Newman's approximation; false: the mean only
};

class WaveDrift {
 public:
  /// `coefficients`: the drift table in SI (modes 1, 2 [N/m^2], 6 [N m/m^2] used), headings
  /// relative to the hull. Both must outlive this object. Throws std::invalid_argument naming the
  /// first component the table does not cover.
  WaveDrift(const WaveField& waves, const RaoTable& coefficients, bool newman);

  /// Surge and sway force [N] and yaw moment [N m] in the body axes of `slow_pose` (world frame;
  /// its yaw sets the headings relative to the hull), at t [s], the hull's reference point at
  /// `ref_world` (world frame).
  Eigen::Vector3d force(double t, const RigidPose& slow_pose, const Eigen::Vector3d& ref_world);
  /// The mean drift (surge, sway, yaw) at the hull heading `yaw` [rad], without ramp.
  Eigen::Vector3d meanForce(double yaw);

 private:
  void coefficientsAt(double yaw);
  const WaveField* waves_;
  const RaoTable* table_;
  bool newman_;
  double yaw_ = 0.0;
  bool have_yaw_ = false;
  /// Per component: D (surge, sway, yaw) at the current relative heading.
  std::vector<Eigen::Vector3d> d_;
};

}  // namespace core
}  // namespace mooring_dynamics
