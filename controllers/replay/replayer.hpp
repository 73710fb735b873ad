#pragma once
// Replays the activations of a run file into a tongue server: row k + 1 of /activations for step
// k + 1, every muscle of the log named, so the server repeats the logged run (lock-step: bit for
// bit). The loop ends after the state of the log's last step.
//
// The log must fit the server: the same muscle names (any order), the same F_max where the log
// has them, and frames that are the server's steps (time of row k = k dt: every step logged,
// no reset in the run); otherwise the replay would not be the logged run, and start() says why.
#include <optional>
#include <string>

#include "controller/controller.hpp"
#include "replay/recorded_activations.hpp"

namespace tongue::replay {

class Replayer final : public controller::Controller {
 public:
  explicit Replayer(RecordedActivations log) : log_(std::move(log)) {}

  // Throws InputError naming the run file and the dataset when the log does not fit the model.
  void start(const controller::Model& model) override;
  void observe(const controller::State&) override {}
  controller::MuscleLevels command(std::int64_t step) override;
  std::optional<std::int64_t> last_step() const override {
    return static_cast<std::int64_t>(log_.frames()) - 1;
  }
  std::string summary() const override;

 private:
  RecordedActivations log_;
};

}  // namespace tongue::replay
