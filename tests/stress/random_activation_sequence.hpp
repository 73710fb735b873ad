#pragma once
// The random activations of the stress test random_activation_test.cpp: before each step every
// muscle, independently, jumps to a new level drawn uniformly from [0, 1] with probability
// dt / mean_hold (so it holds a level for mean_hold seconds on average). Shared with the probe
// random_activation_probe.cpp, which replays the same sequence without a bus.
#include <random>
#include <vector>

namespace tongue::stress {

class RandomActivationSequence {
 public:
  RandomActivationSequence(int num_muscles, double dt_s, double mean_hold_s, unsigned seed)
      : random_(seed), jump_(dt_s / mean_hold_s), levels_(num_muscles, 0.0) {}

  // The levels of the next step (all 0 before the first call), in the muscles' order.
  const std::vector<double>& next() {
    for (double& l : levels_) {
      if (jump_(random_)) {
        l = level_(random_);
        ++jumps_;
      }
    }
    return levels_;
  }
  long jumps() const { return jumps_; }

 private:
  std::mt19937 random_;
  std::uniform_real_distribution<double> level_{0.0, 1.0};
  std::bernoulli_distribution jump_;
  std::vector<double> levels_;
  long jumps_ = 0;
};

}  // namespace tongue::stress
