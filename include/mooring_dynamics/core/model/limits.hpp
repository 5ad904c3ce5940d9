// Resource limits: the size of a problem (nodes, time steps, memory) estimated from its input
// before anything is allocated, refused beyond documented limits (docs/problem_format.md,
// "Limits"). A problem or system file raises them in its `limits:` section.
#pragma once

#include <string>
#include <vector>

namespace mooring_dynamics {
namespace core {

struct Segment;
struct DynamicOptions;

/// Upper bounds on the derived size of a run. Defaults: see the constants' comments.
struct ResourceLimits {
  /// Nodes of all lines together. 10^6 nodes is ~3000 times the paper cases (A.2 has ~300); a
  /// spacing typo (2e-5 m, a 1e7 m line) lands far beyond it. The memory limit binds first for
  /// most models (kBytesPerNode*); this one keeps the node count itself meaningful.
  static constexpr double kDefaultMaxNodes = 1.0e6;
  /// Base time steps duration / dt. 10^7 steps is 12 days of simulated time at dt = 0.1 s, and
  /// about 40 minutes of wall time for the smallest paper case (A.3: ~4300 steps/s).
  static constexpr double kDefaultMaxSteps = 1.0e7;
  /// Estimated memory of the run [MB]: half the CI machine's 8 GB.
  static constexpr double kDefaultMaxMemoryMb = 4096.0;

  /// Size of a problem or system file's text [MB = 2^20 bytes], checked before the YAML reader
  /// sees it: yaml-cpp reads about 1 MB a second (a current profile of 1.4 million inline points,
  /// 84 MB, took 153 s and 5 GB before the solver said anything). 4 MB is a thousand times a
  /// shipped example; long tables go in CSV files (environment.current.file, motion tables).
  static constexpr double kDefaultMaxInputMb = 4.0;

  double max_nodes = kDefaultMaxNodes;
  double max_steps = kDefaultMaxSteps;
  double max_memory_mb = kDefaultMaxMemoryMb;
  double max_input_mb = kDefaultMaxInputMb;

  /// Empty when valid, else "limits.<key> = value: constraint".
  std::string validate() const;
};

/// Working set per node [bytes]: peak resident size over node count, measured as the slope between
/// lines of 7 501 and 30 001 nodes (small_catenary at spacing 0.02 and 0.005 m, /usr/bin/time):
/// 2-D statics 1.5 kB, 2-D dynamics 8.1 kB, 3-D statics and dynamics 25.8 kB per node. Rounded
/// up, so that the estimate bounds the run: 4096 MB hold ~400 000 2-D or ~130 000 3-D nodes.
inline constexpr double kBytesPerNode2dStatic = 2048.0;
inline constexpr double kBytesPerNode2dDynamic = 10240.0;
inline constexpr double kBytesPerNode3d = 32768.0;
/// One node of a stored snapshot (core::NodeResult and its vector slot), rounded up [bytes].
inline constexpr double kBytesPerSnapshotNode = 160.0;

/// Sizes derived from the input without building anything.
struct ResourceEstimate {
  double nodes = 0.0;      ///< nodes of all lines
  double steps = 0.0;      ///< base time steps duration / dt (0 without a dynamic run)
  double samples = 0.0;    ///< output samples
  double snapshots = 0.0;  ///< stored whole-line snapshots
  double memory_mb = 0.0;  ///< estimated peak working set [MB]
  double duration = 0.0, dt = 0.0;  ///< the run's dynamics.duration and dynamics.dt [s]
};

/// Nodes of one line of these segments (an upper bound of buildMesh's count: one per interval
/// of ceil(length / spacing), one per body junction and segment joint, plus the first), in
/// floating point so that absurd inputs cannot overflow.
double estimateLineNodes(const std::vector<Segment>& segments);

/// The estimate for lines of `nodes` nodes in all, with the dynamic options `dyn` (duration 0:
/// statics only) and record columns `record_columns` per sample.
ResourceEstimate estimateResources(double nodes, const DynamicOptions& dyn, bool three_d, std::size_t record_columns);

/// Empty when `est` is within `lim`, else a message naming the key that drives the quantity
/// (`nodes_key`, e.g. "line[0].spacing"), the estimate, the limit and how to raise it.
std::string checkResources(const ResourceEstimate& est, const ResourceLimits& lim, const std::string& nodes_key);

/// `line[i].spacing` checks for a segment list: spacing <= length (a spacing beyond the
/// segment collapses it to one interval). `prefix` is "line" or "lines[k].segments".
std::string validateSpacing(const std::vector<Segment>& segments, const std::string& prefix);

}  // namespace core
}  // namespace mooring_dynamics
