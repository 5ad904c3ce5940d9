// rostest: bad message streams into the lockstep nodes (issue 22). Each test sends one named bad
// stream and checks, from the node's /diagnostics, that the specific counter grew by the expected
// count (a counter of the node itself, not of this test), that a good sample sent after it is
// answered (the node keeps publishing), and that every number the node published during the whole
// run is finite (tensions, positions, forces, wrenches).
//
//   test_bad_streams.test          LineStreams.*   LockstepNode on test/data/small_catenary.yaml
//   test_bad_streams.vessel.test   VesselStreams.* VesselNode on test/data/small_vessel.yaml
//   test_bad_streams.line_failure.test    LineFailure.*    LockstepNode on test/data/fragile_catenary.yaml
//   test_bad_streams.vessel_failure.test  VesselFailure.*  VesselNode on test/data/fragile_vessel.yaml
// The fragile files allow 4 Newton iterations per step (a gentle step needs at most 3) and no step
// cutting, and the launch sets ~max_speed 0, so that a lurch of the top or the vessel reaches the
// solver and its step fails: the node keeps the last good state, publishes it for that sample
// (converged false), reports ERROR naming the line, and continues on the next sample.
//
// The good motion is a small oscillation about the static top (line) or the file's pose (vessel),
// one sample per 0.1 s of stamp. Decisions documented in docs/ros_interface.md ("Bad input"):
// a stamp far in the future is a gap (restart from statics there) and the next normal stamp a bag
// loop (restart again); an unused orientation (line node) is accepted and counted.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/SolveStatic.h"
#include "mooring_dynamics/VesselStatics.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"
#include "mooring_dynamics/ros/nodes/lockstep_monitor.hpp"
#include "mooring_dynamics/ros/nodes/vessel_monitor.hpp"

namespace md = mooring_dynamics;
namespace lk = mooring_dynamics::ros_bridge::lockstep_keys;
namespace vk = mooring_dynamics::ros_bridge::vessel_keys;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kStep = 0.1;            // [s] between good samples (the problems' dt)
constexpr double kAnswerTimeout = 10.0;  // [s, wall] for one answer: a sample costs milliseconds
constexpr int kBurst = 2000;             // samples of the 1 kHz burst
constexpr double kBurstRate = 1000.0;    // [Hz]

struct Diag {
  int level = -1;
  std::string message;
  std::map<std::string, std::string> values;
};

/// "w / t" -> t (the total of a "(window / total)" value); -1 when missing.
long totalOf(const Diag& d, const std::string& key) {
  const auto it = d.values.find(key + " (window / total)");
  if (it == d.values.end()) return -1;
  const auto slash = it->second.find('/');
  return slash == std::string::npos ? -1 : std::stol(it->second.substr(slash + 1));
}

