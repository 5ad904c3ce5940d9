// WaveVelocityCache (include/mooring_dynamics/core/numerics/wave_velocity_cache.hpp): the wave velocity at the nodes of
// the dynamic solver, the sum over a realized sea's components without transcendental functions
// per component, node and evaluation. See docs/method.md, "Wave kinematics".
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "mooring_dynamics/core/numerics/fork_join.hpp"
#include "mooring_dynamics/core/model/scalar.hpp"
#include "mooring_dynamics/core/numerics/wave_velocity_cache.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

// The component sums are compiled for the baseline instruction set, with AVX2 and with
// AVX-512 (function multiversioning, as the elimination kernels of block_lu.hpp); all do the
// same operations in the same order (eight components per lane group in every version, which
// the narrower instruction sets split), so the results do not depend on the machine.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(MD_NO_MULTIVERSION)
#define MD_WAVE_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MD_WAVE_SIMD_CLONES
#endif

#if defined(__GNUC__) || defined(__clang__)
typedef double Lane __attribute__((vector_size(64), aligned(8), may_alias));  // eight components
#define MD_LOAD(p) (*reinterpret_cast<const Lane*>(p))
inline double total(const Lane& v) { return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])); }
constexpr std::size_t kLanes = 8;
#define MD_WAVE_INLINE inline __attribute__((always_inline))
#else
#define MD_WAVE_INLINE inline
typedef double Lane;
#define MD_LOAD(p) (*(p))
inline double total(const Lane& v) { return v; }
constexpr std::size_t kLanes = 1;
#endif

// No contraction of a * b + c into a fused multiply-add in the sums below: AVX-512 has the
// instruction and the other versions do not, and one rounding instead of two would make the
// sums depend on the machine.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

/// Even and odd parts of the Taylor series of e^{u} to the power u^Order (Order odd):
/// cos, sin of u are (even(-u^2), odd(-u^2)) and e^{+-u} = even(u^2) +- odd(u^2). The first
/// term left out is below u^(Order+1) / (Order+1)!: for Order 11 and |u| <= kTaylorRadius = 0.2,
/// 9e-18; for Order 7 and |u| <= kShortTaylorRadius = 0.02, 6e-19 (both under the rounding of
/// the unit first term, 1.1e-16).
template <int Order, class T>
inline void taylorParts(const T& u, const T& u2, T& even, T& odd) {
  static_assert(Order == 7 || Order == 11, "Taylor order 7 or 11");
  if constexpr (Order == 11) {
    even = 1.0 + u2 * (1.0 / 2 + u2 * (1.0 / 24 + u2 * (1.0 / 720 + u2 * (1.0 / 40320 + u2 * (1.0 / 3628800)))));
    odd = u * (1.0 + u2 * (1.0 / 6 + u2 * (1.0 / 120 + u2 * (1.0 / 5040 + u2 * (1.0 / 362880 + u2 * (1.0 / 39916800))))));
  } else {
    even = 1.0 + u2 * (1.0 / 2 + u2 * (1.0 / 24 + u2 * (1.0 / 720)));
    odd = u * (1.0 + u2 * (1.0 / 6 + u2 * (1.0 / 120 + u2 * (1.0 / 5040))));
  }
}

