#pragma once
// ServerBus on an lcm::LCM: raw subscriptions on the activation and command channels (bytes are
// decoded and checked by the loop, never by lcm-gen's decoder on untrusted input), publications
// on the state and model channels.
#include <deque>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "server/server_bus.hpp"

namespace tongue::server {

class LcmServerBus final : public ServerBus {
 public:
  // Throws std::runtime_error naming the URL when LCM cannot be initialized on it.
  LcmServerBus(const std::string& url, const bus::Channels& channels);
  LcmServerBus(const LcmServerBus&) = delete;
  LcmServerBus& operator=(const LcmServerBus&) = delete;

  void publish_model(const tongue_lcm::lcmt_tongue_model& msg) override;
  void publish_state(const tongue_lcm::lcmt_tongue_state& msg) override;
  std::vector<IncomingMessage> receive(int timeout_ms) override;

 private:
  struct Subscriber {
    LcmServerBus* bus;
    IncomingMessage::Channel channel;
  };
  static void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                         Subscriber* subscriber);

  lcm::LCM lcm_;
  bus::Channels channels_;
  Subscriber activation_{this, IncomingMessage::Channel::activation};
  Subscriber command_{this, IncomingMessage::Channel::command};
  std::deque<IncomingMessage> queue_;
};

}  // namespace tongue::server
