// The 3-D ends (end_conditions.hpp): anchors (fixed, moving), free ends, driven tops (position,
// force, surface buoy), subsurface and drifting buoys, the tow point, released ends; their
// factories. The 2-D ends: end_conditions2d.cpp.
#include "mooring_dynamics/core/equations/end_conditions.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "mooring_dynamics/core/equations/equations3d_drifter.hpp"

namespace mooring_dynamics {
namespace core {

namespace {

/// A constant of scalar type S: zero derivatives, or the plain value.
template <class S>
S constantOf(double v) {
  if constexpr (std::is_same_v<S, double>) {
    return v;
  } else {
    S a(v);
    a.derivatives().setZero();
    return a;
  }
}

// =================================================================================================
// 3-D ends
// =================================================================================================

using AD = EndCondition3D::AD;

/// The double and AD forms of dynamicResidual from one template `rows` of the subclass.
template <class Derived>
class DynamicForms3D : public EndCondition3D {
 public:
  void dynamicResidual(const DynamicEnd3D& c, const double* y, double* r) const override {
    static_cast<const Derived*>(this)->rows(c, y, r);
  }
  void dynamicResidual(const DynamicEnd3D& c, const AD* y, AD* r) const override {
    static_cast<const Derived*>(this)->rows(c, y, r);
  }
};

/// The rows every 3-D lower end ends with, from row k: bending-moment free (Omega2 = Omega3 = 0,
/// eq. 33), unit frame, and no twist about the tangent relative to the frame q_ref.
template <class S>
void lowerEndGauge(const double* q_ref, const S* y, S* r) {
  using namespace eq3d;
  r[0] = y[O2];
  r[1] = y[O3];
  r[2] = normDefect(y);
  r[3] = twistGauge(q_ref, y);
}

/// The rows every 3-D top starts with: moment free (Omega1 = Omega2 = Omega3 = 0, eq. 33).
template <class S>
void topMomentFree(const S* y, S* r) {
  using namespace eq3d;
  r[0] = y[O1];
  r[1] = y[O2];
  r[2] = y[O3];
}

/// The anchor (DESIGN.md section 3, eq. 34 in 3-D): at rest, fixed, bending-moment free, unit
/// frame, twist held (to the initial guess's frame in statics, the last level's in dynamics).
class Anchor3D : public DynamicForms3D<Anchor3D> {
 public:
  explicit Anchor3D(const Problem& p) : p_(p) {}
  const char* name() const override { return "anchor"; }
  int staticRows() const override { return 10; }
  void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const override {
    restAtAnchor(y, r);
    lowerEndGauge(c.q_ref, y, r + 6);
  }
  int dynamicRows() const override { return 10; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    restAtAnchor(y, r);
    lowerEndGauge(c.yp + eq3d::Q0, y, r + 6);
  }

 protected:
  template <class S>
  void restAtAnchor(const S* y, S* r) const {
    using namespace eq3d;
    r[0] = y[U1];
    r[1] = y[U2];
    r[2] = y[U3];
    r[3] = y[X] - p_.anchor_x;
    r[4] = y[Y] - p_.anchor_y;
    r[5] = y[Z] - p_.anchor_z;
  }
  const Problem& p_;
};

/// A moving anchor (a line's lower end on a free point or a vessel of a system): its global
/// velocity and position prescribed by the motion, as a fixed anchor's are; the anchor in statics.
class MovingAnchor3D : public EndCondition3D {
 public:
  MovingAnchor3D(const Problem& p, std::function<TopState(double)> motion) : anchor_(p), motion_(std::move(motion)) {}
  const char* name() const override { return "moving anchor"; }
  int staticRows() const override { return anchor_.staticRows(); }
  void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const override { anchor_.staticResidual(c, y, r); }
  int dynamicRows() const override { return 10; }
  void dynamicResidual(const DynamicEnd3D& c, const double* y, double* r) const override { rows(c, y, r); }
  void dynamicResidual(const DynamicEnd3D& c, const AD* y, AD* r) const override { rows(c, y, r); }

