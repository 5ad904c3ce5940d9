// What sweep_io.cpp and sweep_manifest.cpp share: the number format of the files they write and
// the reader of statistics.design_check. Private to src/core/io.
#pragma once

#include <cstdio>
#include <string>

#include "mooring_dynamics/core/io/sweep_io.hpp"
#include "mooring_dynamics/core/io/yaml_reader.hpp"

namespace mooring_dynamics {
namespace core {
namespace sweep_detail {

using namespace yaml;

/// %.12g: twelve significant digits, as the sweep's files write their numbers.
inline std::string fmt12(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

/// statistics.design_check: {consequence_class: 1 | 2, als: [labels]} (the labels are checked
/// against the variations once they are read).
inline void readDesignCheck(const Item& it, SweepSpec& spec) {
  const Map m(it, {"consequence_class", "als"});
  const Item ci = m.required("consequence_class", "1 or 2 (DNV-OS-E301)");
  const long long c = readInteger(ci);
  if (c != 1 && c != 2) ci.fail("must be 1 or 2 (DNV-OS-E301's consequence classes)");
  spec.design_class = static_cast<int>(c);
  spec.als_labels.clear();
  if (m.has("als"))
    for (const Item& li : listItems(m.at("als"))) spec.als_labels.push_back(readString(li));
}

}  // namespace sweep_detail
}  // namespace core
}  // namespace mooring_dynamics
