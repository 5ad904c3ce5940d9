// The lumped-mass line of the fallback step: masses, tangents, stable sub-step (lumped_line.hpp).
#include "lumped_line.hpp"

namespace mooring_dynamics {
namespace core {
namespace lumped {

void lumpMasses(const Setup& s, Line& L) {
  const int n = static_cast<int>(s.mesh->nodes.size());
  L.n = n;
  L.x.assign(n, Vec3::Zero());
  L.v.assign(n, Vec3::Zero());
  L.f.assign(n, Vec3::Zero());
  L.drag_rate.assign(n, 0.0);
  L.mass.assign(n, 0.0);
  L.added.assign(n, 0.0);
  L.body_mass.assign(n, 0.0);
  L.tangent.assign(n, Vec3::Zero());
  L.ref.assign(n > 0 ? n - 1 : 0, 0.0);
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = s.mesh->intervals[static_cast<std::size_t>(j)];
    if (iv.h > 0.0) {
      const Material& m = s.problem->materials[iv.material];
      for (int k : {j, j + 1}) {
        L.mass[k] += 0.5 * iv.h * m.mass;
        L.added[k] += 0.5 * iv.h * m.added_mass;
      }
    } else {
      for (std::size_t b : iv.bodies) {
        const Body& body = s.problem->bodies[b];
        L.body_mass[j] += body.mass + body.added_mass;
      }
    }
  }
  if (const Body* b = s.end_body) L.body_mass[0] += b->mass + b->added_mass;
  if (const Body* b = s.top_body) L.body_mass[static_cast<std::size_t>(n) - 1] += b->mass + b->added_mass;
}

void setReferenceLengths(const Setup& s, const std::vector<Vec3>& tangent, Line& L) {
  for (int j = 0; j + 1 < L.n; ++j) {
    const MeshInterval& iv = s.mesh->intervals[static_cast<std::size_t>(j)];
    const std::size_t a = static_cast<std::size_t>(j);
    L.ref[a] = iv.h;
    if (iv.h > 0.0 && j != s.parted) L.ref[a] = iv.h * chordFactor(tangent[a], tangent[a + 1]);
  }
}

void updateTangents(const Setup& s, Line& L) {
  const int n = L.n;
  for (int j = 0; j < n; ++j) L.tangent[j].setZero();
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = s.mesh->intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == s.parted) continue;
    const Vec3 d = L.x[j + 1] - L.x[j];
    const double len = d.norm();
    if (len < kShortChord * iv.h) continue;
    L.tangent[j] += d / len;
    L.tangent[j + 1] += d / len;
  }
  for (int j = 0; j < n; ++j) {
    const double t = L.tangent[j].norm();
    if (t > 1e-9) L.tangent[j] /= t;
  }
}

double stableSubstep(const Setup& s, const Line& L) {
  const int n = L.n;
  double wmax = 0.0;
  for (int j = 0; j + 1 < n; ++j) {
    const MeshInterval& iv = s.mesh->intervals[static_cast<std::size_t>(j)];
    if (!(iv.h > 0.0) || j == s.parted) continue;
    const Material& m = s.problem->materials[iv.material];
    const double len = (L.x[j + 1] - L.x[j]).norm();
    const double eps = len / L.ref[j] - 1.0;
    // Stiffness of the chord k = EA_t / h (tangent slope, at least the slope at zero strain:
    // the line may be about to snap) between two masses m h / 2.
    const double slope = std::max(m.rawTensionSlope(std::max(eps, 0.0)), m.rawTensionSlope(0.0));
    const double k = slope / L.ref[j];
    const double mj = std::min(L.mass[j] + L.body_mass[j], L.mass[j + 1] + L.body_mass[j + 1]);
    wmax = std::max(wmax, std::sqrt(4.0 * k / std::max(mj, 1e-12)));
    wmax = std::max(wmax, std::sqrt(s.problem->environment.seabed.stiffness * iv.h / std::max(mj, 1e-12)));
  }
  return wmax > 0.0 ? kCourant * 2.0 / wmax : 1e-3;
}

}  // namespace lumped
}  // namespace core
}  // namespace mooring_dynamics
