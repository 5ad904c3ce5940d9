// Largest tension along a line and its utilization: the tension over the minimum breaking load
// (Material::mbl) of the material it acts in, the inverse of the safety factor mooring design
// codes use. Static (one solution) and dynamic (the largest over the output samples).
#pragma once

#include <string>
#include <vector>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/model/result.hpp"

namespace mooring_dynamics {
namespace core {

/// Slack line: the unstretched length [m] over which the tension is below the top of the slack
/// ramp of its material (Material::slackBand / 2; at most that, and 0 beyond the ramp), counted
/// over the intervals whose two nodes are both slack. 0 for materials that carry compression
/// (their tension is taken as slack where it is <= 0).
double slackLength(const std::vector<Material>& materials, const std::vector<Segment>& segments,
                   const std::vector<NodeState>& nodes);

/// The peak tension of one line and its utilization, over one or more states of the line.
struct TensionPeak {
  bool empty = true;            ///< no state seen yet
  double max_tension = 0.0;     ///< largest effective tension along the line [N]
  double s_max = 0.0;           ///< unstretched arclength from the lower end of that node [m]
  double t_max = 0.0;           ///< time of that state [s] (0 in statics)
  bool has_mbl = false;         ///< some node's material gives an MBL
  double utilization = 0.0;     ///< largest T / MBL over the nodes whose material has one [-]
  double s_util = 0.0;          ///< arclength of that node [m]
  double t_util = 0.0;          ///< time of that state [s]
  double mbl = 0.0;             ///< MBL of the material at that node [N]
  std::string material;         ///< and its name
  double slack_length = 0.0;    ///< largest slack length over the states (slackLength) [m]
  double t_slack = 0.0;         ///< time of that state [s]

  /// Take one state of the line into the peak: `nodes` lower end first, node.segment indexing
  /// `segments`, whose material indexes `materials`.
  void add(const std::vector<Material>& materials, const std::vector<Segment>& segments,
           const std::vector<NodeState>& nodes, double t = 0.0);
};

/// The peak of one state (statics).
TensionPeak tensionPeak(const std::vector<Material>& materials, const std::vector<Segment>& segments,
                        const std::vector<NodeState>& nodes);

/// One line of text for a summary: "max tension 1234.5 N at s = 10.00 m; utilization 0.123 of MBL
/// 10000.0 N (chain) at s = ..." or "...; no MBL given". `with_time` adds the times (dynamics).
std::string tensionPeakText(const TensionPeak& p, bool with_time);

}  // namespace core
}  // namespace mooring_dynamics
