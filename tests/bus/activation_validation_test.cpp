#include "bus/activation_validation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tongue::bus {
namespace {

const std::vector<std::string> kMuscles = {"GGp_left", "GGp_right", "SG_left", "SL"};

// The levels held before the message, by model muscle.
Eigen::VectorXd current() {
  Eigen::VectorXd v(4);
  v << 0.1, 0.2, 0.3, 0.4;
  return v;
}

// current() with the accepted check merged in.
Eigen::VectorXd merged(const ActivationCheck& check) {
  Eigen::VectorXd held = current();
  check.merge_into(held);
  return held;
}

Eigen::VectorXd vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

tongue_lcm::lcmt_tongue_activation message(const std::vector<std::string>& names,
                                           const std::vector<double>& levels, int64_t step = 1) {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.utime = 1000;
  msg.step = step;
  msg.num_muscles = static_cast<int32_t>(names.size());
  msg.names = names;
  msg.levels = levels;
  return msg;
}

// Expects msg to be rejected with a reason that contains every one of the parts.
void expect_rejected(const tongue_lcm::lcmt_tongue_activation& msg,
                     const std::vector<std::string>& parts) {
  const ActivationCheck check = check_activation(msg, kMuscles);
  EXPECT_FALSE(check.accepted);
  EXPECT_TRUE(check.levels.empty());
  EXPECT_TRUE(check.named.empty());
  for (const std::string& part : parts) {
    EXPECT_NE(check.reason.find(part), std::string::npos)
        << "reason \"" << check.reason << "\" lacks \"" << part << "\"";
  }
}

TEST(CheckActivation, AcceptsAFullMessageInTheModelsOrder) {
  const auto check = check_activation(
      message({"SL", "SG_left", "GGp_right", "GGp_left"}, {1.0, 0.0, 0.5, 0.25}), kMuscles);
  ASSERT_TRUE(check.accepted) << check.reason;
  EXPECT_TRUE(check.reason.empty());
  EXPECT_EQ(check.levels, (std::vector<double>{1.0, 0.0, 0.5, 0.25}));  // message order
  EXPECT_EQ(check.named, (std::vector<std::size_t>{3, 2, 1, 0}));
  EXPECT_EQ(merged(check), vector({0.25, 0.5, 0.0, 1.0}));  // the model's order
}

TEST(CheckActivation, PartialMessageKeepsTheOtherLevels) {
  const auto check = check_activation(message({"SG_left"}, {0.9}), kMuscles);
  ASSERT_TRUE(check.accepted) << check.reason;
  EXPECT_EQ(check.levels, (std::vector<double>{0.9}));
  EXPECT_EQ(check.named, (std::vector<std::size_t>{2}));
  EXPECT_EQ(merged(check), vector({0.1, 0.2, 0.9, 0.4}));
}

TEST(CheckActivation, EmptyMessageKeepsAllLevels) {
  const auto check = check_activation(message({}, {}, -1), kMuscles);
  ASSERT_TRUE(check.accepted) << check.reason;
  EXPECT_TRUE(check.levels.empty());
  EXPECT_TRUE(check.named.empty());
  EXPECT_EQ(merged(check), current());
}

TEST(CheckActivation, AcceptsTheBoundsZeroAndOne) {
  const auto check = check_activation(message({"SL", "GGp_left"}, {0.0, 1.0}), kMuscles);
  ASSERT_TRUE(check.accepted) << check.reason;
  EXPECT_EQ(merged(check), vector({1.0, 0.2, 0.3, 0.0}));
}

// The sender is repeated in logs and rejection notices: short, printable ASCII.
TEST(CheckActivation, RejectsALongOrUnprintableSender) {
  auto msg = message({"SL"}, {0.5});
  msg.sender = std::string(100, 'x');
  EXPECT_TRUE(check_activation(msg, kMuscles).accepted);
  msg.sender += 'x';
  expect_rejected(msg, {"sender", "101 bytes", "more than 100"});
  msg.sender = "ep_controller:1\nsim_server: shutdown at step 99";
  expect_rejected(msg, {"sender", "byte 10", "printable ASCII"});
  msg.sender = "caf\xc3\xa9";
  expect_rejected(msg, {"sender", "byte 195"});
}

TEST(CheckActivation, RejectsNegativeNumMuscles) {
  auto msg = message({}, {});
  msg.num_muscles = -2;
  expect_rejected(msg, {"num_muscles", "-2", "negative"});
}

TEST(CheckActivation, RejectsNumMusclesNotMatchingNames) {
  auto msg = message({"SL"}, {0.5});
  msg.num_muscles = 2;
  msg.levels = {0.5, 0.5};
  expect_rejected(msg, {"num_muscles = 2", "names has 1"});
}

TEST(CheckActivation, RejectsNumMusclesNotMatchingLevels) {
  auto msg = message({"SL", "SG_left"}, {0.5});
  expect_rejected(msg, {"num_muscles = 2", "levels has 1"});
}

TEST(CheckActivation, RejectsUnknownMuscleName) {
  expect_rejected(message({"SL", "GGx"}, {0.5, 0.5}), {"names[1]", "\"GGx\"", "not a muscle"});
}

TEST(CheckActivation, RejectsDuplicateMuscleName) {
  expect_rejected(message({"SL", "SG_left", "SL"}, {0.5, 0.5, 0.6}),
                  {"names[2]", "\"SL\"", "repeats names[0]"});
}

TEST(CheckActivation, RejectsNaNLevel) {
  expect_rejected(message({"SL", "SG_left"}, {0.5, std::nan("")}),
                  {"levels[1]", "SG_left", "nan", "not finite"});
}

TEST(CheckActivation, RejectsInfiniteLevel) {
  expect_rejected(message({"SL"}, {std::numeric_limits<double>::infinity()}),
                  {"levels[0]", "SL", "inf", "not finite"});
}

TEST(CheckActivation, RejectsLevelAboveOne) {
  expect_rejected(message({"GGp_left"}, {1.0000001}),
                  {"levels[0]", "GGp_left", "1.0000001", "outside [0, 1]"});
}

TEST(CheckActivation, RejectsNegativeLevel) {
  expect_rejected(message({"GGp_left", "SL"}, {0.5, -0.25}),
                  {"levels[1]", "SL", "-0.25", "outside [0, 1]"});
}

TEST(CheckActivation, RejectsStepBelowMinusOne) {
  expect_rejected(message({"SL"}, {0.5}, -2), {"step = -2"});
}

TEST(CheckActivation, OneBadEntryRejectsTheWholeMessage) {
  // The good entries before the bad one are not applied: no half update.
  const auto check =
      check_activation(message({"GGp_left", "GGp_right", "SL"}, {0.9, 0.9, 2.0}), kMuscles);
  EXPECT_FALSE(check.accepted);
  EXPECT_TRUE(check.levels.empty());
  EXPECT_NE(check.reason.find("levels[2]"), std::string::npos) << check.reason;
}

TEST(CheckActivation, MergingIntoTooFewLevelsThrows) {
  const auto check = check_activation(message({"SL"}, {0.5}), kMuscles);
  ASSERT_TRUE(check.accepted) << check.reason;
  Eigen::VectorXd two(2);
  two << 0.1, 0.2;
  EXPECT_THROW(check.merge_into(two), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::bus
