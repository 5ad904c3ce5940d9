#include "mooring_dynamics/core/model/model.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <sstream>

#include "mooring_dynamics/core/model/table.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// Returns "key = value: constraint" when `ok` is false, else "".
std::string check(bool ok, const std::string& key, double value, const std::string& constraint) {
  if (ok) return {};
  return key + " = " + fmt(value) + ": " + constraint;
}

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

// --- Options and problem validation ----------------------------------------------------------

std::string StaticOptions::validate() const {
  std::string e;
  if (!(e = check(finite(tolerance) && tolerance > 0.0, "solver.static.tolerance", tolerance, "must be > 0")).empty()) return e;
  if (max_iterations < 1)
    return "solver.static.max_iterations = " + std::to_string(max_iterations) + ": must be >= 1";
  if (!(e = check(finite(relaxation) && relaxation > 0.0 && relaxation <= 1.0, "solver.static.relaxation", relaxation,
                  "must be in (0, 1]")).empty()) return e;
  if (!(e = check(finite(R2) && R2 > 1.0, "solver.static.R2", R2, "must be > 1")).empty()) return e;
  if (!(e = check(finite(R1) && R1 > R2, "solver.static.R1", R1, "must be > R2 = " + fmt(R2))).empty()) return e;
  return {};
}

double Problem::totalLength() const {
  double L = 0.0;
  for (const auto& s : segments) L += s.length;
  return L;
}

namespace {

std::string validateMaterial(const Material& m) {
  const std::string k = "materials." + m.name + ".";
  std::string e;
  if (m.tension_strain.empty()) {
    if (!(e = check(finite(m.EA) && m.EA > 0.0, k + "EA", m.EA, "must be > 0")).empty()) return e;
  } else {
    if (m.tension_strain.size() < 2)
      return k + "tension_strain has " + std::to_string(m.tension_strain.size()) + " rows: needs at least 2";
    for (std::size_t i = 0; i < m.tension_strain.size(); ++i) {
      const auto& p = m.tension_strain[i];
      const std::string r = k + "tension_strain[" + std::to_string(i) + "]";
      if (!finite(p.first) || !finite(p.second)) return r + " = [" + fmt(p.first) + ", " + fmt(p.second) + "]: must be finite";
      if (i > 0 && !(p.first > m.tension_strain[i - 1].first))
        return r + " strain " + fmt(p.first) + ": strains must increase";
      if (i > 0 && !(p.second > m.tension_strain[i - 1].second))
        return r + " tension " + fmt(p.second) + ": tensions must increase";
    }
  }
  if (!(e = check(finite(m.EI) && m.EI > 0.0, k + "EI", m.EI, "must be > 0 (the formulation needs bending stiffness; use a small value for ropes and chain)")).empty()) return e;
  if (!(e = check(finite(m.GJ) && m.GJ >= 0.0, k + "GJ", m.GJ, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.mass) && m.mass >= 0.0, k + "mass", m.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.added_mass) && m.added_mass >= 0.0, k + "added_mass", m.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.wet_weight), k + "wet_weight", m.wet_weight, "must be finite")).empty()) return e;
  if (!(e = check(finite(m.diameter) && m.diameter > 0.0, k + "diameter", m.diameter, "must be > 0")).empty()) return e;
  if (!(e = check(finite(m.cdn) && m.cdn >= 0.0, k + "cdn", m.cdn, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.cdt) && m.cdt >= 0.0, k + "cdt", m.cdt, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.max_strain) && m.max_strain > 0.0, k + "max_strain", m.max_strain, "must be > 0")).empty()) return e;
  if (!(e = check(finite(m.mbl) && m.mbl >= 0.0, k + "mbl", m.mbl, "must be > 0 (or 0 when not given)")).empty()) return e;
  if (!(e = check(finite(m.mu_axial) && m.mu_axial >= 0.0, k + "mu_axial", m.mu_axial, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(m.mu_lateral) && m.mu_lateral >= 0.0, k + "mu_lateral", m.mu_lateral, "must be >= 0")).empty())
    return e;
  return {};
}

std::string validateBody(const Body& b) {
  const std::string k = "bodies." + b.name + ".";
  std::string e;
  if (!(e = check(finite(b.mass) && b.mass >= 0.0, k + "mass", b.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.added_mass) && b.added_mass >= 0.0, k + "added_mass", b.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wet_weight), k + "wet_weight", b.wet_weight, "must be finite")).empty()) return e;
  if (!(e = check(finite(b.diameter) && b.diameter >= 0.0, k + "diameter", b.diameter, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cd) && b.cd >= 0.0, k + "cd", b.cd, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cdn) && b.cdn >= 0.0, k + "cdn", b.cdn, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cdt) && b.cdt >= 0.0, k + "cdt", b.cdt, "must be >= 0")).empty()) return e;
  return {};
}

