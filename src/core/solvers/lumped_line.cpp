// The lumped-mass line of the fallback step: masses, tangents, stable sub-step, and the
// sub-steps' passes over component arrays (lumped_line.hpp).
//
// The passes (Substeps) are hand-arranged for the compiler's vectorizer, which whole runs show
// pays: the fallback's sub-steps were a third of a design storm's run (the spread mooring's lee
// lines lie slack on the seabed in the fallback for most of their steps) and a quarter of the
// Hs 4 storm bench's; with the passes, 150 s of config/spread_mooring_storm.yaml runs 1.35-1.53
// times faster, config/heaved_slack.yaml 4.3 times, the Hs 4 bench 1.25 times, with the same
// results to the bit (docs/performance.md, "Storms").
// Each loop runs over plain arrays, with selects in place of branches; compiled for the
// baseline instruction set, AVX2 and AVX-512 (function multiversioning, as the block LU's
// kernels), all with the same operations in the same order and no fused multiply-add, so the
// results do not depend on the machine and equal those of a node-by-node loop. This file is
// compiled without errno from sqrt and with floating-point operations that may be evaluated
// before the branch that uses them (-fno-math-errno -fno-trapping-math, CMakeLists.txt), which
// vectorizing the square roots and the selects needs; neither changes a result.
#include "lumped_line.hpp"

#include <cstdlib>
#include <limits>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_LUMPED_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MD_LUMPED_CLONES
#endif

// No contraction of a * b + c into a fused multiply-add: the AVX-512 version has the instruction
// and the others do not, and one rounding instead of two would make the results depend on the
// machine.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

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

Substeps Substeps::of(const Setup& s, const Constants& c, const Line& L, const std::vector<NodeWater>& water) {
  Substeps k;
  const int n = L.n;
  const std::size_t nn = static_cast<std::size_t>(n), ni = nn + 1;
  k.n = n;
  for (int i = 0; i < 3; ++i) {
    k.x[i].resize(nn);
    k.v[i].resize(nn);
    k.f[i].assign(nn, 0.0);
    k.t[i].assign(nn, 0.0);
    k.dir[i].assign(ni, 0.0);
    k.along[i].assign(ni, 0.0);
    k.Tt[i].assign(ni, 0.0);
    k.hd[i].assign(ni, 0.0);
    k.s0[i].assign(ni, 0.0);
    k.s1[i].assign(ni, 0.0);
    for (int j = 0; j < n; ++j) {
      k.x[i][j] = L.x[j][i];
      k.v[i][j] = L.v[j][i];
    }
  }
  k.dr.assign(nn, 0.0);
  k.ms.assign(nn, 0.0);
  k.ma.assign(nn, 0.0);
  k.free.assign(nn, 1.0);
  k.ref.assign(ni, 1.0);  // (1 where the interval carries no force: see intervalPass)
  for (auto* a : {&k.len, &k.chord_rate, &k.eps, &k.Te, &k.damper, &k.hw, &k.q, &k.short_h, &k.EA, &k.band, &k.damper_c,
                  &k.drag, &k.drag_rate, &k.cdn, &k.pcdt})
    a->assign(ni, 0.0);
  k.has_dir.assign(ni, 0.0);
  k.force.assign(ni, 0.0);
  k.comp.assign(ni, 1.0);
  const Environment& env = s.problem->environment;
  k.flat_seabed = env.flatSeabed();
  k.bed_length.assign(nn, 0.0);
  k.bed_onset.assign(nn, 0.0);
  k.bed_acts.assign(nn, 0.0);
  for (int j = 0; j < n; ++j) {
    const Constants::Node& cn = c.nodes[static_cast<std::size_t>(j)];
    if (!cn.m) continue;
    k.bed_length[j] = cn.length;
    k.bed_onset[j] = eq2d::contactOnset(env, *cn.m);
    k.bed_acts[j] = 1.0;
  }
  for (int j = 0; j + 1 < n; ++j) {
    const Constants::Interval& ci = c.intervals[static_cast<std::size_t>(j)];
    if (!ci.m) continue;
    const std::size_t a = static_cast<std::size_t>(j) + 1;
    k.hw[a] = ci.half_weight;
    if (j == s.parted) continue;
    k.force[a] = 1.0;
    k.ref[a] = L.ref[static_cast<std::size_t>(j)];
    k.short_h[a] = kShortChord * ci.h;
    k.EA[a] = ci.m->EA;
    k.band[a] = ci.band;
    k.damper_c[a] = ci.damper;
    k.drag[a] = ci.drag;
    k.drag_rate[a] = ci.drag_rate;
    k.cdn[a] = ci.m->cdn;
    k.pcdt[a] = eq2d::kPi * ci.m->cdt;
    k.comp[a] = ci.m->compression ? 1.0 : 0.0;
    k.all_linear = k.all_linear && ci.linear;
    for (int i = 0; i < 3; ++i) {
      k.s0[i][a] = water[j].w0[i] + water[j + 1].w0[i];
      k.s1[i][a] = water[j].w1[i] + water[j + 1].w1[i];
    }
  }
  return k;
}