/// One lane group's terms of the twelve sums (WaveVelocityCache's order) from its depth factors
/// ch, sh and the cos, sin of its phases at the point; c: the group's constants at the lanes.
/// vx ~ ch cos(th), vz ~ sh sin(th); d/dx turns cos into -sin (times kx), d/dz ch into sh.
MD_WAVE_INLINE void accumulate(const double* c, const Lane& ch, const Lane& sh, const Lane& cth, const Lane& sth,
                               Lane* sx, Lane* sz) {
  using C = WaveVelocityCache;
  constexpr std::size_t G = C::kGroup;
  const Lane p1 = ch * cth, p2 = ch * sth, p3 = sh * cth, p4 = sh * sth;
  const double* cx = c + C::kRowCx * G;
  const double* cz = c + C::kRowCz * G;
  sx[0] += MD_LOAD(cx + 0 * G) * p1;
  sx[1] -= MD_LOAD(cx + 1 * G) * p2;
  sx[2] += MD_LOAD(cx + 2 * G) * p3;
  sx[3] -= MD_LOAD(cx + 3 * G) * p1;
  sx[4] -= MD_LOAD(cx + 4 * G) * p4;
  sx[5] += MD_LOAD(cx + 5 * G) * p1;
  sz[0] += MD_LOAD(cz + 0 * G) * p4;
  sz[1] += MD_LOAD(cz + 1 * G) * p3;
  sz[2] += MD_LOAD(cz + 2 * G) * p2;
  sz[3] -= MD_LOAD(cz + 3 * G) * p4;
  sz[4] += MD_LOAD(cz + 4 * G) * p1;
  sz[5] += MD_LOAD(cz + 5 * G) * p4;
}

/// The twelve sums (WaveVelocityCache's order) over the first `groups` lane groups of kLanes
/// components, for a point displaced by (dx, dz) from its reference, with Taylor series of order
/// Order. `coef` holds the components' constants and `state` the point's reference values,
/// interleaved by lane group (WaveVelocityCache::coef_, state_: two streams through memory,
/// instead of one per quantity). The reference values of those groups (cos B, sin B, E+, E-) are
/// overwritten with those at the displaced point: the point's reference follows it.
template <int Order>
MD_WAVE_SIMD_CLONES void componentSums(const double* __restrict coef, double* __restrict state, std::size_t groups,
                                       double dx, double dz, double* out) {
  using C = WaveVelocityCache;
  constexpr std::size_t G = C::kGroup;  // one row of a group
  Lane sx[6], sz[6], g3 = MD_LOAD(coef) * 0.0;
  for (int q = 0; q < 6; ++q) sx[q] = sz[q] = g3;
  for (std::size_t i = 0; i < groups * G; i += kLanes) {
    // Lanes [i, i + kLanes) of group i / kGroup: rows of kGroup components.
    const double* c = coef + i / C::kGroup * C::kCoefGroup + i % C::kGroup;
    double* st = state + i / C::kGroup * C::kStateGroup + i % C::kGroup;
    // e^{+-k dz}: the exponentials E+- carried from the reference elevation.
    const Lane u = MD_LOAD(c + C::kRowK * G) * dz;
    Lane ev, od;
    taylorParts<Order>(u, u * u, ev, od);
    const Lane Ep = MD_LOAD(st + C::kRowEp * G) * (ev + od);
    const Lane Em = MD_LOAD(st + C::kRowEm * G) * (ev - od);
    const Lane ch = Ep + Em, sh = Ep - Em;
    g3 += MD_LOAD(c + C::kRowG3 * G) * ch;  // the bound on the third derivatives at the new reference
    // cos, sin of kx dx: the phase B carried from the reference abscissa, then A added.
    const Lane d = MD_LOAD(c + C::kRowKx * G) * dx;
    Lane cd, sd;
    taylorParts<Order>(d, -(d * d), cd, sd);
    const Lane cb = MD_LOAD(st + C::kRowCosB * G), sb = MD_LOAD(st + C::kRowSinB * G);
    const Lane cbx = cb * cd - sb * sd, sbx = sb * cd + cb * sd;
    *reinterpret_cast<Lane*>(st + C::kRowCosB * G) = cbx;
    *reinterpret_cast<Lane*>(st + C::kRowSinB * G) = sbx;
    *reinterpret_cast<Lane*>(st + C::kRowEp * G) = Ep;
    *reinterpret_cast<Lane*>(st + C::kRowEm * G) = Em;
    const Lane ca = MD_LOAD(c + C::kRowCosA * G), sa = MD_LOAD(c + C::kRowSinA * G);
    const Lane cth = cbx * ca - sbx * sa, sth = sbx * ca + cbx * sa;
    accumulate(c, ch, sh, cth, sth, sx, sz);
  }
  for (int q = 0; q < 6; ++q) {
    out[q] = total(sx[q]);
    out[6 + q] = total(sz[q]);
  }
  out[12] = total(g3);
}

