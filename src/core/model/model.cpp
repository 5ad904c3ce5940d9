// The model's structs: materials and their tension laws, the environment (seabed, current
// profile), the surface buoy. Their validation (Problem::validate and the options'):
// model_validation.cpp.
#include "mooring_dynamics/core/model/model.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <sstream>

#include "mooring_dynamics/core/model/field_error.hpp"
#include "mooring_dynamics/core/model/table.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The validations' messages: "key = value: constraint" (field_error.hpp).
std::string check(bool ok, const std::string& key, double v, const std::string& c) { return fieldCheck(ok, key, v, c); }
bool finite(double v) { return std::isfinite(v); }

}  // namespace

// --- Material --------------------------------------------------------------------------------

double Material::rawTension(double eps) const {
  if (tension_strain.empty()) return EA * eps;
  return interpolateTable(tension_strain, eps);
}

double Material::rawTensionSlope(double eps) const {
  if (tension_strain.empty()) return EA;
  return interpolateTableSlope(tension_strain, eps);
}

double Material::slackBand() const {
  return kSlackStrain * (tension_strain.empty() ? EA : interpolateTableSlope(tension_strain, 0.0));
}

const std::vector<std::string>& materialKinds() {
  static const std::vector<std::string> kinds = {"chain", "rope", "wire", "rod", "pipe", "umbilical"};
  return kinds;
}

bool materialCarriesCompression(const std::string& kind) {
  return !(kind == "chain" || kind == "rope" || kind == "wire");
}

double Material::tension(double eps) const {
  if (compression) return rawTension(eps);
  const double T = rawTension(eps);
  return slackRamp(T, T, slackBand());
}

double Material::tensionSlope(double eps) const {
  if (compression) return rawTensionSlope(eps);
  const double T = rawTension(eps), b = slackBand();
  if (T >= 0.5 * b) return rawTensionSlope(eps);
  return std::max((T + 0.5 * b) / b, kSlackJacobianFraction) * rawTensionSlope(eps);
}

double Material::strainAt(double T) const {
  if (!compression) {
    // Invert the ramp: the raw tension whose rounded value is T (-b/2 where it reaches zero).
    const double b = slackBand();
    if (T < 0.5 * b) T = T > 0.0 ? std::sqrt(2.0 * b * T) - 0.5 * b : -0.5 * b;
  }
  if (tension_strain.empty()) return T / EA;
  // Invert the increasing piecewise-linear table (extrapolated linearly at both ends).
  std::vector<std::pair<double, double>> inverse;
  inverse.reserve(tension_strain.size());
  for (const auto& p : tension_strain) inverse.emplace_back(p.second, p.first);
  return interpolateTable(inverse, T);
}

// --- Environment -----------------------------------------------------------------------------

double SeabedGrid::depthAt(double x, double y) const {
  // Fractional grid coordinates clamped to the grid; the cell is the one at or west/south of them.
  const double fx = std::clamp((x - x0) / dx, 0.0, static_cast<double>(nx - 1));
  const double fy = std::clamp((y - y0) / dy, 0.0, static_cast<double>(ny - 1));
  const std::size_t ix = std::min(static_cast<std::size_t>(fx), nx - 2);
  const std::size_t iy = std::min(static_cast<std::size_t>(fy), ny - 2);
  const double u = fx - static_cast<double>(ix), v = fy - static_cast<double>(iy);
  return (1.0 - v) * ((1.0 - u) * at(ix, iy) + u * at(ix + 1, iy)) +
         v * ((1.0 - u) * at(ix, iy + 1) + u * at(ix + 1, iy + 1));
}

void SeabedGrid::depthGradient(double x, double y, double& dd_dx, double& dd_dy) const {
  const double gx = (x - x0) / dx, gy = (y - y0) / dy;
  const double xmax = static_cast<double>(nx - 1), ymax = static_cast<double>(ny - 1);
  const bool inside_x = gx > 0.0 && gx < xmax, inside_y = gy > 0.0 && gy < ymax;
  const double fx = std::clamp(gx, 0.0, xmax), fy = std::clamp(gy, 0.0, ymax);
  const std::size_t ix = std::min(static_cast<std::size_t>(fx), nx - 2);
  const std::size_t iy = std::min(static_cast<std::size_t>(fy), ny - 2);
  const double u = fx - static_cast<double>(ix), v = fy - static_cast<double>(iy);
  dd_dx = inside_x ? ((1.0 - v) * (at(ix + 1, iy) - at(ix, iy)) + v * (at(ix + 1, iy + 1) - at(ix, iy + 1))) / dx : 0.0;
  dd_dy = inside_y ? ((1.0 - u) * (at(ix, iy + 1) - at(ix, iy)) + u * (at(ix + 1, iy + 1) - at(ix + 1, iy))) / dy : 0.0;
}