namespace {

// The passes' loops, on raw pointers (restrict: the arrays never overlap).
using Ptr = double* __restrict;
using CPtr = const double* __restrict;
/// Flags as doubles, 1 or 0 (a mask of the same width as the values vectorizes).
using Flags = const double* __restrict;

/// Chords of intervals a = 1 .. n - 1 (interval a - 1) and the nodes' unit tangents: the mean
/// of the adjacent chords' directions, as updateTangents; the direction of each interval's
/// axial force (a0, a1, a2).
MD_LUMPED_CLONES void chordPass(int n, CPtr x0, CPtr x1, CPtr x2, Flags force, CPtr short_h, Ptr len, Ptr d0, Ptr d1,
                                Ptr d2, Ptr has_dir, Ptr t0, Ptr t1, Ptr t2, Ptr a0, Ptr a1, Ptr a2) {
  for (int a = 1; a < n; ++a) {
    const double dx = x0[a] - x0[a - 1], dy = x1[a] - x1[a - 1], dz = x2[a] - x2[a - 1];
    const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double ux = dx / l, uy = dy / l, uz = dz / l;
    const bool valid = (force[a] != 0.0) & !(l < short_h[a]);
    len[a] = l;
    d0[a] = valid ? ux : 0.0;
    d1[a] = valid ? uy : 0.0;
    d2[a] = valid ? uz : 0.0;
    has_dir[a] = l > short_h[a] ? 1.0 : 0.0;
  }
  for (int j = 0; j < n; ++j) {
    const double tx = (0.0 + d0[j]) + d0[j + 1], ty = (0.0 + d1[j]) + d1[j + 1], tz = (0.0 + d2[j]) + d2[j + 1];
    const double tn = std::sqrt(tx * tx + ty * ty + tz * tz);
    const double ux = tx / tn, uy = ty / tn, uz = tz / tn;
    const bool unit = tn > 1e-9;
    t0[j] = unit ? ux : tx;
    t1[j] = unit ? uy : ty;
    t2[j] = unit ? uz : tz;
  }
  // The direction each interval's force acts along: its chord's, or where the chord is too
  // short to have one, its lower node's tangent.
  for (int a = 1; a < n; ++a) {
    const bool own = has_dir[a] != 0.0;
    a0[a] = own ? d0[a] : t0[a - 1];
    a1[a] = own ? d1[a] : t1[a - 1];
    a2[a] = own ? d2[a] : t2[a - 1];
  }
}

/// Strain and elastic tension of linear laws (EA eps, slackRamp without compression) and their
/// constant damper.
MD_LUMPED_CLONES void linearAxialPass(int n, CPtr len, CPtr ref, CPtr EA, CPtr band, CPtr damper_c, Flags comp,
                                      Ptr eps, Ptr Te, Ptr damper) {
  for (int a = 1; a < n; ++a) {
    const double e = len[a] / ref[a] - 1.0;
    const double T = EA[a] * e;
    const double b = band[a];
    const double u = T + 0.5 * b;
    const double r = u * u / (2.0 * b);
    const double inner = T <= -0.5 * b ? 0.0 : r;
    const double ramp = T >= 0.5 * b ? T : inner;
    eps[a] = e;
    Te[a] = comp[a] != 0.0 ? T : ramp;
    damper[a] = damper_c[a];
  }
}

/// Axial force T t of each interval with the damper on the strain rate along `along` (c0, c1,
/// c2; no damper where the chord has no direction of its own). An interval without force (a
/// junction, a parted interval) has all its constants 0 and its reference length 1
/// (Substeps::of): its values come out +-0, which leave the nodes' sums (nodePass, from +0) bit
/// for bit as they would be without it, so no select is needed (here and in dragPass).
MD_LUMPED_CLONES void axialForcePass(int n, CPtr v0, CPtr v1, CPtr v2, CPtr c0, CPtr c1, CPtr c2, Flags has_dir,
                                     CPtr ref, CPtr Te, CPtr damper, Flags comp, Ptr chord_rate, Ptr Tt0, Ptr Tt1,
                                     Ptr Tt2) {
  for (int a = 1; a < n; ++a) {
    const double tx = c0[a], ty = c1[a], tz = c2[a];
    const double dvx = v0[a] - v0[a - 1], dvy = v1[a] - v1[a - 1], dvz = v2[a] - v2[a - 1];
    const double rate = (tx * dvx + ty * dvy + tz * dvz) / ref[a];
    chord_rate[a] = rate;  // (stored whatever has_dir: the compiler then loads ref[a] every time)
    const double eps_rate = has_dir[a] != 0.0 ? rate : 0.0;
    const double T0 = Te[a] + damper[a] * eps_rate;
    // A line without compression neither pushes nor pulls back through the damper below zero.
    const double T0p = T0 < 0.0 ? 0.0 : T0;
    const double Ts = Te[a] > 0.0 ? T0p : 0.0;
    const double T = comp[a] != 0.0 ? T0 : Ts;
    Tt0[a] = T * tx;
    Tt1[a] = T * ty;
    Tt2[a] = T * tz;
  }
}

/// Drag on each interval's chord at its mid-point velocity relative to the water (wx, wy, wz:
/// the sums of its nodes' water velocities at the step's start s0 and end s1, linear in time
/// fraction w), normal and tangential, times sqrt(1 + eps) as in the box rows: half of it to
/// each node (hd), and its rate of change with the nodes' speed (quadratic drag: twice the
/// force per unit speed), a quarter to each node (q): the update treats the drag implicitly.
MD_LUMPED_CLONES void dragPass(int n, double w, CPtr v0, CPtr v1, CPtr v2, CPtr c0, CPtr c1, CPtr c2, CPtr s00,
                               CPtr s01, CPtr s02, CPtr s10, CPtr s11, CPtr s12, CPtr eps, CPtr drag,
                               CPtr drag_rate, CPtr cdn, CPtr pcdt, Ptr hd0, Ptr hd1, Ptr hd2, Ptr q) {
  const double floor2 = eq3d::kDragSpeedFloor * eq3d::kDragSpeedFloor;
  const double omw = 1.0 - w;
  for (int a = 1; a < n; ++a) {
    const double tx = c0[a], ty = c1[a], tz = c2[a];
    const double wx = 0.5 * (omw * s00[a] + w * s10[a]);
    const double wy = 0.5 * (omw * s01[a] + w * s11[a]);
    const double wz = 0.5 * (omw * s02[a] + w * s12[a]);
    const double rx = 0.5 * (v0[a - 1] + v0[a]) - wx;
    const double ry = 0.5 * (v1[a - 1] + v1[a]) - wy;
    const double rz = 0.5 * (v2[a - 1] + v2[a]) - wz;
    const double vt = tx * rx + ty * ry + tz * rz;
    const double nx = rx - vt * tx, ny = ry - vt * ty, nz = rz - vt * tz;
    const double e1 = 1.0 + eps[a];
    const double stretch = std::sqrt(e1 < 0.0 ? 0.0 : e1);
    const double vnn = std::sqrt((nx * nx + ny * ny + nz * nz) + floor2);
    const double cn = cdn[a] * vnn;
    const double ct = pcdt[a] * std::abs(vt);
    const double c2t = ct * vt;
    const double sd = drag[a] * stretch;
    const double cm = cn < ct ? ct : cn;
    hd0[a] = 0.5 * (sd * (cn * nx + c2t * tx));
    hd1[a] = 0.5 * (sd * (cn * ny + c2t * ty));
    hd2[a] = 0.5 * (sd * (cn * nz + c2t * tz));
    q[a] = 0.25 * (drag_rate[a] * stretch * 2.0 * cm);
  }
}

/// Each node's force from its lower interval (at j, as its upper node) and its upper one (at
/// j + 1, as its lower node), in the order of a loop over the intervals; weights along -z.
MD_LUMPED_CLONES void nodePass(int n, CPtr hw, CPtr Tt0, CPtr Tt1, CPtr Tt2, CPtr hd0, CPtr hd1, CPtr hd2, CPtr q,
                               Ptr f0, Ptr f1, Ptr f2, Ptr dr) {
  for (int j = 0; j < n; ++j) {
    f0[j] = (((0.0 - Tt0[j]) + hd0[j]) + Tt0[j + 1]) + hd0[j + 1];
    f1[j] = (((0.0 - Tt1[j]) + hd1[j]) + Tt1[j + 1]) + hd1[j + 1];
    f2[j] = (((((0.0 - hw[j]) - Tt2[j]) + hd2[j]) - hw[j + 1]) + Tt2[j + 1]) + hd2[j + 1];
    dr[j] = (0.0 + q[j]) + q[j + 1];
  }
}

/// Symplectic Euler on the free nodes: M = ms I + ma (I - t t^T) (along t ms, across ms + ma),
/// with the drag linearised about the current velocity and taken at the end of the sub-step
/// (backward Euler in the drag alone: h cd added to both), so the update is stable whatever the
/// relative speed.
MD_LUMPED_CLONES void movePass(int n, double h, CPtr ms, CPtr ma, CPtr dr, Flags free, CPtr t0, CPtr t1, CPtr t2,
                               CPtr f0, CPtr f1, CPtr f2, Ptr v0, Ptr v1, Ptr v2, Ptr x0, Ptr x1, Ptr x2) {
  for (int j = 0; j < n; ++j) {
    const double tf = t0[j] * f0[j] + t1[j] * f1[j] + t2[j] * f2[j];
    const double ftx = tf * t0[j], fty = tf * t1[j], ftz = tf * t2[j];
    const double da = ms[j] + h * dr[j], dc = ms[j] + ma[j] + h * dr[j];
    const double ax = ftx / da + (f0[j] - ftx) / dc;
    const double ay = fty / da + (f1[j] - fty) / dc;
    const double az = ftz / da + (f2[j] - ftz) / dc;
    const double vx = v0[j] + h * ax, vy = v1[j] + h * ay, vz = v2[j] + h * az;
    const bool on = free[j] != 0.0;
    v0[j] = on ? vx : v0[j];
    v1[j] = on ? vy : v1[j];
    v2[j] = on ? vz : v2[j];
    x0[j] = on ? x0[j] + h * vx : x0[j];
    x1[j] = on ? x1[j] + h * vy : x1[j];
    x2[j] = on ? x2[j] + h * vz : x2[j];
  }
}

/// The reaction of a flat seabed at z_bed [N/m, +z] on each node's tributary length: eq. 35's
/// spring on the penetration p = z_bed - z with its onset smoothed over delta (eq2d::seabedSpring),
/// less eq. 36's dashpot on v_z ramped in over the onset (eq2d::contactFraction) while the
/// spring pushes; +0 where the node is not below z_bed (as the solver's rows give).
MD_LUMPED_CLONES void seabedPass(int n, double z_bed, double k, double c, CPtr x2, CPtr v2, CPtr length, CPtr onset,
                                 Flags acts, Ptr f2) {
  for (int j = 0; j < n; ++j) {
    const double z = x2[j], delta = onset[j];
    const double p = z_bed - z;
    const bool onset_part = delta > 0.0 && p < delta;
    const double ramp = k * p * p / (2.0 * delta), linear = k * (p - 0.5 * delta);
    const double spring = onset_part ? ramp : linear;
    const double frac_ramp = p / delta;
    const double fraction = onset_part ? frac_ramp : 1.0;
    const double damped = spring - c * fraction * v2[j];
    const double reaction = spring > 0.0 && c != 0.0 ? damped : spring;
    const double Fbot = z < z_bed ? reaction : 0.0;
    const double sum = f2[j] + length[j] * Fbot;
    f2[j] = acts[j] != 0.0 ? sum : f2[j];
  }
}

/// How many of a[0 .. n) are not finite (NaN compares false).
MD_LUMPED_CLONES long nonFinite(int n, CPtr a) {
  constexpr double big = std::numeric_limits<double>::max();
  long count = 0;
  for (int j = 0; j < n; ++j) count += std::abs(a[j]) <= big ? 0 : 1;
  return count;
}

}  // namespace

