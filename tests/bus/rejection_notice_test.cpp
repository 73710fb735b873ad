// Rejection notices: made from the rejected activation, recognized by its sender, and decoded
// from untrusted bytes only when whole.
#include "bus/rejection_notice.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "wire_bytes.hpp"

namespace tongue::bus {
namespace {

using testing::encoded;

tongue_lcm::lcmt_tongue_activation sent() {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.utime = 1234;
  msg.step = 8;
  msg.num_muscles = 1;
  msg.names = {"flexor"};
  msg.levels = {0.5};
  msg.sender = "sequence_player:42";
  return msg;
}

TEST(RejectionNotice, NamesTheMessageAndIsRecognizedByItsSender) {
  const auto notice = rejection_notice(sent(), 7, "overlapping activation", "why", 99);
  EXPECT_EQ(notice.utime, 99);
  EXPECT_EQ(notice.step, 7);
  EXPECT_EQ(notice.sender, "sequence_player:42");
  EXPECT_EQ(notice.activation_step, 8);
  EXPECT_EQ(notice.activation_utime, 1234);
  EXPECT_EQ(notice.kind, "overlapping activation");
  EXPECT_EQ(notice.reason, "why");
  EXPECT_TRUE(is_about(notice, sent()));
  for (int field = 0; field < 3; ++field) {
    auto other = sent();
    if (field == 0) other.sender = "sequence_player:43";
    if (field == 1) other.step = 9;
    if (field == 2) other.utime = 1235;
    EXPECT_FALSE(is_about(notice, other)) << field;
  }
}

TEST(RejectionNotice, DecodesAWholeNoticeOnly) {
  const auto notice = rejection_notice(sent(), 7, "stale activation", "step 8 <= 9", 99);
  std::vector<std::uint8_t> bytes = encoded(notice);
  tongue_lcm::lcmt_tongue_rejection out;
  std::string reason;
  ASSERT_TRUE(decode_rejection(bytes.data(), static_cast<int>(bytes.size()), out, reason))
      << reason;
  EXPECT_EQ(out.sender, notice.sender);
  EXPECT_EQ(out.reason, notice.reason);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_FALSE(decode_rejection(bytes.data(), static_cast<int>(size), out, reason)) << size;
    EXPECT_NE(reason.find("lcmt_tongue_rejection"), std::string::npos) << reason;
  }
  bytes.push_back(0);
  EXPECT_FALSE(decode_rejection(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("1 trailing bytes"), std::string::npos) << reason;
  bytes.pop_back();
  testing::put_int32(bytes, 8 + 8 + 8, -5);  // the sender's length
  EXPECT_FALSE(decode_rejection(bytes.data(), static_cast<int>(bytes.size()), out, reason));
  EXPECT_NE(reason.find("sender"), std::string::npos) << reason;
  const std::vector<std::uint8_t> activation = encoded(sent());
  EXPECT_FALSE(
      decode_rejection(activation.data(), static_cast<int>(activation.size()), out, reason));
  EXPECT_FALSE(decode_rejection(nullptr, 40, out, reason));
}

}  // namespace
}  // namespace tongue::bus
