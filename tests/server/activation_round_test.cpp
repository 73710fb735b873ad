#include "server/activation_round.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <vector>

namespace tongue::server {
namespace {

// Levels held from the previous step, by model muscle (4 muscles).
fem::Vector held() {
  fem::Vector v(4);
  v << 0.1, 0.2, 0.3, 0.4;
  return v;
}

// An accepted message as bus::check_activation gives it: the named muscles, each at level.
bus::ActivationCheck checked(const std::vector<std::size_t>& named, double level) {
  bus::ActivationCheck check;
  check.accepted = true;
  check.named = named;
  check.levels.assign(named.size(), level);
  return check;
}

TEST(ActivationRound, OneExpectedMessageIsThatMessageOnTheHeldLevels) {
  ActivationRound round(1);
  round.start(held());
  EXPECT_FALSE(round.complete());
  round.add(checked({2}, 0.9));
  EXPECT_TRUE(round.complete());
  EXPECT_EQ(round.received(), 1);
  fem::Vector expected = held();
  expected[2] = 0.9;
  EXPECT_EQ(round.levels(), expected);
}

TEST(ActivationRound, MergesMessagesNamingDifferentMusclesAndKeepsTheUnnamed) {
  ActivationRound round(3);
  round.start(held());
  round.add(checked({0, 3}, 0.7));
  EXPECT_FALSE(round.complete());
  round.add(checked({}, 0.0));  // a controller with nothing to change still counts
  EXPECT_FALSE(round.complete());
  EXPECT_EQ(round.received(), 2);
  round.add(checked({1}, 0.05));
  ASSERT_TRUE(round.complete());
  fem::Vector expected(4);
  expected << 0.7, 0.05, 0.3, 0.7;  // muscle 2, named by nobody, keeps its held level
  EXPECT_EQ(round.levels(), expected);
}

TEST(ActivationRound, FindsAMuscleAnEarlierMessageSet) {
  ActivationRound round(2);
  round.start(held());
  round.add(checked({1, 2}, 0.5));
  EXPECT_EQ(round.already_set({0, 3}), std::nullopt);
  EXPECT_EQ(round.already_set({3, 2}), std::optional<std::size_t>(2));
  EXPECT_THROW(round.add(checked({2}, 0.6)), std::logic_error);
  EXPECT_EQ(round.received(), 1);  // the refused message changed nothing
  EXPECT_EQ(round.levels()[2], 0.5);
}

TEST(ActivationRound, StartClearsTheRound) {
  ActivationRound round(2);
  round.start(held());
  round.add(checked({0}, 1.0));
  fem::Vector next = fem::Vector::Zero(4);
  round.start(next);
  EXPECT_EQ(round.received(), 0);
  EXPECT_EQ(round.already_set({0}), std::nullopt);
  EXPECT_EQ(round.levels(), next);
}

TEST(ActivationRound, ACompleteRoundTakesNoMore) {
  ActivationRound round(1);
  round.start(held());
  round.add(checked({0}, 1.0));
  EXPECT_THROW(round.add(checked({1}, 1.0)), std::logic_error);
}

TEST(ActivationRound, NeedsAtLeastOneMessage) {
  EXPECT_THROW(ActivationRound(0), std::invalid_argument);
  EXPECT_THROW(ActivationRound(-2), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::server