std::string validateBuoy(const SurfaceBuoy& b) {
  const std::string k = "top.buoy.";
  std::string e;
  if (!(e = check(finite(b.diameter) && b.diameter > 0.0, k + "diameter", b.diameter, "must be > 0")).empty()) return e;
  if (b.shape == SurfaceBuoy::Shape::Cylinder &&
      !(e = check(finite(b.height) && b.height > 0.0, k + "height", b.height, "must be > 0")).empty()) return e;
  if (!(e = check(finite(b.mass) && b.mass >= 0.0, k + "mass", b.mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.added_mass) && b.added_mass >= 0.0, k + "added_mass", b.added_mass, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.cd) && b.cd >= 0.0, k + "cd", b.cd, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wind_area) && b.wind_area >= 0.0, k + "wind_area", b.wind_area, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(b.wind_cd) && b.wind_cd >= 0.0, k + "wind_cd", b.wind_cd, "must be >= 0")).empty()) return e;
  return {};
}

}  // namespace

namespace {

/// The environment: densities, gravity, depth, seabed, current, wind and waves.
std::string validateEnvironment(const Environment& env) {
  std::string e;
  if (!(e = check(finite(env.water_density) && env.water_density > 0.0, "environment.water_density", env.water_density, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.air_density) && env.air_density >= 0.0, "environment.air_density", env.air_density, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(env.gravity) && env.gravity > 0.0, "environment.gravity", env.gravity, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.depth) && env.depth > 0.0, "environment.depth", env.depth, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.seabed.stiffness) && env.seabed.stiffness > 0.0, "environment.seabed.stiffness", env.seabed.stiffness, "must be > 0")).empty()) return e;
  if (!(e = check(finite(env.seabed.damping) && env.seabed.damping >= 0.0, "environment.seabed.damping", env.seabed.damping, "must be >= 0")).empty()) return e;
  for (std::size_t i = 0; i < env.seabed.profile.size(); ++i) {
    const auto& p = env.seabed.profile[i];
    const std::string r = "environment.seabed.profile[" + std::to_string(i) + "]";
    if (!finite(p.first) || !finite(p.second)) return r + " = [" + fmt(p.first) + ", " + fmt(p.second) + "]: must be finite";
    if (!(p.second > 0.0)) return r + " depth = " + fmt(p.second) + ": must be > 0";
    if (i > 0 && !(p.first > env.seabed.profile[i - 1].first)) return r + " x = " + fmt(p.first) + ": x must increase";
  }
  if (!env.seabed.grid.empty()) {
    if (!env.seabed.profile.empty())
      return "environment.seabed: has both a profile and a grid; give at most one of profile and grid_file";
    if (!(e = env.seabed.grid.validate()).empty()) return e;
  }
  for (std::size_t i = 0; i < env.current.size(); ++i) {
    const auto& c = env.current[i];
    const std::string r = "environment.current[" + std::to_string(i) + "]";
    if (!(e = check(finite(c.depth) && c.depth >= 0.0, r + ".depth", c.depth, "must be >= 0")).empty()) return e;
    if (i > 0 && !(c.depth > env.current[i - 1].depth)) return r + ".depth = " + fmt(c.depth) + ": depths must increase";
    if (!(e = check(finite(c.speed) && c.speed >= 0.0, r + ".speed", c.speed, "must be >= 0")).empty()) return e;
    if (!(e = check(finite(c.direction), r + ".direction_deg", c.direction, "must be finite")).empty()) return e;
  }
  if (!(e = check(finite(env.wind_speed) && env.wind_speed >= 0.0, "environment.wind.speed", env.wind_speed, "must be >= 0")).empty()) return e;
  if (!(e = check(finite(env.wind_direction), "environment.wind.direction_deg", env.wind_direction, "must be finite")).empty()) return e;
  if (!(e = env.waves.validate()).empty()) return e;
  return {};
}

