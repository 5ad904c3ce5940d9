// Load-case sweeps (docs/design_analysis.md): a base problem file plus named variations of its
// keys, expanded into independent cases. Each case is a complete problem file with a stable name,
// so that it can be run alone with `cable_sim dynamic`.
//
// Keys are dotted paths into the base file's YAML: `environment.waves.hs`, list items by index
// (`lines.2` or `lines[2]`) or by their `name` key (`lines[name=leg_e]`, `vessel.lines[name=bow_1]`).
// Every rejected input raises ProblemError naming the key, the value and the constraint.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mooring_dynamics/core/model/extremes.hpp"

namespace mooring_dynamics {
namespace core {

/// One change to the base file: set the key to a YAML value, or remove it (a map key or a list item).
struct SweepEdit {
  enum class Kind { Set, Remove };
  Kind kind = Kind::Set;
  std::string key;    ///< dotted path
  std::string value;  ///< Set: the value as YAML text (flow style)
  bool path_value = false;  ///< the key names a file (seabed grid, motion table, ship track): value relative to the sweep file
};

/// One value of a variation: a label (part of the case names) and its edits.
struct SweepValue {
  std::string label;
  std::vector<SweepEdit> edits;
  double number = 0.0;  ///< the number set, for plots (when `numeric`)
  bool numeric = false;  ///< the value sets one key to one number
};

struct SweepVariation {
  std::string name;
  bool seeds = false;  ///< the cases along this variation are random seeds of one storm (Gumbel fit of their maxima)
  std::vector<SweepValue> values;
};

struct SweepSpec {
  std::string name;       ///< sweep name (default: the sweep file's stem)
  std::string base_path;  ///< the base problem file (absolute, or as given when the sweep is read from text without a directory)
  std::string sweep_dir;  ///< the sweep file's directory (paths set by the sweep are relative to it)
  std::vector<SweepEdit> common;  ///< `set:` / `remove:` applied to every case before the variations
  std::vector<SweepVariation> variations;
  GumbelMethod gumbel = GumbelMethod::Moments;
  double skip_time = 0.0;  ///< [s] statistics leave out the samples before this time (the start-up transient)
  /// `statistics.design_check`: the DNV-OS-E301-style line check (model/design_check.hpp) in
  /// consequence class 1 or 2; 0 = none. Storms with one of `als_labels` (labels of any variation,
  /// e.g. the broken-line values) are accidental (ALS), the others ULS.
  int design_class = 0;
  std::vector<std::string> als_labels;
};

/// A case: one value of every variation.
struct SweepCase {
  std::string name;                 ///< "<variation>-<label>" joined with "_" in variation order ("base" with no variations)
  std::string storm;                ///< the name without the seeds variation's part (= name without one)
  std::vector<std::size_t> choice;  ///< index of the value of every variation
};

/// Read a sweep file. Throws ProblemError (messages start with the file's path).
SweepSpec loadSweepFromFile(const std::string& path);
/// Read a sweep from text; relative paths (base, path values) are relative to `dir`.
SweepSpec loadSweepFromString(const std::string& yaml_text, const std::string& dir);

/// All cases: the Cartesian product of the variations, the last variation fastest.
std::vector<SweepCase> expandSweep(const SweepSpec& spec);

/// The YAML text of a case's problem file, to be written into `case_dir`: the base file with the
/// common edits and the case's values applied, and the files it names (seabed grid, motion table,
/// ship track) made relative to `case_dir`. Throws ProblemError naming the variation, the value
/// and the key when an edit does not fit the base file.
std::string caseProblemText(const SweepSpec& spec, const SweepCase& c, const std::string& case_dir);

// ---------------------------------------------------------------------------------------------
// The manifest (DIR/manifest.yaml): what `sweep --collect` needs to summarise a sweep's results
// without the sweep file: its name, the fit, the variations' names, labels and numbers, the cases.

struct SweepManifest {
  std::string name;
  GumbelMethod gumbel = GumbelMethod::Moments;
  double skip_time = 0.0;
  int design_class = 0;                 ///< as SweepSpec
  std::vector<std::string> als_labels;  ///< as SweepSpec
  struct Variation {
    std::string name;
    bool seeds = false;
    std::vector<std::string> labels;
    std::vector<double> numbers;  ///< one per label; NaN where the value is not one number
  };
  std::vector<Variation> variations;
  std::vector<SweepCase> cases;
};

SweepManifest manifestOf(const SweepSpec& spec, const std::vector<SweepCase>& cases);
std::string manifestText(const SweepManifest& m);
/// Throws ProblemError naming the file and key when the manifest is malformed.
SweepManifest loadManifestFromFile(const std::string& path);

}  // namespace core
}  // namespace mooring_dynamics
