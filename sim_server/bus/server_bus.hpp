#pragma once
// What the server loop knows of the message bus: it publishes the model, states and rejection
// notices, and receives raw bytes on its activation and command channels. LcmServerBus
// (lcm_server_bus.hpp) is the real one; tests can give the loop their own.
#include <cstdint>
#include <vector>

#include "bus/messages.hpp"

namespace tongue::bus {

struct IncomingMessage {
  enum class Channel { activation, command };
  Channel channel = Channel::activation;
  std::vector<std::uint8_t> bytes;  // as received, not yet decoded
};

class ServerBus {
 public:
  virtual ~ServerBus() = default;
  virtual void publish_model(const tongue_lcm::lcmt_tongue_model& msg) = 0;
  virtual void publish_state(const tongue_lcm::lcmt_tongue_state& msg) = 0;
  virtual void publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) = 0;
  // Waits at most timeout_ms (0: does not wait) for incoming messages and returns those that
  // arrived, in order, a bounded number at a time (the rest come with the next calls); empty on
  // timeout or when a signal cut the wait short.
  virtual std::vector<IncomingMessage> receive(int timeout_ms) = 0;
};

}  // namespace tongue::bus
