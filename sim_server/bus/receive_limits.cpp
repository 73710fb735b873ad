#include "bus/receive_limits.hpp"

#include <algorithm>

#include "bus/activation_validation.hpp"

namespace tongue::bus {

std::size_t activation_limit(const std::vector<std::string>& muscle_names) {
  // Fingerprint, utime, step, num_muscles; per muscle a string (length, bytes, NUL) and a double;
  // the sender string.
  std::size_t largest = 8 + 8 + 8 + 4 + 4 + kMaxSenderBytes + 1;
  for (const std::string& name : muscle_names) largest += 4 + name.size() + 1 + 8;
  return std::max(kLimitFactor * largest, kMinActivationLimit);
}

std::size_t state_limit(const tongue_lcm::lcmt_tongue_model& model) {
  // The fixed fields (lcmt_tongue_state.lcm) with an empty status, then per node an index and 3
  // positions and, in contact, a node, an obstacle and 3 forces; per muscle 3 doubles; per
  // obstacle 3 forces.
  const std::size_t fixed = 8 * 4 + 4 * 3 + 4 + 8 * 2 + 4 + 1 + 5 + 8 * 2 + 4 * 3 + 8;
  const auto nodes = static_cast<std::size_t>(std::max(model.num_nodes, 0));
  const auto muscles = static_cast<std::size_t>(std::max(model.num_muscles, 0));
  const auto obstacles = static_cast<std::size_t>(std::max(model.num_obstacles, 0));
  return kLimitFactor * (fixed + nodes * (4 + 3 * 8 + 4 + 4 + 3 * 8) + muscles * 3 * 8 +
                         obstacles * 3 * 8) +
         kStatusAllowance;
}

}  // namespace tongue::bus
