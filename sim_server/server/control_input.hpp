#pragma once
// What the bus has asked of a server so far, recorded message by message and never acted on
// here: the activations (lock-step: merged into the round for the next step, a sender's unchanged
// repeat taken once; fast and real-time: into the levels held), the command waiting to be run,
// and the rejected messages (counted, reported on stderr at most once per kind per second, and
// for a decodable activation a rejection notice for its sender, at most 100 per second). The
// server loop reads it, publishes the notices and decides when to step.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bus/activation_validation.hpp"
#include "bus/command.hpp"
#include "bus/rejection_notice.hpp"
#include "bus/server_bus.hpp"
#include "common/rate_limited_reporter.hpp"
#include "fem/types.hpp"
#include "server/activation_round.hpp"
#include "server/round_senders.hpp"
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
  void next_round(const fem::Vector& levels);
  void clear_rejected() { rejected_ = 0; }

  // The rejection notices recorded since the last call (utime 0: the publisher stamps them).
  std::vector<tongue_lcm::lcmt_tongue_rejection> take_notices();

  // The command recorded since the last call, if any.
  std::optional<bus::Command> take_command();
  const ActivationRound& round() const { return round_; }
  // Fast and real-time: the levels every step uses until a message changes them.
  const fem::Vector& held() const { return held_; }
  void zero_held() { held_.setZero(); }  // real-time silence with decay
  std::int64_t rejected() const { return rejected_; }
  // Lock-step: activations that repeated one already taken (ignored), since construction.
  std::int64_t repeats() const { return repeats_; }
  // Lock-step: activations tagged with the next step rejected since the round opened, and the
  // last one's kind and sender ("overlapping activation from \"sequence_player:42\"").
  int round_rejections() const { return round_rejections_; }
  const std::string& round_rejection() const { return round_rejection_; }
  // Fast and real-time: steady-clock s of the last accepted activation (or of mark_heard).
  double last_heard() const { return last_heard_; }
  void mark_heard(double now) { last_heard_ = now; }  // a start, a resume or a reset

 private:
  void record_activation(const bus::IncomingMessage& message, std::int64_t step, double now);
  void add_to_round(const tongue_lcm::lcmt_tongue_activation& msg, const RoundSenders::Bytes& bytes,
                    const bus::ActivationCheck& check, std::int64_t step, double now);
  void record_command(const bus::IncomingMessage& message, std::int64_t step);
  void reject(const std::string& kind, const std::string& reason, std::int64_t step);
  // reject, and a notice for msg's sender (rate-limited).
  void reject_activation(const tongue_lcm::lcmt_tongue_activation& msg, const std::string& kind,
                         const std::string& reason, std::int64_t step, double now);

  Mode mode_;
  std::vector<std::string> muscle_names_;
  // Lock-step: the messages accepted for the next step so far, merged; complete only while the
  // loop does not step (paused: a complete round is stepped on resume).
  ActivationRound round_;
  RoundSenders senders_;  // lock-step: who sent what for the open and the last round
  fem::Vector held_;
  std::optional<bus::Command> command_;
  std::int64_t rejected_ = 0;
  std::int64_t repeats_ = 0;
  int round_rejections_ = 0;
  std::string round_rejection_;
  std::vector<tongue_lcm::lcmt_tongue_rejection> notices_;
  double notice_window_start_ = -std::numeric_limits<double>::infinity();  // steady s
  int notices_in_window_ = 0;
  double last_heard_ = 0.0;
  common::RateLimitedReporter reports_;
  // The last activation decoded, kept so that the next one is decoded into its storage.
  tongue_lcm::lcmt_tongue_activation activation_;
};

}  // namespace tongue::server
