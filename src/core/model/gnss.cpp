#include "mooring_dynamics/core/model/gnss.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <GeographicLib/LocalCartesian.hpp>

namespace mooring_dynamics {
namespace core {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// The angle a + s (b - a) along the shorter arc [rad].
double interpolateAngle(double a, double b, double s) {
  const double d = std::remainder(b - a, 2.0 * kPi);
  return a + s * d;
}
}  // namespace

std::string GnssOptions::validate() const {
  auto bad = [](const char* key, double v, const char* what) {
    return std::string("dynamics.gnss.") + key + " = " + num(v) + ": " + what;
  };
  if (!datum_from_first_fix) {
    if (!(std::isfinite(datum_latitude_deg) && std::abs(datum_latitude_deg) <= 90.0))
      return bad("datum.latitude_deg", datum_latitude_deg, "must be in [-90, 90]");
    if (!(std::isfinite(datum_longitude_deg) && std::abs(datum_longitude_deg) <= 180.0))
      return bad("datum.longitude_deg", datum_longitude_deg, "must be in [-180, 180]");
  }
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(antenna[i])) return bad("antenna", antenna[i], "must be finite [m]");
  if (!(std::isfinite(smoothing_time) && smoothing_time >= 0.0))
    return bad("smoothing_time", smoothing_time, "must be >= 0 [s] (0: no smoothing)");
  if (!(std::isfinite(max_speed) && max_speed > 0.0)) return bad("max_speed", max_speed, "must be > 0 [m/s]");
  if (!(std::isfinite(jump_tolerance) && jump_tolerance >= 0.0))
    return bad("jump_tolerance", jump_tolerance, "must be >= 0 [m]");
  if (!(std::isfinite(max_horizontal_sigma) && max_horizontal_sigma > 0.0))
    return bad("max_horizontal_sigma", max_horizontal_sigma, "must be > 0 [m]");
  if (!(std::isfinite(max_heading_gap) && max_heading_gap > 0.0))
    return bad("max_heading_gap", max_heading_gap, "must be > 0 [s]");
  return {};
}

double yawFromHeadingDeg(double heading_deg) { return std::remainder((90.0 - heading_deg) * kDeg, 2.0 * kPi); }

// --- LocalDatum ----------------------------------------------------------------------------------

struct LocalDatum::Impl {
  GeographicLib::LocalCartesian enu;
};

LocalDatum::LocalDatum(double latitude_deg, double longitude_deg)
    : impl_(std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(latitude_deg, longitude_deg, 0.0)})) {}
LocalDatum::~LocalDatum() = default;
LocalDatum::LocalDatum(LocalDatum&&) noexcept = default;
LocalDatum& LocalDatum::operator=(LocalDatum&&) noexcept = default;

Eigen::Vector2d LocalDatum::eastNorth(double latitude_deg, double longitude_deg) const {
  double x, y, z;
  impl_->enu.Forward(latitude_deg, longitude_deg, 0.0, x, y, z);
  return {x, y};
}

// --- TrackSmoother -------------------------------------------------------------------------------

void TrackSmoother::start(double t, const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  t_ = t;
  u_ = u;
  x_ = u - 2.0 * tau_ * v;
  v_ = v;
}

Eigen::Vector2d TrackSmoother::update(double t, const Eigen::Vector2d& u) {
  const double h = t - t_;
  if (tau_ <= 0.0) {  // off: the input itself, its velocity the last segment's
    v_ = (u - u_) / h;
    x_ = u;
  } else {
    // Input u(s) = u_ + r s on [0, h]. Particular solution x_p = u(s) - 2 r / w; the rest,
    // y = x - x_p, is free and critically damped: y(s) = (A + B s) exp(-w s).
    const double w = 1.0 / tau_;
    const Eigen::Vector2d r = (u - u_) / h;
    const Eigen::Vector2d A = x_ - u_ + 2.0 * r / w;  // y(0)
    const Eigen::Vector2d B = (v_ - r) + w * A;       // y'(0) + w y(0)
    const double e = std::exp(-w * h);
    const Eigen::Vector2d y = (A + B * h) * e;
    const Eigen::Vector2d yd = (B - w * (A + B * h)) * e;
    x_ = u - 2.0 * r / w + y;
    v_ = r + yd;
  }
  t_ = t;
  u_ = u;
  return x_;
}

