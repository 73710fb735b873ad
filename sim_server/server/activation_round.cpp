#include "server/activation_round.hpp"

#include <stdexcept>
#include <string>

namespace tongue::server {

ActivationRound::ActivationRound(int expected) : expected_(expected) {
  if (expected < 1)
    throw std::invalid_argument("lock-step needs at least 1 activation message per step, not " +
                                std::to_string(expected));
}

void ActivationRound::start(const fem::Vector& held) {
  held_ = levels_ = held;
  set_.assign(static_cast<std::size_t>(held.size()), false);
  received_ = 0;
}

std::optional<std::size_t> ActivationRound::already_set(
    const std::vector<std::size_t>& named) const {
  for (const std::size_t m : named)
    if (m < set_.size() && set_[m]) return m;
  return std::nullopt;
}

void ActivationRound::add(const bus::ActivationCheck& accepted) {
  if (complete()) throw std::logic_error("ActivationRound::add: the round is already complete");
  if (!accepted.accepted || accepted.levels.size() != accepted.named.size())
    throw std::logic_error("ActivationRound::add: not an accepted message");
  for (const std::size_t m : accepted.named) {
    if (m >= set_.size())
      throw std::logic_error("ActivationRound::add: muscle index " + std::to_string(m) +
                             " out of range");
    if (set_[m])
      throw std::logic_error("ActivationRound::add: muscle " + std::to_string(m) +
                             " is already set in this round");
  }
  accepted.merge_into(levels_);
  for (const std::size_t m : accepted.named) set_[m] = true;
  ++received_;
}

}  // namespace tongue::server
