// ControlInput records what messages ask for and acts on nothing: the round or the hold, the
// command waiting, the rejections counted.
#include "server/control_input.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "server/fake_server_bus.hpp"

namespace tongue::server {
namespace {

using testing::FakeServerBus;

const std::vector<std::string> kMuscles{"flexor", "extensor"};

bus::IncomingMessage activation(std::int64_t step, const std::vector<std::string>& names,
                                const std::vector<double>& levels, const std::string& sender = "",
                                std::int64_t utime = 0) {
  FakeServerBus bus;
  bus.send_activation(step, names, levels, sender, utime);
  return bus.incoming.front();
}

bus::IncomingMessage command(const std::string& name) {
  FakeServerBus bus;
  bus.send_command(name);
  return bus.incoming.front();
}

fem::Vector vector(double a, double b) {
  fem::Vector v(2);
  v << a, b;
  return v;
}

TEST(ControlInput, LockStepTakesOnlyTheNextStepIntoTheRound) {
  ControlInput input(Mode::lockstep, 1, kMuscles);
  input.record(activation(3, {"flexor"}, {0.5}), 3, 0.0);  // stale at step 3
  input.record(activation(5, {"flexor"}, {0.5}), 3, 0.0);  // future
  EXPECT_FALSE(input.round().complete());
  EXPECT_EQ(input.rejected(), 2);
  input.record(activation(4, {"extensor"}, {0.25}), 3, 0.0);
  ASSERT_TRUE(input.round().complete());
  EXPECT_EQ(input.round().levels(), vector(0.0, 0.25));
  input.next_round(vector(0.0, 0.25));
  EXPECT_FALSE(input.round().complete());
}

TEST(ControlInput, ACompleteRoundIsReplacedByTheNextMessageForTheSameStep) {
  ControlInput input(Mode::lockstep, 1, kMuscles);
  input.next_round(vector(0.1, 0.2));
  input.record(activation(1, {"flexor"}, {0.5}), 0, 0.0);
  input.record(activation(1, {"flexor"}, {0.7}), 0, 0.0);  // e.g. while paused
  ASSERT_TRUE(input.round().complete());
  EXPECT_EQ(input.round().levels(), vector(0.7, 0.2));
  EXPECT_EQ(input.rejected(), 0);
}

TEST(ControlInput, TwoControllersMergeAndAnOverlapIsRejected) {
  ControlInput input(Mode::lockstep, 2, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}), 0, 0.0);
  input.record(activation(1, {"flexor"}, {0.3}), 0, 0.0);
  EXPECT_EQ(input.rejected(), 1);
  EXPECT_EQ(input.round().received(), 1);
  input.record(activation(1, {"extensor"}, {0.25}), 0, 0.0);
  ASSERT_TRUE(input.round().complete());
  EXPECT_EQ(input.round().levels(), vector(0.5, 0.25));
}

TEST(ControlInput, FastModeMergesIntoTheHoldWhateverTheStep) {
  ControlInput input(Mode::fast, 1, kMuscles);
  input.record(activation(-1, {"flexor"}, {0.5}), 7, 2.5);
  input.record(activation(99, {"extensor"}, {0.75}), 7, 3.0);
  EXPECT_EQ(input.held(), vector(0.5, 0.75));
  EXPECT_EQ(input.last_heard(), 3.0);
  input.record(activation(1, {"flexor"}, {2.0}), 7, 4.0);  // out of range: the hold stays
  EXPECT_EQ(input.held(), vector(0.5, 0.75));
  EXPECT_EQ(input.last_heard(), 3.0);
  EXPECT_EQ(input.rejected(), 1);
  input.zero_held();
  EXPECT_EQ(input.held(), vector(0.0, 0.0));
}

TEST(ControlInput, ACommandWaitsUntilTaken) {
  ControlInput input(Mode::lockstep, 1, kMuscles);
  EXPECT_EQ(input.take_command(), std::nullopt);
  input.record(command("pause"), 0, 0.0);
  EXPECT_EQ(input.take_command(), bus::Command::pause);
  EXPECT_EQ(input.take_command(), std::nullopt);
  input.record(command("pause please"), 0, 0.0);
  input.record({bus::IncomingMessage::Channel::command, {0, 1, 2}}, 0, 0.0);
  EXPECT_EQ(input.take_command(), std::nullopt);
  EXPECT_EQ(input.rejected(), 2);
}

TEST(ControlInput, ClearStartsFromZeroAndKeepsTheRejections) {
  ControlInput input(Mode::fast, 1, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}), 0, 0.0);
  input.record(activation(1, {"nobody"}, {0.5}), 0, 0.0);
  input.clear(2);
  EXPECT_EQ(input.held(), vector(0.0, 0.0));
  EXPECT_EQ(input.rejected(), 1);
  input.clear_rejected();
  EXPECT_EQ(input.rejected(), 0);
}

// A controller answering a state published again sends its message again, byte for byte: taken
// once, neither counted towards the round nor rejected, so that with two controllers one
// controller's repeat never stands in for the other's message.
TEST(ControlInput, ASendersRepeatIsTakenOnce) {
  ControlInput input(Mode::lockstep, 2, kMuscles);
  input.record(activation(1, {}, {}, "a:1", 100), 0, 0.0);
  input.record(activation(1, {}, {}, "a:1", 100), 0, 0.0);
  EXPECT_EQ(input.round().received(), 1);
  EXPECT_EQ(input.repeats(), 1);
  EXPECT_EQ(input.rejected(), 0);
  input.record(activation(1, {}, {}, "b:2", 100), 0, 0.0);  // the same bytes but its sender
  EXPECT_TRUE(input.round().complete());
  EXPECT_TRUE(input.take_notices().empty());
}

