#pragma once
// What the bus has asked of a server so far, recorded message by message and never acted on
// here: the activations (lock-step: merged into the round for the next step; fast and real-time:
// into the levels held), the command waiting to be run, and the rejected messages (counted, and
// reported on stderr at most once per kind per second). The server loop reads it and decides
// when to step.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bus/activation_validation.hpp"
#include "bus/command.hpp"
#include "bus/server_bus.hpp"
#include "common/rate_limited_reporter.hpp"
#include "fem/types.hpp"
#include "server/activation_round.hpp"
#include "server/server_options.hpp"

namespace tongue::server {

class ControlInput {
 public:
  // Activations are judged by mode's rules (lock-step: rounds of controllers messages tagged
  // with the next step) against muscle_names (the model's order). Throws std::invalid_argument
  // when controllers < 1.
  ControlInput(Mode mode, int controllers, std::vector<std::string> muscle_names);

  // Decodes, checks and records message; step is the run's last accepted step, now the steady
  // clock [s]. A message that cannot be taken is rejected: counted and reported.
  void record(const bus::IncomingMessage& message, std::int64_t step, double now);

  // Step 0: all levels 0, an empty round, no command waiting (rejections are kept).
  void clear(int num_muscles);
  // Lock-step, after a step taken with levels: the next round starts from them.
  void next_round(const fem::Vector& levels) { round_.start(levels); }
  void clear_rejected() { rejected_ = 0; }

  // The command recorded since the last call, if any.
  std::optional<bus::Command> take_command();
  const ActivationRound& round() const { return round_; }
  // Fast and real-time: the levels every step uses until a message changes them.
  const fem::Vector& held() const { return held_; }
  void zero_held() { held_.setZero(); }  // real-time silence with decay
  std::int64_t rejected() const { return rejected_; }
  // Fast and real-time: steady-clock s of the last accepted activation (or of mark_heard).
  double last_heard() const { return last_heard_; }
  void mark_heard(double now) { last_heard_ = now; }  // a start, a resume or a reset

 private:
  void record_activation(const bus::IncomingMessage& message, std::int64_t step, double now);
  void add_to_round(std::int64_t tagged, const bus::ActivationCheck& check, std::int64_t step);
  void record_command(const bus::IncomingMessage& message, std::int64_t step);
  void reject(const std::string& kind, const std::string& reason, std::int64_t step);

  Mode mode_;
  std::vector<std::string> muscle_names_;
  // Lock-step: the messages accepted for the next step so far, merged; complete only while the
  // loop does not step (paused: a complete round is stepped on resume).
  ActivationRound round_;
  fem::Vector held_;
  std::optional<bus::Command> command_;
  std::int64_t rejected_ = 0;
  double last_heard_ = 0.0;
  common::RateLimitedReporter reports_;
  // The last activation decoded, kept so that the next one is decoded into its storage.
  tongue_lcm::lcmt_tongue_activation activation_;
};

}  // namespace tongue::server
