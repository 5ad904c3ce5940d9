// Closed-form elastic catenary of a single homogeneous line (Irvine, "Cable Structures", 1981),
// with or without a frictionless grounded stretch on a flat seabed. Used as an independent
// reference for the box-scheme solver.
#pragma once

namespace mooring_dynamics {
namespace core {

struct CatenaryInput {
  double L = 0.0;    ///< unstretched length [m]
  double w = 0.0;    ///< wet weight per unstretched length [N/m], > 0
  double EA = 0.0;   ///< axial stiffness [N]
  double X = 0.0;    ///< horizontal distance anchor -> top [m], > 0
  double Z = 0.0;    ///< height of the top above the anchor [m], > 0
  bool seabed = false;  ///< anchor on a flat frictionless seabed: line may lie on it
};

struct CatenarySolution {
  double H = 0.0;       ///< horizontal tension [N]
  double V = 0.0;       ///< vertical force at the top [N]
  double Va = 0.0;      ///< vertical force at the anchor [N] (0 when grounded)
  double grounded = 0.0;///< length lying on the seabed [m]
  bool converged = false;
  double topTension() const;
  double anchorTension() const;  ///< tension at the anchor [N]
};

/// Position of the top relative to the anchor for given (H, V) (Irvine's equations).
void catenaryEnd(const CatenaryInput& in, double H, double V, double& X, double& Z);

/// Solve for (H, V) that put the top at (X, Z). Newton with a finite-difference Jacobian.
CatenarySolution solveCatenary(const CatenaryInput& in);

}  // namespace core
}  // namespace mooring_dynamics
