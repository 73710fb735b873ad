// The bus's own receiving side (UdpmReceiver) on a real loopback bus: liblcm's messages, short
// and fragmented, arrive whole; hostile datagrams (the fragment pair that crashes liblcm 1.3.1,
// a 66-byte claim of 256 MB, fragments out of order, garbage) are dropped and counted, and the
// receiver goes on. One udpm port per test, 7961-7967 (ctest runs them in parallel).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/lcm_url.hpp"
#include "bus/udpm_receiver.hpp"
#include "support/lcm_datagrams.hpp"

namespace tongue::bus {
namespace {

using testing::DatagramSender;
using testing::fragment;

constexpr std::size_t kLimit = 1 << 20;  // bytes, the test channel's
const std::string kChannel = "FUZZ_CHANNEL";

// Receives until want messages have come or 3 s have passed (generous on a loaded machine).
std::vector<ReceivedMessage> receive(UdpmReceiver& r, std::size_t want) {
  std::vector<ReceivedMessage> out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (out.size() < want && std::chrono::steady_clock::now() < end) r.receive(50, 64, out);
  return out;
}

// Reads whatever is waiting (the datagrams were sent before: loopback delivers at once, the
// waits absorb a loaded machine).
void drain(UdpmReceiver& r, std::vector<ReceivedMessage>& out) {
  for (int i = 0; i < 10; ++i) r.receive(20, 64, out);
}

// A receiver of kChannel, a raw sender and liblcm's publisher, all on one port.
struct Bus {
  explicit Bus(int port)
      : url("udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304"),
        receiver(parse_lcm_url(url), {{kChannel, kLimit}}),
        sender(port),
        lcm(url) {}
  std::string url;
  UdpmReceiver receiver;
  DatagramSender sender;
  lcm::LCM lcm;
};

class Receiver : public ::testing::Test {
 protected:
  void open(int port) {
    bus_ = std::make_unique<Bus>(port);
    ASSERT_TRUE(bus_->lcm.good());
  }
  std::unique_ptr<Bus> bus_;
};

TEST_F(Receiver, LcmMessagesShortAndFragmentedArriveWhole) {
  open(7961);
  std::vector<std::uint8_t> small(100), large(300000);
  for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<std::uint8_t>(i * 7);
  ASSERT_EQ(bus_->lcm.publish(kChannel, small.data(), small.size()), 0);
  ASSERT_EQ(bus_->lcm.publish(kChannel, large.data(), large.size()), 0);  // 5 fragments
  ASSERT_EQ(bus_->lcm.publish("OTHER", small.data(), small.size()), 0);   // not received
  const auto got = receive(bus_->receiver, 2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].bytes, small);
  EXPECT_EQ(got[1].bytes, large);
  EXPECT_EQ(bus_->receiver.drops().total(), 0);
}

TEST_F(Receiver, OversizeMessagesAreDroppedOnTheirDeclaredSize) {
  open(7962);
  const std::vector<std::uint8_t> big(kLimit + 1);
  ASSERT_EQ(bus_->lcm.publish(kChannel, big.data(), big.size()), 0);
  ASSERT_TRUE(bus_->sender.send(testing::huge_claim(1, kChannel)));
  std::vector<ReceivedMessage> got;
  drain(bus_->receiver, got);
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(bus_->receiver.drops().oversize, 2);
}

// The two datagrams that crash liblcm 1.3.1 (its bounds check offset + size wraps at 2^32).
TEST_F(Receiver, TheOverflowingFragmentPairIsDropped) {
  open(7963);
  for (const auto& d : testing::overflowing_fragments(7, kChannel))
    ASSERT_TRUE(bus_->sender.send(d));
  const std::vector<std::uint8_t> after(10, 1);
  ASSERT_EQ(bus_->lcm.publish(kChannel, after.data(), after.size()), 0);
  const auto got = receive(bus_->receiver, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].bytes, after);
  EXPECT_EQ(bus_->receiver.drops().bad_fragment, 1);
}

