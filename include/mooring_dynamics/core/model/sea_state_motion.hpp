// Wave-frequency motion of a hull in a sea state from its RAOs (issue "Design storms"; problem
// file `vessel.sea_state` with `vessel.raos`, docs/problem_format.md).
//
// Linear superposition over the realized wave components j of the sea (WaveField: amplitude a_j,
// frequency w_j, wavenumber k_j, direction theta_j, phase p_j; eta = a cos(k.x - w t + p)):
//   psi_j(t)  = w_j t - k_j (x_r cos theta_j + y_r sin theta_j) - p_j   (eta_j at the reference
//               point's mean position (x_r, y_r) is a_j cos psi_j)
//   x_d(t)    = r(t) sum_j Re{ a_j X_d(w_j, beta_j) e^{i psi_j} },  d = surge .. yaw
//   beta_j    = theta_j - yaw_0 (the heading relative to the mean hull, rao.hpp), r(t) the sea's ramp
// so that each motion leads the elevation at the reference point by the RAO's phase. Pose: the
// reference point moves by R_0 (x_1, x_2, x_3) from its mean place, and the hull turns by
// R_wf = Rz(x_6) Ry(x_5) Rx(x_4) in its mean axes: R = R_0 R_wf, origin = p_0 + R_0 r + R_0 x_123
// - R r (r the reference point in the body frame; R_0, p_0 the mean pose). Velocities are the
// analytic derivatives (the body twist: the origin's velocity and the angular velocity of the
// Euler rates, in body axes), so the lockstep driver follows the exact motion between samples.
// No low-frequency motion and no forward speed: the hull oscillates about its mean pose.
#pragma once

#include <array>
#include <complex>
#include <vector>

#include <Eigen/Core>

#include "mooring_dynamics/core/model/rao.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/waves.hpp"

namespace mooring_dynamics {
namespace core {

class SeaStateMotion {
 public:
  using Dofs = std::array<double, RaoTable::kDofs>;

  /// Throws std::invalid_argument naming the first wave component whose frequency or heading the
  /// table cannot give (RaoTable::check), e.g. "wave component 3 of 200 (omega 0.31 rad/s, ...)".
  SeaStateMotion(const WaveField& waves, const RaoTable& raos, const RigidPose& mean_pose,
                 const Eigen::Vector3d& reference_point);

  /// Move the mean pose (a hull's slow drift, HullSlowMotion): the waves' phases are taken at
  /// the reference point's new mean place and the RAOs at the headings relative to the new yaw.
  /// Throws std::invalid_argument as the constructor.
  void rebase(const RigidPose& mean_pose);
  const RigidPose& meanPose() const { return mean_; }
  /// at(t) about a mean pose that moves with world velocity `mean_velocity` [m/s] (of the mean
  /// origin) and angular velocity `mean_omega` [rad/s, world]: the twist is the sum.
  PoseSample at(double t, const Eigen::Vector3d& mean_velocity, const Eigen::Vector3d& mean_omega) const;

  /// The six motions of the reference point (surge, sway, heave [m]; roll, pitch, yaw [rad], in
  /// the mean hull axes) and their rates at t [s].
  void motions(double t, Dofs& x, Dofs& rate) const;
  /// The hull's pose (world frame) and body twist at t (has_twist true).
  PoseSample at(double t) const;
  /// Samples at t = k dt, k = 0 .. floor(duration / dt).
  std::vector<PoseSample> generate(double duration, double dt) const;
  /// Variance of each motion once the ramp is over, sum_j a_j^2 |X_d|^2 / 2.
  Dofs variance() const;

 private:
  struct Term {
    double omega = 0.0;
    double offset = 0.0;  ///< k_j (x_r cos theta_j + y_r sin theta_j) + p_j
    std::array<std::complex<double>, RaoTable::kDofs> ax{};  ///< a_j X_d
  };
  void build(const RigidPose& mean_pose);
  const WaveField* waves_ = nullptr;  ///< the sea and the table outlive the motion
  const RaoTable* raos_ = nullptr;
  std::vector<Term> terms_;
  RigidPose mean_;
  Eigen::Matrix3d r0_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d ref_ = Eigen::Vector3d::Zero();
};

}  // namespace core
}  // namespace mooring_dynamics