 private:
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    using namespace eq3d;
    const TopState b = motion_(c.t);
    S V[3];
    globalVelocity(y, V);
    r[0] = V[0] - b.vx;
    r[1] = V[1] - b.vy;
    r[2] = V[2] - b.vz;
    r[3] = y[X] - b.x;
    r[4] = y[Y] - b.y;
    r[5] = y[Z] - b.z;
    lowerEndGauge(c.yp + Q0, y, r + 6);
  }
  Anchor3D anchor_;
  std::function<TopState(double)> motion_;
};

/// A free lower end (towing, drifting; section 5.2) with or without a body: the body's force
/// balance instead of rest and position. In dynamics the balance has the body's inertia and is
/// weighted in time like the junction force rows (eq. 30), so the end keeps its spatial part at
/// the accepted level.
class FreeEnd3D : public DynamicForms3D<FreeEnd3D> {
 public:
  FreeEnd3D(const Problem& p, const Material& m) : p_(p), m_(m) {}
  const char* name() const override { return p_.end_body == Problem::kNoBody ? "free end" : "free end with body"; }
  int staticRows() const override { return 10; }
  void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const override {
    using namespace eq3d;
    r[0] = y[U1];
    r[1] = y[U2];
    r[2] = y[U3];
    freeEndForces(p_, m_, y, *c.water, r + 3);
    lowerEndGauge(c.q_ref, y, r + 6);
  }
  int dynamicRows() const override { return 7; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    using namespace eq3d;
    const auto [am, ak, c1, c0] = c.w;
    S yd[N], yp[N], in1[3], in0[3];
    for (int k = 0; k < N; ++k) {
      yd[k] = (1.0 - am) * (c1 * (y[k] - c.yp[k]) - c0 * c.ydp[k]) + am * c.ydp[k];
      yp[k] = constantOf<S>(c.yp[k]);
    }
    freeEndForces(p_, m_, y, *c.water, r);
    freeEndInertia(p_, y, yd, in1);
    freeEndInertia(p_, yp, yd, in0);
    for (int q = 0; q < 3; ++q) r[q] = (1.0 - ak) * (in1[q] + r[q]) + ak * (in0[q] + S_[q]);
    lowerEndGauge(c.yp + Q0, y, r + 3);
  }
  void acceptLevel(const double* y, const eq3d::Water& w, double, const std::function<TopState(double)>&) override {
    eq3d::freeEndForces(p_, m_, y, w, S_);
  }
  std::vector<double> state() const override { return {S_[0], S_[1], S_[2]}; }
  void setState(const std::vector<double>& s) override {
    for (int i = 0; i < 3; ++i) S_[i] = s.at(static_cast<std::size_t>(i));
  }

