#pragma once
// The reflex delay of the lambda model: the muscle lengths and velocities of past states, so that
// the command for step k + 1 uses the feedback of step k + 1 - D (D = the delay in steps).
// Entries are kept by step number, so states that are not published (real-time with
// --publish-every) or a server reset (the step goes down) are handled alike: the feedback used is
// the latest at or before the wanted step, or the oldest one kept when the history is shorter than
// the delay (the tongue was at that first state before it was seen, as after settling).
#include <cstdint>
#include <deque>
#include <vector>

namespace tongue::ep_controller {

struct Feedback {
  std::int64_t step = 0;
  std::vector<double> lengths_m;       // per muscle, m
  std::vector<double> velocities_m_s;  // per muscle, m/s
};

class DelayBuffer {
 public:
  // delay_steps >= 1: the command for step k + 1 can use at most the state of step k.
  explicit DelayBuffer(int delay_steps);

  // Adds the feedback of a new state. A step at or below the latest one (a reset) drops the
  // entries from that step on. Entries no later command can need are dropped.
  void push(Feedback feedback);

  // The feedback for the command of `step`: the latest entry at or before step - delay, else the
  // oldest entry. Throws std::logic_error when nothing has been pushed.
  const Feedback& for_step(std::int64_t step) const;

  int delay_steps() const { return delay_steps_; }
  std::size_t size() const { return entries_.size(); }

 private:
  int delay_steps_;
  std::deque<Feedback> entries_;
};

}  // namespace tongue::ep_controller
