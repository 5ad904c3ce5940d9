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
  L.chord_len.assign(n > 0 ? n - 1 : 0, 0.0);
  L.chord_dir.assign(n > 0 ? n - 1 : 0, Vec3::Zero());
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

Constants Constants::of(const Setup& s, int n) {
  Constants c;
  const double rho = s.problem->environment.water_density;
  c.intervals.resize(n > 0 ? static_cast<std::size_t>(n) - 1 : 0);
  for (std::size_t j = 0; j < c.intervals.size(); ++j) {
    const MeshInterval& iv = s.mesh->intervals[j];
    if (!(iv.h > 0.0)) continue;
    Interval& ci = c.intervals[j];
    const Material& m = s.problem->materials[iv.material];
    ci.m = &m;
    ci.h = iv.h;
    ci.half_weight = 0.5 * iv.h * m.wet_weight;
    ci.linear = m.tension_strain.empty();
    ci.band = m.slackBand();
    ci.damper = kAxialDampingRatio * std::sqrt(std::max(m.EA, 0.0) * m.mass) * iv.h;
    ci.drag = -0.5 * rho * m.diameter * iv.h;
    ci.drag_rate = 0.5 * rho * m.diameter * iv.h;
  }
  // The seabed acts on each node over half of each adjacent interval, with the upper one's
  // material where both are cable.
  c.nodes.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    Node& cn = c.nodes[static_cast<std::size_t>(j)];
    for (int k : {j - 1, j}) {
      if (k < 0 || k + 1 >= n) continue;
      const Interval& ci = c.intervals[static_cast<std::size_t>(k)];
      if (ci.m) {
        cn.length += 0.5 * ci.h;
        cn.m = ci.m;
      }
    }
  }
  return c;
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
    L.chord_len[j] = len;
    if (len < kShortChord * iv.h) continue;
    L.chord_dir[j] = d / len;
    L.tangent[j] += L.chord_dir[j];
    L.tangent[j + 1] += L.chord_dir[j];
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
