// The DNV-OS-E301-style line check (core/model/design_check.hpp) against hand sums.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mooring_dynamics/core/model/design_check.hpp"

using namespace mooring_dynamics::core;

namespace {
/// Hand sums of a few products: rounding only.
constexpr double kHandTol = 1e-6;  // [N] on values of MN
}  // namespace

TEST(DesignCheck, UlsClass1ByHand) {
  // Mean 1.2 MN, MPM 3.0 MN, MBL 4.88 MN: T_d = 1.1 * 1.2 + 1.5 * 1.8 = 4.02 MN; S_c = 4.636 MN.
  const DesignCheck c = designCheck(1.2e6, 3.0e6, 4.88e6, dnvFactors(1, LimitState::Uls));
  EXPECT_NEAR(c.t_dyn, 1.8e6, kHandTol);
  EXPECT_NEAR(c.design_tension, 4.02e6, kHandTol);
  EXPECT_NEAR(c.strength, 4.636e6, kHandTol);
  EXPECT_NEAR(c.utilization, 4.02 / 4.636, 1e-12);
  EXPECT_TRUE(c.pass);
}

TEST(DesignCheck, Class2FailsWhereClass1Passes) {
  // The same line in class 2: 1.4 * 1.2 + 2.1 * 1.8 = 5.46 MN > 4.636 MN.
  const DesignCheck c = designCheck(1.2e6, 3.0e6, 4.88e6, dnvFactors(2, LimitState::Uls));
  EXPECT_NEAR(c.design_tension, 5.46e6, kHandTol);
  EXPECT_FALSE(c.pass);
  // ALS (a line broken), class 2: 1.0 * 1.2 + 1.25 * 1.8 = 3.45 MN.
  EXPECT_NEAR(designCheck(1.2e6, 3.0e6, 4.88e6, dnvFactors(2, LimitState::Als)).design_tension, 3.45e6, kHandTol);
  EXPECT_NEAR(designCheck(1.2e6, 3.0e6, 4.88e6, dnvFactors(1, LimitState::Als)).design_tension, 3.18e6, kHandTol);
  EXPECT_THROW(dnvFactors(3, LimitState::Uls), std::invalid_argument);
}
