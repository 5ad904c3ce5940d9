// The hand-coded rows and Jacobian of a dynamic half-grid interval (dynamic_interval.hpp), and
// its spatial rows alone, against the AutoDiff templates of equations2d_dynamic.hpp they replace,
// assembled as the step residual (eq. 30 with the mass matrix averaged by alpha_k, eq. 31): in
// and out of seabed contact (the smoothed onset and beyond it, with the dashpot, on a sloping
// bottom), with a depth-dependent current and waves, for a linear and a tabulated tension law.
// The finite difference check of the assembled step Jacobian is in test_dynamics2d.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <random>

#include "mooring_dynamics/core/equations/dynamic_interval.hpp"

using namespace mooring_dynamics::core;
using namespace mooring_dynamics::core::eq2dyn;

namespace {

using AD16 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 2 * N, 1>>;

// Same arithmetic up to reordering: values and slopes agree to rounding of the largest term.
constexpr double kValueRelTol = 1e-12;
constexpr double kSlopeRelTol = 1e-10;

Environment environment() {
  Environment env;
  env.depth = 50.0;
  env.seabed.stiffness = 1e5;
  env.seabed.damping = 650.0;
  env.seabed.profile = {{0.0, 50.0}, {100.0, 40.0}};  // bottom rising 0.1 toward +x
  return env;
}

constexpr double kFrictionSpeedForTest = eq2d::kFrictionSpeed;

Material chain(bool table) {
  Material m;
  m.EA = 6.44e7;
  if (table) m.tension_strain = {{0.0, 0.0}, {0.01, 3e5}, {0.02, 1e6}};
  m.EI = 10.0;
  m.mass = 3.73;
  m.added_mass = 0.48;
  m.wet_weight = 31.85;
  m.diameter = 0.0495;
  m.cdn = 0.5;
  m.cdt = 0.05;
  return m;
}

/// The step residual of one interval as DynamicStepSystem assembled it with AutoDiff.
void referenceRows(const Environment& env, const Material& m, double h, const double* Y, const double* Yp,
                   const double* Ydw, double wr, double ak, const Water* w, const Water* wp, const double* S,
                   double* R, double (*J)[2 * N]) {
  AD16 y[2 * N], ydw[2 * N], yp[2 * N];
  for (int k = 0; k < 2 * N; ++k) {
    y[k] = AD16(Y[k], 2 * N, k);
    ydw[k] = Ydw[k] + wr * (y[k] - Y[k]);  // value Ydw, slope wr along its own unknown
    yp[k] = AD16(Yp[k]);
    yp[k].derivatives().setZero(2 * N);
  }
  AD16 sp[N], in1[N], in0[N];
  intervalSpatial(env, m, h, y, y + N, w[0], w[1], sp);
  intervalInertia(env, m, h, y, y + N, ydw, ydw + N, w[0], w[1], in1);
  intervalInertia(env, m, h, yp, yp + N, ydw, ydw + N, wp[0], wp[1], in0);
  for (int q = 0; q < N; ++q) {
    const AD16 r = q < kWeightedRows ? AD16((1.0 - ak) * in1[q] + ak * in0[q] + (1.0 - ak) * sp[q] + ak * S[q])
                                     : sp[q];
    R[q] = r.value();
    for (int k = 0; k < 2 * N; ++k) J[q][k] = r.derivatives().size() ? r.derivatives()[k] : 0.0;
  }
}

/// Random state of two nodes; z of node a and b set relative to the bottom by the offsets.
void randomState(std::mt19937& rng, const Environment& env, double za_off, double zb_off, double* Y) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < 2; ++j) {
    double* y = Y + N * j;
    y[EPS] = 1e-4 * (1.5 + u(rng));
    y[SN] = 50.0 * u(rng);
    y[U] = 0.5 * u(rng);
    y[V] = 0.8 * u(rng);
    y[PHI] = 1.2 + 0.3 * u(rng);
    y[OMEGA] = 0.2 * u(rng);
    y[X] = 30.0 + 0.5 * j + u(rng);
    y[Z] = env.seabedElevation(y[X]) + (j == 0 ? za_off : zb_off);
  }
}

}  // namespace