 private:
  const Problem& p_;
  const Material& m_;
  double S_[3] = {0.0, 0.0, 0.0};  ///< spatial part of the balance at the accepted level [N]
};

/// The velocity rows of a driven top (eq. 34) from row 0: V - v - kappa (x - y_x). With a winch
/// paying out at dL/dt the line runs through the top, and V is the velocity of the material
/// there: V - (v - dL/dt m) - kappa (x - y_x), m the top interval's mean (1 + eps) e1 (as the
/// coordinates row, eq. 42, has it), the node below taken at the previous level (docs/method.md
/// "Winch").
template <class S>
void prescribedVelocity(const DynamicEnd3D& c, double kappa, const S* y, S* r) {
  using namespace eq3d;
  const TopState& in = *c.input;
  S V[3];
  globalVelocity(y, V);
  const double v[3] = {in.vx, in.vy, in.vz};
  const double x[3] = {in.x, in.y, in.z};
  for (int i = 0; i < 3; ++i) r[i] = V[i] - v[i] - kappa * (x[i] - y[X + i]);
  if (c.payout == 0.0) return;
  S R[9];
  quat::matrix(y + Q0, R);
  double Rb[9] = {0.0}, pb = 0.0;
  if (c.below) {
    quat::matrix(c.below + Q0, Rb);
    pb = 1.0 + c.below[EPS];
  }
  const double wb = c.below ? 0.5 : 0.0;  // weight of the node below in the mean
  for (int i = 0; i < 3; ++i)
    r[i] += c.payout * ((1.0 - wb) * (1.0 + y[EPS]) * R[3 * i] + wb * pb * Rb[3 * i]);
}

/// The force rows of a top with the force prescribed from row 0: the internal force equals it.
template <class S>
void prescribedForce(const Material& m, const double* f, const S* y, S* r) {
  S F[3];
  eq3d::internalForce(m, y, F);
  r[0] = F[0] - f[0];
  r[1] = F[1] - f[1];
  r[2] = F[2] - f[2];
}

/// A top in 3-D dynamics over an anchored line: moment free, and the top motion's velocity
/// (eq. 34), with the position error fed back (as in 2-D), or a force table's force. The static
/// rows are the subclass's (position, force, surface buoy).
class DrivenTop3D : public DynamicForms3D<DrivenTop3D> {
 public:
  DrivenTop3D(const Problem& p, const Material& m) : p_(p), m_(m), kappa_(feedbackGain(p)) {}
  int staticRows() const override { return 6; }
  int dynamicRows() const override { return 6; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    topMomentFree(y, r);
    const TopState& in = *c.input;
    if (in.force) {
      const double f[3] = {in.fx, in.fy, in.fz};
      prescribedForce(m_, f, y, r + 3);
    } else {
      const double kappa = c.winch ? 1.0 / (kPositionFeedbackSteps * p_.dynamics.dt) : kappa_;
      prescribedVelocity(c, kappa, y, r + 3);
    }
  }

 protected:
  const Problem& p_;
  const Material& m_;

 private:
  double kappa_;
};

class PositionTop3D : public DrivenTop3D {
 public:
  using DrivenTop3D::DrivenTop3D;
  const char* name() const override { return "position top"; }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override { positionRows(p_.top, y, r); }
  /// Moment free and at the prescribed position (the tow point's static rows too).
  template <class S>
  static void positionRows(const TopBoundary& tb, const S* y, S* r) {
    using namespace eq3d;
    topMomentFree(y, r);
    r[3] = y[X] - tb.x;
    r[4] = y[Y] - tb.y;
    r[5] = y[Z] - tb.z;
  }
};

class ForceTop3D : public DrivenTop3D {
 public:
  using DrivenTop3D::DrivenTop3D;
  const char* name() const override { return "force top"; }
  double characteristicForce() const override {
    const TopBoundary& tb = p_.top;
    return std::sqrt(tb.fx * tb.fx + tb.fy * tb.fy + tb.fz * tb.fz);
  }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override {
    topMomentFree(y, r);
    const double f[3] = {p_.top.fx, p_.top.fy, p_.top.fz};
    prescribedForce(m_, f, y, r + 3);
  }
};

/// The line's pull balances the surface buoy's net buoyancy, drag and wind (statics, rows 3-5).
void surfaceBuoyBalance(const Problem& p, const Material& m, const AD* y, AD* r) {
  AD F[3], B[3];
  eq3d::internalForce(m, y, F);
  eq3d::buoyForce(p.environment, p.top.buoy, y[eq3d::Z], B);
  for (int i = 0; i < 3; ++i) r[i] = F[i] - B[i];
}

class SurfaceBuoyTop3D : public DrivenTop3D {
 public:
  using DrivenTop3D::DrivenTop3D;
  const char* name() const override { return "surface buoy"; }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override {
    topMomentFree(y, r);
    surfaceBuoyBalance(p_, m_, y, r + 3);
  }
};

/// A point body at the top whose balance is weighted in time (eq. 30) in dynamics: the
/// generalized-alpha form (1 - ak)(inertia + spatial) + ak (inertia + spatial) at the last level,
/// whose spatial part it keeps.
class WeightedTopBody3D : public EndCondition3D {
 public:
  std::vector<double> state() const override { return {S_[0], S_[1], S_[2]}; }
  void setState(const std::vector<double>& s) override {
    for (int i = 0; i < 3; ++i) S_[i] = s.at(static_cast<std::size_t>(i));
  }

