// Readers of motion RAO tables (core/model/rao.hpp; docs/problem_format.md "vessel.raos").
//  * WAMIT `.4` (the numeric motion output of WAMIT and of codes that write its format):
//    whitespace-separated rows PER BETA I |X| phase Re(X) Im(X): the wave period [s], the heading
//    [deg], the mode 1-6, and the nondimensional RAO, translations X / A and rotations X L / A
//    with L the run's ULEN. Re and Im are used; every (period, heading) needs all six modes.
//  * CSV: rows omega [rad/s], heading_deg, dof (1-6), amplitude (m per m; rotations in rad per m,
//    or deg per m), phase_deg; a header line starting with a letter and '#' comments are skipped.
// Drift coefficient tables (core/model/wave_drift.hpp), read into a RaoTable of real SI values
// (surge, sway [N per m^2 of wave amplitude], yaw [N m per m^2]; modes 3-5 zero unless given):
//  * WAMIT `.8` (momentum) or `.9` (pressure integration) mean drift: rows PER BETA1 BETA2 I |F|
//    phase Re(F) Im(F), forces F / (rho g A^2 L), moments F / (rho g A^2 L^2), L = ULEN; the rows
//    with BETA1 = BETA2 are used (the mean drift of unidirectional waves), Re(F) the value.
//  * CSV: rows omega [rad/s], heading_deg, surge, sway, yaw (SI, per m^2 of wave amplitude).
// Phases are leads (rao.hpp) unless RaoSource::phase_lag. Headings are taken modulo 360 deg; a
// heading given twice (0 and 360) must carry the same values.
#pragma once

#include <string>

#include "mooring_dynamics/core/model/rao.hpp"

namespace mooring_dynamics {
namespace core {

/// Parse a WAMIT `.4` text. Throws ProblemError naming `source`, the line and the constraint.
RaoTable parseWamitRaos(const std::string& text, const std::string& source, const RaoSource& how);
/// Parse the CSV form. Throws ProblemError naming `source`, the line and the constraint.
RaoTable parseCsvRaos(const std::string& text, const std::string& source, const RaoSource& how);
/// Parse a WAMIT `.8`/`.9` mean drift text into SI with rho_g = rho g [N/m^3]. Throws ProblemError
/// naming `source`, the line and the constraint (surge, sway and yaw needed at every frequency and
/// heading).
RaoTable parseWamitDrift(const std::string& text, const std::string& source, const RaoSource& how, double rho_g);
/// Parse the drift CSV form (SI). Throws ProblemError naming `source`, the line and the constraint.
RaoTable parseCsvDrift(const std::string& text, const std::string& source, const RaoSource& how);
/// Read a drift table how.file in how.format (rho_g for WAMIT's scaling).
RaoTable loadDrift(const RaoSource& how, double rho_g);
/// Read how.file in how.format; the table carries how.extend and how.symmetry.
RaoTable loadRaos(const RaoSource& how);

}  // namespace core
}  // namespace mooring_dynamics