/// The line: materials, bodies and the segments from the anchor up with their bodies.
std::string validateLine(const Problem& p) {
  std::string e;
  if (p.materials.empty()) return "materials: at least one material is needed";
  for (const auto& m : p.materials)
    if (!(e = validateMaterial(m)).empty()) return e;
  for (const auto& b : p.bodies)
    if (!(e = validateBody(b)).empty()) return e;
  if (p.segments.empty()) return "line: at least one segment is needed";
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    const Segment& s = p.segments[i];
    const std::string r = "line[" + std::to_string(i) + "]";
    if (s.material >= p.materials.size()) return r + ".material index " + std::to_string(s.material) + ": unknown material";
    if (!(e = check(finite(s.length) && s.length > 0.0, r + ".length", s.length, "must be > 0")).empty()) return e;
    if (!(e = check(finite(s.spacing) && s.spacing > 0.0, r + ".spacing", s.spacing, "must be > 0")).empty()) return e;
    if (!(e = check(s.spacing <= s.length, r + ".spacing", s.spacing,
                    "must be <= the segment length " + r + ".length = " + fmt(s.length) +
                        " m (a spacing beyond the segment collapses it to one interval)")).empty()) return e;
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      const auto& bp = s.bodies[j];
      const std::string rb = r + ".bodies[" + std::to_string(j) + "]";
      if (bp.body >= p.bodies.size()) return rb + ".body index " + std::to_string(bp.body) + ": unknown body";
      if (!(e = check(finite(bp.at) && bp.at >= 0.0 && bp.at <= s.length, rb + ".at", bp.at,
                      "must be within [0, " + fmt(s.length) + "] (the segment length)")).empty()) return e;
    }
  }
  return {};
}

/// The anchor: finite, not above the surface nor below the seabed; in the plane y = 0 in 2-D.
std::string validateAnchor(const Problem& p) {
  std::string e;
  const Environment& env = p.environment;
  if (!(e = check(finite(p.anchor_x), "anchor.x", p.anchor_x, "must be finite")).empty()) return e;
  if (!(e = check(finite(p.anchor_y), "anchor.y", p.anchor_y, "must be finite")).empty()) return e;
  if (!(e = check(finite(p.anchor_z) && p.anchor_z <= 0.0, "anchor.z", p.anchor_z, "must be <= 0 (z = 0 is the sea surface)")).empty()) return e;
  if (p.formulation == Formulation::TwoD) {
    // The 2-D equations live in the vertical plane y = 0.
    constexpr const char* kPlanar = "must be 0 with model: 2d (the 2-D line lies in the plane y = 0); use model: 3d";
    if (!(e = check(p.anchor_y == 0.0, "anchor.y", p.anchor_y, kPlanar)).empty()) return e;
    if (p.top.type == TopBoundary::Type::Position && !(e = check(p.top.y == 0.0, "top.position.y", p.top.y, kPlanar)).empty()) return e;
    if (p.top.type == TopBoundary::Type::Force && !(e = check(p.top.fy == 0.0, "top.force.y", p.top.fy, kPlanar)).empty()) return e;
  }
  const double zb = env.seabedElevation(p.anchor_x, p.anchor_y);
  if (!(e = check(p.anchor_z >= zb - 1e-6 * env.depth, "anchor.z", p.anchor_z,
                  "is below the seabed elevation " + fmt(zb) + " m at anchor.x")).empty()) return e;
  return {};
}

/// A free lower end: 3-D only, with a tow point or a drifting buoy above it.
std::string validateLowerEnd(const Problem& p) {
  std::string e;
  if (p.lower_end == Problem::LowerEnd::Free) {
    if (p.formulation != Formulation::ThreeD)
      return "free_end: a free lower end (towing) needs model: 3d";
    if (p.end_body != Problem::kNoBody && p.end_body >= p.bodies.size())
      return "free_end.body index " + std::to_string(p.end_body) + ": unknown body";
    if (p.top.type != TopBoundary::Type::Position && p.top.type != TopBoundary::Type::Buoy)
      return "top: a line with a free lower end needs top.position (the tow point) or top.buoy (a drifting "
             "surface buoy); a force or body top leaves the line's position undetermined";
    if (p.top.type == TopBoundary::Type::Buoy && p.dynamics.top_motion.type != TopMotion::Type::Hold &&
        p.dynamics.top_motion.type != TopMotion::Type::ForceTable)
      return "dynamics.top_motion: a drifting buoy (top.buoy with free_end:) moves with the current and the wind; "
             "only type hold (no extra force) or force_table (an extra force on the buoy) apply";
  }
  return {};
}

