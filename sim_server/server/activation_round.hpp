#pragma once
// Lock-step with several controllers: the activations accepted for the next step, merged until
// the expected number of messages has arrived. Each controller names its own muscles: a message
// naming a muscle that an earlier message of the round already set is refused whole (the caller
// rejects it), and muscles nobody names keep the level they had during the previous step. With
// one expected message a round is simply that message applied to the held levels.
#include <cstddef>
#include <optional>
#include <vector>

#include "bus/activation_validation.hpp"
#include "fem/types.hpp"

namespace tongue::server {

class ActivationRound {
 public:
  // expected: accepted messages that complete a round. Throws std::invalid_argument below 1.
  explicit ActivationRound(int expected);

  // Starts a new, empty round from held (the levels of the step just taken), clearing the last.
  void start(const fem::Vector& held);

  // The first muscle (model index) of named that this round has already set, or nullopt.
  std::optional<std::size_t> already_set(const std::vector<std::size_t>& named) const;

  // Adds an accepted message: each muscle it names takes its level. Throws std::logic_error
  // when the round is complete, or a muscle is already set or out of range (the caller checks
  // first).
  void add(const bus::ActivationCheck& accepted);

  int expected() const { return expected_; }
  int received() const { return received_; }
  bool complete() const { return received_ == expected_; }
  // The held levels with every muscle named so far replaced.
  const fem::Vector& levels() const { return levels_; }
  // The levels the round started from.
  const fem::Vector& held() const { return held_; }

 private:
  int expected_;
  int received_ = 0;
  fem::Vector held_, levels_;
  std::vector<bool> set_;  // by model muscle: named by a message of this round
};

}  // namespace tongue::server