TEST_F(Receiver, FragmentsOutOfOrderOrInconsistentAreDropped) {
  open(7964);
  const std::vector<std::uint8_t> ten(10, 2);
  const testing::Datagram cases[][2] = {
      // second fragment at the wrong offset
      {fragment(1, 20, 0, 0, 2, kChannel, ten), fragment(1, 20, 5, 1, 2, "", ten)},
      // second fragment of another size declared
      {fragment(2, 20, 0, 0, 2, kChannel, ten), fragment(2, 21, 10, 1, 2, "", ten)},
      // fragment 2 of 3 where 1 is due
      {fragment(3, 30, 0, 0, 3, kChannel, ten), fragment(3, 30, 10, 2, 3, "", ten)},
      // more data than declared
      {fragment(4, 15, 0, 0, 2, kChannel, ten), fragment(4, 15, 10, 1, 2, "", ten)},
      // less data than declared in the last fragment
      {fragment(5, 25, 0, 0, 2, kChannel, ten), fragment(5, 25, 10, 1, 2, "", ten)},
  };
  for (const auto& pair : cases)
    for (const auto& d : pair) ASSERT_TRUE(bus_->sender.send(d));
  std::vector<ReceivedMessage> got;
  drain(bus_->receiver, got);
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(bus_->receiver.drops().bad_fragment, 5);
}

TEST_F(Receiver, AHandMadeFragmentedMessageArrivesWhole) {
  open(7965);
  const std::vector<std::uint8_t> a(10, 3), b(7, 4);
  ASSERT_TRUE(bus_->sender.send(fragment(9, 17, 0, 0, 2, kChannel, a)));
  ASSERT_TRUE(bus_->sender.send(fragment(9, 17, 10, 1, 2, "", b)));
  const auto got = receive(bus_->receiver, 1);
  ASSERT_EQ(got.size(), 1u);
  std::vector<std::uint8_t> whole = a;
  whole.insert(whole.end(), b.begin(), b.end());
  EXPECT_EQ(got[0].bytes, whole);
}

// Seeded random datagrams, half of them with a valid magic: none is delivered as a message of
// the wrong size, and the receiver still takes a real message afterwards.
TEST_F(Receiver, RandomDatagramsNeverStopIt) {
  open(7966);
  std::mt19937 random(42);
  constexpr int kDatagrams = 3000;
  for (int i = 0; i < kDatagrams; ++i) {
    testing::Datagram d(random() % 200);
    for (auto& byte : d) byte = static_cast<std::uint8_t>(random());
    if (d.size() >= 4 && i % 2 == 0) {
      d[0] = 'L', d[1] = 'C', d[2] = '0', d[3] = (i % 4 == 0) ? '2' : '3';
    }
    bus_->sender.send(d);
    if (i % 500 == 0) {
      std::vector<ReceivedMessage> got;
      bus_->receiver.receive(0, 64, got);  // keep the socket buffer from filling
      for (const auto& m : got) EXPECT_LE(m.bytes.size(), kLimit);
    }
  }
  std::vector<ReceivedMessage> got;
  drain(bus_->receiver, got);
  const std::vector<std::uint8_t> after(10, 5);
  ASSERT_EQ(bus_->lcm.publish(kChannel, after.data(), after.size()), 0);
  got = receive(bus_->receiver, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].bytes, after);
  std::printf("random datagrams: %d sent, %lld dropped as not LCM or bad fragments\n", kDatagrams,
              static_cast<long long>(bus_->receiver.drops().total()));
}

TEST_F(Receiver, ABatchIsBounded) {
  open(7967);
  const std::vector<std::uint8_t> one(8, 6);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(bus_->lcm.publish(kChannel, one.data(), one.size()), 0);
  std::vector<ReceivedMessage> first;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (first.empty() && std::chrono::steady_clock::now() < end)
    bus_->receiver.receive(50, 10, first);
  EXPECT_LE(first.size(), 10u);
  EXPECT_EQ(receive(bus_->receiver, 100 - first.size()).size() + first.size(), 100u);
}

}  // namespace
}  // namespace tongue::bus