/// The twelve sums at the point's reference itself (no displacement: no Taylor series, the
/// reference values unchanged) at the current time: what componentSums gives for dx = dz = 0 at
/// under half the operations per component.
MD_WAVE_SIMD_CLONES void referenceSums(const double* __restrict coef, const double* __restrict state, std::size_t groups,
                                       double* out) {
  using C = WaveVelocityCache;
  constexpr std::size_t G = C::kGroup;
  Lane sx[6], sz[6];
  for (int q = 0; q < 6; ++q) sx[q] = sz[q] = MD_LOAD(coef) * 0.0;
  for (std::size_t i = 0; i < groups * G; i += kLanes) {
    const double* c = coef + i / C::kGroup * C::kCoefGroup + i % C::kGroup;
    const double* st = state + i / C::kGroup * C::kStateGroup + i % C::kGroup;
    const Lane Ep = MD_LOAD(st + C::kRowEp * G), Em = MD_LOAD(st + C::kRowEm * G);
    const Lane ch = Ep + Em, sh = Ep - Em;
    const Lane cb = MD_LOAD(st + C::kRowCosB * G), sb = MD_LOAD(st + C::kRowSinB * G);
    const Lane ca = MD_LOAD(c + C::kRowCosA * G), sa = MD_LOAD(c + C::kRowSinA * G);
    const Lane cth = cb * ca - sb * sa, sth = sb * ca + cb * sa;
    accumulate(c, ch, sh, cth, sth, sx, sz);
  }
  for (int q = 0; q < 6; ++q) {
    out[q] = total(sx[q]);
    out[6 + q] = total(sz[q]);
  }
}

#undef MD_LOAD
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif

}  // namespace

// One component's constants before sorting: the depth factors as A (E+ +- E-) with
// E+- = e^{+-k (z + o+-)}: deep water (1 - e^{-2kh})^{-1} (e^{kz} +- e^{-k(z + 2h)}), else
// (2 sinh kh)^{-1} (e^{k(z + h)} +- e^{-k(z + h)}); every exponent stays in range.
struct WaveVelocityCache::Component {
  double k, kx, omega, phase, aw, cd, A, op, om, z_skip, coth;
};

WaveVelocityCache::WaveVelocityCache(const WaveField* field, std::size_t points, bool horizontal_plane,
                                     bool across_times)
    : field_(field), plane_(horizontal_plane), across_times_(across_times) {
  if (empty()) return;
  const WaveField& f = *field_;
  nc_ = f.components_.size();
  if (plane_) {
    // Points in the horizontal plane: the phases depend on x and y through the distance along
    // the one direction of travel, xi = x cos(theta) + y sin(theta) (the tables below in xi).
    direction_ = f.components_.front().direction;
    for (const WaveComponent& c : f.components_)
      if (c.direction != direction_)
        throw std::invalid_argument("WaveVelocityCache: points off the x-z plane need one direction of travel");
    cos_dir_ = std::cos(direction_);
    sin_dir_ = std::sin(direction_);
  }
  np_ = (nc_ + kGroup - 1) / kGroup * kGroup;
  const std::vector<Component> comps = sortedComponents();
  // Bound on the velocity's third derivatives (linearRadius).
  double g3 = 0.0;
  for (const Component& c : comps) g3 += std::abs(c.aw) * c.k * c.k * c.k * c.coth;
  const double third = 2.0 * std::sqrt(2.0) * g3 / 6.0;
  lin_radius_ = third > 0.0 ? std::cbrt(kLinearTolerance / third) : 0.0;
  fillTables(comps);
  allocatePoints(points);
}

