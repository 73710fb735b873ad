#include "state_watcher.hpp"

#include <string>
#include <vector>

#include "bus/published_decode.hpp"
#include "bus/receive_limits.hpp"

namespace tongue::runner {

StateWatcher::StateWatcher(const std::string& url, const std::string& channel)
    : url_(bus::parse_lcm_url(url)),
      lcm_(url),
      receiver_(lcm_, url_, {{channel, bus::kStateLimitBeforeModel}}, "run_experiment") {}

void StateWatcher::poll(int timeout_ms) {
  std::vector<bus::ReceivedMessage> received;
  // The first batch may wait; the ones after it take only what is already there, and a bounded
  // number of them, so that a flood on the state channel cannot hold the runner in here.
  constexpr int kMaxBatches = 32;
  int wait_ms = timeout_ms;
  for (int batch = 0;
       batch < kMaxBatches && receiver_.receive(wait_ms, received) && !received.empty();
       ++batch, wait_ms = 0) {
    for (const bus::ReceivedMessage& m : received) {
      tongue_lcm::lcmt_tongue_state s;
      std::string reason;
      if (bus::decode_state(m.bytes.data(), static_cast<int>(m.bytes.size()), s, reason)) {
        on_state(s);
      } else {
        reports_.report("state", "run_experiment: rejected undecodable state: " + reason);
      }
    }
    received.clear();
  }
}

double StateWatcher::steps_per_second() const {
  const double span = std::chrono::duration<double>(last_at_ - first_at_).count();
  return (driving_ && *last_step_ > first_step_ && span > 0.0)
             ? static_cast<double>(*last_step_ - first_step_) / span
             : 0.0;
}

void StateWatcher::on_state(const tongue_lcm::lcmt_tongue_state& s) {
  // The pace counts from the first step the controllers drove (state 0 comes before they
  // start).
  if (s.step >= 1 && !driving_) {
    driving_ = true;
    first_step_ = s.step;
    first_at_ = Clock::now();
  }
  last_step_ = s.step;
  last_at_ = Clock::now();
  if (!s.converged) unconverged_ = true;
}

}  // namespace tongue::runner
