#include "sequence_player/sequence_player.hpp"

#include <cmath>
#include <stdexcept>

#include "controller/number_text.hpp"

namespace tongue::sequence_player {

void SequencePlayer::start(const controller::Model& model) {
  if (!(model.dt > 0.0) || !std::isfinite(model.dt))
    throw std::runtime_error("the model's dt is " + controller::number_text(model.dt) +
                             " s, not > 0");
  dt_ = model.dt;
  sequence_.emplace(spec_, model.muscle_names, model.muscle_max_forces);
  if (spec_.duration_s) last_step_ = steps_covering(*spec_.duration_s, dt_);
}

controller::MuscleLevels SequencePlayer::command(std::int64_t step) {
  return sequence_->levels_at(static_cast<double>(step) * dt_);
}

std::string SequencePlayer::summary() const {
  if (!sequence_) return {};
  return std::to_string(spec_.entries.size()) + " entries over " +
         std::to_string(sequence_->driven_muscles().size()) + " muscles from " + spec_.source;
}

}  // namespace tongue::sequence_player
