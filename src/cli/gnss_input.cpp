#include "gnss_input.hpp"

#include "mooring_dynamics/core/io/gnss_track_io.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {
std::vector<core::GnssTrack::Result> follow(core::GnssTrack& track, const std::string& path, std::ostream& out) {
  if (path.empty())
    throw core::ProblemError("dynamics.gnss.track: not given; cable_sim needs the track as a CSV of (t, latitude, "
                             "longitude, heading) rows");
  const std::vector<core::GnssTrackRow> rows = core::loadGnssTrack(path);
  std::vector<core::GnssTrack::Result> poses = core::followTrack(track, rows);
  out << "GNSS track " << path << ": " << rows.size() << " fixes, " << poses.size() << " accepted";
  for (std::size_t v = 1; v < core::GnssTrack::kVerdicts; ++v)
    if (long n = track.counts()[v]) out << ", " << n << " " << core::GnssTrack::name(static_cast<core::GnssTrack::Verdict>(v));
  if (track.headingGapsReported() > 0) out << ", " << track.headingGapsReported() << " heading gaps";
  out << "\n";
  if (poses.empty()) throw core::ProblemError(path + ": no fix accepted (dynamics.gnss)");
  return poses;
}
}  // namespace

void gnssTopTable(core::Problem& problem, std::ostream& out) {
  core::DynamicOptions& dyn = problem.dynamics;
  if (problem.formulation != core::Formulation::ThreeD)
    throw core::ProblemError("dynamics.gnss: a ship track moves the top in the horizontal plane; the line needs "
                             "model: 3d");
  if (problem.top.type != core::TopBoundary::Type::Position)
    throw core::ProblemError("dynamics.gnss: the track moves the top; top must be a position");
  if (dyn.top_motion.type != core::TopMotion::Type::Hold)
    throw core::ProblemError("dynamics.gnss and dynamics.top_motion: give one motion of the top");
  core::RigidPose start;
  start.position = Eigen::Vector3d(problem.top.x, problem.top.y, problem.top.z);
  core::GnssTrack track(dyn.gnss, start, Eigen::Vector2d(problem.top.tow_vx, problem.top.tow_vy));
  const auto poses = follow(track, dyn.gnss.track, out);
  dyn.top_motion.type = core::TopMotion::Type::PositionTable;
  dyn.top_motion.table.clear();
  // A tow starts from its steady state at top.tow_velocity, the smoother's start: a row one second
  // before the first, on that velocity, gives the table that velocity at t = 0 (rows at t <= 0
  // are not followed; they only shape the start).
  const Eigen::Vector3d& x0 = poses.front().pose.position;
  if (problem.top.tow_vx != 0.0 || problem.top.tow_vy != 0.0)
    dyn.top_motion.table.emplace_back(-1.0, x0.x() - problem.top.tow_vx, x0.y() - problem.top.tow_vy, x0.z());
  for (const auto& p : poses) {
    const Eigen::Vector3d& x = p.pose.position;
    dyn.top_motion.table.emplace_back(p.t - poses.front().t, x.x(), x.y(), x.z());
  }
  if (!(dyn.duration > 0.0)) dyn.duration = dyn.top_motion.table.back().t;
}

std::vector<core::PoseSample> gnssVesselSamples(const core::SystemProblem& s, std::ostream& out) {
  core::GnssTrack track(s.dynamics.gnss, s.vessel.pose, Eigen::Vector2d::Zero());
  const auto poses = follow(track, s.dynamics.gnss.track, out);
  std::vector<core::PoseSample> samples;
  for (const auto& p : poses) samples.push_back({p.t - poses.front().t, p.pose});
  return samples;
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
