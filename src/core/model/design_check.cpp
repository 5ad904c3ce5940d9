// DNV-OS-E301-style line check (design_check.hpp).
#include "mooring_dynamics/core/model/design_check.hpp"

#include <stdexcept>

namespace mooring_dynamics {
namespace core {

DesignFactors dnvFactors(int consequence_class, LimitState state) {
  DesignFactors f;
  if (consequence_class == 1) {
    f.gamma_mean = state == LimitState::Uls ? 1.10 : 1.00;
    f.gamma_dyn = state == LimitState::Uls ? 1.50 : 1.10;
  } else if (consequence_class == 2) {
    f.gamma_mean = state == LimitState::Uls ? 1.40 : 1.00;
    f.gamma_dyn = state == LimitState::Uls ? 2.10 : 1.25;
  } else {
    throw std::invalid_argument("consequence_class = " + std::to_string(consequence_class) + ": must be 1 or 2");
  }
  return f;
}

DesignCheck designCheck(double mean_tension, double mpm, double mbl, const DesignFactors& f) {
  DesignCheck c;
  c.t_mean = mean_tension;
  c.t_dyn = mpm - mean_tension;
  c.design_tension = f.gamma_mean * c.t_mean + f.gamma_dyn * c.t_dyn;
  c.strength = f.strength_factor * mbl;
  c.utilization = c.design_tension / c.strength;
  c.pass = c.design_tension <= c.strength;
  return c;
}

const char* toString(LimitState s) { return s == LimitState::Uls ? "ULS" : "ALS"; }

}  // namespace core
}  // namespace mooring_dynamics