 protected:
  /// An external force on the body [N]: a force table's, else none.
  static void extraForce(const TopState& in, double* extra) {
    extra[0] = in.force ? in.fx : 0.0;
    extra[1] = in.force ? in.fy : 0.0;
    extra[2] = in.force ? in.fz : 0.0;
  }
  double S_[3] = {0.0, 0.0, 0.0};  ///< spatial part of the balance at the accepted level [N]
};

/// Subsurface buoy at the top (TopBoundary::Body): its force balance, with its inertia in
/// dynamics, weighted in time like the junction rows; a force table adds an external force.
class SubsurfaceBodyTop3D : public WeightedTopBody3D {
 public:
  SubsurfaceBodyTop3D(const Problem& p, const Material& m) : p_(p), m_(m) {}
  const char* name() const override { return "subsurface body"; }
  int staticRows() const override { return 6; }
  void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const override {
    topMomentFree(y, r);
    const double none[3] = {0.0, 0.0, 0.0};
    eq3d::topBodyForces(p_, m_, y, *c.water, none, r + 3);
  }
  int dynamicRows() const override { return 6; }
  void dynamicResidual(const DynamicEnd3D& c, const double* y, double* r) const override { rows(c, y, r); }
  void dynamicResidual(const DynamicEnd3D& c, const AD* y, AD* r) const override { rows(c, y, r); }
  void acceptLevel(const double* y, const eq3d::Water& w, double t,
                   const std::function<TopState(double)>& top) override {
    double extra[3];
    extraForce(top(t), extra);
    eq3d::topBodyForces(p_, m_, y, w, extra, S_);
  }

 private:
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    using namespace eq3d;
    const auto [am, ak, c1, c0] = c.w;
    topMomentFree(y, r);
    S yd[N], yp[N], sp[3], in1[3], in0[3];
    for (int k = 0; k < N; ++k) {
      yd[k] = (1.0 - am) * (c1 * (y[k] - c.yp[k]) - c0 * c.ydp[k]) + am * c.ydp[k];
      yp[k] = constantOf<S>(c.yp[k]);
    }
    double extra[3];
    extraForce(*c.input, extra);
    topBodyForces(p_, m_, y, *c.water, extra, sp);
    topBodyInertia(p_, y, yd, in1);
    topBodyInertia(p_, yp, yd, in0);
    for (int i = 0; i < 3; ++i) r[3 + i] = (1.0 - ak) * (in1[i] + sp[i]) + ak * (in0[i] + S_[i]);
  }
  const Problem& p_;
  const Material& m_;
};

/// Drifting buoy (a surface buoy over a free lower end, drifting.hpp). Statics: the buoy held
/// horizontally in the drifting frame (the horizontal balance is the outer iteration's residual)
/// and its draft balance vertically. Dynamics: its force balance with inertia, weighted in time
/// like the subsurface body's rows; then the top node's kinematics dx_n/dt = V_n in
/// generalized-alpha form (the weighted rate of x_n against the alpha_k-weighted global
/// velocity), which with both ends free is all that fixes where the line is.
class DriftingBuoy3D : public WeightedTopBody3D {
 public:
  DriftingBuoy3D(const Problem& p, const Material& m) : p_(p), m_(m) {}
  const char* name() const override { return "drifting buoy"; }
  int staticRows() const override { return 6; }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override {
    using namespace eq3d;
    topMomentFree(y, r);
    surfaceBuoyBalance(p_, m_, y, r + 3);
    r[3] = y[X] - p_.top.x;
    r[4] = y[Y] - p_.top.y;
  }
  int dynamicRows() const override { return 9; }
  void dynamicResidual(const DynamicEnd3D& c, const double* y, double* r) const override { rows(c, y, r); }
  void dynamicResidual(const DynamicEnd3D& c, const AD* y, AD* r) const override { rows(c, y, r); }
  void acceptLevel(const double* y, const eq3d::Water&, double t,
                   const std::function<TopState(double)>& top) override {
    double extra[3];
    extraForce(top(t), extra);
    eq3d::driftBuoyForces(p_.environment, p_.top.buoy, m_, y, extra, S_);
  }