class Harness {
 public:
  Harness(const std::string& kind, const std::string& node, const std::string& problem_file)
      : kind_(kind), node_(node), problem_file_(problem_file) {
    ros::NodeHandle nh;
    if (line()) {
      const md::core::Problem p =
          md::core::loadProblemFromFile(std::string(MD_SOURCE_DIR) + "/test/data/" + problem_file_);
      const md::ros_bridge::StaticTop top = md::ros_bridge::staticTop(p);
      x0_ = top.x;
      z0_ = top.z;
      pose_pub_ = nh.advertise<geometry_msgs::PoseStamped>(node_ + "/top_pose", kBurst + 100);
      subs_.push_back(nh.subscribe<md::CableState>(node_ + "/cable_state", 5000,
                                                   [this](const md::CableState::ConstPtr& m) { onState(*m, true); }));
      subs_.push_back(nh.subscribe<geometry_msgs::WrenchStamped>(
          node_ + "/top_wrench", 5000,
          [this](const geometry_msgs::WrenchStamped::ConstPtr& m) { onWrench(*m, false, true); }));
    } else {
      pose_pub_ = nh.advertise<geometry_msgs::PoseStamped>(node_ + "/vessel_pose", kBurst + 100);
      subs_.push_back(nh.subscribe<geometry_msgs::WrenchStamped>(
          node_ + "/wrench", 5000, [this](const geometry_msgs::WrenchStamped::ConstPtr& m) { onWrench(*m, true, true); }));
      subs_.push_back(nh.subscribe<geometry_msgs::WrenchStamped>(
          node_ + "/wrench_world", 5000,
          [this](const geometry_msgs::WrenchStamped::ConstPtr& m) { onWrench(*m, false, false); }));
      for (const char* l : {"bow", "port_quarter", "stbd_quarter"})
        subs_.push_back(nh.subscribe<md::CableState>(node_ + "/lines/" + l + "/cable_state", 5000,
                                                     [this](const md::CableState::ConstPtr& m) { onState(*m, false); }));
    }
    subs_.push_back(nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) { onDiag(*m); }));
  }

  bool line() const { return kind_ == "line"; }

  /// Waits until the node is up and connected both ways.
  bool connect() {
    const ros::WallTime w0 = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - w0).toSec() < 60.0) {
      bool all = pose_pub_.getNumSubscribers() > 0;
      for (const auto& s : subs_) all = all && s.getNumPublishers() > 0;
      if (all && diagCount() > 0) return true;
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

  ros::Time next() {
    t_ += ros::Duration(kStep);
    return t_;
  }
  ros::Time now() const { return t_; }
  void setTime(const ros::Time& t) { t_ = t; }

  /// A good sample at `stamp`: line: the top 5 cm about its static position; vessel: 10 cm of surge.
  geometry_msgs::PoseStamped good(const ros::Time& stamp) const {
    geometry_msgs::PoseStamped m;
    m.header.stamp = stamp;
    m.header.frame_id = "world";
    const double s = 0.05 * std::sin(stamp.toSec());
    m.pose.position.x = line() ? x0_ : 2.0 * s;
    m.pose.position.z = line() ? z0_ + s : 0.0;
    m.pose.orientation.w = 1.0;
    return m;
  }

  void send(const geometry_msgs::PoseStamped& m) { pose_pub_.publish(m); }

  /// Answers (line: ~cable_state; vessel: ~wrench) with this stamp received so far.
  int answers(const ros::Time& stamp) const {
    std::lock_guard<std::mutex> l(mu_);
    const auto it = answers_.find(stamp.toNSec());
    return it == answers_.end() ? 0 : it->second;
  }
  bool waitAnswer(const ros::Time& stamp, double timeout = kAnswerTimeout) const {
    const ros::WallTime w0 = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - w0).toSec() < timeout) {
      if (answers(stamp) > 0) return true;
      ros::WallDuration(0.002).sleep();
    }
    return answers(stamp) > 0;
  }
  /// A good sample at the next stamp, answered: everything sent before it has been handled (the
  /// node handles its input queue in order on one thread).
  bool settle() {
    const ros::Time t = next();
    send(good(t));
    return waitAnswer(t);
  }

  /// The overall status of a diagnostics message published after this call (the second one, so
  /// that one in flight does not count).
  Diag freshDiag() {
    const long n0 = diagCount();
    const ros::WallTime w0 = ros::WallTime::now();
    while (ros::ok() && diagCount() < n0 + 2 && (ros::WallTime::now() - w0).toSec() < 10.0)
      ros::WallDuration(0.01).sleep();
    std::lock_guard<std::mutex> l(mu_);
    return diag_;
  }

  /// The state of `line` (its line_name) / the answer wrench published with `stamp`.
  bool state(const std::string& line, const ros::Time& stamp, md::CableState& out) const {
    std::lock_guard<std::mutex> l(mu_);
    const auto a = states_.find(line);
    if (a == states_.end()) return false;
    const auto b = a->second.find(stamp.toNSec());
    if (b == a->second.end()) return false;
    out = b->second;
    return true;
  }
  /// state(), waiting for it: a vessel's line states follow its wrench, which may answer first.
  bool waitState(const std::string& line, const ros::Time& stamp, md::CableState& out,
                 double timeout = kAnswerTimeout) const {
    const ros::WallTime w0 = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - w0).toSec() < timeout) {
      if (state(line, stamp, out)) return true;
      ros::WallDuration(0.002).sleep();
    }
    return state(line, stamp, out);
  }
  bool wrench(const ros::Time& stamp, geometry_msgs::WrenchStamped& out) const {
    std::lock_guard<std::mutex> l(mu_);
    const auto b = wrenches_.find(stamp.toNSec());
    if (b == wrenches_.end()) return false;
    out = b->second;
    return true;
  }
  Diag latestDiag() const {
    std::lock_guard<std::mutex> l(mu_);
    return diag_;
  }
  /// Waits (up to 5 s) for a diagnostics status whose message contains `text`; the last one seen.
  Diag waitDiag(const std::string& text) {
    const ros::WallTime w0 = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - w0).toSec() < 5.0) {
      const Diag d = latestDiag();
      if (d.message.find(text) != std::string::npos) return d;
      ros::WallDuration(0.01).sleep();
    }
    return latestDiag();
  }

  long nonFinite() const { return non_finite_; }
  long outputs() const { return outputs_; }
  std::string lastNonFinite() const {
    std::lock_guard<std::mutex> l(mu_);
    return last_non_finite_;
  }

  template <class Srv>
  bool call(const std::string& name, Srv& srv) {
    return ros::service::call(node_ + "/" + name, srv);
  }

  double x0_ = 0.0, z0_ = 0.0;

 private:
  long diagCount() const {
    std::lock_guard<std::mutex> l(mu_);
    return diag_count_;
  }
  void bad(const std::string& what) {
    std::lock_guard<std::mutex> l(mu_);
    ++non_finite_;
    last_non_finite_ = what;
  }
  void onState(const md::CableState& m, bool answer) {
    ++outputs_;
    auto fin = [](double v) { return std::isfinite(v); };
    bool ok = fin(m.top_force.x) && fin(m.top_force.y) && fin(m.top_force.z) && fin(m.anchor_force.x) &&
              fin(m.anchor_force.y) && fin(m.anchor_force.z) && fin(m.min_tension) && !m.positions.empty();
    for (std::size_t i = 0; i < m.positions.size() && ok; ++i)
      ok = fin(m.positions[i].x) && fin(m.positions[i].y) && fin(m.positions[i].z) && fin(m.tension[i]) &&
           fin(m.shear[i]) && fin(m.strain[i]) && fin(m.angle[i]) && fin(m.s[i]);
    if (!ok) bad("cable_state of " + m.line_name + " at stamp " + std::to_string(m.header.stamp.toSec()));
    std::lock_guard<std::mutex> l(mu_);
    if (answer) ++answers_[m.header.stamp.toNSec()];
    states_[m.line_name][m.header.stamp.toNSec()] = m;
  }
  /// `answer`: counts as the answer to its stamp; `keep`: kept by stamp (the wrench of record).
  void onWrench(const geometry_msgs::WrenchStamped& m, bool answer, bool keep) {
    ++outputs_;
    const auto& f = m.wrench.force;
    const auto& q = m.wrench.torque;
    if (!(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z) && std::isfinite(q.x) && std::isfinite(q.y) &&
          std::isfinite(q.z)))
      bad("wrench at stamp " + std::to_string(m.header.stamp.toSec()));
    std::lock_guard<std::mutex> l(mu_);
    if (answer) ++answers_[m.header.stamp.toNSec()];
    if (keep) wrenches_[m.header.stamp.toNSec()] = m;
  }
  void onDiag(const diagnostic_msgs::DiagnosticArray& a) {
    const std::string suffix = line() ? " lockstep" : " vessel lockstep";
    for (const auto& s : a.status) {
      if (s.name.size() < suffix.size() || s.name.compare(s.name.size() - suffix.size(), suffix.size(), suffix) != 0)
        continue;
      Diag d;
      d.level = s.level;
      d.message = s.message;
      for (const auto& kv : s.values) d.values[kv.key] = kv.value;
      std::lock_guard<std::mutex> l(mu_);
      diag_ = d;
      ++diag_count_;
    }
  }

  std::string kind_, node_, problem_file_;
  ros::Publisher pose_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Time t_{100.0};
  mutable std::mutex mu_;
  std::map<uint64_t, int> answers_;
  std::map<std::string, std::map<uint64_t, md::CableState>> states_;
  std::map<uint64_t, geometry_msgs::WrenchStamped> wrenches_;
  Diag diag_;
  long diag_count_ = 0;
  std::atomic<long> non_finite_{0}, outputs_{0};
  std::string last_non_finite_;
};