// --- GnssTrack -----------------------------------------------------------------------------------

const char* GnssTrack::name(Verdict v) {
  switch (v) {
    case Verdict::Accepted: return "accepted";
    case Verdict::NoFix: return "no_fix";
    case Verdict::BadValue: return "bad_value";
    case Verdict::Covariance: return "covariance";
    case Verdict::Backward: return "backward_stamp";
    case Verdict::Jump: return "jump";
    case Verdict::NoHeading: return "no_heading";
  }
  return "?";
}

GnssTrack::GnssTrack(const GnssOptions& options, const RigidPose& start, const Eigen::Vector2d& start_velocity)
    : options_(options), start_(start), start_velocity_(start_velocity), smoother_(options.smoothing_time) {
  const std::string err = options.validate();
  if (!err.empty()) throw std::invalid_argument(err);
  if (!options.datum_from_first_fix)
    datum_ = std::make_unique<LocalDatum>(options.datum_latitude_deg, options.datum_longitude_deg);
}

GnssTrack::~GnssTrack() = default;

GnssTrack::Result GnssTrack::reject(Verdict v, double t, const std::string& message) {
  ++counts_[static_cast<std::size_t>(v)];
  Result r;
  r.verdict = v;
  r.t = t;
  r.message = message;
  return r;
}

GnssTrack::Result GnssTrack::addHeading(double t, double yaw) {
  if (!std::isfinite(t) || !std::isfinite(yaw))
    return reject(Verdict::BadValue, t, "heading at t = " + num(t) + ": yaw = " + num(yaw) + " must be finite");
  if (!headings_.empty() && !(t > headings_.back().first))
    return reject(Verdict::Backward, t, "heading stamp " + num(t) + " s is not after the last heading's " +
                                            num(headings_.back().first) + " s");
  headings_.emplace_back(t, yaw);
  ++counts_[static_cast<std::size_t>(Verdict::Accepted)];
  Result r;
  r.t = t;
  return r;
}

bool GnssTrack::headingAt(double t, double& yaw, double& gap) const {
  if (headings_.empty()) return false;
  // The last sample at or before t and the first after it.
  std::size_t k = headings_.size();
  while (k > 0 && headings_[k - 1].first > t) --k;
  if (k == 0) {  // every heading is later than the fix: the first one
    yaw = headings_.front().second;
    gap = headings_.front().first - t;
  } else if (k == headings_.size()) {  // none later: held from the last
    yaw = headings_.back().second;
    gap = t - headings_.back().first;
  } else {
    const auto& a = headings_[k - 1];
    const auto& b = headings_[k];
    yaw = interpolateAngle(a.second, b.second, (t - a.first) / (b.first - a.first));
    gap = std::min(t - a.first, b.first - t);
  }
  return true;
}

