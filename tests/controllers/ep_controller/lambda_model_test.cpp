#include "ep_controller/lambda_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tongue::ep_controller {
namespace {

const LambdaConstants k;

TEST(LambdaModel, ConstantsAreTheSpeechartOnes) {
  // docs/controllers.md; a changed constant must be a decision, not an accident.
  EXPECT_EQ(k.c_per_mm, 0.112);
  EXPECT_EQ(k.mu_s, 0.01);
  EXPECT_EQ(k.f1, 0.80);
  EXPECT_EQ(k.f2, 0.5);
  EXPECT_EQ(k.f3, 0.43);
  EXPECT_EQ(k.f4, 0.8 / 1.5);
  EXPECT_EQ(k.f5, 0.023 / 0.7);
}

TEST(LambdaModel, NoForceAtOrBelowTheThreshold) {
  EXPECT_EQ(stretch_beyond_threshold_mm(50.0, 50.0, 0.0), 0.0);
  EXPECT_EQ(stretch_beyond_threshold_mm(45.0, 50.0, 0.0), 0.0);
  // Lengthening at 100 mm/s adds mu * 100 = 1 mm: still 4 mm short of the threshold.
  EXPECT_EQ(stretch_beyond_threshold_mm(45.0, 50.0, 100.0), 0.0);
  EXPECT_EQ(exponential_force(0.0, 5.2), 0.0);
  const MuscleLaw law{5.2, 37.0, 60.0};
  const MuscleCommand c = muscle_command(law, 50.0, 45.0, 0.0, true);
  EXPECT_EQ(c.stretch_mm, 0.0);
  EXPECT_EQ(c.force_n, 0.0);
  EXPECT_EQ(c.level, 0.0);
}

TEST(LambdaModel, StretchIsLengthMinusLambdaPlusMuTimesVelocity) {
  // Exact in binary: 53 - 50 = 3 mm; 0.01 s * 50 mm/s = 0.5 mm (to round-off).
  EXPECT_EQ(stretch_beyond_threshold_mm(53.0, 50.0, 0.0), 3.0);
  EXPECT_NEAR(stretch_beyond_threshold_mm(53.0, 50.0, 50.0), 3.0 + k.mu_s * 50.0, 1e-12);
  // Shortening lowers the stretch: the velocity term damps the reflex.
  EXPECT_NEAR(stretch_beyond_threshold_mm(53.0, 50.0, -100.0), 3.0 - k.mu_s * 100.0, 1e-12);
  // At the threshold length only the velocity counts.
  EXPECT_NEAR(stretch_beyond_threshold_mm(50.0, 50.0, 200.0), 2.0, 1e-12);
}

TEST(LambdaModel, ForceGrowsExponentiallyWithSlopeC) {
  const double rho = 4.4;
  for (const double a : {0.5, 3.0, 10.0, 20.0}) {
    const double m = exponential_force(a, rho);
    EXPECT_GT(m, 0.0);
    // ln(M / rho + 1) / A recovers c (relative round-off of exp and log: ~1e-15).
    EXPECT_NEAR(std::log(m / rho + 1.0) / a, k.c_per_mm, 1e-12);
  }
  // Linear in rho.
  EXPECT_NEAR(exponential_force(7.0, 2.0 * rho), 2.0 * exponential_force(7.0, rho), 1e-12);
  // Small stretches: M ~ rho c A (expm1 keeps them accurate).
  EXPECT_NEAR(exponential_force(1e-9, rho) / (rho * k.c_per_mm * 1e-9), 1.0, 1e-8);
}

TEST(LambdaModel, VelocityFactorFollowsItsFormula) {
  for (const double r : {-1.0, -0.2, 0.0, 0.3, 2.0}) {
    const double expected = k.f1 + k.f2 * std::atan(k.f3 + k.f4 * r) + k.f5 * r;
    EXPECT_DOUBLE_EQ(velocity_factor(r), expected) << "r = " << r;
  }
  // About 1 at rest (0.80 + 0.5 atan 0.43 = 1.003): the static law is unchanged there.
  EXPECT_NEAR(velocity_factor(0.0), 1.0, 0.005);
  // Lower while shortening, higher while lengthening.
  EXPECT_LT(velocity_factor(-0.5), velocity_factor(0.0));
  EXPECT_GT(velocity_factor(0.5), velocity_factor(0.0));
  // Very fast shortening would make it negative: clamped at 0 (a muscle cannot push).
  EXPECT_EQ(velocity_factor(-100.0), 0.0);
}

TEST(LambdaModel, VelocityFactorScalesTheForceByVelocityOverRestLength) {
  const MuscleLaw law{5.2, 1e9, 40.0};  // a cap out of reach
  const double v = -20.0;               // mm/s, shortening: r = -0.5 / s
  const MuscleCommand with = muscle_command(law, 40.0, 45.0, v, true);
  const MuscleCommand without = muscle_command(law, 40.0, 45.0, v, false);
  EXPECT_EQ(with.stretch_mm, without.stretch_mm);
  EXPECT_DOUBLE_EQ(with.force_n, without.force_n * velocity_factor(v / law.rest_length_mm));
}

TEST(LambdaModel, LevelIsForceOverMaxForceCappedAtOne) {
  const MuscleLaw law{5.2, 18.5, 60.0};
  const MuscleCommand small = muscle_command(law, 50.0, 55.0, 0.0, false);
  EXPECT_DOUBLE_EQ(small.level, small.force_n / law.max_force_n);
  EXPECT_LT(small.level, 1.0);
  // 40 mm beyond threshold: rho (e^4.48 - 1) = 455 N, far above F_max.
  const MuscleCommand big = muscle_command(law, 50.0, 90.0, 0.0, false);
  EXPECT_GT(big.force_n, law.max_force_n);
  EXPECT_EQ(big.level, 1.0);
  EXPECT_EQ(force_level(-1.0, 10.0), 0.0);
}

}  // namespace
}  // namespace tongue::ep_controller
