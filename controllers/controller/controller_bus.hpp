#pragma once
// A controller's connection to one tongue server on an LCM bus: receiving on the server's state,
// model and rejection channels from construction (so nothing published after it is missed),
// queues what arrives, and publishes activations (named by the controller's sender name) and
// commands. Every message received is checked before it is queued, since any process on the bus
// can send on those channels: its size against the channel's limit (bus/receive_limits.hpp)
// before it is copied, its bytes by the checked decoders (bus/published_decode.hpp,
// bus/rejection_notice.hpp), and, once the model is known, a state against it (its muscles, its
// node indices, finite values) and a later model against the first (the same muscles). A
// rejected message is counted and reported on stderr (at most one line per kind per second),
// never thrown.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/bus_receiver.hpp"
#include "bus/channels.hpp"
#include "bus/command.hpp"
#include "bus/lcm_url.hpp"
#include "bus/messages.hpp"
#include "common/rate_limited_reporter.hpp"

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
  // program names the controller in its reports, sender the activations it sends
  // (lcmt_tongue_activation.sender). Throws std::invalid_argument for a URL bus::parse_lcm_url
  // rejects, std::runtime_error naming the URL when LCM cannot be opened or received on.
  ControllerBus(const std::string& url, const bus::Channels& channels, const std::string& program,
                std::string sender);
  ControllerBus(const ControllerBus&) = delete;
  ControllerBus& operator=(const ControllerBus&) = delete;

  // Waits at most timeout_ms for messages and queues those that arrived (a bounded batch: the
  // rest come with the next calls). Returns false when the wait was cut short by a signal (the
  // caller looks at its flag). Throws when LCM fails.
  bool poll(int timeout_ms);

  // The model the controller works with: states are checked against it from now on (those
  // already queued too), and later models must have its muscles.
  void set_model(const Model& model);

  std::deque<State>& states() { return states_; }
  std::deque<Model>& models() { return models_; }
  // Messages received and rejected so far (undecodable, or not fitting the model).
  std::int64_t rejected() const { return rejected_; }
  // The rejection notices received, for any sender (a notice comes from the server or from a
  // process forging one).
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
  void take(const bus::ReceivedMessage& message);
  // Why state does not fit the model, or nullopt.
  std::optional<std::string> misfit(const State& state) const;
  void reject(const std::string& kind, const std::string& reason);
  void publish(const Activation& msg);

  std::string url_;
  bus::Channels channels_;
  std::string program_;
  std::string sender_;
  bus::LcmUrl parsed_url_;
  lcm::LCM lcm_;
  bus::BusReceiver receiver_;
  common::RateLimitedReporter reports_;
  std::optional<Model> model_;
  std::deque<State> states_;
  std::deque<Model> models_;
  std::int64_t rejected_ = 0;
  std::deque<Rejection> rejections_;
  std::optional<Activation> last_activation_;
};

// Wall-clock microseconds, the utime of the messages sent.
std::int64_t wall_utime();

}  // namespace tongue::controller
