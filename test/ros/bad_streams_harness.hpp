// Shared by the bad-input rostests of the lockstep nodes (test_bad_streams.cpp,
// test_step_failure.cpp): the Harness that drives one node (LockstepNode, ~kind line, or VesselNode,
// ~kind vessel) with good samples and keeps what it publishes by stamp and its latest
// /diagnostics status, Stream (a counter's growth over one stream, and the checks every stream
// shares) and the tests' main.
//
// The good motion is a small oscillation about the static top (line) or the file's pose (vessel),
// one sample per 0.1 s of stamp.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>

#include "mooring_dynamics/CableState.h"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/ros/tools/companions.hpp"

namespace bad_streams_test {

namespace md = mooring_dynamics;

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
inline long totalOf(const Diag& d, const std::string& key) {
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

inline Harness* g_h = nullptr;

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

/// The tests' main: ~kind (line or vessel), ~node and ~problem_file (under test/data/); the node
/// must come up, and the first good sample starts its run (from the file's statics).
inline int harnessMain(int argc, char** argv, const std::string& name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
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

}  // namespace bad_streams_test