 private:
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    using namespace eq3d;
    const auto [am, ak, c1, c0] = c.w;
    topMomentFree(y, r);
    S yd[N], ydw[N], yp[N], sp[3], in1[3], in0[3], V1[3], V0[3];
    for (int k = 0; k < N; ++k) {
      yd[k] = c1 * (y[k] - c.yp[k]) - c0 * c.ydp[k];
      ydw[k] = (1.0 - am) * yd[k] + am * c.ydp[k];
      yp[k] = constantOf<S>(c.yp[k]);
    }
    double extra[3];
    extraForce(*c.input, extra);
    const SurfaceBuoy& b = p_.top.buoy;
    driftBuoyForces(p_.environment, b, m_, y, extra, sp);
    driftBuoyInertia(b, y, ydw, in1);
    driftBuoyInertia(b, yp, ydw, in0);
    globalVelocity(y, V1);
    globalVelocity(yp, V0);
    for (int i = 0; i < 3; ++i) {
      r[3 + i] = (1.0 - ak) * (in1[i] + sp[i]) + ak * (in0[i] + S_[i]);
      r[6 + i] = ydw[X + i] - ((1.0 - ak) * V1[i] + ak * V0[i]);
    }
  }
  const Problem& p_;
  const Material& m_;
};

/// The tow point (the top over a free lower end, sections 5.2 and 7.1): at the prescribed
/// position in statics (the steady tow in the frame moving with it); in dynamics its velocity
/// (eq. 34, no position feedback) and its position are both prescribed, three more rows than a
/// top over an anchor, for the three the free end does not have.
class TowPoint3D : public DynamicForms3D<TowPoint3D> {
 public:
  TowPoint3D(const Problem& p, const Material& m) : p_(p), m_(m) {}
  const char* name() const override { return "tow point"; }
  int staticRows() const override { return 6; }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override {
    PositionTop3D::positionRows(p_.top, y, r);
  }
  int dynamicRows() const override { return 9; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    using namespace eq3d;
    topMomentFree(y, r);
    const TopState& in = *c.input;
    if (in.force) {
      // (A force table on a tow point: the force rows with the position rows below.)
      const double f[3] = {in.fx, in.fy, in.fz};
      prescribedForce(m_, f, y, r + 3);
    } else {
      constexpr double kNoFeedback = 0.0;  // the position is prescribed by rows 6-8 itself
      prescribedVelocity(c, kNoFeedback, y, r + 3);
    }
    const double x[3] = {in.x, in.y, in.z};
    for (int i = 0; i < 3; ++i) r[6 + i] = y[X + i] - x[i];
  }

 private:
  const Problem& p_;
  const Material& m_;
};

/// The rows of a free end's kinematics, dx/dt = V at its node, in generalized-alpha form (the
/// weighted rate of x against the alpha_k-weighted global velocity, as the drifting buoy's rows
/// 6-8): in a part of a line with no end held in place, all that fixes where the part is.
template <class S>
void freeKinematics(const DynamicEnd3D& c, const S* y, S* r) {
  using namespace eq3d;
  const auto [am, ak, c1, c0] = c.w;
  S yp[N], V1[3], V0[3];
  for (int k = 0; k < N; ++k) yp[k] = constantOf<S>(c.yp[k]);
  globalVelocity(y, V1);
  globalVelocity(yp, V0);
  for (int i = 0; i < 3; ++i) {
    const S ydw = (1.0 - am) * (c1 * (y[X + i] - c.yp[X + i]) - c0 * c.ydp[X + i]) + am * c.ydp[X + i];
    r[i] = ydw - ((1.0 - ak) * V1[i] + ak * V0[i]);
  }
}

/// A released (let-go or parted) upper end: moment free and no force, F = 0 at the new level;
/// with `kinematics` (a part whose lower end holds no position either: a towed line's) also
/// dx/dt = V, 9 rows instead of 6.
class ReleasedTop3D : public DynamicForms3D<ReleasedTop3D> {
 public:
  ReleasedTop3D(const Material& m, bool kinematics) : m_(m), kinematics_(kinematics) {}
  const char* name() const override { return "released top"; }
  int staticRows() const override { return 6; }
  void staticResidual(const StaticEnd3D&, const AD* y, AD* r) const override {
    topMomentFree(y, r);
    eq3d::internalForce(m_, y, r + 3);
  }
  int dynamicRows() const override { return kinematics_ ? 9 : 6; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    topMomentFree(y, r);
    eq3d::internalForce(m_, y, r + 3);
    if (kinematics_) freeKinematics(c, y, r + 6);
  }

