#pragma once
// A run's simulated time counted in steps, not summed: after k steps of dt from t0 the time is
// t0 + k dt, so that 30 steps of 4 ms end at 0.12 s, not at the 0.12000000000000008 s that adding
// 0.004 thirty times gives. A step of another length starts a new count from the time reached.
#include <cstdint>

namespace tongue::scene_run {

class StepClock {
 public:
  // The time after one more step of dt [s].
  double advance(double dt) {
    if (dt != dt_) {
      origin_ = now();
      dt_ = dt;
      steps_ = 0;
    }
    ++steps_;
    return now();
  }
  double now() const { return origin_ + static_cast<double>(steps_) * dt_; }

 private:
  double origin_ = 0.0;  // s
  double dt_ = 0.0;      // s
  std::int64_t steps_ = 0;
};

}  // namespace tongue::scene_run