void Substeps::flatSeabed(const Environment& env) {
  seabedPass(n, -env.depth, env.seabed.stiffness, env.seabed.damping, x[2].data(), v[2].data(), bed_length.data(),
             bed_onset.data(), bed_acts.data(), f[2].data());
}

void Substeps::chords() {
  chordPass(n, x[0].data(), x[1].data(), x[2].data(), force.data(), short_h.data(), len.data(),
            dir[0].data(), dir[1].data(), dir[2].data(), has_dir.data(), t[0].data(), t[1].data(), t[2].data(),
            along[0].data(), along[1].data(), along[2].data());
}

void Substeps::axial(const Constants& c) {
  if (all_linear) {
    linearAxialPass(n, len.data(), ref.data(), EA.data(), band.data(), damper_c.data(), comp.data(), eps.data(),
                    Te.data(), damper.data());
    return;
  }
  for (int a = 1; a < n; ++a) {
    if (force[a] == 0.0) continue;
    const Constants::Interval& ci = c.intervals[static_cast<std::size_t>(a) - 1];
    const Material& m = *ci.m;
    eps[a] = len[a] / ref[a] - 1.0;
    damper[a] = ci.linear ? ci.damper
                          : kAxialDampingRatio * std::sqrt(std::max(m.rawTensionSlope(std::max(eps[a], 0.0)), 0.0) * m.mass) * ci.h;
    Te[a] = ci.tension(eps[a]);
  }
}

