// Section readers shared by the problem-file and system-file loaders (problem_io.cpp,
// system_io.cpp). Internal to the core: the public API is problem_io.hpp.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mooring_dynamics/core/model/model.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"

namespace mooring_dynamics {
namespace core {
namespace sections {

using yaml::Item;
using yaml::Map;

void readEnvironment(const Item& it, Environment& env, const std::string& base_dir);
std::size_t lookup(const Item& it, const std::map<std::string, std::size_t>& table,
                   const std::vector<std::string>& order, const std::string& kind);
void readBuoy(const Item& it, SurfaceBuoy& buoy);
void readSolver(const Item& it, StaticOptions& opt);
void readLine(const Item& it, Problem& pb, const std::map<std::string, std::size_t>& mat_index,
              const std::vector<std::string>& mat_names, const std::map<std::string, std::size_t>& body_index,
              const std::vector<std::string>& body_names);
/// Names of the materials and bodies, in file order, for lookups.
struct Catalogue {
  std::map<std::string, std::size_t> mat_index, body_index;
  std::vector<std::string> mat_names, body_names;
};
void readCatalogue(const Map& top, std::vector<Material>& materials, std::vector<Body>& bodies, Catalogue& cat);
Formulation readModel(const Item& mi);
/// `limits:` {max_nodes, max_steps, max_memory_mb} (limits.hpp, docs/problem_format.md "Limits").
void readLimits(const Item& it, ResourceLimits& lim);
/// One YAML document from text (ProblemError on syntax errors or several documents).
YAML::Node parseYaml(const std::string& yaml_text);
/// A file's text (ProblemError when it cannot be read).
std::string readFileText(const std::string& path);
/// A file named in a problem: a relative `path` is relative to `base_dir` (the problem file's
/// folder; empty: as given). Empty stays empty.
std::string relativeTo(const std::string& path, const std::string& base_dir);

}  // namespace sections
}  // namespace core
}  // namespace mooring_dynamics
