#include "server/state_repeater.hpp"

#include <stdexcept>

namespace tongue::server {

StateRepeater::StateRepeater(int first_ms, int max_repeats)
    : first_s_(first_ms * 1e-3), max_repeats_(max_repeats) {
  if (first_ms < 0) throw std::invalid_argument("the first repeat must come after >= 0 ms");
  if (max_repeats < 0) throw std::invalid_argument("the number of repeats must be >= 0");
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
  interval_s_ *= 2.0;
  next_s_ = now + interval_s_;
  return true;
}

std::optional<double> StateRepeater::next() const {
  if (left_ == 0) return std::nullopt;
  return next_s_;
}

}  // namespace tongue::server