// Anonymous messages (no sender) count as they come, as before senders existed.
TEST(ControlInput, MessagesWithoutASenderAreNeverRepeats) {
  ControlInput input(Mode::lockstep, 2, kMuscles);
  input.record(activation(1, {}, {}), 0, 0.0);
  input.record(activation(1, {}, {}), 0, 0.0);
  EXPECT_TRUE(input.round().complete());
  EXPECT_EQ(input.repeats(), 0);
}

// A repeat that arrives after its step was taken (the answer to a repeated state crossed the
// state of the next step) is ignored, not rejected as stale; another stale message still is.
TEST(ControlInput, ALateRepeatOfTheStepJustTakenIsIgnored) {
  ControlInput input(Mode::lockstep, 1, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}, "a:1", 7), 0, 0.0);
  ASSERT_TRUE(input.round().complete());
  input.next_round(input.round().levels());
  input.record(activation(1, {"flexor"}, {0.5}, "a:1", 7), 1, 0.0);
  EXPECT_EQ(input.repeats(), 1);
  EXPECT_EQ(input.rejected(), 0);
  input.record(activation(1, {"flexor"}, {0.5}, "a:1", 8), 1, 0.0);  // not the same message
  EXPECT_EQ(input.rejected(), 1);
  input.next_round(input.round().levels());
  input.record(activation(1, {"flexor"}, {0.5}, "a:1", 7), 2, 0.0);  // two steps late: stale
  EXPECT_EQ(input.rejected(), 2);
}

TEST(ControlInput, ASecondDifferentMessageFromOneSenderIsRejected) {
  ControlInput input(Mode::lockstep, 2, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}, "a:1", 1), 0, 0.0);
  input.record(activation(1, {"extensor"}, {0.5}, "a:1", 2), 0, 0.0);
  EXPECT_EQ(input.round().received(), 1);
  EXPECT_EQ(input.rejected(), 1);
  const auto notices = input.take_notices();
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0].kind, "second activation");
  EXPECT_NE(notices[0].reason.find("\"a:1\" already sent another activation for step 1"),
            std::string::npos)
      << notices[0].reason;
}

// Every rejected activation that could be decoded leaves a notice naming it (sender, step tag,
// utime) and saying why; the round remembers the last rejection for the silence report.
TEST(ControlInput, ARejectedActivationLeavesANoticeForItsSender) {
  ControlInput input(Mode::lockstep, 2, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}, "first:1", 10), 0, 0.0);
  input.record(activation(1, {"flexor"}, {0.3}, "second:2", 20), 0, 0.0);
  input.record({bus::IncomingMessage::Channel::activation, {1, 2, 3}}, 0, 0.0);  // no sender
  EXPECT_EQ(input.rejected(), 2);
  const auto notices = input.take_notices();
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0].sender, "second:2");
  EXPECT_EQ(notices[0].activation_step, 1);
  EXPECT_EQ(notices[0].activation_utime, 20);
  EXPECT_EQ(notices[0].step, 0);
  EXPECT_EQ(notices[0].kind, "overlapping activation");
  EXPECT_NE(notices[0].reason.find("\"flexor\" is already set for step 1"), std::string::npos);
  EXPECT_TRUE(input.take_notices().empty());
  EXPECT_EQ(input.round_rejections(), 1);
  EXPECT_EQ(input.round_rejection(), "overlapping activation from \"second:2\"");
  input.next_round(vector(0.0, 0.0));
  EXPECT_EQ(input.round_rejections(), 0);
}

// A sender longer than any controller may give is rejected without a notice (no one could read
// it as theirs, and the notice channel's limit counts on short senders); a sender at the limit
// gets one.
TEST(ControlInput, NoNoticeForASenderOverTheLimit) {
  ControlInput input(Mode::lockstep, 1, kMuscles);
  input.record(activation(1, {"flexor"}, {0.5}, std::string(bus::kMaxSenderBytes + 1, 's'), 1), 0,
               0.0);
  EXPECT_EQ(input.rejected(), 1);
  EXPECT_TRUE(input.take_notices().empty());
  input.record(activation(1, {"nobody"}, {0.5}, std::string(bus::kMaxSenderBytes, 's'), 2), 0, 0.0);
  EXPECT_EQ(input.take_notices().size(), 1u);
}

// A flood of bad activations is not answered by a flood of notices: at most 100 per second.
TEST(ControlInput, NoticesAreLimitedTo100PerSecond) {
  ControlInput input(Mode::fast, 1, kMuscles);
  for (int i = 0; i < 150; ++i) input.record(activation(-1, {"nobody"}, {0.5}), 0, 0.5);
  EXPECT_EQ(input.rejected(), 150);
  EXPECT_EQ(input.take_notices().size(), 100u);
  input.record(activation(-1, {"nobody"}, {0.5}), 0, 1.2);  // 0.7 s later: still that second
  EXPECT_TRUE(input.take_notices().empty());
  input.record(activation(-1, {"nobody"}, {0.5}), 0, 1.6);
  EXPECT_EQ(input.take_notices().size(), 1u);
}

}  // namespace
}  // namespace tongue::server