GnssTrack::Result GnssTrack::addFix(const GnssFix& f) {
  const std::string at = "fix at t = " + num(f.t) + " s: ";
  if (!f.has_fix) return reject(Verdict::NoFix, f.t, at + "status NO_FIX");
  if (!std::isfinite(f.t)) return reject(Verdict::BadValue, f.t, at + "stamp must be finite");
  if (!(std::isfinite(f.latitude_deg) && std::abs(f.latitude_deg) <= 90.0))
    return reject(Verdict::BadValue, f.t, at + "latitude = " + num(f.latitude_deg) + ": must be in [-90, 90] deg");
  if (!(std::isfinite(f.longitude_deg) && std::abs(f.longitude_deg) <= 180.0))
    return reject(Verdict::BadValue, f.t, at + "longitude = " + num(f.longitude_deg) + ": must be in [-180, 180] deg");
  if (std::isfinite(f.horizontal_variance) &&
      !(f.horizontal_variance <= options_.max_horizontal_sigma * options_.max_horizontal_sigma))
    return reject(Verdict::Covariance, f.t,
                  at + "horizontal standard deviation " + num(std::sqrt(std::max(f.horizontal_variance, 0.0))) +
                      " m exceeds dynamics.gnss.max_horizontal_sigma = " + num(options_.max_horizontal_sigma) + " m");
  if (started_ && !(f.t > last_t_))
    return reject(Verdict::Backward, f.t, at + "not after the last accepted fix (t = " + num(last_t_) + " s)");
  double yaw = 0.0, gap = 0.0;
  if (!headingAt(f.t, yaw, gap)) return reject(Verdict::NoHeading, f.t, at + "no heading received yet");

  if (!datum_) datum_ = std::make_unique<LocalDatum>(f.latitude_deg, f.longitude_deg);
  const Eigen::Vector2d antenna = datum_->eastNorth(f.latitude_deg, f.longitude_deg);
  if (started_) {
    // A jump: further than the vessel can go at max_speed, plus the fixes' own noise.
    const double dist = (antenna - last_antenna_).norm(), reach = options_.max_speed * (f.t - last_t_);
    if (!(dist <= reach + options_.jump_tolerance))
      return reject(Verdict::Jump, f.t,
                    at + "jump of " + num(dist) + " m in " + num(f.t - last_t_) + " s: more than dynamics.gnss.max_speed = " +
                        num(options_.max_speed) + " m/s allows (" + num(reach) + " m) plus jump_tolerance = " +
                        num(options_.jump_tolerance) + " m");
  }

  // The body origin under the antenna (level heading yaw), then smoothed.
  const RigidPose level = RigidPose::fromRollPitchYaw(Eigen::Vector3d::Zero(), 0.0, 0.0, yaw);
  const Eigen::Vector2d origin = antenna - (level.orientation * options_.antenna).head<2>();
  Eigen::Vector2d smooth;
  if (!started_) {
    smoother_.start(f.t, origin, start_velocity_);
    smooth = smoother_.position();
    // A datum at the first fix: the track is placed so that its first pose is the start's.
    if (options_.datum_from_first_fix) offset_ = start_.position.head<2>() - smooth;
  } else {
    smooth = smoother_.update(f.t, origin);
  }
  started_ = true;
  last_t_ = f.t;
  last_antenna_ = antenna;
  // Headings before the one at or before this fix are no longer needed (fixes only go forward).
  std::size_t keep = 0;
  while (keep + 1 < headings_.size() && headings_[keep + 1].first <= f.t) ++keep;
  if (keep > 0) headings_.erase(headings_.begin(), headings_.begin() + static_cast<long>(keep));

  Result r;
  r.t = f.t;
  r.heading_gap = gap;
  if (gap > options_.max_heading_gap) ++heading_gaps_;
  const Eigen::Vector3d p(smooth.x() + offset_.x(), smooth.y() + offset_.y(), start_.position.z());
  r.pose = RigidPose::fromRollPitchYaw(p, 0.0, 0.0, yaw);
  ++counts_[static_cast<std::size_t>(Verdict::Accepted)];
  return r;
}

std::vector<GnssTrack::Result> followTrack(GnssTrack& track, const std::vector<GnssTrackRow>& rows) {
  std::vector<GnssTrack::Result> out;
  for (const GnssTrackRow& row : rows) {
    track.addHeading(row.t, yawFromHeadingDeg(row.heading_deg));
    GnssFix f;
    f.t = row.t;
    f.latitude_deg = row.latitude_deg;
    f.longitude_deg = row.longitude_deg;
    GnssTrack::Result r = track.addFix(f);
    if (r.ok()) out.push_back(std::move(r));
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