 private:
  const Material& m_;
  bool kinematics_;
};

/// A released lower end (an anchor let go, the upper part of a parted line): no force, F = 0,
/// bending-moment free with the lower end's gauge, and, with `kinematics` (the part's top holds
/// no position: a top driven by velocity, a body), dx/dt = V: 10 rows as the anchor's, else 7 as
/// a free end's under a tow point.
class ReleasedLowerEnd3D : public DynamicForms3D<ReleasedLowerEnd3D> {
 public:
  ReleasedLowerEnd3D(const Material& m, bool kinematics) : m_(m), kinematics_(kinematics) {}
  const char* name() const override { return "released lower end"; }
  int staticRows() const override { return 10; }
  void staticResidual(const StaticEnd3D& c, const AD* y, AD* r) const override {
    using namespace eq3d;
    r[0] = y[U1];
    r[1] = y[U2];
    r[2] = y[U3];
    internalForce(m_, y, r + 3);
    lowerEndGauge(c.q_ref, y, r + 6);
  }
  int dynamicRows() const override { return kinematics_ ? 10 : 7; }
  template <class S>
  void rows(const DynamicEnd3D& c, const S* y, S* r) const {
    eq3d::internalForce(m_, y, r);
    lowerEndGauge(c.yp + eq3d::Q0, y, r + 3);
    if (kinematics_) freeKinematics(c, y, r + 7);
  }

 private:
  const Material& m_;
  bool kinematics_;
};

}  // namespace

// --- Factories -------------------------------------------------------------------------------------

std::unique_ptr<EndCondition3D> makeLowerEnd3D(const Problem& problem, const Material& end_material) {
  if (problem.lower_end == Problem::LowerEnd::Free) return std::make_unique<FreeEnd3D>(problem, end_material);
  return std::make_unique<Anchor3D>(problem);
}

std::unique_ptr<EndCondition3D> makeMovingAnchor3D(const Problem& problem, std::function<TopState(double)> motion) {
  return std::make_unique<MovingAnchor3D>(problem, std::move(motion));
}

std::unique_ptr<EndCondition3D> makeUpperEnd3D(const Problem& problem, const Material& top_material) {
  const bool free_below = problem.lower_end == Problem::LowerEnd::Free;
  switch (problem.top.type) {
    case TopBoundary::Type::Position:
      if (free_below) return std::make_unique<TowPoint3D>(problem, top_material);
      return std::make_unique<PositionTop3D>(problem, top_material);
    case TopBoundary::Type::Force:
      return std::make_unique<ForceTop3D>(problem, top_material);
    case TopBoundary::Type::Buoy:
      if (free_below) return std::make_unique<DriftingBuoy3D>(problem, top_material);
      return std::make_unique<SurfaceBuoyTop3D>(problem, top_material);
    case TopBoundary::Type::Body:
      return std::make_unique<SubsurfaceBodyTop3D>(problem, top_material);
  }
  throw std::logic_error("makeUpperEnd3D: unknown top type");
}

std::unique_ptr<EndCondition3D> makeReleasedUpperEnd3D(const Material& top_material, int rows) {
  if (rows != 6 && rows != 9) throw std::logic_error("makeReleasedUpperEnd3D: rows must be 6 or 9");
  return std::make_unique<ReleasedTop3D>(top_material, rows == 9);
}

std::unique_ptr<EndCondition3D> makeReleasedLowerEnd3D(const Material& end_material, int rows) {
  if (rows != 10 && rows != 7) throw std::logic_error("makeReleasedLowerEnd3D: rows must be 10 or 7");
  return std::make_unique<ReleasedLowerEnd3D>(end_material, rows == 10);
}

}  // namespace core
}  // namespace mooring_dynamics
