#include "bus/lcm_server_bus.hpp"

#include <cerrno>
#include <iterator>
#include <stdexcept>

namespace tongue::bus {
namespace {

// Messages LCM may hold per subscription between two reads of the loop. LCM's default (30) drops
// every message beyond it, so a burst of a few dozen bad activations could also drop the valid
// activation or the shutdown that follows it; the ring buffer (recv_buf_size in the URL) and the
// socket's receive buffer still bound what is held.
constexpr int kQueueCapacity = 100000;

}  // namespace

LcmServerBus::LcmServerBus(const std::string& url, const Channels& channels)
    : lcm_(url), channels_(channels) {
  if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus at '" + url + "'");
  for (auto* subscriber : {&activation_, &command_}) {
    const std::string& channel =
        subscriber == &activation_ ? channels_.activation : channels_.command;
    lcm::Subscription* subscription =
        lcm_.subscribeFunction(channel, &LcmServerBus::on_message, subscriber);
    if (subscription == nullptr || subscription->setQueueCapacity(kQueueCapacity) != 0)
      throw std::runtime_error("cannot subscribe to " + channel + " on '" + url + "'");
  }
}

void LcmServerBus::on_message(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/,
                              Subscriber* subscriber) {
  const auto* data = static_cast<const std::uint8_t*>(rbuf->data);
  IncomingMessage message;
  message.channel = subscriber->channel;
  message.bytes.assign(data, data + rbuf->data_size);
  subscriber->bus->queue_.push_back(std::move(message));
}

void LcmServerBus::publish_model(const tongue_lcm::lcmt_tongue_model& msg) {
  if (lcm_.publish(channels_.model, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.model);
}

void LcmServerBus::publish_state(const tongue_lcm::lcmt_tongue_state& msg) {
  if (lcm_.publish(channels_.state, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.state);
}

void LcmServerBus::publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) {
  if (lcm_.publish(channels_.rejection, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.rejection);
}

std::vector<IncomingMessage> LcmServerBus::receive(int timeout_ms) {
  if (queue_.empty()) {
    // Waits for the first message, then takes whatever else is already there without waiting.
    int handled = lcm_.handleTimeout(timeout_ms < 0 ? 0 : timeout_ms);
    while (handled > 0) handled = lcm_.handleTimeout(0);
    // A signal (SIGINT, SIGTERM) interrupts the wait: the loop then looks at its stop flag.
    if (handled < 0 && errno != EINTR)
      throw std::runtime_error("LCM failed while receiving messages");
  }
  std::vector<IncomingMessage> out(std::make_move_iterator(queue_.begin()),
                                   std::make_move_iterator(queue_.end()));
  queue_.clear();
  return out;
}

}  // namespace tongue::bus
