// Where a moored vessel's pose comes from, sample by sample, when the problem file computes it
// (issue "Design storms"): its wave-frequency response to `vessel.sea_state` through its RAOs
// (SeaStateMotion), about a mean pose that is the file's pose or, with `vessel.low_frequency`,
// the hull's slow surge, sway and yaw (HullSlowMotion) moved by the lines' wrench after each step
// and, with `low_frequency.wave_drift`, by the sea's mean and slowly varying drift (WaveDrift).
//
//   VesselMotionSource src(system);
//   for (k = 0 ..) { PoseSample p = src.sample(k dt); lockstep.onSample(p.t, p.pose, &p.twist);
//                    src.advance(dt, lockstep.wrench()); }
//
// The lines' wrench of a step moves the slow pose of the next one (a one-step lag, dt being a
// small fraction of the slow periods). Frames: world REP 103; the twist in body axes.
#pragma once

#include <memory>

#include "mooring_dynamics/core/model/hull_slow_motion.hpp"
#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/core/model/sea_state_motion.hpp"
#include "mooring_dynamics/core/model/system.hpp"
#include "mooring_dynamics/core/model/wave_drift.hpp"
#include "mooring_dynamics/core/model/waves.hpp"
#include "mooring_dynamics/core/solvers/vessel_statics.hpp"

namespace mooring_dynamics {
namespace core {

class VesselMotionSource {
 public:
  /// For a system whose vessel has `sea_state` or `low_frequency` (or both). Throws
  /// std::invalid_argument naming the key when it has neither or the inputs are invalid.
  explicit VesselMotionSource(const SystemProblem& system);

  /// The vessel's pose and body twist at t [s] (samples in increasing time).
  PoseSample sample(double t);
  /// After the lines' step to the last sample: advance the slow motion by dt [s] under their
  /// wrench `w` (nothing without low_frequency).
  void advance(double dt, const VesselWrench& w);

  /// The slow pose now (the file's pose without low_frequency).
  RigidPose slowPose() const;
  /// The wave drift (surge, sway [N], yaw [N m], slow body axes) of the last advance(); zero
  /// without wave_drift.
  const Eigen::Vector3d& lastDrift() const { return last_drift_; }

 private:
  RigidPose file_pose_;
  Eigen::Vector3d last_origin_ = Eigen::Vector3d::Zero();  ///< the last sample's body origin (world)
  WaveField sea_;
  RaoTable raos_;
  std::unique_ptr<SeaStateMotion> wave_motion_;
  std::unique_ptr<HullSlowMotion> slow_;
  RaoTable drift_table_;
  std::unique_ptr<WaveDrift> drift_;
  Eigen::Vector3d drift_reference_ = Eigen::Vector3d::Zero();  ///< body frame: where the sea's phase is taken
  double last_t_ = 0.0;
  Eigen::Vector3d last_drift_ = Eigen::Vector3d::Zero();
};

}  // namespace core
}  // namespace mooring_dynamics
