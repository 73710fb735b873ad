#include "state_watcher.hpp"

#include <stdexcept>

namespace tongue::runner {

StateWatcher::StateWatcher(const std::string& url, const std::string& channel) : lcm_(url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open the LCM bus " + url);
  lcm_.subscribe(channel, &StateWatcher::on_state, this);
}

double StateWatcher::steps_per_second() const {
  const double span = std::chrono::duration<double>(last_at_ - first_at_).count();
  return (driving_ && *last_step_ > first_step_ && span > 0.0)
             ? static_cast<double>(*last_step_ - first_step_) / span
             : 0.0;
}

void StateWatcher::on_state(const lcm::ReceiveBuffer*, const std::string&,
                            const tongue_lcm::lcmt_tongue_state* s) {
  // The pace counts from the first step the controllers drove (state 0 comes before they
  // start).
  if (s->step >= 1 && !driving_) {
    driving_ = true;
    first_step_ = s->step;
    first_at_ = Clock::now();
  }
  last_step_ = s->step;
  last_at_ = Clock::now();
  if (!s->converged) unconverged_ = true;
}

}  // namespace tongue::runner
