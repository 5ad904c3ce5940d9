// The 2-D ends (end_conditions.hpp): the anchor and the driven tops (position, force, surface buoy,
// subsurface body) in the x-z plane, and their factories. The 3-D ends: end_conditions3d.cpp.
#include <cmath>
#include <stdexcept>
#include <utility>

#include "mooring_dynamics/core/equations/end_conditions.hpp"
#include "mooring_dynamics/core/equations/equations2d_dynamic.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

// =================================================================================================
// 2-D ends
// =================================================================================================

using ADs = EndCondition2D::ADs;
using ADd = EndCondition2D::ADd;

/// The anchor (eq. 33 in statics, eq. 34 in dynamics): position fixed, moment free, at rest.
class Anchor2D : public EndCondition2D {
 public:
  explicit Anchor2D(const Problem& p) : p_(p) {}
  const char* name() const override { return "anchor"; }
  int staticRows() const override { return 3; }
  void staticResidual(const ADs* y, ADs* r) const override {
    using namespace eq2d;
    r[0] = y[X] - p_.anchor_x;
    r[1] = y[Z] - p_.anchor_z;
    r[2] = y[OMEGA];
  }
  int dynamicRows() const override { return 5; }
  void dynamicResidual(const TopState&, const ADd* y, ADd* r) const override {
    using namespace eq2dyn;
    r[0] = y[U];
    r[1] = y[V];
    r[2] = y[OMEGA];
    r[3] = y[X] - p_.anchor_x;
    r[4] = y[Z] - p_.anchor_z;
  }

 private:
  const Problem& p_;
};

/// A top in 2-D dynamics: moment free, and the top motion's velocity (eq. 34), its velocity with
/// the position error fed back, or its force (a force table's instants). The static rows are the
/// subclass's (position, force, surface buoy, subsurface body).
class DrivenTop2D : public EndCondition2D {
 public:
  DrivenTop2D(const Problem& p, const Material& m) : p_(p), m_(m), kappa_(feedbackGain(p)) {}
  int staticRows() const override { return 3; }
  int dynamicRows() const override { return 3; }
  void dynamicResidual(const TopState& in, const ADd* y, ADd* r) const override {
    using namespace eq2dyn;
    r[0] = y[OMEGA];
    if (in.force) {
      ADd Fx, Fz;
      internalForce(m_, y, Fx, Fz);
      r[1] = Fx - in.fx;
      r[2] = Fz - in.fz;
    } else if (p_.dynamics.top_motion.prescribe_position) {
      // The top's position is a constraint on the integral of the line's shape from the anchor,
      // which the generalized-alpha schemes with rho_inf > 0 do not damp when imposed directly (it
      // blew up within a second, test_dynamics2d); fed back through the velocity it decays with
      // time constant kPositionFeedbackSteps * dt, and the drift of the plain velocity condition
      // vanishes.
      ADd Vx, Vz;
      globalVelocity(y, Vx, Vz);
      r[1] = Vx - in.vx - kappa_ * (in.x - y[X]);
      r[2] = Vz - in.vz - kappa_ * (in.z - y[Z]);
    } else {
      ADd Vx, Vz;
      globalVelocity(y, Vx, Vz);
      r[1] = Vx - in.vx;
      r[2] = Vz - in.vz;
    }
  }

 protected:
  const Problem& p_;
  const Material& m_;

 private:
  double kappa_;
};

/// Top at a prescribed position (section 5.1).
class PositionTop2D : public DrivenTop2D {
 public:
  using DrivenTop2D::DrivenTop2D;
  const char* name() const override { return "position top"; }
  void staticResidual(const ADs* y, ADs* r) const override {
    using namespace eq2d;
    r[0] = y[OMEGA];
    r[1] = y[X] - p_.top.x;
    r[2] = y[Z] - p_.top.z;
  }
};

/// Top with a prescribed force: the line's internal force there equals it.
class ForceTop2D : public DrivenTop2D {
 public:
  using DrivenTop2D::DrivenTop2D;
  const char* name() const override { return "force top"; }
  double characteristicForce() const override { return std::hypot(p_.top.fx, p_.top.fz); }
  void staticResidual(const ADs* y, ADs* r) const override {
    using namespace eq2d;
    r[0] = y[OMEGA];
    ADs Fx, Fz;
    internalForce(m_, y, Fx, Fz);
    r[1] = Fx - p_.top.fx;
    r[2] = Fz - p_.top.fz;
  }
};

/// Surface buoy: the line's pull balances the buoy's net buoyancy at its draft, drag and wind.
class SurfaceBuoyTop2D : public DrivenTop2D {
 public:
  using DrivenTop2D::DrivenTop2D;
  const char* name() const override { return "surface buoy"; }
  void staticResidual(const ADs* y, ADs* r) const override {
    using namespace eq2d;
    r[0] = y[OMEGA];
    ADs Fx, Fz, Bx, Bz;
    internalForce(m_, y, Fx, Fz);
    buoyForce(p_.environment, p_.top.buoy, y[Z], Bx, Bz);
    r[1] = Fx - Bx;
    r[2] = Fz - Bz;
  }
};

/// A submerged body at the top: the line's pull balances its net buoyancy and drag.
/// (Problem::validate() keeps it to the 3-D model for now; the rows are the 2-D form.)
class SubsurfaceBodyTop2D : public DrivenTop2D {
 public:
  using DrivenTop2D::DrivenTop2D;
  const char* name() const override { return "subsurface body"; }
  void staticResidual(const ADs* y, ADs* r) const override {
    using namespace eq2d;
    r[0] = y[OMEGA];
    ADs Fx, Fz, Pt, Pn;
    internalForce(m_, y, Fx, Fz);
    bodyLoad(p_.environment, p_.bodies[p_.top.body], y[PHI], y[Z], Pt, Pn);
    r[1] = Fx - (Pt * sin(y[PHI]) + Pn * cos(y[PHI]));
    r[2] = Fz - (Pt * cos(y[PHI]) - Pn * sin(y[PHI]));
  }
};

}  // namespace

std::unique_ptr<EndCondition2D> makeLowerEnd2D(const Problem& problem) {
  return std::make_unique<Anchor2D>(problem);
}

std::unique_ptr<EndCondition2D> makeUpperEnd2D(const Problem& problem, const Material& top_material) {
  switch (problem.top.type) {
    case TopBoundary::Type::Position:
      return std::make_unique<PositionTop2D>(problem, top_material);
    case TopBoundary::Type::Force:
      return std::make_unique<ForceTop2D>(problem, top_material);
    case TopBoundary::Type::Buoy:
      return std::make_unique<SurfaceBuoyTop2D>(problem, top_material);
    case TopBoundary::Type::Body:
      return std::make_unique<SubsurfaceBodyTop2D>(problem, top_material);
  }
  throw std::logic_error("makeUpperEnd2D: unknown top type");
}

}  // namespace core
}  // namespace mooring_dynamics
