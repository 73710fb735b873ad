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

TEST(DelayBuffer, GapsUseTheLatestStateAtOrBeforeTheWantedOne) {
  DelayBuffer buffer(2);
  for (const std::int64_t k : {0, 5, 10, 15}) buffer.push(at(k));  // published every 5th step
  EXPECT_EQ(buffer.for_step(16).step, 10);
  EXPECT_EQ(buffer.for_step(17).step, 15);
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
  const DelayBuffer empty(2);
  EXPECT_THROW(empty.for_step(1), std::logic_error);
}

}  // namespace
}  // namespace tongue::ep_controller
