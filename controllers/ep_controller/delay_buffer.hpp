#pragma once
// The reflex delay of the lambda model: the muscle lengths and velocities of past states, so that
// the command for step k + 1 uses the feedback of the time (k + 1) dt - d, D = d / dt steps back
// (at least one step: the state of step k + 1 is what the command produces). When D is not a
// whole number of steps the feedback is interpolated linearly between the two states around
// that time, so that the delay is d at any dt (rounding D to whole steps made it 16 ms instead
// of 12 at dt 8 ms, and the /ai/ closed loop's RMS error against its dt = 0.1 ms run 0.62 mm
// instead of 0.10 mm at dt 6 ms, where 12 ms is two steps).
// Entries are kept by step number, so states that are not published (real-time with
// --publish-every) or a server reset (the step goes down) are handled alike: the feedback is
// interpolated between the entries around the wanted step, or is the oldest one kept when the
// history is shorter than the delay (the tongue was at that first state before it was seen, as
// after settling), or the latest one when no later state has come yet.
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
  // delay_steps >= 1: the command for step k + 1 can use at most the state of step k. A delay
  // within 1e-9 of a whole number of steps is taken as that number (d / dt in floating point).
  explicit DelayBuffer(double delay_steps);

  // Adds the feedback of a new state. A step at or below the latest one (a reset) drops the
  // entries from that step on. Entries no later command can need are dropped.
  void push(Feedback feedback);

  // The feedback for the command of `step`, at step - delay as above; its `step` is the entry's
  // at or before that point. Throws std::logic_error when nothing has been pushed.
  Feedback for_step(std::int64_t step) const;

  double delay_steps() const { return delay_steps_; }
  std::size_t size() const { return entries_.size(); }

 private:
  double delay_steps_;
  std::deque<Feedback> entries_;
};

}  // namespace tongue::ep_controller