Harness* g_h = nullptr;

/// Counters before and after a stream, and the checks every stream shares: the node answers the
/// good sample that follows, and nothing it ever published is non-finite.
class Stream {
 public:
  Stream() : before_(g_h->freshDiag()) {}
  /// After the stream: a good sample is answered, then a fresh status.
  const Diag& after() {
    EXPECT_TRUE(g_h->settle()) << "the node does not answer a good sample after the stream";
    after_ = g_h->freshDiag();
    EXPECT_EQ(g_h->nonFinite(), 0) << g_h->lastNonFinite();
    return after_;
  }
  long grew(const std::string& key) const {
    const long a = totalOf(after_, key), b = totalOf(before_, key);
    EXPECT_GE(b, 0) << "no diagnostics value \"" << key << " (window / total)\"";
    return a - b;
  }
  const Diag& before() const { return before_; }
  /// The counts that changed, for failure messages.
  std::string changes() const {
    std::string out = "counts that changed:";
    for (const auto& kv : after_.values) {
      const auto b = before_.values.find(kv.first);
      if (kv.first.find("(window / total)") != std::string::npos && b != before_.values.end() &&
          totalOf(after_, kv.first.substr(0, kv.first.size() - 17)) != totalOf(before_, kv.first.substr(0, kv.first.size() - 17)))
        out += "\n  " + kv.first + ": " + b->second + " -> " + kv.second;
    }
    return out + "\nlast message: " + after_.message;
  }

 private:
  Diag before_, after_;
};

geometry_msgs::PoseStamped withPosition(geometry_msgs::PoseStamped m, int axis, double v) {
  (axis == 0 ? m.pose.position.x : axis == 1 ? m.pose.position.y : m.pose.position.z) = v;
  return m;
}
geometry_msgs::PoseStamped withQuaternion(geometry_msgs::PoseStamped m, double x, double y, double z, double w) {
  m.pose.orientation.x = x;
  m.pose.orientation.y = y;
  m.pose.orientation.z = z;
  m.pose.orientation.w = w;
  return m;
}