std::string SeabedGrid::validate() const {
  const std::string k = "environment.seabed.grid" + (source.empty() ? std::string() : " (" + source + ")") + ".";
  std::string e;
  if (!(e = check(finite(x0), k + "x0", x0, "must be finite")).empty()) return e;
  if (!(e = check(finite(y0), k + "y0", y0, "must be finite")).empty()) return e;
  if (!(e = check(finite(dx) && dx > 0.0, k + "dx", dx, "must be > 0")).empty()) return e;
  if (!(e = check(finite(dy) && dy > 0.0, k + "dy", dy, "must be > 0")).empty()) return e;
  if (nx < 2) return k + "nx = " + std::to_string(nx) + ": must be >= 2 (for a depth varying in x only use seabed.profile)";
  if (ny < 2) return k + "ny = " + std::to_string(ny) + ": must be >= 2 (for a depth varying in x only use seabed.profile)";
  if (depths.size() != nx * ny)
    return k + "depths has " + std::to_string(depths.size()) + " values: must have nx * ny = " +
           std::to_string(nx * ny);
  for (std::size_t i = 0; i < depths.size(); ++i) {
    const std::string r = k + "depths[" + std::to_string(i) + "] (ix = " + std::to_string(i % nx) +
                          ", iy = " + std::to_string(i / nx) + ")";
    if (!(e = check(finite(depths[i]) && depths[i] > 0.0, r, depths[i], "must be > 0 (depth, positive down)")).empty())
      return e;
  }
  return {};
}

double Environment::seabedElevation(double x, double y) const {
  if (!seabed.grid.empty()) return -seabed.grid.depthAt(x, y);
  if (seabed.profile.empty()) return -depth;
  return -interpolateTableClamped(seabed.profile, x);
}

void Environment::seabedGradient(double x, double y, double& dzdx, double& dzdy) const {
  dzdx = dzdy = 0.0;
  if (!seabed.grid.empty()) {
    seabed.grid.depthGradient(x, y, dzdx, dzdy);
    dzdx = -dzdx;
    dzdy = -dzdy;
    return;
  }
  if (seabed.profile.size() < 2) return;
  if (x <= seabed.profile.front().first || x >= seabed.profile.back().first) return;
  dzdx = -interpolateTableSlope(seabed.profile, x);
}

double Environment::seabedElevation(double x) const { return seabedElevation(x, 0.0); }

double Environment::seabedSlope(double x) const {
  double dzdx, dzdy;
  seabedGradient(x, 0.0, dzdx, dzdy);
  return dzdx;
}

