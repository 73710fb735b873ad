#include "ep_controller/delay_buffer.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace tongue::ep_controller {
namespace {

constexpr double kWholeSteps = 1e-9;  // relative: d / dt off a whole number by round-off only

double whole_if_close(double steps) {
  const double nearest = std::round(steps);
  return std::abs(steps - nearest) <= kWholeSteps * nearest ? nearest : steps;
}

}  // namespace

DelayBuffer::DelayBuffer(double delay_steps) : delay_steps_(whole_if_close(delay_steps)) {
  if (!(delay_steps_ >= 1.0) || !std::isfinite(delay_steps_))
    throw std::invalid_argument("the delay must be at least 1 step, got " +
                                common::number_text(delay_steps));
}

void DelayBuffer::push(Feedback feedback) {
  while (!entries_.empty() && entries_.back().step >= feedback.step) entries_.pop_back();
  entries_.push_back(std::move(feedback));
  // The next command is for step latest + 1 and wants the point latest + 1 - delay; an entry is
  // needed while the one after it is not later than that point.
  const double oldest_wanted = static_cast<double>(entries_.back().step) + 1.0 - delay_steps_;
  while (entries_.size() > 1 && static_cast<double>(entries_[1].step) <= oldest_wanted)
    entries_.pop_front();
}

Feedback DelayBuffer::for_step(std::int64_t step) const {
  if (entries_.empty()) throw std::logic_error("DelayBuffer::for_step: no feedback yet");
  const double wanted = static_cast<double>(step) - delay_steps_;
  const auto at = [](const Feedback& f) { return static_cast<double>(f.step); };
  if (wanted <= at(entries_.front())) return entries_.front();
  if (wanted >= at(entries_.back())) return entries_.back();
  std::size_t i = 1;  // the first entry later than wanted
  while (at(entries_[i]) <= wanted) ++i;
  const Feedback& before = entries_[i - 1];
  const Feedback& after = entries_[i];
  const double theta = (wanted - at(before)) / (at(after) - at(before));
  Feedback f = before;
  for (std::size_t m = 0; m < f.lengths_m.size(); ++m) {
    f.lengths_m[m] += theta * (after.lengths_m[m] - before.lengths_m[m]);
    f.velocities_m_s[m] += theta * (after.velocities_m_s[m] - before.velocities_m_s[m]);
  }
  return f;
}

}  // namespace tongue::ep_controller