/// Sends `bad` at the next stamp and checks it is not answered once a later good one is.
void sendUnanswered(const geometry_msgs::PoseStamped& bad) {
  g_h->send(bad);
  const ros::Time probe = g_h->next();
  g_h->send(g_h->good(probe));
  ASSERT_TRUE(g_h->waitAnswer(probe));
  EXPECT_EQ(g_h->answers(bad.header.stamp), 0) << "the bad sample was answered";
}

// ---------------------------------------------------------------------------------------------
// Streams common to both nodes (the key differs where the nodes differ).

void nanPosition(const std::string& key) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 0, kNaN));
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void infPosition(const std::string& key) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 2, kInf));
  sendUnanswered(withPosition(g_h->good(g_h->next()), 0, -kInf));
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
void backwardStamp(const std::string& key) {
  Stream s;
  g_h->settle();
  // Back by 0.4567 s (<= loop_back, 1 s), off the 0.1 s grid of the earlier good samples.
  sendUnanswered(g_h->good(g_h->now() - ros::Duration(0.4567)));
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void duplicateStamp(const std::string& key) {
  Stream s;
  const ros::Time t = g_h->next();
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->waitAnswer(t));
  g_h->send(g_h->good(t));
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->settle());
  EXPECT_EQ(g_h->answers(t), 1) << "a duplicate stamp was answered again";
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
/// A stamp 1e6 s ahead: a gap over ~max_gap, so the run restarts from statics there (published
/// with that stamp); the next normal stamp goes back by 1e6 s, more than ~loop_back: a bag loop,
/// restarted again. Both answered.
void farFutureStamp(const std::string& gap_key, const std::string& loop_key) {
  Stream s;
  const ros::Time far = g_h->now() + ros::Duration(1e6);
  g_h->send(g_h->good(far));
  EXPECT_TRUE(g_h->waitAnswer(far));
  s.after();
  EXPECT_EQ(s.grew(gap_key), 1) << s.changes();
  EXPECT_EQ(s.grew(loop_key), 1) << s.changes();
}
void hugeJump(const std::string& key) {
  Stream s;
  auto m = g_h->good(g_h->next());
  m.pose.position.x += 1000.0;  // 1 km in 0.1 s: 10 km/s > max_speed (50 m/s)
  sendUnanswered(m);
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
/// The source really moved: jumps_to_reinit (3) jumps in a row to a reachable place restart there.
/// The speed is taken from the last accepted sample, so the third sample, 0.3 s after it, must
/// still be too fast: 20 m down (66 m/s over 0.3 s, above max_speed = 50 m/s).
void repeatedJumps(const std::string& key) {
  constexpr double kDrop = 20.0;  // [m]
  Stream s;
  for (int i = 0; i < 3; ++i) {
    auto m = g_h->good(g_h->next());
    m.pose.position.z -= kDrop;
    g_h->send(m);
  }
  ASSERT_TRUE(g_h->waitAnswer(g_h->now())) << "the third jump restarts and is answered";
  // Back to the good track: jumps again (from the new place), and the third restarts again.
  for (int i = 0; i < 3; ++i) g_h->send(g_h->good(g_h->next()));
  ASSERT_TRUE(g_h->waitAnswer(g_h->now()));
  s.after();
  EXPECT_EQ(s.grew(key), 2) << s.changes();
}
/// 2000 samples at 1 kHz, 1 ms of stamp apart. The node answers every sample it receives, once,
/// in order; its input queue (100) holds what arrives while it works, and what a slower node
/// cannot take in time the transport drops before the node sees it (compare the samples sent
/// with `motion samples`). Checked: the node's own counts agree with this test's answers.
void burst() {
  Stream s;
  ros::WallRate rate(kBurstRate);
  std::vector<ros::Time> stamps;
  for (int i = 0; i < kBurst; ++i) {
    g_h->setTime(g_h->now() + ros::Duration(1.0 / kBurstRate));
    stamps.push_back(g_h->now());
    g_h->send(g_h->good(g_h->now()));
    rate.sleep();
  }
  // The last sample that got through is answered within the timeout; wait until answers stop.
  int answered = -1;
  for (int quiet = 0; quiet < 20;) {
    int n = 0;
    for (const auto& t : stamps) n += g_h->answers(t) > 0 ? 1 : 0;
    quiet = n == answered ? quiet + 1 : 0;
    answered = n;
    ros::WallDuration(0.05).sleep();
  }
  // Answered more than once: none (the last one answered excepted: a silent source gets the last
  // state republished, the line node's ~republish_when_silent).
  int twice = 0, last = -1;
  for (int i = 0; i < kBurst; ++i)
    if (g_h->answers(stamps[static_cast<std::size_t>(i)]) > 0) last = i;
  for (int i = 0; i < last; ++i) twice += g_h->answers(stamps[static_cast<std::size_t>(i)]) > 1 ? 1 : 0;
  s.after();
  const long received = s.grew("motion samples");
  EXPECT_EQ(twice, 0) << "a sample answered twice";
  EXPECT_EQ(received, answered + 1) << "every sample the node received (and the settling one) was answered; sent "
                                    << kBurst << ", " << s.changes();
  EXPECT_EQ(s.grew("states published"), answered + 1) << s.changes();
  EXPECT_GE(answered, 100) << "at least a queue's worth of the burst";
  ::testing::Test::RecordProperty("burst_sent", kBurst);
  ::testing::Test::RecordProperty("burst_answered", answered);
  std::printf("burst: %d samples sent at %g Hz, %d received and answered\n", kBurst, kBurstRate, answered);
}
void silentTopic(bool republishes) {
  Stream s;
  const ros::Time last = g_h->now();
  const int before = g_h->answers(last);
  // ~motion_timeout is 0.5 s in the launch files: 1.5 s of silence.
  ros::WallDuration(1.5).sleep();
  const Diag d = g_h->freshDiag();
  EXPECT_EQ(d.level, 1) << d.message;  // WARN
  EXPECT_NE(d.message.find("no motion for"), std::string::npos) << d.message;
  if (republishes) {
    EXPECT_GT(g_h->answers(last), before) << "the last good state is republished while silent";
  }
  const Diag& a = s.after();
  EXPECT_EQ(a.message.find("no motion for"), std::string::npos) << a.message;
}
void wrongFrame(const std::string& key) {
  Stream s;
  auto m = g_h->good(g_h->next());
  m.header.frame_id = "nowhere";  // no tf to world: dropped after ~tf_timeout
  sendUnanswered(m);
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void zeroStamp(const std::string& key) {
  Stream s;
  auto m = g_h->good(ros::Time(0));
  g_h->send(m);
  ASSERT_TRUE(g_h->settle());
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}
void alternating(const std::string& key) {
  Stream s;
  std::vector<ros::Time> good;
  for (int i = 0; i < 10; ++i) {
    good.push_back(g_h->next());
    g_h->send(g_h->good(good.back()));
    g_h->send(withPosition(g_h->good(g_h->next()), 2, kNaN));
  }
  ASSERT_TRUE(g_h->waitAnswer(good.back()));
  for (const auto& t : good) EXPECT_EQ(g_h->answers(t), 1) << t.toSec();
  s.after();
  EXPECT_EQ(s.grew(key), 10) << s.changes();
}
/// 1 ns after the last accepted stamp: a tiny but valid step, answered with finite values.
void nanosecondStep() {
  Stream s;
  const ros::Time t = g_h->next();
  g_h->send(g_h->good(t));
  ASSERT_TRUE(g_h->waitAnswer(t));
  const ros::Time t1 = t + ros::Duration(0, 1);
  g_h->setTime(t1);
  g_h->send(g_h->good(t1));
  EXPECT_TRUE(g_h->waitAnswer(t1));
  s.after();
}
void resetThenContinue(const std::string& key) {
  Stream s;
  std_srvs::Trigger tr;
  ASSERT_TRUE(g_h->call("reset", tr));
  EXPECT_TRUE(tr.response.success) << tr.response.message;
  s.after();
  EXPECT_EQ(s.grew(key), 1) << s.changes();
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// LockstepNode (one line, model: 2d).

TEST(LineStreams, NanPosition) { nanPosition(lk::kNonFinite); }
TEST(LineStreams, InfPosition) { infPosition(lk::kNonFinite); }
TEST(LineStreams, NanQuaternionAcceptedAndCounted) {
  // The line's top is a moment-free point: the orientation is not used, so a bad one does not
  // drop the sample; it is counted (and a non-finite one warns).
  Stream s;
  const auto m = withQuaternion(g_h->good(g_h->next()), kNaN, 0, 0, 1);
  g_h->send(m);
  EXPECT_TRUE(g_h->waitAnswer(m.header.stamp));
  const Diag& d = s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonFinite), 1) << s.changes();
  (void)d;
}
TEST(LineStreams, InfQuaternionAcceptedAndCounted) {
  Stream s;
  const auto m = withQuaternion(g_h->good(g_h->next()), 0, kInf, 0, 1);
  g_h->send(m);
  EXPECT_TRUE(g_h->waitAnswer(m.header.stamp));
  s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonFinite), 1) << s.changes();
}
TEST(LineStreams, ZeroAndNonUnitQuaternionsAcceptedAndCounted) {
  Stream s;
  const auto a = withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 0);
  const auto b = withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 1.1);
  g_h->send(a);
  g_h->send(b);
  EXPECT_TRUE(g_h->waitAnswer(b.header.stamp));
  EXPECT_EQ(g_h->answers(a.header.stamp), 1);
  s.after();
  EXPECT_EQ(s.grew(lk::kOrientationNonUnit), 2) << s.changes();
}
TEST(LineStreams, BackwardStamp) { backwardStamp(lk::kStampBack); }
TEST(LineStreams, DuplicateStamp) { duplicateStamp(lk::kSameStamp); }
TEST(LineStreams, FarFutureStamp) { farFutureStamp(lk::kReinitGap, lk::kReinitLoop); }
TEST(LineStreams, HugeJump) { hugeJump(lk::kJump); }
TEST(LineStreams, RepeatedJumpsRestart) { repeatedJumps(lk::kReinitJumps); }
TEST(LineStreams, FarAwayPoseCannotStart) {
  // Three jumps in a row to a point 10 km away: the restart there fails (out of reach), counted
  // and ERROR; the next good sample starts the run again from statics.
  Stream s;
  for (int i = 0; i < 3; ++i) g_h->send(withPosition(g_h->good(g_h->next()), 0, 1e4));
  const Diag& d = s.after();
  EXPECT_EQ(s.grew(lk::kStartFailed), 1) << s.changes();
  EXPECT_EQ(s.grew(lk::kJump), 2) << s.changes();
  (void)d;
}
TEST(LineStreams, Burst1kHz) { burst(); }
TEST(LineStreams, SilentTopic) { silentTopic(true); }
TEST(LineStreams, WrongFrameId) { wrongFrame(lk::kUnknownFrame); }
TEST(LineStreams, ZeroStamp) { zeroStamp(lk::kZeroStamp); }
TEST(LineStreams, OffPlaneY) {
  Stream s;
  sendUnanswered(withPosition(g_h->good(g_h->next()), 1, 0.5));  // model: 2d, |y| > 1 mm
  s.after();
  EXPECT_EQ(s.grew(lk::kOffPlane), 1) << s.changes();
}
TEST(LineStreams, AlternatingGoodAndBad) { alternating(lk::kNonFinite); }
TEST(LineStreams, NanosecondStep) { nanosecondStep(); }
TEST(LineStreams, SolveStaticBadValues) {
  Stream s;
  md::SolveStatic nan_req;
  nan_req.request.mode = md::SolveStatic::Request::TOP_POSITION;
  nan_req.request.top_position.x = kNaN;
  ASSERT_TRUE(g_h->call("solve_static", nan_req));
  EXPECT_FALSE(nan_req.response.success);
  EXPECT_NE(nan_req.response.message.find("top_position.x = nan"), std::string::npos) << nan_req.response.message;
  md::SolveStatic neg_force;
  neg_force.request.mode = md::SolveStatic::Request::TOP_FORCE;
  neg_force.request.top_force.z = -kInf;
  ASSERT_TRUE(g_h->call("solve_static", neg_force));
  EXPECT_FALSE(neg_force.response.success);
  EXPECT_NE(neg_force.response.message.find("top_force.z"), std::string::npos) << neg_force.response.message;
  md::SolveStatic mode;
  mode.request.mode = 7;
  ASSERT_TRUE(g_h->call("solve_static", mode));
  EXPECT_FALSE(mode.response.success);
  EXPECT_NE(mode.response.message.find("mode = 7"), std::string::npos) << mode.response.message;
  md::SolveStatic y;
  y.request.mode = md::SolveStatic::Request::TOP_POSITION;
  y.request.top_position.x = g_h->x0_;
  y.request.top_position.y = 5.0;
  ASSERT_TRUE(g_h->call("solve_static", y));
  EXPECT_FALSE(y.response.success);
  EXPECT_NE(y.response.message.find("top_position.y = 5"), std::string::npos) << y.response.message;
  md::SolveStatic far;
  far.request.mode = md::SolveStatic::Request::TOP_POSITION;
  far.request.top_position.x = 1e4;
  far.request.reinitialise = true;
  ASSERT_TRUE(g_h->call("solve_static", far));
  EXPECT_FALSE(far.response.success);
  EXPECT_FALSE(far.response.reinitialised);
  s.after();
  EXPECT_EQ(s.grew(lk::kRequestRejected), 5) << s.changes();
  EXPECT_EQ(s.grew(lk::kReinitRequest), 0) << "a rejected request does not touch the run";
}
TEST(LineStreams, ResetThenContinue) { resetThenContinue(lk::kReinitRequest); }