std::vector<WaveVelocityCache::Component> WaveVelocityCache::sortedComponents() const {
  const WaveField& f = *field_;
  const double h = f.depth_;
  std::vector<Component> comps;
  for (std::size_t i = 0; i < nc_; ++i) {
    const WaveComponent& c = f.components_[i];
    const WaveField::Kinematics& q = f.kin_[i];
    Component m{};
    m.k = c.k;
    // Along x (the x-z plane: the velocity's x component) or along the direction of travel (the
    // horizontal velocity, split into x and y by velocity3).
    m.kx = plane_ ? c.k : c.k * q.cd;
    m.omega = c.omega;
    m.phase = c.phase;
    m.aw = q.aw;
    m.cd = plane_ ? 1.0 : q.cd;
    if (q.deep) {
      m.A = 1.0 / q.den;
      m.op = 0.0;
      m.om = 2.0 * h;
      m.z_skip = q.z_skip;
      m.coth = (1.0 + q.e2kh) / q.den;
    } else if (q.den > 0.0) {
      m.A = 0.5 / q.den;
      m.op = m.om = h;
      m.z_skip = -std::numeric_limits<double>::infinity();
      m.coth = 1.0 / std::tanh(c.k * h);
    } else {  // k h = 0: no velocity (a omega = 0)
      m.A = 0.0;
      m.op = m.om = h;
      m.z_skip = -std::numeric_limits<double>::infinity();
      m.coth = 0.0;
    }
    comps.push_back(m);
  }
  std::stable_sort(comps.begin(), comps.end(),
                   [](const Component& a, const Component& b) { return a.z_skip < b.z_skip; });
  return comps;
}

void WaveVelocityCache::fillTables(const std::vector<Component>& comps) {
  // Structure of arrays, padded with zero terms (skipped by no point: z_skip = +inf).
  for (auto* v : {&k_, &kx_, &op_, &om_, &omega_, &phase_}) v->assign(np_, 0.0);
  z_skip_.assign(np_, std::numeric_limits<double>::infinity());
  k_upto_.assign(np_, 0.0);
  kx_upto_.assign(np_, 0.0);
  // The kernel's constants, interleaved by lane group (kCoefGroup per group; cos A = 1 until
  // setTime), a cache line of slack in front for the alignment of coefData().
  coef_.assign(np_ / kGroup * kCoefGroup + kAlignSlack, 0.0);
  double* const coef = coefData();
  for (std::size_t i = 0; i < np_; ++i) coef[coefIndex(i, kRowCosA)] = 1.0;
  for (std::size_t i = 0; i < nc_; ++i) {
    const Component& c = comps[i];
    k_[i] = c.k;
    kx_[i] = c.kx;
    op_[i] = c.op;
    om_[i] = c.om;
    omega_[i] = c.omega;
    phase_[i] = c.phase;
    z_skip_[i] = c.z_skip;
    kx_max_ = std::max(kx_max_, std::abs(c.kx));
    k_max_ = std::max(k_max_, c.k);
    kx_upto_[i] = kx_max_;
    k_upto_[i] = k_max_;
    coef[coefIndex(i, kRowG3)] = c.A * std::abs(c.aw) * c.k * c.k * c.k;
    coef[coefIndex(i, kRowK)] = c.k;
    coef[coefIndex(i, kRowKx)] = c.kx;
    const double ax = c.A * c.aw * c.cd, az = c.A * c.aw;
    const double pw[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};  // powers of kx, k
    for (int q = 0; q < 6; ++q) {
      const double f_q = std::pow(c.kx, pw[q][0]) * std::pow(c.k, pw[q][1]);
      coef[coefIndex(i, kRowCx + q)] = ax * f_q;
      coef[coefIndex(i, kRowCz + q)] = az * f_q;
    }
  }
  for (std::size_t i = nc_; i < np_; ++i) {  // the padding's prefixes: those of all components
    kx_upto_[i] = kx_max_;
    k_upto_[i] = k_max_;
  }
}

void WaveVelocityCache::allocatePoints(std::size_t points) {
  exact_.assign(points, Exact{});
  x_ref_.assign(points, std::numeric_limits<double>::quiet_NaN());
  z_ref_.assign(points, std::numeric_limits<double>::quiet_NaN());
  valid_.assign(points, 0);
  moves_.assign(points, 0);
  state_.assign(points * (np_ / kGroup * kStateGroup) + kAlignSlack, 0.0);
}

