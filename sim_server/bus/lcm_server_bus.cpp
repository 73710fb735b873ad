#include "bus/lcm_server_bus.hpp"

#include <stdexcept>

#include "bus/receive_limits.hpp"

namespace tongue::bus {
LcmServerBus::LcmServerBus(const std::string& url, const Channels& channels,
                           std::size_t activation_limit)
    : url_(parse_lcm_url(url)),
      lcm_(url),
      channels_(channels),
      receiver_(lcm_, url_,
                {{channels_.activation, activation_limit}, {channels_.command, kCommandLimit}},
                "sim_server") {}

template <typename Message>
void LcmServerBus::publish(const std::string& channel, const Message& msg) {
  const int size = msg.getEncodedSize();
  encoded_.resize(static_cast<std::size_t>(size));  // no reallocation once it has grown
  if (msg.encode(encoded_.data(), 0, size) != size ||
      lcm_.publish(channel, encoded_.data(), static_cast<unsigned>(size)) != 0)
    throw std::runtime_error("cannot publish on " + channel);
}

void LcmServerBus::publish_model(const tongue_lcm::lcmt_tongue_model& msg) {
  publish(channels_.model, msg);
}

void LcmServerBus::publish_state(const tongue_lcm::lcmt_tongue_state& msg) {
  publish(channels_.state, msg);
}

void LcmServerBus::publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) {
  if (lcm_.publish(channels_.rejection, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.rejection);
}

std::vector<IncomingMessage> LcmServerBus::receive(int timeout_ms) {
  std::vector<ReceivedMessage> received;
  // A signal (SIGINT, SIGTERM) cuts the wait short: the loop then looks at its stop flag.
  receiver_.receive(timeout_ms, received);
  std::vector<IncomingMessage> out;
  out.reserve(received.size());
  for (ReceivedMessage& m : received) {
    IncomingMessage message;
    message.channel = m.channel == channels_.command ? IncomingMessage::Channel::command
                                                     : IncomingMessage::Channel::activation;
    message.bytes = std::move(m.bytes);
    out.push_back(std::move(message));
  }
  return out;
}

}  // namespace tongue::bus