// ---------------------------------------------------------------------------------------------
// VesselNode (three lines, model: 3d).

TEST(VesselStreams, NanPosition) { nanPosition(vk::kNonFinitePosition); }
TEST(VesselStreams, InfPosition) { infPosition(vk::kNonFinitePosition); }
TEST(VesselStreams, NanQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, kNaN, 1));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonFiniteOrientation), 1) << s.changes();
}
TEST(VesselStreams, InfQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), kInf, 0, 0, 1));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonFiniteOrientation), 1) << s.changes();
}
TEST(VesselStreams, ZeroQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 0));
  s.after();
  EXPECT_EQ(s.grew(vk::kNonUnitOrientation), 1) << s.changes();
}
TEST(VesselStreams, NonUnitQuaternion) {
  Stream s;
  sendUnanswered(withQuaternion(g_h->good(g_h->next()), 0, 0, 0, 1.1));  // norm 1.1
  const auto near = withQuaternion(g_h->good(g_h->next()), 0, 0, 0.0015, 1.0);  // norm off 1 by 1.1e-6
  g_h->send(near);
  EXPECT_TRUE(g_h->waitAnswer(near.header.stamp)) << "accepted (normalized)";
  s.after();
  EXPECT_EQ(s.grew(vk::kNonUnitOrientation), 1) << "within 1e-3 of unit norm is accepted (normalized)";
}
TEST(VesselStreams, BackwardStamp) { backwardStamp(vk::kStampBack); }
TEST(VesselStreams, DuplicateStamp) { duplicateStamp(vk::kSameStamp); }
TEST(VesselStreams, FarFutureStamp) { farFutureStamp(vk::kRestartGap, vk::kRestartLoop); }
TEST(VesselStreams, HugeJump) { hugeJump(vk::kJump); }
TEST(VesselStreams, RepeatedJumpsRestart) { repeatedJumps(vk::kRestartJumps); }
TEST(VesselStreams, FarAwayPoseCannotStart) {
  // Three jumps in a row to a pose 10 km away: the restart there fails (no line reaches), counted;
  // the run goes on from its last good state with the next good sample.
  Stream s;
  for (int i = 0; i < 3; ++i) g_h->send(withPosition(g_h->good(g_h->next()), 0, 1e4));
  s.after();
  EXPECT_EQ(s.grew(vk::kStartFailed), 1) << s.changes();
  EXPECT_EQ(s.grew(vk::kJump), 2) << s.changes();
}
TEST(VesselStreams, Burst1kHz) { burst(); }
TEST(VesselStreams, SilentTopic) { silentTopic(false); }
TEST(VesselStreams, WrongFrameId) { wrongFrame(vk::kUnknownFrame); }
TEST(VesselStreams, ZeroStamp) { zeroStamp(vk::kZeroStamp); }
TEST(VesselStreams, AlternatingGoodAndBad) { alternating(vk::kNonFinitePosition); }
TEST(VesselStreams, NanosecondStep) { nanosecondStep(); }
TEST(VesselStreams, SolveStaticBadValues) {
  Stream s;
  md::VesselStatics nan_pose;
  nan_pose.request.pose.position.x = kNaN;
  nan_pose.request.pose.orientation.w = 1.0;
  ASSERT_TRUE(g_h->call("solve_static", nan_pose));
  EXPECT_FALSE(nan_pose.response.success);
  EXPECT_NE(nan_pose.response.message.find("pose.position"), std::string::npos) << nan_pose.response.message;
  md::VesselStatics q;
  q.request.pose.orientation.w = 2.0;
  ASSERT_TRUE(g_h->call("solve_static", q));
  EXPECT_FALSE(q.response.success);
  EXPECT_NE(q.response.message.find("orientation"), std::string::npos) << q.response.message;
  md::VesselStatics dof;
  dof.request.use_file_pose = true;
  dof.request.offset_dof = "sideways";
  dof.request.offset_range = 5.0;
  dof.request.offset_steps = 3;
  ASSERT_TRUE(g_h->call("solve_static", dof));
  EXPECT_FALSE(dof.response.success);
  EXPECT_NE(dof.response.message.find("sideways"), std::string::npos) << dof.response.message;
  md::VesselStatics range;
  range.request.use_file_pose = true;
  range.request.offset_dof = "surge";
  range.request.offset_range = -5.0;
  range.request.offset_steps = 3;
  ASSERT_TRUE(g_h->call("solve_static", range));
  EXPECT_FALSE(range.response.success);
  EXPECT_NE(range.response.message.find("offset_range"), std::string::npos) << range.response.message;
  md::VesselStatics steps;
  steps.request.use_file_pose = true;
  steps.request.offset_dof = "yaw";
  steps.request.offset_range = 5.0;
  steps.request.offset_steps = 0;
  ASSERT_TRUE(g_h->call("solve_static", steps));
  EXPECT_FALSE(steps.response.success);
  EXPECT_NE(steps.response.message.find("offset_steps"), std::string::npos) << steps.response.message;
  s.after();
  EXPECT_EQ(s.grew(vk::kRequestRejected), 5) << s.changes();
}
TEST(VesselStreams, ResetThenContinue) { resetThenContinue(vk::kRestartReset); }

