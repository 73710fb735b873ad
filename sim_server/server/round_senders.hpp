#pragma once
// Lock-step: what each named sender sent for the round being collected (the activations for step
// k + 1) and for the round last taken (step k), byte for byte, so that a message a controller
// repeats unchanged (its answer to a state published again after a loss) is taken once: a repeat
// is idempotent by its sender and step. Messages with an empty sender are not recorded: they
// count as they come, as before senders existed.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tongue::server {

class RoundSenders {
 public:
  using Bytes = std::vector<std::uint8_t>;
  enum class Seen {
    new_sender,  // nothing from this sender in the round (or no sender)
    repeat,      // the very bytes already taken from this sender
    changed,     // another message already taken from this sender
  };

  // What a message (bytes, from sender) is to the round being collected.
  Seen in_open_round(const std::string& sender, const Bytes& bytes) const;
  // Whether it repeats what sender sent for the round last taken.
  bool repeats_last_round(const std::string& sender, const Bytes& bytes) const;

  // The message is taken into the round being collected.
  void take(const std::string& sender, const Bytes& bytes);
  // The round being collected starts again for the same step (a complete round, paused, that a
  // further message replaces): nothing recorded for it.
  void reopen() { open_.clear(); }
  // The round being collected was taken: it becomes the last round, and a new one opens.
  void next_round();
  // Step 0 again: nothing recorded.
  void clear();

 private:
  std::map<std::string, Bytes> open_, last_;
};

}  // namespace tongue::server
