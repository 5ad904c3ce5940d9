// The manifest of a sweep's folder (sweep_io.hpp): what `cable_sim sweep` writes next to the
// cases (the variations, the cases and their labels, the statistics' settings) and what
// `--collect` reads back.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/sweep_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"
#include "problem_sections.hpp"
#include "sweep_detail.hpp"

namespace mooring_dynamics {
namespace core {

using namespace yaml;
using sweep_detail::fmt12;
using sweep_detail::readDesignCheck;

SweepManifest manifestOf(const SweepSpec& spec, const std::vector<SweepCase>& cases) {
  SweepManifest m;
  m.name = spec.name;
  m.gumbel = spec.gumbel;
  m.skip_time = spec.skip_time;
  m.design_class = spec.design_class;
  m.als_labels = spec.als_labels;
  for (const auto& v : spec.variations) {
    SweepManifest::Variation mv;
    mv.name = v.name;
    mv.seeds = v.seeds;
    for (const auto& val : v.values) {
      mv.labels.push_back(val.label);
      mv.numbers.push_back(val.numeric ? val.number : std::numeric_limits<double>::quiet_NaN());
    }
    m.variations.push_back(mv);
  }
  m.cases = cases;
  return m;
}

std::string manifestText(const SweepManifest& m) {
  YAML::Emitter e;
  e << YAML::Comment("cable_sim sweep manifest: read by 'cable_sim sweep --collect'");
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << m.name;
  e << YAML::Key << "gumbel_fit" << YAML::Value << gumbelMethodName(m.gumbel);
  e << YAML::Key << "skip_time" << YAML::Value << fmt12(m.skip_time);
  if (m.design_class > 0)
    e << YAML::Key << "design_check" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "consequence_class"
      << YAML::Value << m.design_class << YAML::Key << "als" << YAML::Value << YAML::Flow << m.als_labels << YAML::EndMap;
  e << YAML::Key << "variations" << YAML::Value << YAML::BeginSeq;
  for (const auto& v : m.variations) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << v.name << YAML::Key << "seeds"
      << YAML::Value << v.seeds << YAML::Key << "labels" << YAML::Value << YAML::Flow << v.labels << YAML::Key
      << "numbers" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double d : v.numbers) {
      if (std::isfinite(d)) e << fmt12(d);
      else e << YAML::Null;
    }
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "cases" << YAML::Value << YAML::BeginSeq;
  for (const auto& c : m.cases)
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << c.name << YAML::Key << "storm"
      << YAML::Value << c.storm << YAML::Key << "choice" << YAML::Value << YAML::Flow << c.choice << YAML::EndMap;
  e << YAML::EndSeq << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

SweepManifest loadManifestFromFile(const std::string& path) {
  try {
    const YAML::Node root = sections::parseYaml(sections::readFileText(path));
    const Item top_item{root, "", YAML::Mark::null_mark()};
    const Map top(top_item, {"name", "gumbel_fit", "skip_time", "design_check", "variations", "cases"});
    SweepManifest m;
    m.skip_time = top.number("skip_time", Range::NonNegative);
    if (top.has("design_check")) {
      SweepSpec d;
      readDesignCheck(top.at("design_check"), d);
      m.design_class = d.design_class;
      m.als_labels = d.als_labels;
    }
    m.name = readString(top.required("name"));
    const Item gi = top.required("gumbel_fit");
    try {
      m.gumbel = gumbelMethodFromName(readString(gi));
    } catch (const std::invalid_argument&) {
      gi.failQuoted("needs moments or mle");
    }
    for (const Item& vi : listItems(top.required("variations"))) {
      const Map vm(vi, {"name", "seeds", "labels", "numbers"});
      SweepManifest::Variation v;
      v.name = readString(vm.required("name"));
      v.seeds = readBool(vm.required("seeds"));
      for (const Item& li : listItems(vm.required("labels"))) v.labels.push_back(readString(li));
      for (const Item& ni : listItems(vm.required("numbers")))
        v.numbers.push_back(ni.node.IsNull() ? std::numeric_limits<double>::quiet_NaN() : readNumber(ni));
      if (v.numbers.size() != v.labels.size()) vm.at("numbers").failNoValue("needs one number (or ~) per label");
      m.variations.push_back(v);
    }
    for (const Item& ci : listItems(top.required("cases"))) {
      const Map cm(ci, {"name", "storm", "choice"});
      SweepCase c;
      c.name = readString(cm.required("name"));
      c.storm = readString(cm.required("storm"));
      for (const Item& k : listItems(cm.required("choice"))) {
        const long long v = readInteger(k);
        if (v < 0) k.fail("must be >= 0");
        c.choice.push_back(static_cast<std::size_t>(v));
      }
      if (c.choice.size() != m.variations.size()) cm.at("choice").failNoValue("needs one index per variation");
      for (std::size_t v = 0; v < c.choice.size(); ++v)
        if (c.choice[v] >= m.variations[v].labels.size()) cm.at("choice").failNoValue("index out of range of variation " + m.variations[v].name);
      m.cases.push_back(c);
    }
    return m;
  } catch (const ProblemError& e) {
    throw ProblemError(path + ": " + e.what());
  }
}

}  // namespace core
}  // namespace mooring_dynamics
