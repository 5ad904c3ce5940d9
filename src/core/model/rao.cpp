// Motion RAO tables: bilinear interpolation in frequency and heading (rao.hpp).
#include "mooring_dynamics/core/model/rao.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mooring_dynamics {
namespace core {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// beta in [0, 360).
double wrapDeg(double beta) {
  double w = std::fmod(beta, 360.0);
  if (w < 0.0) w += 360.0;
  if (w >= 360.0) w = 0.0;
  return w;
}

/// Sway, roll and yaw change sign under the port-starboard mirror (y -> -y).
bool flipsUnderMirror(int dof) { return dof == 1 || dof == 3 || dof == 5; }

}  // namespace

const char* raoDofName(int dof) {
  static const char* names[] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};
  return dof >= 0 && dof < RaoTable::kDofs ? names[dof] : "?";
}

RaoTable::RaoTable(std::vector<double> omega, std::vector<double> headings_deg,
                   std::array<std::vector<std::complex<double>>, kDofs> values)
    : omega_(std::move(omega)), headings_(std::move(headings_deg)), values_(std::move(values)) {
  if (omega_.empty()) throw std::invalid_argument("no frequencies");
  if (headings_.empty()) throw std::invalid_argument("no headings");
  for (std::size_t i = 0; i < omega_.size(); ++i) {
    if (!std::isfinite(omega_[i]) || !(omega_[i] > 0.0))
      throw std::invalid_argument("frequency " + num(omega_[i]) + " rad/s: must be finite and > 0");
    if (i > 0 && !(omega_[i] > omega_[i - 1]))
      throw std::invalid_argument("frequencies must increase (" + num(omega_[i - 1]) + " then " + num(omega_[i]) + " rad/s)");
  }
  for (std::size_t i = 0; i < headings_.size(); ++i) {
    if (!std::isfinite(headings_[i]) || headings_[i] < 0.0 || headings_[i] >= 360.0)
      throw std::invalid_argument("heading " + num(headings_[i]) + " deg: must be in [0, 360)");
    if (i > 0 && !(headings_[i] > headings_[i - 1]))
      throw std::invalid_argument("headings must increase (" + num(headings_[i - 1]) + " then " + num(headings_[i]) +
                                  " deg)");
  }
  for (int d = 0; d < kDofs; ++d) {
    if (values_[d].size() != omega_.size() * headings_.size())
      throw std::invalid_argument(std::string(raoDofName(d)) + ": " + std::to_string(values_[d].size()) +
                                  " values for " + std::to_string(omega_.size()) + " frequencies x " +
                                  std::to_string(headings_.size()) + " headings");
    for (const std::complex<double>& v : values_[d])
      if (!std::isfinite(v.real()) || !std::isfinite(v.imag()))
        throw std::invalid_argument(std::string(raoDofName(d)) + ": a value is not finite");
  }
}

RaoTable::HeadingBracket RaoTable::bracketHeading(double heading_deg) const {
  double beta = wrapDeg(heading_deg);
  HeadingBracket hb;
  if (symmetry == RaoSymmetry::PortStarboard && beta > 180.0) {
    beta = 360.0 - beta;
    hb.mirrored = true;
  }
  // The tabulated headings as a circle (PortStarboard: folded onto [0, 180], no wrap).
  const std::size_t n = headings_.size();
  if (n == 1) {
    hb.gap = symmetry == RaoSymmetry::PortStarboard ? 180.0 : 360.0;
    return hb;
  }
  const auto it = std::upper_bound(headings_.begin(), headings_.end(), beta);
  if (it == headings_.begin() || it == headings_.end()) {  // between the last and the first
    hb.a = n - 1;
    hb.b = 0;
    if (symmetry == RaoSymmetry::PortStarboard) {  // folded: no wrap; exact ends only
      const bool at_end = beta == headings_.back() || beta == headings_.front();
      hb.a = hb.b = beta == headings_.front() ? 0 : n - 1;
      hb.gap = at_end ? 0.0 : 360.0;
      return hb;
    }
    hb.gap = headings_.front() + 360.0 - headings_.back();
    const double from = beta >= headings_.back() ? beta - headings_.back() : beta + 360.0 - headings_.back();
    hb.w = from / hb.gap;
    return hb;
  }
  hb.b = static_cast<std::size_t>(it - headings_.begin());
  hb.a = hb.b - 1;
  hb.gap = headings_[hb.b] - headings_[hb.a];
  hb.w = (beta - headings_[hb.a]) / hb.gap;
  return hb;
}

