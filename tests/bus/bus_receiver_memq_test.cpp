// BusReceiver on the in-process bus (memq://), where liblcm receives: the size limit is checked
// before the copy, and one receive() returns a bounded batch.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/bus_receiver.hpp"
#include "bus/lcm_url.hpp"

namespace tongue::bus {
namespace {

TEST(BusReceiverMemq, OversizeMessagesAreDroppedAndBatchesBounded) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  BusReceiver receiver(lcm, parse_lcm_url("memq://"), {{"IN", 100}}, "test");
  const std::vector<std::uint8_t> fits(100, 1), too_big(101, 2);
  lcm.publish("IN", too_big.data(), too_big.size());
  for (int i = 0; i < 100; ++i) lcm.publish("IN", fits.data(), fits.size());
  lcm.publish("OTHER", fits.data(), fits.size());
  std::vector<ReceivedMessage> got;
  ASSERT_TRUE(receiver.receive(100, got));
  EXPECT_EQ(got.size(), BusReceiver::kBatch);
  for (int call = 0; call < 10 && got.size() < 100; ++call) receiver.receive(10, got);
  EXPECT_EQ(got.size(), 100u);
  for (const ReceivedMessage& m : got) EXPECT_EQ(m.bytes, fits);
  EXPECT_EQ(receiver.drops().oversize, 1);
}

}  // namespace
}  // namespace tongue::bus
