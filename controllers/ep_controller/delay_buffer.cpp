#include "ep_controller/delay_buffer.hpp"

#include <stdexcept>
#include <string>

namespace tongue::ep_controller {

DelayBuffer::DelayBuffer(int delay_steps) : delay_steps_(delay_steps) {
  if (delay_steps < 1)
    throw std::invalid_argument("the delay must be at least 1 step, got " +
                                std::to_string(delay_steps));
}

void DelayBuffer::push(Feedback feedback) {
  while (!entries_.empty() && entries_.back().step >= feedback.step) entries_.pop_back();
  entries_.push_back(std::move(feedback));
  // The next command is for step latest + 1 and wants step latest + 1 - delay; an entry is
  // needed while the one after it is later than that.
  const std::int64_t oldest_wanted = entries_.back().step + 1 - delay_steps_;
  while (entries_.size() > 1 && entries_[1].step <= oldest_wanted) entries_.pop_front();
}

const Feedback& DelayBuffer::for_step(std::int64_t step) const {
  if (entries_.empty()) throw std::logic_error("DelayBuffer::for_step: no feedback yet");
  const std::int64_t wanted = step - delay_steps_;
  for (auto it = entries_.rbegin(); it != entries_.rend(); ++it)
    if (it->step <= wanted) return *it;
  return entries_.front();
}

}  // namespace tongue::ep_controller