std::string RaoTable::check(double omega, double heading_deg) const {
  if (omega_.empty()) return "the RAO table is empty";
  if (!std::isfinite(omega) || !std::isfinite(heading_deg)) return "frequency or heading not finite";
  if (extend == RaoExtend::None && (omega < omega_.front() || omega > omega_.back()))
    return "frequency " + num(omega) + " rad/s is outside the table's " + num(omega_.front()) + " to " +
           num(omega_.back()) + " rad/s";
  if (symmetry == RaoSymmetry::PortStarboard && headings_.back() > 180.0)
    return "symmetry port_starboard: the table has heading " + num(headings_.back()) + " deg, above 180";
  if (symmetry == RaoSymmetry::PortStarboard) {
    const double b = wrapDeg(heading_deg), folded = b > 180.0 ? 360.0 - b : b;
    if (folded < headings_.front() || folded > headings_.back())
      return "heading " + num(heading_deg) + " deg (" + num(folded) +
             " deg folded by the port-starboard symmetry) is outside the table's headings " +
             num(headings_.front()) + " to " + num(headings_.back()) + " deg";
  }
  const HeadingBracket hb = bracketHeading(heading_deg);
  const bool exact = std::any_of(headings_.begin(), headings_.end(), [&](double h) {
    const double b = wrapDeg(heading_deg);
    return h == b || (symmetry == RaoSymmetry::PortStarboard && h == 360.0 - b);
  });
  if (!exact && hb.gap > kMaxHeadingGapDeg)
    return "heading " + num(heading_deg) + " deg falls in a gap of " + num(hb.gap) +
           " deg between the table's headings (at most " + num(kMaxHeadingGapDeg) + " deg)";
  return {};
}

std::array<std::complex<double>, RaoTable::kDofs> RaoTable::at(double omega, double heading_deg) const {
  const std::string e = check(omega, heading_deg);
  if (!e.empty()) throw std::invalid_argument(e);
  std::array<std::complex<double>, kDofs> out{};
  if (omega < omega_.front() || omega > omega_.back()) {
    if (extend == RaoExtend::Zero) return out;
    omega = std::clamp(omega, omega_.front(), omega_.back());  // RaoExtend::Hold, by the file's choice
  }
  // Frequency bracket.
  std::size_t j1 = static_cast<std::size_t>(std::upper_bound(omega_.begin(), omega_.end(), omega) - omega_.begin());
  double wf = 0.0;
  std::size_t j0 = 0;
  if (j1 >= omega_.size()) {
    j0 = j1 = omega_.size() - 1;
  } else if (j1 == 0) {
    j0 = 0;
  } else {
    j0 = j1 - 1;
    wf = (omega - omega_[j0]) / (omega_[j1] - omega_[j0]);
  }
  const HeadingBracket hb = bracketHeading(heading_deg);
  for (int d = 0; d < kDofs; ++d) {
    const std::complex<double> va = (1.0 - wf) * value(d, hb.a, j0) + wf * value(d, hb.a, j1);
    const std::complex<double> vb = (1.0 - wf) * value(d, hb.b, j0) + wf * value(d, hb.b, j1);
    std::complex<double> v = (1.0 - hb.w) * va + hb.w * vb;
    if (hb.mirrored && flipsUnderMirror(d)) v = -v;
    out[d] = v;
  }
  return out;
}

}  // namespace core
}  // namespace mooring_dynamics
