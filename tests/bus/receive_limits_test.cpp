// The channel limits hold the largest legitimate message with room to spare (kLimitFactor):
// an activation naming every muscle with the longest sender, a notice about such an activation.
#include "bus/receive_limits.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bus/activation_validation.hpp"
#include "bus/rejection_notice.hpp"
#include "wire_bytes.hpp"

namespace tongue::bus {
namespace {

tongue_lcm::lcmt_tongue_activation naming_all(const std::vector<std::string>& muscles) {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.step = 1;
  msg.num_muscles = static_cast<std::int32_t>(muscles.size());
  msg.names = muscles;
  msg.levels.assign(muscles.size(), 0.5);
  msg.sender = std::string(kMaxSenderBytes, 's');
  return msg;
}

TEST(ReceiveLimits, ActivationLimitHoldsEveryMuscleAndTheLongestSender) {
  std::vector<std::string> muscles;
  for (int i = 0; i < 200; ++i) muscles.push_back("muscle_with_a_long_name_" + std::to_string(i));
  const std::size_t size = testing::encoded(naming_all(muscles)).size();
  EXPECT_GT(size, kMinActivationLimit);  // the floor is not what passes it
  EXPECT_EQ(activation_limit(muscles), kLimitFactor * size);
  EXPECT_EQ(activation_limit({"SL"}), kMinActivationLimit);
}

TEST(ReceiveLimits, RejectionLimitHoldsANoticeWithTheLongestTexts) {
  // The longest reason check_activation gives: a name it cannot print, escaped and cut.
  auto msg = naming_all({"SL"});
  msg.names[0] = std::string(100000, '\x01');
  const ActivationCheck check = check_activation(msg, {"SL"});
  ASSERT_FALSE(check.accepted);
  const auto notice = rejection_notice(msg, 7, "overlapping activation", check.reason, 0);
  EXPECT_LE(kLimitFactor * testing::encoded(notice).size(), kRejectionLimit);
}

}  // namespace
}  // namespace tongue::bus
