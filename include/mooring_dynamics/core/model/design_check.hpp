// The ultimate- and accidental-limit-state check of a mooring line in the form of DNV-OS-E301
// (Position Mooring, Ch. 2 Sec. 2, "Design equation" and the partial safety factor tables):
//
//   design tension     T_d = gamma_mean T_c,mean + gamma_dyn T_c,dyn
//   design equation    S_c - T_d >= 0,  S_c = 0.95 MBL (the characteristic strength of a chain,
//                      wire or fibre rope from its minimum breaking strength)
//
// with T_c,mean the characteristic mean tension (pretension and mean environmental loads: the
// storm's mean top tension over its seeds) and T_c,dyn the characteristic dynamic tension, the
// most probable maximum of the storm less the mean (MPM - T_c,mean). Partial factors for a
// dynamic analysis as this package reads the standard's tables (the user can set them):
//   ULS, consequence class 1: gamma_mean 1.10, gamma_dyn 1.50;  class 2: 1.40, 2.10
//   ALS (one line broken), class 1: 1.00, 1.10;                  class 2: 1.00, 1.25
// Left out: the quasi-static factors, the rule for T_c,mean > 2/3 T_c,dyn of newer editions,
// fatigue (FLS), anchors, and the transient motion after a line breaks.
#pragma once

#include <string>

namespace mooring_dynamics {
namespace core {

enum class LimitState { Uls, Als };

struct DesignFactors {
  double gamma_mean = 1.10;       ///< on the characteristic mean tension [-], > 0
  double gamma_dyn = 1.50;        ///< on the characteristic dynamic tension [-], > 0
  double strength_factor = 0.95;  ///< S_c = strength_factor * MBL [-], in (0, 1]
};

/// The factors of DNV-OS-E301 for a dynamic analysis: consequence class 1 or 2, ULS or ALS.
/// Throws std::invalid_argument for another class.
DesignFactors dnvFactors(int consequence_class, LimitState state);

struct DesignCheck {
  double t_mean = 0.0;          ///< T_c,mean [N]
  double t_dyn = 0.0;           ///< T_c,dyn = MPM - T_c,mean [N] (>= 0 for an MPM above the mean)
  double design_tension = 0.0;  ///< T_d [N]
  double strength = 0.0;        ///< S_c [N]
  double utilization = 0.0;     ///< T_d / S_c [-]
  bool pass = false;            ///< T_d <= S_c
};

/// The check of one line in one storm: mean tension and MPM [N], MBL [N] > 0.
DesignCheck designCheck(double mean_tension, double mpm, double mbl, const DesignFactors& f);

/// "ULS" or "ALS".
const char* toString(LimitState s);

}  // namespace core
}  // namespace mooring_dynamics
