// The active force-length relation of a fibre segment: zero force at and below the zero-force
// length, the plateau from the rest length on, a continuous slope that is its derivative, and
// the plain fibre model's constant tension as an option.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/force_length.hpp"

namespace tongue::model {
namespace {

TEST(ActiveForceLength, IsZeroUpToTheZeroForceLengthAndOneFromTheRestLengthOn) {
  const ActiveForceLength f;
  EXPECT_EQ(f.zero_force_length(), 0.5);
  for (const double lambda : {0.0, 0.1, 0.3, 0.5}) {
    EXPECT_EQ(f.value(lambda), 0.0) << lambda;
    EXPECT_EQ(f.slope(lambda), 0.0) << lambda;
  }
  for (const double lambda : {1.0, 1.2, 2.0, 10.0}) {
    EXPECT_EQ(f.value(lambda), 1.0) << lambda;
    EXPECT_EQ(f.slope(lambda), 0.0) << lambda;
  }
  // Half way up the limb, s = 1/2: f = s^2 (6 - 8 s + 3 s^2) = 11/16, by hand; df/dlambda =
  // 12 s (1 - s)^2 / (1 - lambda_0) = 3 (exact in binary floating point up to one rounding).
  EXPECT_NEAR(f.value(0.75), 11.0 / 16.0, 1e-15);
  EXPECT_NEAR(f.slope(0.75), 3.0, 1e-14);
}

TEST(ActiveForceLength, RisesMonotonicallyWithAContinuousSlopeThatIsItsDerivative) {
  for (const double lambda0 : {0.0, 0.3, 0.5, 0.9}) {
    const ActiveForceLength f(lambda0);
    double previous = -1.0;
    for (double lambda = 0.0; lambda <= 1.2; lambda += 0.01) {
      const double v = f.value(lambda);
      EXPECT_GE(v, previous) << "lambda_0 " << lambda0 << ", lambda " << lambda;
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
      previous = v;
      // Central differences with h = 1e-6: truncation h^2 |f'''| / 6 <= 8e-12 (1 - lambda_0)^-3
      // (|d3f/ds3| <= 48) and round-off eps / h ~ 2e-10; within h of lambda_0, where f'' jumps
      // by 12 (1 - lambda_0)^-2, the error is at most h times that. 1e-4 (1 - lambda_0)^-2
      // holds all three with room.
      const double h = 1e-6;
      const double fd = (f.value(lambda + h) - f.value(lambda - h)) / (2 * h);
      EXPECT_NEAR(f.slope(lambda), fd, 1e-4 / ((1 - lambda0) * (1 - lambda0)))
          << "lambda_0 " << lambda0 << ", lambda " << lambda;
    }
    // Continuous value and slope where the pieces meet (C1): 1e-10 either side changes f by
    // at most 2e-10 |f'| (|f'| <= 1.8 / (1 - lambda_0)) and f' by 2e-10 |f''| (|f''| <=
    // 12 / (1 - lambda_0)^2), below 1e-8 (1 - lambda_0)^-2; a kink would show as a jump of
    // order 1 in the slope.
    const double tolerance = 1e-8 / ((1 - lambda0) * (1 - lambda0));
    for (const double joint : {lambda0, 1.0}) {
      EXPECT_NEAR(f.value(joint - 1e-10), f.value(joint + 1e-10), tolerance) << joint;
      EXPECT_NEAR(f.slope(joint - 1e-10), f.slope(joint + 1e-10), tolerance) << joint;
    }
  }
}

TEST(ActiveForceLength, ConstantTensionIsOneAtEveryLength) {
  const ActiveForceLength f = ActiveForceLength::constant_tension();
  EXPECT_TRUE(f.is_constant());
  EXPECT_FALSE(ActiveForceLength().is_constant());
  for (const double lambda : {0.0, 0.2, 0.75, 1.0, 3.0}) {
    EXPECT_EQ(f.value(lambda), 1.0);
    EXPECT_EQ(f.slope(lambda), 0.0);
  }
}

TEST(ActiveForceLength, RejectsAZeroForceLengthOutsideZeroOne) {
  for (const double bad : {-0.1, 1.0, 1.5, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(ActiveForceLength{bad}, std::invalid_argument) << bad;
  }
  try {
    ActiveForceLength{1.0};
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zero-force length"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tongue::model