/// The steady tow velocity: only for a towed line.
std::string validateTowVelocity(const Problem& p) {
  std::string e;
  if (!(e = check(finite(p.top.tow_vx) && finite(p.top.tow_vy), "top.tow_velocity", std::hypot(p.top.tow_vx, p.top.tow_vy),
                  "must be finite")).empty()) return e;
  if ((p.top.tow_vx != 0.0 || p.top.tow_vy != 0.0) && p.lower_end != Problem::LowerEnd::Free)
    return "top.tow_velocity = (" + fmt(p.top.tow_vx) + ", " + fmt(p.top.tow_vy) +
           "): only for a line with a free lower end (free_end:); an anchored line has no steady tow";
  if ((p.top.tow_vx != 0.0 || p.top.tow_vy != 0.0) && p.top.type == TopBoundary::Type::Buoy)
    return "top.tow_velocity = (" + fmt(p.top.tow_vx) + ", " + fmt(p.top.tow_vy) +
           "): a drifting buoy is not towed; the statics find its drift velocity";
  return {};
}

/// The top boundary of its type (section 5.1).
std::string validateTop(const Problem& p) {
  std::string e;
  const Environment& env = p.environment;
  switch (p.top.type) {
    case TopBoundary::Type::Force:
      if (!(e = check(finite(p.top.fx), "top.force.x", p.top.fx, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.fz), "top.force.z", p.top.fz, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.fy), "top.force.y", p.top.fy, "must be finite")).empty()) return e;
      break;
    case TopBoundary::Type::Position: {
      if (!(e = check(finite(p.top.x), "top.position.x", p.top.x, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.z), "top.position.z", p.top.z, "must be finite")).empty()) return e;
      if (!(e = check(finite(p.top.y), "top.position.y", p.top.y, "must be finite")).empty()) return e;
      // A top below the seabed has no equilibrium: the statics would iterate to their limit.
      const double ztop_bed = env.seabedElevation(p.top.x, p.top.y);
      if (p.top.z < ztop_bed - 1e-6 * env.depth)
        return "top.position.z = " + fmt(p.top.z) + ": below the seabed (z = " + fmt(ztop_bed) +
               " m under the top; environment.depth = " + fmt(env.depth) +
               " m); the top must lie above the seabed (z = 0 is the sea surface)";
      double reach = 0.0;
      for (const auto& s : p.segments) reach += s.length * (1.0 + p.materials[s.material].max_strain);
      const double dx = p.top.x - p.anchor_x, dy = p.top.y - p.anchor_y, dz = p.top.z - p.anchor_z;
      const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (!(dist < reach) && p.lower_end == Problem::LowerEnd::Anchor) {
        const std::string at = p.formulation == Formulation::TwoD
                                   ? fmt(p.top.x) + ", " + fmt(p.top.z)
                                   : fmt(p.top.x) + ", " + fmt(p.top.y) + ", " + fmt(p.top.z);
        return "top.position = (" + at + "): " + fmt(dist) +
               " m from the anchor, farther than the stretched line can reach (" + fmt(reach) +
               " m: unstretched length " + fmt(p.totalLength()) + " m at each material's max_strain)";
      }
      break;
    }
    case TopBoundary::Type::Buoy:
      if (!(e = validateBuoy(p.top.buoy)).empty()) return e;
      break;
    case TopBoundary::Type::Body:
      if (p.top.body >= p.bodies.size()) return "top.body index " + std::to_string(p.top.body) + ": unknown body";
      if (p.formulation != Formulation::ThreeD)
        return "top.body: a subsurface buoy at the top needs model: 3d";
      if (p.lower_end != Problem::LowerEnd::Anchor)
        return "top.body with free_end: a line free at both ends under a subsurface body is not supported; a drifting "
               "system takes a surface buoy at the top (top.buoy)";
      if (p.dynamics.top_motion.type != TopMotion::Type::Hold && p.dynamics.top_motion.type != TopMotion::Type::ForceTable)
        return "dynamics.top_motion: with top.body the top is free; only type hold (no extra force) or force_table "
               "(an extra force on the body) apply";
      break;
  }
  return {};
}

/// dynamics.events of a single line (the events' own fields are checked by DynamicOptions).
std::string validateEvents(const Problem& p) {
  for (std::size_t i = 0; i < p.dynamics.events.size(); ++i) {
    const LineEvent& ev = p.dynamics.events[i];
    const std::string k = "dynamics.events[" + std::to_string(i) + "]";
    if (p.formulation != Formulation::ThreeD)
      return k + ": line events run in the 3-D solver; set formulation: 3d (a planar problem gives the same results there)";
    if (!ev.line.empty()) return k + ".line = " + ev.line + ": only a system file names the line of an event";
    const std::string e = validateEventOnLine(ev, k, "the line", p.segments, p.materials,
                                              p.lower_end == Problem::LowerEnd::Free);
    if (!e.empty()) return e;
  }
  return {};
}