void WaveVelocityCache::setTime(double t) {
  if (empty() || (have_time_ && t == t_)) return;
  t_ = t;
  have_time_ = true;
  ramp_ = field_->rampFactor(t);
  double* const coef = coefData();
  for (std::size_t i = 0; i < nc_; ++i) {
    const double a = phase_[i] - omega_[i] * t;
    sinCos(a, coef[coefIndex(i, kRowSinA)], coef[coefIndex(i, kRowCosA)]);
  }
}

std::size_t WaveVelocityCache::seenAt(double zc) const {
  // The components this elevation sees (a prefix: sorted by z_skip), whole lanes of them (the
  // extra ones, below their skip depth, add less than 1e-12 m/s each).
  const std::size_t seen =
      static_cast<std::size_t>(std::upper_bound(z_skip_.begin(), z_skip_.begin() + static_cast<std::ptrdiff_t>(nc_), zc) -
                               z_skip_.begin());
  return (seen + kGroup - 1) / kGroup * kGroup;
}

std::size_t WaveVelocityCache::componentsAt(double z) const {
  if (empty()) return 0;
  const double zc = std::min(0.0, std::max(-field_->depth_, z));
  return zc < field_->z_all_negligible_ ? 0 : seenAt(zc);
}

void WaveVelocityCache::velocity(std::size_t p, double x, double z, double& vx, double& vz) {
  vx = vz = 0.0;
  if (empty()) return;
  const WaveField& f = *field_;
  const double zc = std::min(0.0, std::max(-f.depth_, z));
  if (zc < f.z_all_negligible_) return;
  Exact& ex = exact_[p];
  const bool inside = z < 0.0 && z > -f.depth_;  // not clamped: the expansion holds
  double* const st = stateData() + p * (np_ / kGroup * kStateGroup);  // point p's groups
  if (inside && ex.valid) {
    const double dx = x - ex.x, dz = z - ex.z;
    if (dx * dx + dz * dz <= ex.radius * ex.radius && (ex.t == t_ || across_times_)) {
      // Within the point's expansion radius of its reference: the second-order Taylor
      // expansion about it (expansionRadius), with the sums there at this time first if they
      // are of another (the reference's values, cos and sin of B and E+-, do not change).
      if (ex.t != t_) {
        double sums[12];
        referenceSums(coefData(), st, ex.components / kGroup, sums);
        ex.t = t_;
        ex.setSums(sums, ramp_);
      }
      auto taylor = [dx, dz](const double* v) {
        return v[0] + v[1] * dx + v[2] * dz + 0.5 * v[3] * dx * dx + v[4] * dx * dz + 0.5 * v[5] * dz * dz;
      };
      vx = taylor(ex.vx);
      vz = taylor(ex.vz);
      return;
    }
  }
  // The exact sum at (x, zc), which becomes the point's reference. The components summed: those
  // a point up to kMaxExpansionRadius higher sees, so that every one left out stays below the
  // negligible velocity within the expansion radius.
  const std::size_t n = seenAt(std::min(0.0, zc + kMaxExpansionRadius));
  const double kx_n = n > 0 ? kx_upto_[n - 1] : 0.0, k_n = n > 0 ? k_upto_[n - 1] : 0.0;
  // The reference: moved to the point by every exact evaluation (componentSums), computed
  // afresh when the point jumped beyond the Taylor series' reach (also when it is NaN) and
  // every kResync moves, so that the rounding of the carried values does not build up.
  constexpr int kResync = 512;  // rounding of 512 moves: ~1e-13 relative at worst (test_wave_velocity_cache)
  double dx = x - x_ref_[p], dz = zc - z_ref_[p];
  if (!(std::abs(dx) * kx_n <= kTaylorRadius && std::abs(dz) * k_n <= kTaylorRadius) || moves_[p] >= kResync) {
    x_ref_[p] = x;
    z_ref_[p] = zc;
    dx = dz = 0.0;
    valid_[p] = 0;
    moves_[p] = 0;
  }
  // Components [valid, n) have no reference values yet (or stale ones): compute them there.
  for (std::size_t i = valid_[p]; i < n; ++i) {
    sinCos(kx_[i] * x_ref_[p], st[stateIndex(i, kRowSinB)], st[stateIndex(i, kRowCosB)]);
    st[stateIndex(i, kRowEp)] = std::exp(k_[i] * (z_ref_[p] + op_[i]));
    st[stateIndex(i, kRowEm)] = std::exp(-k_[i] * (z_ref_[p] + om_[i]));
  }
  valid_[p] = std::max(valid_[p], n);
  double sums[13];
  // The shorter series where the largest argument among the components summed allows it
  // (a deep point sees long waves only, and moves little in a step).
  if (n == 0 || std::max(std::abs(dx) * kx_n, std::abs(dz) * k_n) <= kShortTaylorRadius)
    componentSums<7>(coefData(), st, n / kGroup, dx, dz, sums);
  else
    componentSums<11>(coefData(), st, n / kGroup, dx, dz, sums);
  if (dx != 0.0 || dz != 0.0) {  // [0, n) now refer to (x, zc); the others are stale
    x_ref_[p] = x;
    z_ref_[p] = zc;
    valid_[p] = n;
    ++moves_[p];
  }
  vx = sums[0] * ramp_;
  vz = sums[6] * ramp_;
  ex.valid = inside;
  if (!inside) return;
  ex.t = t_;
  ex.x = x;
  ex.z = z;
  ex.components = n;
  ex.radius = expansionRadiusFor(sums[12], k_n);
  ex.setSums(sums, ramp_);
}

