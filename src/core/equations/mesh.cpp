#include "mooring_dynamics/core/equations/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mooring_dynamics {
namespace core {

double Mesh::minSpacing() const {
  double h = std::numeric_limits<double>::infinity();
  for (const auto& iv : intervals)
    if (iv.h > 0.0) h = std::min(h, iv.h);
  return h;
}

namespace {

/// Appends a zero-length junction interval carrying `bodies`, or merges them into the junction
/// that was just added.
void addJunction(Mesh& mesh, bool& last_was_junction, const std::vector<std::size_t>& bodies,
                 std::size_t material, std::size_t segment) {
  if (last_was_junction) {
    auto& b = mesh.intervals.back().bodies;
    b.insert(b.end(), bodies.begin(), bodies.end());
    mesh.nodes.back().material = material;
    mesh.nodes.back().segment = segment;
    return;
  }
  MeshInterval iv;
  iv.h = 0.0;
  iv.material = material;
  iv.bodies = bodies;
  mesh.intervals.push_back(iv);
  mesh.nodes.push_back({mesh.nodes.back().s, material, segment});
  last_was_junction = true;
}

void addPiece(Mesh& mesh, bool& last_was_junction, double length, double spacing, std::size_t material,
              std::size_t segment) {
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
  const double h = length / n;
  const double s0 = mesh.nodes.back().s;
  mesh.nodes.back().material = material;  // the piece's first node belongs to the piece
  mesh.nodes.back().segment = segment;
  for (int i = 1; i <= n; ++i) {
    MeshInterval iv;
    iv.h = h;
    iv.material = material;
    mesh.intervals.push_back(iv);
    mesh.nodes.push_back({i == n ? s0 + length : s0 + i * h, material, segment});
  }
  last_was_junction = false;
}

}  // namespace

Mesh buildMesh(const Problem& problem) {
  Mesh mesh;
  mesh.nodes.push_back({0.0, problem.segments.front().material, 0});
  bool last_was_junction = false;
  for (std::size_t si = 0; si < problem.segments.size(); ++si) {
    const Segment& seg = problem.segments[si];
    if (si > 0) addJunction(mesh, last_was_junction, {}, seg.material, si);
    // Body positions split the segment into pieces.
    std::vector<std::pair<double, std::size_t>> placed;
    for (const auto& bp : seg.bodies) placed.emplace_back(bp.at, bp.body);
    std::sort(placed.begin(), placed.end());
    double start = 0.0;
    std::size_t k = 0;
    while (k <= placed.size()) {
      const double stop = k < placed.size() ? placed[k].first : seg.length;
      if (stop - start > 1e-9 * seg.length) {
        addPiece(mesh, last_was_junction, stop - start, seg.spacing, seg.material, si);
        start = stop;
      }
      if (k == placed.size()) break;
      std::vector<std::size_t> here;
      while (k < placed.size() && placed[k].first - stop <= 1e-9 * seg.length) here.push_back(placed[k++].second);
      addJunction(mesh, last_was_junction, here, seg.material, si);
    }
  }
  return mesh;
}

}  // namespace core
}  // namespace mooring_dynamics
