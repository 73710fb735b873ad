// The two halves of lock-step's loss recovery without a bus: when a state is published again
// (StateRepeater) and how a sender's repeated message is told from a new one (RoundSenders).
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <vector>

#include "server/round_senders.hpp"
#include "server/state_repeater.hpp"

namespace tongue::server {
namespace {

// Times compared in s after sums of doubles: a nanosecond is far below any interval used.
constexpr double kTimeTolerance = 1e-9;

TEST(StateRepeater, RepeatsAfterDoublingIntervalsUpToTheLongestAtMostMaxTimes) {
  StateRepeater repeater(50, 4, 150);
  repeater.restart(10.0);
  EXPECT_FALSE(repeater.due(10.049));
  std::vector<double> times;
  double now = 10.0;
  while (const std::optional<double> next = repeater.next()) {
    now = *next;
    ASSERT_TRUE(repeater.due(now));
    EXPECT_FALSE(repeater.due(now));  // once per repeat
    times.push_back(now);
  }
  ASSERT_EQ(times.size(), 4u);
  EXPECT_NEAR(times[0], 10.05, kTimeTolerance);
  EXPECT_NEAR(times[1], 10.15, kTimeTolerance);
  EXPECT_NEAR(times[2], 10.30, kTimeTolerance);  // 200 ms capped at the longest, 150
  EXPECT_NEAR(times[3], 10.45, kTimeTolerance);
  EXPECT_FALSE(repeater.due(100.0));
  EXPECT_EQ(repeater.total(), 4);

  repeater.restart(20.0);  // a new state: its own repeats
  EXPECT_NEAR(repeater.next().value_or(0.0), 20.05, kTimeTolerance);
  EXPECT_TRUE(repeater.due(20.05));
  EXPECT_EQ(repeater.total(), 5);
}

TEST(StateRepeater, ZeroMillisecondsOrRepeatsMeansNever) {
  for (const auto& [first_ms, repeats] : {std::pair{0, 6}, std::pair{50, 0}}) {
    StateRepeater repeater(first_ms, repeats, 1000);
    repeater.restart(0.0);
    EXPECT_EQ(repeater.next(), std::nullopt);
    EXPECT_FALSE(repeater.due(1e9));
  }
  EXPECT_THROW(StateRepeater(-1, 6, 1000), std::invalid_argument);
  EXPECT_THROW(StateRepeater(50, -1, 1000), std::invalid_argument);
  EXPECT_THROW(StateRepeater(50, 6, 40), std::invalid_argument);
}

TEST(RoundSenders, TellsRepeatsFromChangedMessagesPerSender) {
  using Seen = RoundSenders::Seen;
  const RoundSenders::Bytes a{1, 2, 3}, b{1, 2, 4};
  RoundSenders senders;
  EXPECT_EQ(senders.in_open_round("x", a), Seen::new_sender);
  senders.take("x", a);
  EXPECT_EQ(senders.in_open_round("x", a), Seen::repeat);
  EXPECT_EQ(senders.in_open_round("x", b), Seen::changed);
  EXPECT_EQ(senders.in_open_round("y", a), Seen::new_sender);
  EXPECT_FALSE(senders.repeats_last_round("x", a));

  senders.next_round();
  EXPECT_EQ(senders.in_open_round("x", a), Seen::new_sender);
  EXPECT_TRUE(senders.repeats_last_round("x", a));
  EXPECT_FALSE(senders.repeats_last_round("x", b));
  senders.take("x", b);
  senders.reopen();  // the open round again from nothing; the last round stays
  EXPECT_EQ(senders.in_open_round("x", b), Seen::new_sender);
  EXPECT_TRUE(senders.repeats_last_round("x", a));
  senders.clear();
  EXPECT_FALSE(senders.repeats_last_round("x", a));
}

TEST(RoundSenders, AnEmptySenderIsNeverRecorded) {
  RoundSenders senders;
  senders.take("", {1});
  EXPECT_EQ(senders.in_open_round("", {1}), RoundSenders::Seen::new_sender);
  senders.next_round();
  EXPECT_FALSE(senders.repeats_last_round("", {1}));
}

}  // namespace
}  // namespace tongue::server
