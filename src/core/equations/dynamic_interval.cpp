#include "mooring_dynamics/core/equations/dynamic_interval.hpp"

#include <cmath>

namespace mooring_dynamics {
namespace core {
namespace eq2dyn {

namespace {

/// Distributed load (f1, f2) per unit length at a node (eqs. 1-2: wet weight less the seabed
/// reaction of eqs. 35-36 with the smoothed onset, drag on the velocity relative to the water)
/// and, when df1 is non-null, its gradient along the node's unknowns; distributedLoad and
/// seabedReaction of equations2d_dynamic.hpp differentiated by hand.
void nodeLoad(const Environment& env, const Material& m, const NodeView& nv, double& f1, double& f2, double* df1,
              double* df2) {
  const double* y = nv.y;
  const double c = nv.c, s = nv.s;
  const Water& w = *nv.w;
  // Seabed reaction F (eq. 35 spring, eq. 36 dashpot, both ramped over the contact onset).
  double F = 0.0, dF[N] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const double zb = env.seabedElevation(y[X]);
  if (y[Z] < zb) {
    const double delta = eq2d::contactOnset(env, m);
    const double slope = env.seabedSlope(y[X]);
    const double p = zb - y[Z];  // penetration; dp/dx = slope, dp/dz = -1
    const double k = env.seabed.stiffness;
    const bool onset = delta > 0.0 && p < delta;
    const double spring = onset ? k * p * p / (2.0 * delta) : k * (p - 0.5 * delta);
    double dFdp = onset ? k * p / delta : k;
    F = spring;
    if (spring > 0.0 && env.seabed.damping != 0.0) {
      const double b = env.seabed.damping;
      const double frac = onset ? p / delta : 1.0, dfrac = onset ? 1.0 / delta : 0.0;
      const double Vz = y[U] * c - y[V] * s;  // global vertical velocity
      F = spring - b * frac * Vz;
      dFdp -= b * dfrac * Vz;
      dF[U] = -b * frac * c;
      dF[V] = b * frac * s;
      dF[PHI] = b * frac * (y[U] * s + y[V] * c);
    }
    dF[X] = dFdp * slope;
    dF[Z] = -dFdp;
  }
  // Drag on the relative velocity (ur, vr) along t and n; the current depends on z.
  const double wx = waterX(w, y);
  const double wt = wx * s + w.wz * c, wn = wx * c - w.wz * s;
  const double ur = y[U] - wt, vr = y[V] - wn;
  const double stretch = std::sqrt(1.0 + y[EPS]);
  const double rho = env.water_density;
  const double weight = m.wet_weight - F;
  const double Kt = 0.5 * rho * m.diameter * eq2d::kPi * m.cdt;
  const double Kn = 0.5 * rho * m.diameter * m.cdn;
  const double qt = signedSquare(ur), qn = signedSquare(vr);
  f1 = -weight * c - Kt * qt * stretch;
  f2 = weight * s - Kn * qn * stretch;
  // Seabed friction along the line, -mu F ramp(u) (eq2d::frictionRamp).
  const bool friction = m.mu_axial > 0.0 && F > 0.0;
  const double ramp = friction ? eq2d::frictionRamp(y[U]) : 0.0;
  if (friction) f1 -= m.mu_axial * F * ramp;
  if (!df1) return;
  // Gradients: d(u|u|) = 2 |u| du; dstretch/deps = 1 / (2 stretch).
  const double gt = Kt * 2.0 * std::abs(ur) * stretch, gn = Kn * 2.0 * std::abs(vr) * stretch;
  for (int k = 0; k < N; ++k) {
    df1[k] = dF[k] * c;
    df2[k] = -dF[k] * s;
  }
  df1[PHI] += weight * s;
  df2[PHI] += weight * c;
  const double dst = 0.5 / stretch;
  df1[EPS] -= Kt * qt * dst;
  df2[EPS] -= Kn * qn * dst;
  df1[U] -= gt;                        // dur/du = 1
  df1[PHI] -= gt * (-wn);              // dur/dphi = -dwt/dphi = -wn
  df1[Z] -= gt * (-w.dwx_dz * s);      // dur/dz = -s dwx/dz
  df2[V] -= gn;                        // dvr/dv = 1
  df2[PHI] -= gn * wt;                 // dvr/dphi = -dwn/dphi = wt
  df2[Z] -= gn * (-w.dwx_dz * c);      // dvr/dz = -c dwx/dz
  if (friction) {
    for (int k = 0; k < N; ++k) df1[k] -= m.mu_axial * ramp * dF[k];
    df1[U] -= m.mu_axial * F * eq2d::frictionRampSlope(y[U]);
  }
}

/// Inertia rows 0-3 per unit length at a node (eq. 8 as in `inertia`), I = M(Y) Yd~, and when
/// dI is non-null its gradient along the node's unknowns: through the state Y when `state` is
/// true (the new level), and through the weighted rate (d Yd~_k / d Y_k = wr) always.
void nodeInertia(const Environment& env, const Material& m, const NodeView& nv, const double* yd, double wr,
                 bool state, double* I, double (*dI)[N]) {
  const double* y = nv.y;
  const double c = nv.c, s = nv.s;
  const Water& w = *nv.w;
  const double wx = waterX(w, y);
  const double wt = wx * s + w.wz * c;
  const double rhoA = 0.25 * env.water_density * eq2d::kPi * m.diameter * m.diameter;
  const double ra = rhoA + m.added_mass;
  const double G = m.mass * y[U] + ra * wt;
  I[0] = -m.mass * yd[U] + m.mass * y[V] * yd[PHI];                     // eq. 1
  I[1] = -(m.mass + m.added_mass) * yd[V] - G * yd[PHI];                // eq. 2
  I[2] = -yd[EPS];                                                      // eq. 3
  I[3] = -(1.0 + y[EPS]) * yd[PHI];                                     // eq. 4
  if (!dI) return;
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < N; ++k) dI[r][k] = 0.0;
  dI[0][U] = -m.mass * wr;
  dI[0][PHI] = m.mass * y[V] * wr;
  dI[1][V] = -(m.mass + m.added_mass) * wr;
  dI[1][PHI] = -G * wr;
  dI[2][EPS] = -wr;
  dI[3][PHI] = -(1.0 + y[EPS]) * wr;
  if (!state) return;
  const double wn = wx * c - w.wz * s;  // dwt/dphi
  dI[0][V] = m.mass * yd[PHI];
  dI[1][U] = -m.mass * yd[PHI];
  dI[1][PHI] -= ra * wn * yd[PHI];
  dI[1][Z] = -ra * w.dwx_dz * s * yd[PHI];
  dI[3][EPS] = -yd[PHI];
}

}  // namespace

void nodeLoadValue(const Environment& env, const Material& m, const NodeView& nv, double& f1, double& f2) {
  nodeLoad(env, m, nv, f1, f2, nullptr, nullptr);
}

void intervalSpatialRows(const Material& m, double h, const NodeView& a, const NodeView& b, double f1a, double f2a,
                         double f1b, double f2b, double* sp) {
  const double* Ya = a.y;
  const double* Yb = b.y;
  const double Ta = eq2d::tension(m, Ya[EPS]), Tb = eq2d::tension(m, Yb[EPS]);
  const double pa3 = 1.0 + Ya[EPS], pb3 = 1.0 + Yb[EPS];
  const double dphi = Yb[PHI] - Ya[PHI];
  sp[0] = Tb - Ta - 0.5 * (Ya[SN] + Yb[SN]) * dphi + 0.5 * h * (f1a + f1b);   // eq. 1
  sp[1] = Yb[SN] - Ya[SN] + 0.5 * (Ta + Tb) * dphi + 0.5 * h * (f2a + f2b);   // eq. 2
  sp[2] = Yb[U] - Ya[U] - 0.5 * (Ya[V] + Yb[V]) * dphi;                       // eq. 3
  sp[3] = Yb[V] - Ya[V] + 0.5 * (Ya[U] + Yb[U]) * dphi;                       // eq. 4
  sp[4] = dphi - 0.5 * h * (Ya[OMEGA] + Yb[OMEGA]);                           // eq. 5
  sp[5] = m.EI * (Yb[OMEGA] - Ya[OMEGA]) +
          0.5 * h * (Ya[SN] * pa3 * pa3 * pa3 + Yb[SN] * pb3 * pb3 * pb3);    // eq. 6
  sp[6] = Yb[X] - Ya[X] - 0.5 * h * (pa3 * a.s + pb3 * b.s);                  // eq. 42
  sp[7] = Yb[Z] - Ya[Z] - 0.5 * h * (pa3 * a.c + pb3 * b.c);
}

void nodeStepTerms(const Environment& env, const Material& m, const NodeView& now, const NodeView& prev,
                   const double* yd, const StepWeights& wts, bool jacobian, NodeTerms& out) {
  nodeLoad(env, m, now, out.f1, out.f2, jacobian ? out.df1 : nullptr, jacobian ? out.df2 : nullptr);
  // Inertia at both levels applied to the weighted rate (eq. 13).
  nodeInertia(env, m, now, yd, wts.wr, true, out.I, jacobian ? out.dI : nullptr);
  nodeInertia(env, m, prev, yd, wts.wr, false, out.Ip, jacobian ? out.dIp : nullptr);
}

void intervalStepRows(const Environment& env, const Material& m, double h, const NodeView& a, const NodeView& b,
                      const NodeView& pa, const NodeView& pb, const double* yda, const double* ydb,
                      const StepWeights& wts, const double* Sprev, double* R, double (*J)[2 * N]) {
  NodeTerms ta, tb;
  nodeStepTerms(env, m, a, pa, yda, wts, J != nullptr, ta);
  nodeStepTerms(env, m, b, pb, ydb, wts, J != nullptr, tb);
  intervalStepRows(m, h, a, b, ta, tb, wts, Sprev, R, J);
}

namespace {

using Block = double[N][2 * N];  ///< an interval's 8 rows on the 16 unknowns of its two nodes

/// Rows 0-1 of the spatial Jacobian: the loads' derivatives (nodeStepTerms), then the force
/// balance, eqs. 1 and 2 (h times K dY/ds + F on the half grid).
void forceBalanceJacobian(const Material& m, double hh, const double* Ya, const double* Yb, const NodeTerms& ta,
                          const NodeTerms& tb, Block& D) {
  const double Ta = eq2d::tension(m, Ya[EPS]), Tb = eq2d::tension(m, Yb[EPS]);
  const double dphi = Yb[PHI] - Ya[PHI];
  const double dTa = m.tensionSlope(Ya[EPS]), dTb = m.tensionSlope(Yb[EPS]);
  const double Snm = 0.5 * (Ya[SN] + Yb[SN]), Tm = 0.5 * (Ta + Tb);
  for (int k = 0; k < N; ++k) {
    D[0][k] = hh * ta.df1[k];
    D[0][N + k] = hh * tb.df1[k];
    D[1][k] = hh * ta.df2[k];
    D[1][N + k] = hh * tb.df2[k];
  }
  // eq. 1
  D[0][EPS] -= dTa;
  D[0][N + EPS] += dTb;
  D[0][SN] -= 0.5 * dphi;
  D[0][N + SN] -= 0.5 * dphi;
  D[0][PHI] += Snm;
  D[0][N + PHI] -= Snm;
  // eq. 2
  D[1][EPS] += 0.5 * dTa * dphi;
  D[1][N + EPS] += 0.5 * dTb * dphi;
  D[1][SN] -= 1.0;
  D[1][N + SN] += 1.0;
  D[1][PHI] -= Tm;
  D[1][N + PHI] += Tm;
}

/// Rows 2-5: velocity compatibility (eqs. 3, 4), the curvature (eq. 5) and the moment (eq. 6).
void compatibilityJacobian(const Material& m, double hh, const double* Ya, const double* Yb, Block& D) {
  const double pa3 = 1.0 + Ya[EPS], pb3 = 1.0 + Yb[EPS];
  const double dphi = Yb[PHI] - Ya[PHI];
  const double Vm = 0.5 * (Ya[V] + Yb[V]), Um = 0.5 * (Ya[U] + Yb[U]);
  // eq. 3
  D[2][U] = -1.0;
  D[2][N + U] = 1.0;
  D[2][V] = D[2][N + V] = -0.5 * dphi;
  D[2][PHI] = Vm;
  D[2][N + PHI] = -Vm;
  // eq. 4
  D[3][V] = -1.0;
  D[3][N + V] = 1.0;
  D[3][U] = D[3][N + U] = 0.5 * dphi;
  D[3][PHI] = -Um;
  D[3][N + PHI] = Um;
  // eq. 5
  D[4][PHI] = -1.0;
  D[4][N + PHI] = 1.0;
  D[4][OMEGA] = D[4][N + OMEGA] = -hh;
  // eq. 6
  D[5][OMEGA] = -m.EI;
  D[5][N + OMEGA] = m.EI;
  D[5][SN] = hh * pa3 * pa3 * pa3;
  D[5][N + SN] = hh * pb3 * pb3 * pb3;
  D[5][EPS] = hh * Ya[SN] * 3.0 * pa3 * pa3;
  D[5][N + EPS] = hh * Yb[SN] * 3.0 * pb3 * pb3;
}

/// Rows 6-7: the coordinates (eq. 42).
void coordinateJacobian(double hh, const NodeView& a, const NodeView& b, Block& D) {
  const double pa3 = 1.0 + a.y[EPS], pb3 = 1.0 + b.y[EPS];
  D[6][X] = -1.0;
  D[6][N + X] = 1.0;
  D[6][EPS] = -hh * a.s;
  D[6][N + EPS] = -hh * b.s;
  D[6][PHI] = -hh * pa3 * a.c;
  D[6][N + PHI] = -hh * pb3 * b.c;
  D[7][Z] = -1.0;
  D[7][N + Z] = 1.0;
  D[7][EPS] = -hh * a.c;
  D[7][N + EPS] = -hh * b.c;
  D[7][PHI] = hh * pa3 * a.s;
  D[7][N + PHI] = hh * pb3 * b.s;
}

/// The step's Jacobian from the spatial one D: the weighted rows (eq. 30) times 1 - alpha_k, plus
/// the inertia at both levels averaged over the nodes (eq. 13), alpha_k-weighted.
void stepJacobian(const Block& D, const NodeTerms& ta, const NodeTerms& tb, double hh, double ak, double (*J)[2 * N]) {
  const double wk = 1.0 - ak;
  for (int q = 0; q < N; ++q) {
    const double f = q < kWeightedRows ? wk : 1.0;
    for (int k = 0; k < 2 * N; ++k) J[q][k] = f * D[q][k];
  }
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k < N; ++k) {
      J[q][k] += hh * (wk * ta.dI[q][k] + ak * ta.dIp[q][k]);
      J[q][N + k] += hh * (wk * tb.dI[q][k] + ak * tb.dIp[q][k]);
    }
}

}  // namespace

void intervalStepRows(const Material& m, double h, const NodeView& a, const NodeView& b, const NodeTerms& ta,
                      const NodeTerms& tb, const StepWeights& wts, const double* Sprev, double* R, double (*J)[2 * N]) {
  const double ak = wts.ak, wk = 1.0 - ak, hh = 0.5 * h;
  // Spatial part K dY/ds + F times h (eqs. 1-6, 42 on the half grid, eq. 11).
  double sp[N];
  intervalSpatialRows(m, h, a, b, ta.f1, ta.f2, tb.f1, tb.f2, sp);
  // Inertia at both levels applied to the weighted rate, averaged over the nodes (eq. 13).
  for (int q = 0; q < N; ++q) {
    if (q < kWeightedRows) {
      const double in1 = q < 4 ? hh * (ta.I[q] + tb.I[q]) : 0.0;
      const double in0 = q < 4 ? hh * (ta.Ip[q] + tb.Ip[q]) : 0.0;
      R[q] = wk * in1 + ak * in0 + wk * sp[q] + ak * Sprev[q];  // eqs. 30-31 (alpha_k weights)
    } else {
      R[q] = sp[q];  // coordinates at the new level
    }
  }
  if (!J) return;
  // Jacobian of the spatial rows; columns k (node a) and N + k (node b).
  Block D;
  for (int q = 0; q < N; ++q)
    for (int k = 0; k < 2 * N; ++k) D[q][k] = 0.0;
  forceBalanceJacobian(m, hh, a.y, b.y, ta, tb, D);
  compatibilityJacobian(m, hh, a.y, b.y, D);
  coordinateJacobian(hh, a, b, D);
  stepJacobian(D, ta, tb, hh, ak, J);
}

}  // namespace eq2dyn
}  // namespace core
}  // namespace mooring_dynamics
