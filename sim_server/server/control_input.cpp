#include "server/control_input.hpp"

#include <utility>

#include "common/untrusted_text.hpp"

namespace tongue::server {
namespace {

// Rejections of one kind are reported on stderr at most once per this many seconds.
constexpr double kReportInterval = 1.0;
// At most this many rejection notices per second go on the bus, so that a flood of bad
// activations is not answered by a flood of notices (a controller needs only its first).
constexpr int kNoticesPerSecond = 100;

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
  senders_.clear();
  round_rejections_ = 0;
  command_.reset();
}

void ControlInput::next_round(const fem::Vector& levels) {
  round_.start(levels);
  senders_.next_round();
  round_rejections_ = 0;
}

std::vector<tongue_lcm::lcmt_tongue_rejection> ControlInput::take_notices() {
  return std::exchange(notices_, {});
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
    reject_activation(msg, "invalid activation", check.reason, step, now);
    return;
  }
  if (mode_ != Mode::lockstep) {
    check.merge_into(held_);  // held from the next step on
    last_heard_ = now;
    return;
  }
  add_to_round(msg, message.bytes, check, step, now);
}

void ControlInput::add_to_round(const tongue_lcm::lcmt_tongue_activation& msg,
                                const RoundSenders::Bytes& bytes, const bus::ActivationCheck& check,
                                std::int64_t step, double now) {
  const std::int64_t tagged = msg.step;
  // A repeat of a message already taken, for this step or the one just made: the sender
  // answered a state published again (a loss, or a slow answer), and it is taken once.
  if ((tagged == step && senders_.repeats_last_round(msg.sender, bytes)) ||
      (tagged == step + 1 &&
       senders_.in_open_round(msg.sender, bytes) == RoundSenders::Seen::repeat)) {
    ++repeats_;
    return;
  }
  if (tagged <= step) {
    reject_activation(msg, "stale activation",
                      "step " + std::to_string(tagged) + " <= current step " + std::to_string(step),
                      step, now);
    return;
  }
  if (tagged > step + 1) {
    reject_activation(msg, "future activation",
                      "step " + std::to_string(tagged) + " > next step " + std::to_string(step + 1),
                      step, now);
    return;
  }
  // A complete round not yet stepped (paused): a further message starts the next one (with one
  // controller: the latest activation for k + 1 is the one stepped on resume).
  if (round_.complete()) {
    round_.start(round_.held());
    senders_.reopen();
  }
  if (senders_.in_open_round(msg.sender, bytes) == RoundSenders::Seen::changed) {
    reject_activation(msg, "second activation",
                      "sender " + common::quoted_untrusted(msg.sender, bus::kMaxSenderBytes) +
                          " already sent another activation for step " + std::to_string(step + 1) +
                          " (one message per controller and step)",
                      step, now);
    return;
  }
  if (const auto muscle = round_.already_set(check.named)) {
    reject_activation(msg, "overlapping activation",
                      "\"" + muscle_names_[*muscle] + "\" is already set for step " +
                          std::to_string(step + 1) + " by an earlier message (each of the " +
                          std::to_string(round_.expected()) + " controllers names its own muscles)",
                      step, now);
    return;
  }
  round_.add(check);
  senders_.take(msg.sender, bytes);
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

void ControlInput::reject_activation(const tongue_lcm::lcmt_tongue_activation& msg,
                                     const std::string& kind, const std::string& reason,
                                     std::int64_t step, double now) {
  reject(kind, reason, step);
  if (mode_ == Mode::lockstep && msg.step == step + 1) {
    ++round_rejections_;
    round_rejection_ = kind + " from " + common::quoted_untrusted(msg.sender, bus::kMaxSenderBytes);
  }
  // A sender longer than any a controller may give names no one who could read the notice.
  if (msg.sender.size() > bus::kMaxSenderBytes) return;
  if (now - notice_window_start_ >= 1.0) {
    notice_window_start_ = now;
    notices_in_window_ = 0;
  }
  if (notices_in_window_ >= kNoticesPerSecond) return;
  ++notices_in_window_;
  notices_.push_back(bus::rejection_notice(msg, step, kind, reason, 0));
}

void ControlInput::reject(const std::string& kind, const std::string& reason, std::int64_t step) {
  ++rejected_;
  reports_.report(
      kind, "sim_server: rejected " + kind + " at step " + std::to_string(step) + ": " + reason);
}

}  // namespace tongue::server
