// Piecewise-linear tables (x increasing), usable with double and with automatic-differentiation
// scalars: the interval is chosen on the value, the interpolation is done in the scalar type.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "mooring_dynamics/core/model/scalar.hpp"

namespace mooring_dynamics {
namespace core {

using Table = std::vector<std::pair<double, double>>;

/// Index i of the interval [x_i, x_{i+1}] used for x (end intervals extend outward).
inline std::size_t tableInterval(const Table& t, double x) {
  std::size_t lo = 0, hi = t.size() - 1;
  if (t.size() < 2 || x <= t[1].first) return 0;
  if (x >= t[hi - 1].first) return hi - 1;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    if (t[mid].first <= x) lo = mid; else hi = mid;
  }
  return lo;
}

/// Linear interpolation, extrapolated with the end slopes.
template <class S>
S interpolateTable(const Table& t, const S& x) {
  if (t.size() == 1) return S(t[0].second) + 0.0 * x;
  const std::size_t i = tableInterval(t, value(x));
  const double slope = (t[i + 1].second - t[i].second) / (t[i + 1].first - t[i].first);
  return t[i].second + slope * (x - t[i].first);
}

inline double interpolateTableSlope(const Table& t, double x) {
  if (t.size() < 2) return 0.0;
  const std::size_t i = tableInterval(t, x);
  return (t[i + 1].second - t[i].second) / (t[i + 1].first - t[i].first);
}

/// Linear interpolation, held constant beyond the ends.
template <class S>
S interpolateTableClamped(const Table& t, const S& x) {
  if (value(x) <= t.front().first) return S(t.front().second) + 0.0 * x;
  if (value(x) >= t.back().first) return S(t.back().second) + 0.0 * x;
  return interpolateTable(t, x);
}

}  // namespace core
}  // namespace mooring_dynamics