// ---------------------------------------------------------------------------------------------
// A step that fails at its smallest cut (the fragile files, ~max_speed 0).

namespace {

constexpr double kLurch = 5.0;  // [m] in 0.1 s: far more than 4 Newton iterations can follow

bool sameState(const md::CableState& a, const md::CableState& b) {
  if (a.positions.size() != b.positions.size()) return false;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    if (a.positions[i].x != b.positions[i].x || a.positions[i].y != b.positions[i].y ||
        a.positions[i].z != b.positions[i].z || a.tension[i] != b.tension[i])
      return false;
  return a.top_force.x == b.top_force.x && a.top_force.z == b.top_force.z;
}

/// Gentle samples, then one lurch: the answer to the lurch is the previous answer's state (the
/// step failed at once: one base step per sample, no cutting), bit for bit, marked not converged;
/// ERROR names the line; the next gentle sample is answered from there, converged.
void failureKeepsLastGoodState(const std::vector<std::string>& lines, const std::string& kept_key) {
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(g_h->settle());
  const ros::Time good = g_h->now();
  Stream s;
  auto m = g_h->good(g_h->next());
  m.pose.position.x += kLurch;
  g_h->send(m);
  ASSERT_TRUE(g_h->waitAnswer(m.header.stamp)) << "the failed sample is answered (with the last good state)";
  for (const auto& l : lines) {
    md::CableState before, failed;
    ASSERT_TRUE(g_h->state(l, good, before)) << l;
    ASSERT_TRUE(g_h->waitState(l, m.header.stamp, failed)) << l;
    EXPECT_TRUE(before.converged) << l;
    EXPECT_FALSE(failed.converged) << l << ": the kept state is not the state at this stamp";
    EXPECT_TRUE(sameState(before, failed)) << l << ": the last good state, bit for bit";
  }
  geometry_msgs::WrenchStamped wb, wf;
  ASSERT_TRUE(g_h->wrench(good, wb));
  ASSERT_TRUE(g_h->wrench(m.header.stamp, wf));
  EXPECT_EQ(wb.wrench.force.x, wf.wrench.force.x);
  EXPECT_EQ(wb.wrench.force.z, wf.wrench.force.z);
  EXPECT_EQ(wb.wrench.torque.z, wf.wrench.torque.z);
  const Diag d = g_h->waitDiag("last good state");
  EXPECT_EQ(d.level, 2) << d.message;  // ERROR
  bool named = false;
  for (const auto& l : lines) named = named || d.message.find("line " + l) != std::string::npos;
  EXPECT_TRUE(named) << "the message names the failed line: " << d.message;
  // The next gentle sample continues from the kept state and converges.
  const Diag& a = s.after();
  EXPECT_EQ(s.grew(kept_key), 1) << s.changes();
  md::CableState next;
  ASSERT_TRUE(g_h->waitState(lines[0], g_h->now(), next));
  EXPECT_TRUE(next.converged);
  (void)a;
}

/// Three lurches in a row (~failures_to_reinit, 3): two kept states, then a restart from statics
/// at the third sample's pose, converged.
void repeatedFailuresRestart(const std::vector<std::string>& lines, const std::string& kept_key,
                             const std::string& restart_key) {
  ASSERT_TRUE(g_h->settle());
  Stream s;
  ros::Time last;
  for (int i = 1; i <= 3; ++i) {
    auto m = g_h->good(g_h->next());
    m.pose.position.x += kLurch;
    g_h->send(m);
    last = m.header.stamp;
  }
  ASSERT_TRUE(g_h->waitAnswer(last));
  md::CableState st;
  ASSERT_TRUE(g_h->waitState(lines[0], last, st));
  EXPECT_TRUE(st.converged) << "restarted from statics at the sample";
  // Back to the gentle track: 5 m back in 0.1 s fails again; the third time restarts again.
  for (int i = 0; i < 3; ++i) g_h->send(g_h->good(g_h->next()));
  ASSERT_TRUE(g_h->waitAnswer(g_h->now()));
  s.after();
  EXPECT_EQ(s.grew(kept_key), 4) << s.changes();
  EXPECT_EQ(s.grew(restart_key), 2) << s.changes();
}

}  // namespace

