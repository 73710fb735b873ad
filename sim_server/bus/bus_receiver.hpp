#pragma once
// How the server and the controllers receive: raw bytes on the channels they name, each message
// no larger than its channel's limit, a bounded number per call. On udpm the bytes come from a
// UdpmReceiver and liblcm never receives (its lcm::LCM only publishes: liblcm opens its receive
// socket and thread on the first subscribe or handle, lcm_udpm.c); on memq (in-process) from
// liblcm's raw subscriptions, the limit checked before the copy. Drops are counted and reported
// on stderr, at most one line per kind per second.
#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/lcm_url.hpp"
#include "bus/udpm_receiver.hpp"
#include "common/rate_limited_reporter.hpp"

namespace tongue::bus {

class BusReceiver {
 public:
  // Messages one receive() returns at most: the caller handles those before reading more, so
  // that a command or a signal is seen within one batch of a flood.
  static constexpr std::size_t kBatch = 64;

  // lcm must outlive the receiver. program prefixes the drop reports ("sim_server"). limits as
  // for UdpmReceiver. Throws std::runtime_error when lcm is not open or the bus cannot be
  // received on.
  BusReceiver(lcm::LCM& lcm, const LcmUrl& url, const std::map<std::string, std::size_t>& limits,
              const std::string& program);
  ~BusReceiver();
  BusReceiver(const BusReceiver&) = delete;
  BusReceiver& operator=(const BusReceiver&) = delete;

  void set_limit(const std::string& channel, std::size_t max_bytes);

  // Waits at most timeout_ms for messages and appends at most kBatch to out, in order. Returns
  // false when the wait was cut short by a signal (the caller looks at its flag). Throws
  // std::runtime_error when the bus fails.
  bool receive(int timeout_ms, std::vector<ReceivedMessage>& out);

  // Datagrams and messages dropped so far (on memq only oversize ones can be).
  DropCounts drops() const;

 private:
  struct Subscription {
    BusReceiver* receiver;
    std::size_t limit;
    lcm::Subscription* lcm = nullptr;
  };
  static void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                         Subscription* s);
  void report(const std::string& kind, const std::string& detail);

  lcm::LCM& lcm_;
  std::string program_;
  common::RateLimitedReporter reports_;
  std::unique_ptr<UdpmReceiver> udpm_;
  // memq: the subscriptions (owned by lcm_, released in the destructor) and what they got.
  std::map<std::string, std::unique_ptr<Subscription>> subscriptions_;
  std::deque<ReceivedMessage> pending_;
  DropCounts memq_drops_;
};

}  // namespace tongue::bus
