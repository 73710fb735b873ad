// Raw bytes on the activation channel: whole messages decode, anything else fails with a reason.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "bus/activation_validation.hpp"
#include "bus/messages.hpp"
#include "wire_bytes.hpp"

namespace tongue::bus {
namespace {

std::vector<std::uint8_t> encoded_activation() {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.utime = 55;
  msg.step = 3;
  msg.num_muscles = 2;
  msg.names = {"GGp_left", "SL"};
  msg.levels = {0.5, 0.75};
  return testing::encoded(msg);
}

using testing::put_int32;

constexpr std::size_t kNumMusclesOffset = 24;  // after fingerprint, utime, step
constexpr std::size_t kFirstNameOffset = 28;

TEST(DecodeActivation, DecodesAWholeMessage) {
  const auto bytes = encoded_activation();
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason = "stale";
  ASSERT_TRUE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason))
      << reason;
  EXPECT_TRUE(reason.empty());
  EXPECT_EQ(out.utime, 55);
  EXPECT_EQ(out.step, 3);
  EXPECT_EQ(out.names, (std::vector<std::string>{"GGp_left", "SL"}));
  EXPECT_EQ(out.levels, (std::vector<double>{0.5, 0.75}));
}

TEST(DecodeActivation, EveryTruncationFailsWithAReason) {
  const auto bytes = encoded_activation();
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    tongue_lcm::lcmt_tongue_activation out;
    std::string reason;
    EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(size), out, reason))
        << "size " << size;
    EXPECT_NE(reason.find("lcmt_tongue_activation"), std::string::npos) << reason;
  }
}

TEST(DecodeActivation, ShortMessageNamesItsSize) {
  const auto bytes = encoded_activation();
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), 10, out, reason));
  EXPECT_NE(reason.find("10 bytes"), std::string::npos) << reason;
}

TEST(DecodeActivation, TruncatedLevelsAreReported) {
  const auto bytes = encoded_activation();
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()) - 3, out, reason));
  EXPECT_NE(reason.find("truncated"), std::string::npos) << reason;
}

TEST(DecodeActivation, GarbageFailsOnTheFingerprint) {
  std::mt19937 random(12345);
  std::vector<std::uint8_t> bytes(200);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(random());
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("fingerprint"), std::string::npos) << reason;
}

TEST(DecodeActivation, AnotherMessageTypeFailsOnTheFingerprint) {
  tongue_lcm::lcmt_tongue_command command;
  command.utime = 1;
  command.command = "reset and some more text to be long enough";
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(command.getEncodedSize()));
  command.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("fingerprint"), std::string::npos) << reason;
}

TEST(DecodeActivation, GarbageAfterAValidFingerprintFails) {
  // Random bodies behind the right fingerprint: none may crash, throw or allocate without bound.
  const auto valid = encoded_activation();
  std::mt19937 random(777);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> bytes(valid.begin(), valid.begin() + 8);
    bytes.resize(8 + random() % 120);
    for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(random());
    tongue_lcm::lcmt_tongue_activation out;
    std::string reason;
    if (!decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason)) {
      EXPECT_FALSE(reason.empty());
    }
  }
}

TEST(DecodeActivation, NegativeCountFails) {
  auto bytes = encoded_activation();
  put_int32(bytes, kNumMusclesOffset, -1);
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("num_muscles = -1"), std::string::npos) << reason;
}

TEST(DecodeActivation, HugeCountFailsWithoutAllocating) {
  auto bytes = encoded_activation();
  put_int32(bytes, kNumMusclesOffset, 2'000'000'000);
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("num_muscles = 2000000000"), std::string::npos) << reason;
}

TEST(DecodeActivation, BadStringLengthFails) {
  for (const std::int32_t length : {0, -5, 1'000'000}) {
    auto bytes = encoded_activation();
    put_int32(bytes, kFirstNameOffset, length);
    tongue_lcm::lcmt_tongue_activation out;
    std::string reason;
    EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
    EXPECT_NE(reason.find("names[0]"), std::string::npos) << reason;
    EXPECT_NE(reason.find(std::to_string(length)), std::string::npos) << reason;
  }
}

TEST(DecodeActivation, UnterminatedStringFails) {
  auto bytes = encoded_activation();
  bytes[kFirstNameOffset + 4 + 8] = 'x';  // the NUL after "GGp_left"
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("names[0] is not NUL-terminated"), std::string::npos) << reason;
}

TEST(DecodeActivation, TrailingBytesFail) {
  auto bytes = encoded_activation();
  bytes.push_back(0);
  bytes.push_back(0);
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("2 trailing bytes"), std::string::npos) << reason;
}

TEST(DecodeActivation, NullDataFails) {
  tongue_lcm::lcmt_tongue_activation out;
  std::string reason;
  EXPECT_FALSE(decode_activation(nullptr, 0, out, reason));
  EXPECT_FALSE(reason.empty());
  EXPECT_FALSE(decode_activation(nullptr, 16, out, reason));
  EXPECT_FALSE(reason.empty());
}

}  // namespace
}  // namespace tongue::bus
