#pragma once
// Plays an activation sequence (activation_sequence.hpp) into a tongue server: the levels at the
// time of step k + 1, (k + 1) dt, are sent for step k + 1, as sim_batch applies a scene's
// schedule (a step to t_{k+1} uses the levels at t_{k+1}).
#include <optional>
#include <string>

#include "controller/controller.hpp"
#include "sequence_player/activation_sequence.hpp"

namespace tongue::sequence_player {

class SequencePlayer final : public controller::Controller {
 public:
  explicit SequencePlayer(SequenceSpec spec) : spec_(std::move(spec)) {}

  void start(const controller::Model& model) override;
  void observe(const controller::State&) override {}
  controller::MuscleLevels command(std::int64_t step) override;
  std::optional<std::int64_t> last_step() const override { return last_step_; }
  std::string summary() const override;

 private:
  SequenceSpec spec_;
  std::optional<ActivationSequence> sequence_;
  double dt_ = 0.0;
  std::optional<std::int64_t> last_step_;
};

}  // namespace tongue::sequence_player
