#include "server/state_repeater.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tongue::server {

StateRepeater::StateRepeater(int first_ms, int max_repeats, int longest_ms)
    : first_s_(first_ms * 1e-3), max_repeats_(max_repeats), longest_s_(longest_ms * 1e-3) {
  if (first_ms < 0) throw std::invalid_argument("the first repeat must come after >= 0 ms");
  if (max_repeats < 0) throw std::invalid_argument("the number of repeats must be >= 0");
  if (longest_ms < first_ms)
    throw std::invalid_argument("the longest interval between repeats (" +
                                std::to_string(longest_ms) + " ms) is below the first (" +
                                std::to_string(first_ms) + " ms)");
}

void StateRepeater::restart(double now) {
  left_ = first_s_ > 0.0 ? max_repeats_ : 0;
  interval_s_ = first_s_;
  next_s_ = now + interval_s_;
}

bool StateRepeater::due(double now) {
  if (left_ == 0 || now < next_s_) return false;
  --left_;
  ++total_;
  interval_s_ = std::min(2.0 * interval_s_, longest_s_);
  next_s_ = now + interval_s_;
  return true;
}

std::optional<double> StateRepeater::next() const {
  if (left_ == 0) return std::nullopt;
  return next_s_;
}

}  // namespace tongue::server
