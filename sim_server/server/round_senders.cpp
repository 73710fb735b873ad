#include "server/round_senders.hpp"

#include <utility>

namespace tongue::server {

RoundSenders::Seen RoundSenders::in_open_round(const std::string& sender,
                                               const Bytes& bytes) const {
  if (sender.empty()) return Seen::new_sender;
  const auto it = open_.find(sender);
  if (it == open_.end()) return Seen::new_sender;
  return it->second == bytes ? Seen::repeat : Seen::changed;
}

bool RoundSenders::repeats_last_round(const std::string& sender, const Bytes& bytes) const {
  if (sender.empty()) return false;
  const auto it = last_.find(sender);
  return it != last_.end() && it->second == bytes;
}

void RoundSenders::take(const std::string& sender, const Bytes& bytes) {
  if (!sender.empty()) open_[sender] = bytes;
}

void RoundSenders::next_round() {
  last_ = std::move(open_);
  open_.clear();
}

void RoundSenders::clear() {
  open_.clear();
  last_.clear();
}

}  // namespace tongue::server