namespace {

/// The interval of a current table (size(), depth(i) [m], comp(i, cx, cy) [m/s]) that depth d
/// interpolates in: i with depth(i-1) < d <= depth(i), d strictly inside the table; 0 when d
/// takes an end's value (and for tables of fewer than two points).
/// The smallest i >= 1 with depth(i) >= d, for depth(0) < d <= depth(n - 1): a bisection, so a
/// table of a million points costs 20 comparisons per lookup (the depths increase, validated).
template <class Table>
std::size_t intervalAtOrAbove(const Table& table, double d) {
  std::size_t lo = 1, hi = table.size() - 1;  // the answer lies in [lo, hi]
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (d > table.depth(mid)) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

template <class Table>
std::size_t valueInterval(const Table& table, double d) {
  const std::size_t n = table.size();
  if (n < 2 || d <= table.depth(0) || d >= table.depth(n - 1)) return 0;
  return intervalAtOrAbove(table, d);
}

/// Whether valueInterval(table, d) is i > 0, without the search.
template <class Table>
bool inValueInterval(const Table& table, std::size_t i, double d) {
  return d > table.depth(i - 1) && d <= table.depth(i) && d < table.depth(table.size() - 1);
}

/// The velocity components (not speed and direction) at depth d, linear in interval i.
template <class Table>
void interpolateIn(const Table& table, std::size_t i, double d, double& ux, double& uy) {
  double ax, ay, bx, by;
  table.comp(i - 1, ax, ay);
  table.comp(i, bx, by);
  const double w = (d - table.depth(i - 1)) / (table.depth(i) - table.depth(i - 1));
  ux = ax + w * (bx - ax);
  uy = ay + w * (by - ay);
}

/// The current table's interpolation, shared by Environment and CurrentProfile: linear in depth
/// between its points and held beyond the first and last. With `slope`, the vertical gradient
/// d(ux, uy)/dz [1/s] instead: that of the interval interpolated in, the lower one at the last
/// point (see Environment::currentGradientAt).
template <class Table>
void interpolateCurrent(const Table& table, double z, bool slope, double& ux, double& uy) {
  ux = uy = 0.0;
  const std::size_t n = table.size();
  if (n == 0 || (slope && n < 2)) return;
  const double d = std::max(0.0, -z);
  if (!slope) {
    const std::size_t i = valueInterval(table, d);
    if (i > 0) interpolateIn(table, i, d, ux, uy);
    else table.comp(n == 1 || d <= table.depth(0) ? 0 : n - 1, ux, uy);
    return;
  }
  if (d <= table.depth(0) || d > table.depth(n - 1)) return;
  // d in (depth[i-1], depth[i]] uses interval i; du/dz = -du/dd (depth grows downward, z upward).
  const std::size_t i = intervalAtOrAbove(table, d);
  double ax, ay, bx, by;
  table.comp(i - 1, ax, ay);
  table.comp(i, bx, by);
  const double dd = table.depth(i) - table.depth(i - 1);  // > 0 (validated)
  ux = -(bx - ax) / dd;
  uy = -(by - ay) / dd;
}

/// Environment::current as interpolateCurrent's table: components from speed and direction.
struct PointTable {
  const std::vector<CurrentPoint>& points;
  std::size_t size() const { return points.size(); }
  double depth(std::size_t i) const { return points[i].depth; }
  void comp(std::size_t i, double& cx, double& cy) const {
    cx = points[i].speed * std::cos(points[i].direction);
    cy = points[i].speed * std::sin(points[i].direction);
  }
};

}  // namespace

void Environment::currentAt(double z, double& ux, double& uy) const {
  interpolateCurrent(PointTable{current}, z, false, ux, uy);
}

void Environment::currentGradientAt(double z, double& dux_dz, double& duy_dz) const {
  interpolateCurrent(PointTable{current}, z, true, dux_dz, duy_dz);
}

CurrentProfile::CurrentProfile(const std::vector<CurrentPoint>& table) {
  for (const CurrentPoint& c : table) {
    depth_.push_back(c.depth);
    ux_.push_back(c.speed * std::cos(c.direction));
    uy_.push_back(c.speed * std::sin(c.direction));
  }
}

void CurrentProfile::at(double z, double& ux, double& uy) const { interpolateCurrent(*this, z, false, ux, uy); }

void CurrentProfile::atAndAround(double z, double dz, double& ux, double& uy, double& ux_above,
                                 double& ux_below) const {
  const double d = std::max(0.0, -z);
  const std::size_t i = valueInterval(*this, d);
  if (i > 0) interpolateIn(*this, i, d, ux, uy);
  else at(z, ux, uy);
  // A neighbour in the same interval interpolates there; any other takes its own search.
  auto eastAt = [&](double zq) {
    const double dq = std::max(0.0, -zq);
    double e, north;
    if (i > 0 && inValueInterval(*this, i, dq)) interpolateIn(*this, i, dq, e, north);
    else at(zq, e, north);
    return e;
  };
  ux_above = eastAt(z + dz);
  ux_below = eastAt(z - dz);
}

void CurrentProfile::gradientAt(double z, double& dux_dz, double& duy_dz) const {
  interpolateCurrent(*this, z, true, dux_dz, duy_dz);
}

// --- Surface buoy ----------------------------------------------------------------------------

double SurfaceBuoy::submergedVolume(double d) const {
  const double h = totalHeight();
  d = std::clamp(d, 0.0, h);
  const double R = 0.5 * diameter;
  if (shape == Shape::Sphere) return kPi * d * d * (3.0 * R - d) / 3.0;  // spherical cap
  return kPi * R * R * d;
}

double SurfaceBuoy::submergedVolumeSlope(double d) const {
  const double h = totalHeight();
  if (d <= 0.0 || d >= h) return 0.0;
  const double R = 0.5 * diameter;
  if (shape == Shape::Sphere) return kPi * d * (2.0 * R - d);  // waterplane area
  return kPi * R * R;
}

double SurfaceBuoy::submergedArea(double d) const {
  const double h = totalHeight();
  d = std::clamp(d, 0.0, h);
  const double R = 0.5 * diameter;
  if (shape == Shape::Sphere) {
    // Circular segment of height d.
    const double c = std::clamp((R - d) / R, -1.0, 1.0);
    return R * R * std::acos(c) - (R - d) * std::sqrt(std::max(0.0, 2.0 * R * d - d * d));
  }
  return diameter * d;
}

double SurfaceBuoy::submergedAreaSlope(double d) const {
  const double h = totalHeight();
  if (d <= 0.0 || d >= h) return 0.0;
  const double R = 0.5 * diameter;
  if (shape == Shape::Sphere) return 2.0 * std::sqrt(std::max(0.0, 2.0 * R * d - d * d));  // chord
  return diameter;
}

}  // namespace core
}  // namespace mooring_dynamics
