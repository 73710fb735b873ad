#pragma once
// A controller's connection to one tongue server on an LCM bus: subscribed to the server's state,
// model and rejection channels from construction (so nothing published after it is missed),
// queues what arrives, and publishes activations (named by the controller's sender name) and
// commands. The subscriptions are released before the LCM instance goes.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/command.hpp"
#include "bus/messages.hpp"

namespace tongue::controller {

using State = tongue_lcm::lcmt_tongue_state;
using Model = tongue_lcm::lcmt_tongue_model;
using Activation = tongue_lcm::lcmt_tongue_activation;
using Rejection = tongue_lcm::lcmt_tongue_rejection;

// Levels for some muscles (names as in the model), in [0, 1] of each muscle's max force.
struct MuscleLevels {
  std::vector<std::string> names;
  std::vector<double> levels;
};

class ControllerBus {
 public:
  // sender names the activations sent (lcmt_tongue_activation.sender). Throws
  // std::runtime_error naming the URL when LCM cannot be opened or subscribed to.
  ControllerBus(const std::string& url, const bus::Channels& channels, std::string sender);
  ~ControllerBus();
  ControllerBus(const ControllerBus&) = delete;
  ControllerBus& operator=(const ControllerBus&) = delete;

  // Waits at most timeout_ms for messages and queues all that have arrived. Returns false when
  // the wait was cut short by a signal (the caller looks at its flag). Throws when LCM fails.
  bool poll(int timeout_ms);

  std::deque<State>& states() { return states_; }
  std::deque<Model>& models() { return models_; }
  // The rejection notices received, for any sender (undecodable bytes on the channel are
  // dropped: a notice comes from the server or from a process forging one).
  std::deque<Rejection>& rejections() { return rejections_; }

  // Throws std::runtime_error naming the channel when LCM cannot publish.
  void send_activation(std::int64_t step, const MuscleLevels& levels);
  // The last activation again, byte for byte (its utime too): the answer to a repeated state,
  // which the server takes once. Nothing when none was sent.
  void resend_activation();
  const std::optional<Activation>& last_activation() const { return last_activation_; }
  void send_command(bus::Command command);

  const std::string& url() const { return url_; }
  const bus::Channels& channels() const { return channels_; }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const State* msg);
  void on_model(const lcm::ReceiveBuffer*, const std::string&, const Model* msg);
  void on_rejection(const lcm::ReceiveBuffer* rbuf, const std::string&);
  void publish(const Activation& msg);

  std::string url_;
  bus::Channels channels_;
  std::string sender_;
  lcm::LCM lcm_;
  std::vector<lcm::Subscription*> subscriptions_;  // owned by lcm_, released in the destructor
  std::deque<State> states_;
  std::deque<Model> models_;
  std::deque<Rejection> rejections_;
  std::optional<Activation> last_activation_;
};

// Wall-clock microseconds, the utime of the messages sent.
std::int64_t wall_utime();

}  // namespace tongue::controller