TEST(LineFailure, KeepsLastGoodStatePublishesAndContinues) {
  failureKeepsLastGoodState({"fragile catenary"}, lk::kFailedKept);
}
TEST(LineFailure, RepeatedFailuresRestartFromStatics) {
  repeatedFailuresRestart({"fragile catenary"}, lk::kFailedKept, lk::kReinitFailures);
}
TEST(VesselFailure, KeepsLastGoodStatePublishesAndContinues) {
  failureKeepsLastGoodState({"bow", "port_quarter", "stbd_quarter"}, vk::kFailedKept);
}
TEST(VesselFailure, RepeatedFailuresRestartFromStatics) {
  repeatedFailuresRestart({"bow", "port_quarter", "stbd_quarter"}, vk::kFailedKept, vk::kRestartFailures);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_bad_streams");
  ros::NodeHandle pnh("~");
  std::string kind = "line", node = "/cable", file = "small_catenary.yaml";
  pnh.param<std::string>("kind", kind, kind);
  pnh.param<std::string>("node", node, node);
  pnh.param<std::string>("problem_file", file, file);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  Harness h(kind, node, file);
  g_h = &h;
  if (!h.connect()) {
    ADD_FAILURE() << "the node " << node << " did not come up";
    return 1;
  }
  // The first sample starts the run (from the file's statics).
  const ros::Time t = h.next();
  h.send(h.good(t));
  if (!h.waitAnswer(t, 60.0)) {
    ADD_FAILURE() << "the first sample was not answered";
    return 1;
  }
  const int rc = RUN_ALL_TESTS();
  spinner.stop();
  return rc;
}
