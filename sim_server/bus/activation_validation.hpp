#pragma once
// Checks on incoming activation messages, before anything reaches the model. A message is
// applied whole or not at all: one bad entry rejects it, so the model's activations are never
// half-updated, and the reason names the field and the value for the state's status and the log.
#include <cstddef>
#include <string>
#include <vector>

#include "bus/messages.hpp"

namespace tongue::bus {

struct ActivationCheck {
  bool accepted = false;
  // The full level vector by muscle index (the model's order) to apply; only when accepted.
  std::vector<double> levels;
  // The model indices of the muscles the message names, in the message's order; only when
  // accepted (lock-step with several controllers merges messages by these).
  std::vector<std::size_t> named;
  // Why the message was rejected, naming the field and its value; empty when accepted.
  std::string reason;
};

// Checks msg against the model's muscles. Rejects it when num_muscles is negative or differs from
// the size of names or levels, step is below -1, a name is not in muscle_names or appears twice,
// or a level is NaN, infinite or outside [0, 1]. When accepted, levels holds current_levels with
// the named muscles replaced: a message naming only some muscles keeps the others as they are.
// Throws std::invalid_argument when current_levels and muscle_names differ in size (a caller
// error, not a bad message).
ActivationCheck check_activation(const tongue_lcm::lcmt_tongue_activation& msg,
                                 const std::vector<std::string>& muscle_names,
                                 const std::vector<double>& current_levels);

// Decodes raw bytes received on the activation channel (an lcm::ReceiveBuffer's data and
// data_size) into out. Returns false, with reason saying what is wrong, for bytes that are not a
// whole lcmt_tongue_activation: too short, another type's fingerprint, a negative or impossible
// count, a bad string, or trailing bytes. The structure is checked before lcm-gen's decode()
// runs, so hostile counts cannot make it allocate without bound or throw. out is unspecified on
// failure.
bool decode_activation(const void* data, int size, tongue_lcm::lcmt_tongue_activation& out,
                       std::string& reason);

}  // namespace tongue::bus
