#include "mooring_dynamics/core/model/winch.hpp"

#include <algorithm>

#include "mooring_dynamics/core/model/field_error.hpp"

namespace mooring_dynamics {
namespace core {

double WinchProgram::lengthAt(double time) const {
  if (t.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (time <= t.front()) return length.front();
  if (time >= t.back()) return length.back() + rate_after * (time - t.back());
  const auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
  const double w = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return length[k - 1] + w * (length[k] - length[k - 1]);
}

double WinchProgram::rateAt(double time) const {
  if (t.empty() || time <= t.front()) return 0.0;
  if (time > t.back()) return rate_after;
  const auto k = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), time) - t.begin());
  return (length[k] - length[k - 1]) / (t[k] - t[k - 1]);
}

WinchProgram WinchProgram::toward(double t0, double L0, double rate, double target) {
  WinchProgram p;
  p.t = {t0};
  p.length = {L0};
  if (std::isnan(target)) {
    p.rate_after = rate;
  } else if (target != L0 && rate != 0.0) {
    p.t.push_back(t0 + std::abs(target - L0) / std::abs(rate));
    p.length.push_back(target);
  }
  return p;
}

std::string Winch::validate(const std::string& key) const {
  const std::string k = key + ".";
  if (!std::isfinite(rate)) return fieldError(k + "rate", rate, "must be a finite rate [m/s] (> 0 pays out)");
  if (rate != 0.0 && !table.empty())
    return k + "rate = " + fieldNumber(rate) + " and " + k + "table (" + std::to_string(table.size()) +
           " rows): give one of them, not both";
  if (rate == 0.0 && table.empty()) return k + "rate / table: the winch needs a rate [m/s] or a table of [t, length]";
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string rk = k + "table[" + std::to_string(i) + "]";
    if (table[i].size() != 2) return rk + ": a row is [t, length] ([s], [m])";
    if (!(std::isfinite(table[i][0]) && table[i][0] >= 0.0)) return fieldError(rk + " t", table[i][0], "must be >= 0 [s]");
    if (!(std::isfinite(table[i][1]) && table[i][1] > 0.0)) return fieldError(rk + " length", table[i][1], "must be > 0 [m]");
    if (i > 0 && !(table[i][0] > table[i - 1][0])) return fieldError(rk + " t", table[i][0], "times must increase");
  }
  if (!(std::isfinite(min_length) && min_length >= 0.0))
    return fieldError(k + "min_length", min_length, "must be >= 0 [m] (0: none)");
  if (!(std::isfinite(max_length) && max_length >= 0.0))
    return fieldError(k + "max_length", max_length, "must be >= 0 [m] (0: none)");
  if (max_length > 0.0 && !(max_length > min_length))
    return fieldError(k + "max_length", max_length, "must be > min_length = " + fieldNumber(min_length) + " m");
  return {};
}

WinchProgram Winch::program(double L0) const {
  WinchProgram p;
  if (table.empty()) return WinchProgram::toward(0.0, L0, rate, std::numeric_limits<double>::quiet_NaN());
  for (const auto& row : table) {
    p.t.push_back(row[0]);
    p.length.push_back(row[1]);
  }
  return p;
}

double winchLimitCrossing(const WinchProgram& p, double lo, double hi, double t0, double t1) {
  std::vector<double> ts = {t0};
  for (double tk : p.t)
    if (tk > t0 && tk < t1) ts.push_back(tk);
  ts.push_back(t1);
  auto outside = [&](double L) { return L < lo || L > hi; };
  if (outside(p.lengthAt(t0))) return t0;
  for (std::size_t i = 1; i < ts.size(); ++i) {
    const double La = p.lengthAt(ts[i - 1]), Lb = p.lengthAt(ts[i]);
    if (!outside(Lb)) continue;
    const double bound = Lb > hi ? hi : lo;  // linear on the piece: where it meets the bound
    return ts[i - 1] + (bound - La) / (Lb - La) * (ts[i] - ts[i - 1]);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string validateWinchOnLine(const Winch& w, const std::string& key, double L0, double top_start, double spacing,
                                double duration) {
  const std::string k = key + ".";
  constexpr double kStartMismatch = 1e-3;  // [m] the table starts from the file's line
  if (!w.table.empty() && std::abs(w.table.front()[1] - L0) > kStartMismatch)
    return fieldError(k + "table[0] length", w.table.front()[1],
               "must be the line's length in the file, " + fieldNumber(L0) + " m (the run starts from its statics)");
  const double shortest = top_start + kWinchShortestTopFraction * spacing;
  if (!(L0 >= shortest))
    return key + ": the top segment gives the winch " + fieldNumber(L0 - top_start) +
           " m (above its start or its last inline body): it needs at least " +
           fieldNumber(kWinchShortestTopFraction) + " of its spacing, " + fieldNumber(kWinchShortestTopFraction * spacing) + " m";
  if (w.min_length > 0.0 && L0 < w.min_length)
    return fieldError(k + "min_length", w.min_length, "is above the line's length " + fieldNumber(L0) + " m");
  if (w.max_length > 0.0 && L0 > w.max_length)
    return fieldError(k + "max_length", w.max_length, "is below the line's length " + fieldNumber(L0) + " m");
  const WinchProgram p = w.program(L0);
  const double lo = std::max(w.min_length, shortest);
  const double hi = w.max_length > 0.0 ? w.max_length : std::numeric_limits<double>::infinity();
  const double tc = winchLimitCrossing(p, lo, hi, 0.0, duration);
  if (std::isnan(tc)) return {};
  const double Lc = p.lengthAt(std::min(duration, tc + 1e-9 * std::max(1.0, duration)));
  if (Lc > hi) return k + "max_length = " + fieldNumber(hi) + " m: the winch passes it at t = " + fieldNumber(tc) + " s";
  if (w.min_length >= shortest)
    return k + "min_length = " + fieldNumber(w.min_length) + " m: the winch passes it at t = " + fieldNumber(tc) + " s";
  return key + ": the winch would take in the whole top segment at t = " + fieldNumber(tc) + " s (length " + fieldNumber(shortest) +
         " m = its start at s = " + fieldNumber(top_start) + " m + " + fieldNumber(kWinchShortestTopFraction) +
         " spacing); it can haul in only the top segment";
}

}  // namespace core
}  // namespace mooring_dynamics