void Substeps::intervalForces(double w) {
  axialForcePass(n, v[0].data(), v[1].data(), v[2].data(), along[0].data(), along[1].data(), along[2].data(),
                 has_dir.data(), ref.data(), Te.data(), damper.data(), comp.data(), chord_rate.data(), Tt[0].data(),
                 Tt[1].data(), Tt[2].data());
  dragPass(n, w, v[0].data(), v[1].data(), v[2].data(), along[0].data(), along[1].data(), along[2].data(),
           s0[0].data(), s0[1].data(), s0[2].data(), s1[0].data(), s1[1].data(), s1[2].data(), eps.data(), drag.data(),
           drag_rate.data(), cdn.data(), pcdt.data(), hd[0].data(), hd[1].data(), hd[2].data(), q.data());
}

void Substeps::nodeSums() {
  nodePass(n, hw.data(), Tt[0].data(), Tt[1].data(), Tt[2].data(), hd[0].data(), hd[1].data(), hd[2].data(),
           q.data(), f[0].data(), f[1].data(), f[2].data(), dr.data());
}

void Substeps::move(double h) {
  movePass(n, h, ms.data(), ma.data(), dr.data(), free.data(), t[0].data(), t[1].data(), t[2].data(), f[0].data(),
           f[1].data(), f[2].data(), v[0].data(), v[1].data(), v[2].data(), x[0].data(), x[1].data(), x[2].data());
}

int Substeps::firstNonFinite() const {
  long bad = 0;
  for (int i = 0; i < 3; ++i) bad += nonFinite(n, x[i].data()) + nonFinite(n, v[i].data());
  if (bad == 0) return -1;
  for (int j = 0; j < n; ++j)
    if (!pos(j).allFinite() || !vel(j).allFinite()) return j;
  return -1;
}

}  // namespace lumped
}  // namespace core
}  // namespace mooring_dynamics
