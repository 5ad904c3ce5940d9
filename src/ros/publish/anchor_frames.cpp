#include "mooring_dynamics/ros/publish/anchor_frames.hpp"

#include "mooring_dynamics/core/model/rigid_pose.hpp"
#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

namespace {
/// A frame at world position (x, y, z) [m], axes parallel to the world's.
geometry_msgs::TransformStamped fixedFrame(double x, double y, double z, const std::string& world_frame,
                                           const std::string& child, const ros::Time& stamp) {
  core::RigidPose at;
  at.position = Eigen::Vector3d(x, y, z);
  return vesselTransform(at, world_frame, child, stamp);
}
}  // namespace

std::vector<geometry_msgs::TransformStamped> anchorFrames(const core::Problem& problem, const std::string& world_frame,
                                                          const std::string& prefix, const ros::Time& stamp) {
  if (problem.lower_end != core::Problem::LowerEnd::Anchor) return {};
  return {fixedFrame(problem.anchor_x, problem.anchor_y, problem.anchor_z, world_frame, prefix + "anchor", stamp)};
}

std::vector<geometry_msgs::TransformStamped> anchorFrames(const core::SystemProblem& system,
                                                          const std::string& world_frame, const std::string& prefix,
                                                          const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const core::SystemPoint& p : system.points)
    if (p.type == core::SystemPoint::Type::Anchor || p.type == core::SystemPoint::Type::Fixed)
      frames.push_back(fixedFrame(p.x, p.y, p.z, world_frame, prefix + p.name, stamp));
  return frames;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
