#include "mooring_dynamics/ros/nodes/gnss_input.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mooring_dynamics {
namespace ros_bridge {

core::GnssFix toGnssFix(const sensor_msgs::NavSatFix& msg) {
  core::GnssFix f;
  f.t = msg.header.stamp.toSec();
  f.latitude_deg = msg.latitude;
  f.longitude_deg = msg.longitude;
  f.has_fix = msg.status.status >= sensor_msgs::NavSatStatus::STATUS_FIX;
  f.horizontal_variance = msg.position_covariance_type == sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN
                              ? std::numeric_limits<double>::quiet_NaN()
                              : std::max(msg.position_covariance[0], msg.position_covariance[4]);
  return f;
}

double yawOf(const geometry_msgs::Quaternion& q) {
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!std::isfinite(n) || std::abs(n - 1.0) > core::kUnitQuaternionTolerance)
    return std::numeric_limits<double>::quiet_NaN();
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

GnssInput::GnssInput(ros::NodeHandle& pnh, const core::GnssOptions& options, const core::RigidPose& start,
                     const Eigen::Vector2d& start_velocity, PoseCallback on_pose, RejectCallback on_reject)
    : track_(options, start, start_velocity), on_pose_(std::move(on_pose)), on_reject_(std::move(on_reject)) {
  std::string type;
  pnh.param<std::string>("heading_type", type, "quaternion");
  if (type == "imu") {
    heading_sub_ = pnh.subscribe<sensor_msgs::Imu>(
        "heading", 100, [this](const sensor_msgs::Imu::ConstPtr& m) { onHeading(m->header.stamp, m->orientation); });
  } else if (type == "quaternion") {
    heading_sub_ = pnh.subscribe<geometry_msgs::QuaternionStamped>(
        "heading", 100,
        [this](const geometry_msgs::QuaternionStamped::ConstPtr& m) { onHeading(m->header.stamp, m->quaternion); });
  } else {
    throw std::runtime_error("parameter " + pnh.resolveName("heading_type") + " = \"" + type +
                             "\": must be \"imu\" (sensor_msgs/Imu) or \"quaternion\" (geometry_msgs/QuaternionStamped)");
  }
  fix_sub_ = pnh.subscribe<sensor_msgs::NavSatFix>("fix", 100,
                                                   [this](const sensor_msgs::NavSatFix::ConstPtr& m) { onFix(*m); });
}

void GnssInput::note(const core::GnssTrack::Result& r) {
  if (r.ok()) return;
  last_rejection_ = std::string("GNSS ") + core::GnssTrack::name(r.verdict) + ": " + r.message;
  if (on_reject_) on_reject_(last_rejection_);
}

void GnssInput::onFix(const sensor_msgs::NavSatFix& msg) {
  if (msg.header.stamp.isZero()) {
    core::GnssTrack::Result r;
    r.verdict = core::GnssTrack::Verdict::BadValue;
    r.message = "header.stamp = 0: a fix needs its time";
    note(r);
    return;
  }
  const core::GnssTrack::Result r = track_.addFix(toGnssFix(msg));
  note(r);
  if (r.ok()) on_pose_(msg.header.stamp, r.pose);
}

void GnssInput::onHeading(const ros::Time& stamp, const geometry_msgs::Quaternion& q) {
  note(track_.addHeading(stamp.toSec(), yawOf(q)));
}

long GnssInput::rejected() const {
  long n = 0;
  for (std::size_t v = 1; v < core::GnssTrack::kVerdicts; ++v) n += track_.counts()[v];
  return n;
}

std::vector<std::pair<std::string, std::string>> GnssInput::values() const {
  std::vector<std::pair<std::string, std::string>> kv;
  for (std::size_t v = 0; v < core::GnssTrack::kVerdicts; ++v)
    kv.emplace_back(std::string("gnss ") + core::GnssTrack::name(static_cast<core::GnssTrack::Verdict>(v)),
                    std::to_string(track_.counts()[v]));
  kv.emplace_back("gnss heading gaps", std::to_string(track_.headingGapsReported()));
  if (!last_rejection_.empty()) kv.emplace_back("gnss last rejection", last_rejection_);
  return kv;
}

std::string GnssInput::topics() const {
  return "GNSS " + fix_sub_.getTopic() + " + heading " + heading_sub_.getTopic();
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