double WaveVelocityCache::expansionRadiusFor(double g3, double k_n) {
  // Along a unit direction each derivative of a component brings a factor of at most k_i
  // (|k_i cos(theta_i)| <= k_i; z turns ch into sh and back, |sh| <= ch), so the third
  // derivatives at the reference are below 2^{3/2} G3 with G3 = sum_i A_i a_i omega_i k_i^3 ch_i
  // (g3, the sum at the reference; ramp <= 1), and within a distance r of it below
  // 2^{3/2} G3 e^{k_n r} (the depth factors grow by at most e^{k_i r}). The remainder of the
  // second-order expansion over r is then below 2^{3/2} G3 e^{k_n r} r^3 / 6 <= kLinearTolerance
  // for the r below (r0 without the growth, which bounds r; then the growth at r0).
  const double third = 2.0 * std::sqrt(2.0) * g3 / 6.0;
  if (!(third > 0.0)) return kMaxExpansionRadius;
  const double r0 = std::min(kMaxExpansionRadius, std::cbrt(kLinearTolerance / third));
  return std::min(r0, std::cbrt(kLinearTolerance / (third * std::exp(k_n * r0))));
}

double WaveVelocityCache::expansionRadius(std::size_t p) const {
  return p < exact_.size() && exact_[p].valid ? exact_[p].radius : 0.0;
}

void WaveVelocityCache::velocity3(std::size_t p, double x, double y, double z, double& vx, double& vy, double& vz) {
  if (!plane_ && !empty()) throw std::logic_error("WaveVelocityCache::velocity3 needs a cache built for the horizontal plane");
  double vh;
  velocity(p, x * cos_dir_ + y * sin_dir_, z, vh, vz);  // at xi along the direction of travel
  vx = vh * cos_dir_;
  vy = vh * sin_dir_;
}

int balancedWaterSplit(const WaveVelocityCache& cache, const std::vector<double>& z, int meeting, double water_work,
                       double rest_work) {
  if (meeting == 0 || cache.empty()) return meeting;
  std::vector<double> cost;  // water work of each point
  for (double zj : z) cost.push_back(static_cast<double>(cache.componentsAt(zj)) + water_work);
  const int n = static_cast<int>(z.size());
  return balancedSplit(cost, rest_work * (meeting - (n - meeting)));
}

}  // namespace core
}  // namespace mooring_dynamics
