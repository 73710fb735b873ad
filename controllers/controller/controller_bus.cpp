#include "controller/controller_bus.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "bus/published_decode.hpp"
#include "bus/receive_limits.hpp"
#include "bus/rejection_notice.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::controller {
namespace {

bool all_finite(const std::vector<double>& values) {
  for (const double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

// Muscle and landmark names print in messages and are matched against input files: short
// printable names, as the server's scenes give them.
std::optional<std::string> bad_names(const std::vector<std::string>& names, const char* what) {
  constexpr std::size_t kLongest = 64;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& n = names[i];
    bool printable = !n.empty() && n.size() <= kLongest;
    for (const char c : n) printable = printable && c > ' ' && c < 0x7f;
    if (!printable)
      return std::string(what) + "[" + std::to_string(i) + "] = " + common::quoted_untrusted(n) +
             " is not a name (1-64 printable characters)";
  }
  return std::nullopt;
}

// Why model cannot be controlled, or nullopt.
std::optional<std::string> bad_model(const Model& model) {
  if (const auto why = bad_names(model.muscle_names, "muscle_names")) return why;
  if (const auto why = bad_names(model.landmark_names, "landmark_names")) return why;
  if (!(std::isfinite(model.dt) && model.dt > 0.0)) return "dt is not a positive time";
  if (!all_finite(model.muscle_max_forces) || !all_finite(model.rest_positions))
    return "a value is not finite";
  return std::nullopt;
}

}  // namespace

std::int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

ControllerBus::ControllerBus(const std::string& url, const bus::Channels& channels,
                             const std::string& program, std::string sender)
    : url_(url),
      channels_(channels),
      program_(program),
      sender_(std::move(sender)),
      parsed_url_(bus::parse_lcm_url(url)),
      lcm_(url),
      receiver_(lcm_, parsed_url_,
                {{channels_.state, bus::kStateLimitBeforeModel},
                 {channels_.model, bus::kModelLimit},
                 {channels_.rejection, bus::kRejectionLimit}},
                program),
      reports_(1.0) {}

bool ControllerBus::poll(int timeout_ms) {
  std::vector<bus::ReceivedMessage> received;
  const bool whole = receiver_.receive(timeout_ms, received);
  for (const bus::ReceivedMessage& m : received) take(m);
  return whole;
}

void ControllerBus::take(const bus::ReceivedMessage& message) {
  const int size = static_cast<int>(message.bytes.size());
  std::string reason;
  if (message.channel == channels_.model) {
    Model model;
    if (!bus::decode_model(message.bytes.data(), size, model, reason))
      return reject("undecodable model", reason);
    if (const auto why = bad_model(model)) return reject("model", *why);
    if (model_ && model.muscle_names != model_->muscle_names)
      return reject("model", "its " + std::to_string(model.num_muscles) +
                                 " muscles are not the first model's " +
                                 std::to_string(model_->num_muscles));
    models_.push_back(std::move(model));
    return;
  }
  if (message.channel == channels_.rejection) {
    Rejection notice;
    if (!bus::decode_rejection(message.bytes.data(), size, notice, reason))
      return reject("undecodable rejection notice", reason);
    rejections_.push_back(std::move(notice));
    return;
  }
  State state;
  if (!bus::decode_state(message.bytes.data(), size, state, reason))
    return reject("undecodable state", reason);
  if (const auto why = misfit(state)) return reject("state", *why);
  states_.push_back(std::move(state));
}

std::optional<std::string> ControllerBus::misfit(const State& s) const {
  const std::string step = "step " + std::to_string(s.step) + ": ";
  if (!all_finite(s.positions) || !all_finite(s.muscle_lengths) ||
      !all_finite(s.muscle_velocities) || !all_finite(s.activations) || !std::isfinite(s.time))
    return step + "a value is not finite";
  if (!model_) return std::nullopt;
  if (s.num_muscles != model_->num_muscles)
    return step + std::to_string(s.num_muscles) + " muscles, the model has " +
           std::to_string(model_->num_muscles);
  for (const std::int32_t node : s.node_indices)
    if (node < 0 || node >= model_->num_nodes)
      return step + "node index " + std::to_string(node) + " outside the model's " +
             std::to_string(model_->num_nodes) + " nodes";
  return std::nullopt;
}

void ControllerBus::set_model(const Model& model) {
  model_ = model;
  receiver_.set_limit(channels_.state, bus::state_limit(model));
  std::deque<State> queued;
  queued.swap(states_);
  for (State& s : queued) {
    if (const auto why = misfit(s)) {
      reject("state", *why);
    } else {
      states_.push_back(std::move(s));
    }
  }
}

void ControllerBus::reject(const std::string& kind, const std::string& reason) {
  ++rejected_;
  reports_.report(kind, program_ + ": rejected " + kind + ": " + reason);
}

void ControllerBus::send_activation(std::int64_t step, const MuscleLevels& levels) {
  Activation msg;
  msg.utime = wall_utime();
  msg.step = step;
  msg.num_muscles = static_cast<std::int32_t>(levels.names.size());
  msg.names = levels.names;
  msg.levels = levels.levels;
  msg.sender = sender_;
  publish(msg);
  last_activation_ = std::move(msg);
}

void ControllerBus::resend_activation() {
  if (last_activation_) publish(*last_activation_);
}

void ControllerBus::publish(const Activation& msg) {
  if (lcm_.publish(channels_.activation, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.activation);
}

void ControllerBus::send_command(bus::Command command) {
  const tongue_lcm::lcmt_tongue_command msg = bus::command_message(command, wall_utime());
  if (lcm_.publish(channels_.command, &msg) != 0)
    throw std::runtime_error("cannot publish on " + channels_.command);
}

}  // namespace tongue::controller
