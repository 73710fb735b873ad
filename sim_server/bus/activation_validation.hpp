#pragma once
// Checks on incoming activation messages, before anything reaches the model. A message is
// applied whole or not at all: one bad entry rejects it, so the model's activations are never
// half-updated, and the reason names the field and the value for the state's status and the log.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "bus/messages.hpp"

namespace tongue::bus {

// A checked message: which muscles it sets, and to what. Only the bus checks levels; whoever
// holds the activations merges an accepted check into them with merge_into.
struct ActivationCheck {
  bool accepted = false;
  // The model indices of the muscles the message names, in the message's order, each once;
  // only when accepted (lock-step with several controllers merges messages by these).
  std::vector<std::size_t> named;
  // levels[i] in [0, 1] is the level of muscle named[i]; only when accepted.
  std::vector<double> levels;
  // Why the message was rejected, naming the field and its value; empty when accepted.
  std::string reason;

  // Sets the named muscles' entries of held (by model muscle) to their levels; the others keep
  // theirs. Throws std::invalid_argument when a named index is outside held.
  void merge_into(Eigen::VectorXd& held) const;
};

// The longest sender name an activation may give: the server repeats it in rejection notices.
inline constexpr std::size_t kMaxSenderBytes = 100;

// Checks msg against the model's muscles. Rejects it when num_muscles is negative or differs from
// the size of names or levels, step is below -1, the sender is longer than kMaxSenderBytes or has
// a byte outside printable ASCII, a name is not in muscle_names or appears twice, or a level is
// NaN, infinite or outside [0, 1].
ActivationCheck check_activation(const tongue_lcm::lcmt_tongue_activation& msg,
                                 const std::vector<std::string>& muscle_names);

// Decodes raw bytes received on the activation channel (an lcm::ReceiveBuffer's data and
// data_size) into out. Returns false, with reason saying what is wrong, for bytes that are not a
// whole lcmt_tongue_activation: too short, another type's fingerprint, a negative or impossible
// count, a bad string, or trailing bytes. The structure is checked before lcm-gen's decode()
// runs, so hostile counts cannot make it allocate without bound or throw. out is unspecified on
// failure.
bool decode_activation(const void* data, int size, tongue_lcm::lcmt_tongue_activation& out,
                       std::string& reason);

}  // namespace tongue::bus
