// The command names and the check of raw command bytes: whole messages decode, anything else
// fails with a reason, and nothing hostile reaches lcm-gen's decoder.
#include "bus/command.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "wire_bytes.hpp"

namespace tongue::bus {
namespace {

using testing::encoded;
using testing::put_int32;

constexpr std::size_t kLengthOffset = 16;  // after fingerprint and utime

bool decodes(const std::vector<std::uint8_t>& bytes, std::string& reason,
             tongue_lcm::lcmt_tongue_command& out) {
  return decode_command(bytes.data(), static_cast<int>(bytes.size()), out, reason);
}

TEST(Command, EveryNameParsesBackToItsCommand) {
  EXPECT_EQ(kCommands.size(), 5u);
  for (const Command c : kCommands) EXPECT_EQ(parse_command(command_name(c)), c);
  EXPECT_EQ(command_name(Command::describe), "describe");
  EXPECT_EQ(command_names("|"), "reset|pause|resume|shutdown|describe");
}

TEST(Command, OnlyExactNamesParse) {
  for (const char* name : {"", "Reset", "reset ", "stop", "shutdown\n"})
    EXPECT_EQ(parse_command(name), std::nullopt) << name;
}

TEST(Command, TheMessageOfACommandCarriesItsName) {
  const tongue_lcm::lcmt_tongue_command msg = command_message(Command::pause, 42);
  EXPECT_EQ(msg.utime, 42);
  EXPECT_EQ(msg.command, "pause");
}

TEST(DecodeCommand, DecodesAWholeMessage) {
  const auto bytes = encoded(command_message(Command::shutdown, 7));
  tongue_lcm::lcmt_tongue_command out;
  std::string reason = "stale";
  ASSERT_TRUE(decodes(bytes, reason, out)) << reason;
  EXPECT_TRUE(reason.empty());
  EXPECT_EQ(out.utime, 7);
  EXPECT_EQ(out.command, "shutdown");
}

TEST(DecodeCommand, AnEmptyNameDecodes) {
  // Length 1: just the NUL. Decodable; parse_command then refuses it.
  tongue_lcm::lcmt_tongue_command msg;
  msg.utime = 0;
  const auto bytes = encoded(msg);
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  ASSERT_TRUE(decodes(bytes, reason, out)) << reason;
  EXPECT_EQ(out.command, "");
}

TEST(DecodeCommand, EveryTruncationFailsWithAReason) {
  const auto bytes = encoded(command_message(Command::describe, 1));
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    tongue_lcm::lcmt_tongue_command out;
    std::string reason;
    EXPECT_FALSE(decode_command(bytes.data(), static_cast<int>(size), out, reason)) << size;
    EXPECT_NE(reason.find("lcmt_tongue_command"), std::string::npos) << reason;
  }
}

TEST(DecodeCommand, BadStringLengthsFailNamingTheLength) {
  for (const std::int32_t length : {0, -1, -5, std::numeric_limits<std::int32_t>::min(), 10,
                                    std::numeric_limits<std::int32_t>::max()}) {
    auto bytes = encoded(command_message(Command::reset, 1));
    put_int32(bytes, kLengthOffset, length);
    tongue_lcm::lcmt_tongue_command out;
    std::string reason;
    EXPECT_FALSE(decodes(bytes, reason, out)) << length;
    EXPECT_NE(reason.find("string length " + std::to_string(length)), std::string::npos) << reason;
  }
}

TEST(DecodeCommand, The43ByteMessageWithAZeroLengthFails) {
  auto bytes = encoded(command_message(Command::reset, 1));  // 8 + 8 + 4 + 6 bytes
  bytes.resize(43, 'x');
  put_int32(bytes, kLengthOffset, 0);
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  EXPECT_FALSE(decodes(bytes, reason, out));
  EXPECT_NE(reason.find("string length 0"), std::string::npos) << reason;
}

TEST(DecodeCommand, UnterminatedStringFails) {
  auto bytes = encoded(command_message(Command::reset, 1));
  bytes.back() = 'x';  // the NUL after "reset"
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  EXPECT_FALSE(decodes(bytes, reason, out));
  EXPECT_NE(reason.find("command is not NUL-terminated"), std::string::npos) << reason;
}

TEST(DecodeCommand, TrailingBytesFail) {
  auto bytes = encoded(command_message(Command::reset, 1));
  bytes.insert(bytes.end(), {0, 0, 0});
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  EXPECT_FALSE(decodes(bytes, reason, out));
  EXPECT_NE(reason.find("3 trailing bytes"), std::string::npos) << reason;
}

TEST(DecodeCommand, AnotherTypeFailsOnTheFingerprint) {
  tongue_lcm::lcmt_tongue_activation activation;
  activation.utime = 1;
  activation.step = 2;
  activation.num_muscles = 1;
  activation.names = {"shutdown"};
  activation.levels = {0.5};
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(activation.getEncodedSize()));
  activation.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  EXPECT_FALSE(decodes(bytes, reason, out));
  EXPECT_NE(reason.find("fingerprint"), std::string::npos) << reason;
}

TEST(DecodeCommand, RandomBytesAfterTheFingerprintNeverThrow) {
  const auto valid = encoded(command_message(Command::reset, 1));
  std::mt19937 random(4242);
  for (int trial = 0; trial < 5000; ++trial) {
    std::vector<std::uint8_t> bytes(valid.begin(), valid.begin() + 8);
    bytes.resize(8 + random() % 80);
    for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(random());
    tongue_lcm::lcmt_tongue_command out;
    std::string reason;
    if (!decodes(bytes, reason, out)) {
      EXPECT_FALSE(reason.empty());
    }
  }
}

TEST(DecodeCommand, NullDataFails) {
  tongue_lcm::lcmt_tongue_command out;
  std::string reason;
  EXPECT_FALSE(decode_command(nullptr, 0, out, reason));
  EXPECT_FALSE(reason.empty());
  EXPECT_FALSE(decode_command(nullptr, 32, out, reason));
  EXPECT_FALSE(reason.empty());
  EXPECT_FALSE(decode_command("x", -1, out, reason));
  EXPECT_FALSE(reason.empty());
}

}  // namespace
}  // namespace tongue::bus
