#include "ep_controller/delay_buffer.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace tongue::ep_controller {
namespace {

// Feedback whose length tells the step it came from.
Feedback at(std::int64_t step) {
  return Feedback{step, {0.05 + 1e-4 * static_cast<double>(step)}, {0.0}};
}

TEST(DelayBuffer, CommandForStepKPlusOneUsesStepKPlusOneMinusDelay) {
  DelayBuffer buffer(3);
  for (std::int64_t k = 0; k <= 10; ++k) {
    buffer.push(at(k));
    const std::int64_t expected = std::max<std::int64_t>(0, k + 1 - 3);
    EXPECT_EQ(buffer.for_step(k + 1).step, expected) << "command for step " << k + 1;
  }
  // Only what later commands can need is kept: steps 8..10 for delay 3.
  EXPECT_LE(buffer.size(), 3u);
}

TEST(DelayBuffer, ShortHistoryUsesTheOldestState) {
  DelayBuffer buffer(5);
  buffer.push(at(7));  // joined a running server at step 7
  EXPECT_EQ(buffer.for_step(8).step, 7);
  buffer.push(at(8));
  EXPECT_EQ(buffer.for_step(9).step, 7);
}

TEST(DelayBuffer, DelayOfOneUsesTheLatestState) {
  DelayBuffer buffer(1);
  buffer.push(at(0));
  buffer.push(at(1));
  EXPECT_EQ(buffer.for_step(2).step, 1);
  EXPECT_EQ(buffer.size(), 1u);
}

TEST(DelayBuffer, GapsAreInterpolatedBetweenTheStatesAroundTheWantedOne) {
  DelayBuffer buffer(2);
  for (const std::int64_t k : {0, 5, 10, 15}) buffer.push(at(k));  // published every 5th step
  const Feedback f = buffer.for_step(16);  // wants step 14: 4/5 of the way from 10 to 15
  EXPECT_EQ(f.step, 10);
  EXPECT_NEAR(f.lengths_m[0], at(14).lengths_m[0], 1e-15);
  EXPECT_EQ(buffer.for_step(17).step, 15);
  EXPECT_EQ(buffer.for_step(17).lengths_m, at(15).lengths_m);
}

TEST(DelayBuffer, AFractionalDelayInterpolatesLengthsAndVelocities) {
  DelayBuffer buffer(1.5);  // 12 ms at dt 8 ms
  buffer.push(Feedback{0, {0.050}, {0.10}});
  buffer.push(Feedback{1, {0.052}, {0.30}});
  buffer.push(Feedback{2, {0.058}, {0.50}});
  // The command for step 3 wants step 1.5.
  const Feedback f = buffer.for_step(3);
  EXPECT_EQ(f.step, 1);
  EXPECT_NEAR(f.lengths_m[0], 0.055, 1e-15);
  EXPECT_NEAR(f.velocities_m_s[0], 0.40, 1e-15);
  // Step 0.5 is no longer needed by any later command: steps 1 and 2 are kept.
  EXPECT_EQ(buffer.size(), 2u);
}

TEST(DelayBuffer, ADelayOffAWholeStepByRoundOffIsThatStep) {
  const DelayBuffer buffer(0.011 / 0.0001);  // 109.99999999999999 in floating point
  EXPECT_EQ(buffer.delay_steps(), 110.0);
}

TEST(DelayBuffer, AResetDropsTheLaterHistory) {
  DelayBuffer buffer(2);
  for (std::int64_t k = 0; k <= 6; ++k) buffer.push(at(k));
  buffer.push(at(0));  // the server went back to step 0
  EXPECT_EQ(buffer.size(), 1u);
  EXPECT_EQ(buffer.for_step(1).step, 0);
  EXPECT_EQ(buffer.for_step(1).lengths_m, at(0).lengths_m);
}

TEST(DelayBuffer, RejectsNoDelayAndEmptyUse) {
  EXPECT_THROW(DelayBuffer(0), std::invalid_argument);
  EXPECT_THROW(DelayBuffer(0.5), std::invalid_argument);
  const DelayBuffer empty(2);
  EXPECT_THROW(empty.for_step(1), std::logic_error);
}

}  // namespace
}  // namespace tongue::ep_controller
