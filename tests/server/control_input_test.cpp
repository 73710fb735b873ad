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
                                const std::vector<double>& levels) {
  FakeServerBus bus;
  bus.send_activation(step, names, levels);
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

}  // namespace
}  // namespace tongue::server
