#pragma once
// ServerBus on an lcm::LCM: raw subscriptions on the activation and command channels (their bytes
// go to decode_activation and decode_command, never straight to lcm-gen's decoder), publications
// on the state and model channels.
#include <deque>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/server_bus.hpp"

namespace tongue::bus {

class LcmServerBus final : public ServerBus {
 public:
  // Throws std::runtime_error naming the URL when LCM cannot be initialized on it.
  LcmServerBus(const std::string& url, const Channels& channels);
  LcmServerBus(const LcmServerBus&) = delete;
  LcmServerBus& operator=(const LcmServerBus&) = delete;

  void publish_model(const tongue_lcm::lcmt_tongue_model& msg) override;
  void publish_state(const tongue_lcm::lcmt_tongue_state& msg) override;
  void publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) override;
  std::vector<IncomingMessage> receive(int timeout_ms) override;

 private:
  struct Subscriber {
    LcmServerBus* bus;
    IncomingMessage::Channel channel;
  };
  static void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                         Subscriber* subscriber);

  lcm::LCM lcm_;
  Channels channels_;
  Subscriber activation_{this, IncomingMessage::Channel::activation};
  Subscriber command_{this, IncomingMessage::Channel::command};
  std::deque<IncomingMessage> queue_;
};

}  // namespace tongue::bus
