// Node layout along the line (paper section 3, eq. 14): uniform spacing within each piece of a
// segment; a zero-length interval (two nodes at the same arclength) at every segment junction and
// at every inline body, carrying the body's concentrated load and the jump of material.
#pragma once

#include <cstddef>
#include <vector>

#include "mooring_dynamics/core/model/model.hpp"

namespace mooring_dynamics {
namespace core {

struct MeshNode {
  double s = 0.0;         ///< unstretched arclength from the anchor [m]
  std::size_t material = 0;
  std::size_t segment = 0;
};

/// The half-grid interval between nodes a = index and b = index + 1.
struct MeshInterval {
  double h = 0.0;                   ///< unstretched length [m]; 0 at junctions
  std::size_t material = 0;         ///< material of the interval (h > 0)
  std::vector<std::size_t> bodies;  ///< inline bodies concentrated here (h == 0)
};

struct Mesh {
  std::vector<MeshNode> nodes;
  std::vector<MeshInterval> intervals;  ///< intervals[j] joins nodes[j] and nodes[j + 1]
  double minSpacing() const;            ///< smallest non-zero interval [m]
};

/// Uniform mesh of every segment piece with the segment's spacing (ceil(length / spacing) intervals).
Mesh buildMesh(const Problem& problem);

}  // namespace core
}  // namespace mooring_dynamics
