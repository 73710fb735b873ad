// One activation message through an in-process LCM bus (memq://), received as raw bytes the way
// the server receives it and decoded with decode_activation.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "bus/activation_validation.hpp"
#include "bus/channels.hpp"

namespace tongue::bus {
namespace {

struct RawReceiver {
  int count = 0;
  std::string channel;
  std::vector<unsigned char> bytes;

  void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel_name) {
    ++count;
    channel = channel_name;
    const auto* data = static_cast<const unsigned char*>(buffer->data);
    bytes.assign(data, data + buffer->data_size);
  }
};

TEST(MemqRoundTrip, ActivationArrivesIntact) {
  lcm::LCM bus("memq://");
  ASSERT_TRUE(bus.good());
  const Channels channels("TEST_MEMQ_");

  RawReceiver receiver;
  lcm::Subscription* subscription =
      bus.subscribe(channels.activation, &RawReceiver::on_message, &receiver);
  ASSERT_NE(subscription, nullptr);

  tongue_lcm::lcmt_tongue_activation sent;
  sent.utime = 1'234'567;
  sent.step = 8;
  sent.num_muscles = 2;
  sent.names = {"SG_left", "SL"};
  sent.levels = {0.125, 1.0};
  ASSERT_EQ(bus.publish(channels.activation, &sent), 0);

  ASSERT_GT(bus.handleTimeout(1000), 0) << "nothing received within 1 s";
  ASSERT_EQ(receiver.count, 1);
  EXPECT_EQ(receiver.channel, "TEST_MEMQ_ACTIVATION");

  tongue_lcm::lcmt_tongue_activation received;
  std::string reason;
  ASSERT_TRUE(decode_activation(receiver.bytes.data(), static_cast<int>(receiver.bytes.size()),
                                received, reason))
      << reason;
  EXPECT_EQ(received.utime, sent.utime);
  EXPECT_EQ(received.step, sent.step);
  EXPECT_EQ(received.names, sent.names);
  EXPECT_EQ(received.levels, sent.levels);

  // Nothing else is pending.
  EXPECT_EQ(bus.handleTimeout(10), 0);
  bus.unsubscribe(subscription);
}

}  // namespace
}  // namespace tongue::bus