TEST(DynamicInterval, RowsAndJacobianMatchAutoDiff) {
  const Environment env = environment();
  const double h = 0.5;
  const double delta = eq2d::contactOnset(env, chain(false));
  // Elevations above the bottom: both free; a in the smoothed onset, b beyond it; both deep in.
  const double offsets[][2] = {{0.3, 0.8}, {-0.4 * delta, -3.0 * delta}, {-5.0 * delta, -2.0 * delta}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  // mu > 0: seabed friction (ramp and Coulomb parts), and strains inside the slack ramp.
  for (double mu : {0.0, 0.7})
  for (bool table : {false, true})
    for (const auto& off : offsets)
      for (int trial = 0; trial < 5; ++trial) {
        Material m = chain(table);
        m.mu_axial = mu;
        double Y[2 * N], Yp[2 * N], Ydw[2 * N], S[N];
        randomState(rng, env, off[0], off[1], Y);
        randomState(rng, env, off[0], off[1], Yp);
        if (mu > 0.0 && trial % 2 == 0)
          for (int j = 0; j < 2; ++j) Y[N * j + U] = 0.8 * kFrictionSpeedForTest * u(rng);  // viscous part
        if (mu > 0.0 && trial % 2 == 1)
          for (int j = 0; j < 2; ++j) Y[N * j + EPS] = 0.4 * kSlackStrain * u(rng);  // inside the slack ramp
        for (double& v : Ydw) v = u(rng);
        for (double& v : S) v = 10.0 * u(rng);
        Water w[2], wp[2];
        for (int j = 0; j < 2; ++j) {
          for (Water* x : {&w[j], &wp[j]}) {
            x->wx = 0.5 + 0.3 * u(rng);
            x->wz = 0.2 * u(rng);
            x->z = Y[N * j + Z] + 0.01 * u(rng);
            x->dwx_dz = 0.01 * u(rng);
          }
        }
        const double wr = 10.0, ak = 1.0 / 3.0;
        double Rref[N], Jref[N][2 * N], R[N], J[N][2 * N];
        referenceRows(env, m, h, Y, Yp, Ydw, wr, ak, w, wp, S, Rref, Jref);
        const NodeView na{Y, std::cos(Y[PHI]), std::sin(Y[PHI]), &w[0]};
        const NodeView nb{Y + N, std::cos(Y[N + PHI]), std::sin(Y[N + PHI]), &w[1]};
        const NodeView pa{Yp, std::cos(Yp[PHI]), std::sin(Yp[PHI]), &wp[0]};
        const NodeView pb{Yp + N, std::cos(Yp[N + PHI]), std::sin(Yp[N + PHI]), &wp[1]};
        intervalStepRows(env, m, h, na, nb, pa, pb, Ydw, Ydw + N, StepWeights{ak, wr}, S, R, J);
        for (int q = 0; q < N; ++q) {
          double row_scale = std::abs(Rref[q]);
          for (int k = 0; k < 2 * N; ++k) row_scale = std::max(row_scale, std::abs(Jref[q][k]));
          EXPECT_NEAR(R[q], Rref[q], kValueRelTol * std::max(1.0, row_scale)) << "row " << q;
          for (int k = 0; k < 2 * N; ++k)
            EXPECT_NEAR(J[q][k], Jref[q][k], kSlopeRelTol * std::max(1.0, row_scale))
                << "row " << q << " column " << k << " table " << table << " offsets " << off[0] << ", " << off[1];
        }
        // Without J only the rows are computed, with the same values.
        double R2[N];
        intervalStepRows(env, m, h, na, nb, pa, pb, Ydw, Ydw + N, StepWeights{ak, wr}, S, R2, nullptr);
        for (int q = 0; q < N; ++q) EXPECT_EQ(R2[q], R[q]);
        // The accepted state's spatial rows (intervalSpatialRows from nodeLoadValue) against the
        // template's.
        double sp_ref[N], sp[N], f1a, f2a, f1b, f2b;
        intervalSpatial(env, m, h, Y, Y + N, w[0], w[1], sp_ref);
        nodeLoadValue(env, m, na, f1a, f2a);
        nodeLoadValue(env, m, nb, f1b, f2b);
        intervalSpatialRows(m, h, na, nb, f1a, f2a, f1b, f2b, sp);
        for (int q = 0; q < N; ++q)
          EXPECT_NEAR(sp[q], sp_ref[q], kValueRelTol * std::max(1.0, std::abs(sp_ref[q]))) << "spatial row " << q;
        ++checked;
      }
  EXPECT_EQ(checked, 60);
}

// The reference is not blind to what it checks: a Jacobian entry the seabed dashpot owns (row 0,
// eq. 1, along node a's u in contact) is nonzero, so a missing term would fail the test above.
TEST(DynamicInterval, ContactTermsAreExercised) {
  const Environment env = environment();
  const Material m = chain(false);
  double Y[2 * N], Yp[2 * N], Ydw[2 * N] = {}, S[N] = {};
  std::mt19937 rng(3);
  randomState(rng, env, -3.0 * eq2d::contactOnset(env, m), 0.5, Y);
  randomState(rng, env, 0.5, 0.5, Yp);
  Water w[2], wp[2];
  double R[N], J[N][2 * N], Jfree[N][2 * N];
  referenceRows(env, m, 0.5, Y, Yp, Ydw, 10.0, 0.0, w, wp, S, R, J);
  Y[Z] += 1.0;  // lift node a off the bottom
  referenceRows(env, m, 0.5, Y, Yp, Ydw, 10.0, 0.0, w, wp, S, R, Jfree);
  // Spring k h / 2 cos(phi) ~ 1e4 and dashpot b h / 2 cos^2(phi) ~ 20 in these units: far above
  // an entry that would be zero without contact.
  constexpr double kContactEntry = 1.0;
  EXPECT_GT(std::abs(J[0][Z] - Jfree[0][Z]), kContactEntry);
  EXPECT_GT(std::abs(J[0][U] - Jfree[0][U]), kContactEntry);
}


// The 2-D step builds a junction's cos and sin from the nodes' tables (sinCos once per node)
// instead of calling cos() and sin() in AutoDiff: that must give angleOf's values and
// derivatives bit for bit (signed zeros included), for an unknown of the step (unit derivative
// along its phi) and for a previous-level value (zero derivatives), or the shipped runs change.
TEST(DynamicInterval, AngleFromTablesIsAngleOfBitForBit) {
  auto bits = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  for (double phi : {-2.9, -1.0, -1e-9, 0.0, 0.3, 1.5707963267948966, 2.0, 3.1}) {
    for (bool unknown : {true, false}) {
      AD16 y[N];
      y[PHI] = unknown ? AD16(phi, 2 * N, PHI) : AD16(phi);
      if (!unknown) y[PHI].derivatives().setZero(2 * N);
      double s, c;
      sinCos(phi, s, c);
      const Angle<AD16> ref = angleOf(y);
      const AD16 ct(c, y[PHI].derivatives() * (-s)), st(s, y[PHI].derivatives() * c);
      EXPECT_EQ(bits(ct.value()), bits(ref.c.value())) << phi;
      EXPECT_EQ(bits(st.value()), bits(ref.s.value())) << phi;
      for (int k = 0; k < 2 * N; ++k) {
        EXPECT_EQ(bits(ct.derivatives()[k]), bits(ref.c.derivatives()[k])) << phi << " lane " << k;
        EXPECT_EQ(bits(st.derivatives()[k]), bits(ref.s.derivatives()[k])) << phi << " lane " << k;
      }
    }
  }
}
