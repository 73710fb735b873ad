#pragma once
// A bus::ServerBus in memory, for driving ServerLoop without a network: messages are queued
// encoded, as they would arrive, and everything the loop publishes is kept in order.
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "bus/messages.hpp"
#include "bus/server_bus.hpp"

namespace tongue::server::testing {

class FakeServerBus final : public bus::ServerBus {
 public:
  using Channel = bus::IncomingMessage::Channel;

  void publish_model(const tongue_lcm::lcmt_tongue_model& msg) override {
    models.push_back(msg);
    published.push_back('m');
  }
  void publish_state(const tongue_lcm::lcmt_tongue_state& msg) override {
    states.push_back(msg);
    published.push_back('s');
    if (on_state) on_state(msg);
  }
  void publish_rejection(const tongue_lcm::lcmt_tongue_rejection& msg) override {
    rejections.push_back(msg);
    published.push_back('r');
  }
  // Everything queued, at once (as LCM hands over a burst); with nothing queued it waits the
  // whole timeout, as a quiet bus does.
  std::vector<bus::IncomingMessage> receive(int timeout_ms) override {
    ++receives;
    if (incoming.empty() && timeout_ms > 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    std::vector<bus::IncomingMessage> out(incoming.begin(), incoming.end());
    incoming.clear();
    return out;
  }

  void send_raw(Channel channel, std::vector<std::uint8_t> bytes) {
    incoming.push_back({channel, std::move(bytes)});
  }
  // sender "" names none (every message then counts as it comes).
  void send_activation(std::int64_t step, const std::vector<std::string>& names,
                       const std::vector<double>& levels, const std::string& sender = "",
                       std::int64_t utime = 0) {
    tongue_lcm::lcmt_tongue_activation msg;
    msg.utime = utime;
    msg.step = step;
    msg.num_muscles = static_cast<std::int32_t>(names.size());
    msg.names = names;
    msg.levels = levels;
    msg.sender = sender;
    send_raw(Channel::activation, encode(msg));
  }
  void send_command(const std::string& command) {
    tongue_lcm::lcmt_tongue_command msg;
    msg.utime = 0;
    msg.command = command;
    send_raw(Channel::command, encode(msg));
  }

  template <typename Message>
  static std::vector<std::uint8_t> encode(const Message& msg) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  }

  std::deque<bus::IncomingMessage> incoming;
  std::vector<tongue_lcm::lcmt_tongue_model> models;
  std::vector<tongue_lcm::lcmt_tongue_state> states;
  std::vector<tongue_lcm::lcmt_tongue_rejection> rejections;
  std::string published;  // 'm' model, 's' state, 'r' rejection, in the order published
  int receives = 0;
  // Called on every state published, e.g. a controller that answers it.
  std::function<void(const tongue_lcm::lcmt_tongue_state&)> on_state;
};

}  // namespace tongue::server::testing
