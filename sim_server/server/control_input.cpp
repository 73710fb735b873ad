#include "server/control_input.hpp"

#include <utility>

#include "common/untrusted_text.hpp"

namespace tongue::server {
namespace {

// Rejections of one kind are reported on stderr at most once per this many seconds.
constexpr double kReportInterval = 1.0;

}  // namespace

ControlInput::ControlInput(Mode mode, int controllers, std::vector<std::string> muscle_names)
    : mode_(mode),
      muscle_names_(std::move(muscle_names)),
      round_(controllers),
      reports_(kReportInterval) {
  clear(static_cast<int>(muscle_names_.size()));
}

void ControlInput::record(const bus::IncomingMessage& message, std::int64_t step, double now) {
  if (message.channel == bus::IncomingMessage::Channel::activation) {
    record_activation(message, step, now);
  } else {
    record_command(message, step);
  }
}

void ControlInput::clear(int num_muscles) {
  held_ = fem::Vector::Zero(num_muscles);
  round_.start(held_);
  command_.reset();
}

std::optional<bus::Command> ControlInput::take_command() {
  return std::exchange(command_, std::nullopt);
}

void ControlInput::record_activation(const bus::IncomingMessage& message, std::int64_t step,
                                     double now) {
  tongue_lcm::lcmt_tongue_activation& msg = activation_;
  // lcm-gen's decode leaves the arrays alone when the count is 0: emptied first (their storage
  // stays).
  msg.names.clear();
  msg.levels.clear();
  std::string reason;
  if (!bus::decode_activation(message.bytes.data(), static_cast<int>(message.bytes.size()), msg,
                              reason)) {
    reject("undecodable activation", reason, step);
    return;
  }
  const bus::ActivationCheck check = bus::check_activation(msg, muscle_names_);
  if (!check.accepted) {
    reject("invalid activation", check.reason, step);
    return;
  }
  if (mode_ != Mode::lockstep) {
    check.merge_into(held_);  // held from the next step on
    last_heard_ = now;
    return;
  }
  add_to_round(msg.step, check, step);
}

void ControlInput::add_to_round(std::int64_t tagged, const bus::ActivationCheck& check,
                                std::int64_t step) {
  if (tagged <= step) {
    reject("stale activation",
           "step " + std::to_string(tagged) + " <= current step " + std::to_string(step), step);
    return;
  }
  if (tagged > step + 1) {
    reject("future activation",
           "step " + std::to_string(tagged) + " > next step " + std::to_string(step + 1), step);
    return;
  }
  // A complete round not yet stepped (paused): a further message starts the next one (with one
  // controller: the latest activation for k + 1 is the one stepped on resume).
  if (round_.complete()) round_.start(round_.held());
  if (const auto muscle = round_.already_set(check.named)) {
    reject("overlapping activation",
           "\"" + muscle_names_[*muscle] + "\" is already set for step " +
               std::to_string(step + 1) + " by an earlier message (each of the " +
               std::to_string(round_.expected()) + " controllers names its own muscles)",
           step);
    return;
  }
  round_.add(check);
}

void ControlInput::record_command(const bus::IncomingMessage& message, std::int64_t step) {
  tongue_lcm::lcmt_tongue_command msg;
  std::string reason;
  if (!bus::decode_command(message.bytes.data(), static_cast<int>(message.bytes.size()), msg,
                           reason)) {
    reject("undecodable command", reason, step);
    return;
  }
  const std::optional<bus::Command> command = bus::parse_command(msg.command);
  if (!command) {
    reject("unknown command", common::quoted_untrusted(msg.command), step);
    return;
  }
  command_ = command;
}

void ControlInput::reject(const std::string& kind, const std::string& reason, std::int64_t step) {
  ++rejected_;
  reports_.report(
      kind, "sim_server: rejected " + kind + " at step " + std::to_string(step) + ": " + reason);
}

}  // namespace tongue::server