/// dynamics.winch of a single line (its own fields are checked by DynamicOptions): a top the
/// winch can drive, its program against the line (validateWinchOnLine).
std::string validateWinch(const Problem& p) {
  const Winch& w = p.dynamics.winch;
  if (!w.given) return {};
  const std::string k = "dynamics.winch";
  if (!w.line.empty()) return k + ".line = " + w.line + ": only a system file names the line of a winch";
  const bool free_below = p.lower_end == Problem::LowerEnd::Free;
  const char* top_kind = p.top.type == TopBoundary::Type::Force ? "force"
                    : p.top.type == TopBoundary::Type::Body ? "body"
                    : p.top.type == TopBoundary::Type::Buoy ? "buoy"
                                                            : "position";
  if (p.top.type == TopBoundary::Type::Force || p.top.type == TopBoundary::Type::Body ||
      (p.top.type == TopBoundary::Type::Buoy && free_below))
    return k + ": top: " + top_kind + (free_below ? " over a free lower end" : "") +
           ": the winch sits at a top whose motion is prescribed (top: position, or a surface buoy over an "
           "anchor); this top's position follows from its forces";
  if (p.dynamics.top_motion.type == TopMotion::Type::ForceTable)
    return k + ": dynamics.top_motion.type = force_table: the winch sits at a top whose motion is prescribed; a "
               "force table leaves the top's position to its forces";
  return validateWinchOnSegments(w, k, p.segments, p.dynamics.duration);
}

}  // namespace

double winchBase(const std::vector<Segment>& segments) {
  double base = 0.0;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) base += segments[i].length;
  double last_body = 0.0;
  for (const BodyPlacement& b : segments.back().bodies) last_body = std::max(last_body, b.at);
  return base + last_body;
}

std::string validateWinchOnSegments(const Winch& w, const std::string& key, const std::vector<Segment>& segments,
                                    double duration) {
  double L = 0.0;
  for (const Segment& g : segments) L += g.length;
  return validateWinchOnLine(w, key, L, winchBase(segments), segments.back().spacing, duration);
}

std::string validateEventOnLine(const LineEvent& ev, const std::string& key, const std::string& line,
                                const std::vector<Segment>& segments, const std::vector<Material>& materials,
                                bool lower_end_free) {
  double length = 0.0;
  bool any_mbl = false;
  for (const Segment& g : segments) {
    length += g.length;
    any_mbl = any_mbl || materials[g.material].mbl > 0.0;
  }
  if (ev.s > length * (1.0 + 1e-12))
    return key + ".s = " + std::to_string(ev.s) + ": beyond the top of " + line + " (unstretched length " +
           std::to_string(length) + " m)";
  if (ev.at_mbl && !any_mbl) return key + ".tension = mbl: no material of " + line + " has an mbl";
  if (ev.type == LineEvent::Type::Release && ev.end == LineEvent::End::Anchor && lower_end_free)
    return key + ".end = anchor: " + line + "'s lower end is free already";
  return {};
}

std::string Problem::validate() const {
  std::string e;
  if (!(e = validateEnvironment(environment)).empty()) return e;
  if (!(e = validateLine(*this)).empty()) return e;
  if (!(e = validateAnchor(*this)).empty()) return e;
  if (!(e = validateLowerEnd(*this)).empty()) return e;
  if (!(e = validateTowVelocity(*this)).empty()) return e;
  if (!(e = validateTop(*this)).empty()) return e;
  if (!(e = static_options.validate()).empty()) return e;
  if (!(e = dynamics.validate()).empty()) return e;
  if (!(e = validateEvents(*this)).empty()) return e;
  if (!(e = validateWinch(*this)).empty()) return e;
  return validateResources();
}

std::string Problem::validateResources() const {
  std::string e;
  if (!(e = limits.validate()).empty()) return e;
  // The segment with the most intervals names the key to change.
  std::size_t worst = 0;
  for (std::size_t i = 1; i < segments.size(); ++i)
    if (segments[i].length / segments[i].spacing > segments[worst].length / segments[worst].spacing) worst = i;
  const std::string key = segments.empty() ? std::string("line")
                                           : "line[" + std::to_string(worst) + "].spacing = " +
                                                 fmt(segments[worst].spacing) + " (line[" + std::to_string(worst) +
                                                 "].length = " + fmt(segments[worst].length) + " m)";
  return checkResources(estimateResources(estimateLineNodes(segments), dynamics, formulation == Formulation::ThreeD,
                                          4 * dynamics.record_s.size()),
                        limits, key);
}

}  // namespace core
}  // namespace mooring_dynamics
