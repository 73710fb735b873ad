#include "replay/replayer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_text.hpp"
#include "controller/input_error.hpp"
#include "controller/muscle_selection.hpp"

namespace tongue::replay {
namespace {

// Frame times may differ from k dt by the round-off of summing dt (about k eps dt); a millionth
// of dt is far above that and far below any real mismatch (another dt, every second frame).
constexpr double kTimeTolerance = 1e-6;  // fraction of dt

}  // namespace

void Replayer::start(const controller::Model& model) {
  const auto fail = [&](const std::string& dataset, const std::string& reason) {
    throw controller::InputError(log_.path, dataset, reason);
  };
  std::vector<std::string> logged = log_.muscle_names, served = model.muscle_names;
  std::sort(logged.begin(), logged.end());
  std::sort(served.begin(), served.end());
  if (logged != served)
    fail("/muscles/names", "the log's muscles (" + controller::joined_names(log_.muscle_names) +
                               ") are not the server's (" +
                               controller::joined_names(model.muscle_names) +
                               "): replay into a server running the same scene");
  if (!log_.max_forces_n.empty()) {
    for (std::size_t j = 0; j < log_.muscles(); ++j) {
      const auto it =
          std::find(model.muscle_names.begin(), model.muscle_names.end(), log_.muscle_names[j]);
      const double served_force =
          model.muscle_max_forces[static_cast<std::size_t>(it - model.muscle_names.begin())];
      if (served_force != log_.max_forces_n[j])
        fail("/muscles/max_force",
             log_.muscle_names[j] + " has F_max " + common::number_text(log_.max_forces_n[j]) +
                 " N in the log, " + common::number_text(served_force) + " N on the server");
    }
  }
  if (log_.resets > 0)
    fail("resets", "the logged run was reset " + std::to_string(log_.resets) +
                       " time(s): its frames are not one run of steps");
  for (std::size_t k = 0; k < log_.frames(); ++k) {
    const double expected = static_cast<double>(k) * model.dt;
    if (std::abs(log_.time_s[k] - expected) > kTimeTolerance * model.dt)
      fail("/time", "frame " + std::to_string(k) + " is at " + common::number_text(log_.time_s[k]) +
                        " s, step " + std::to_string(k) + " of the server (dt " +
                        common::number_text(model.dt) + " s) at " + common::number_text(expected) +
                        " s: the log must hold every step of one run with the server's dt");
  }
}

controller::MuscleLevels Replayer::command(std::int64_t step) {
  if (step < 0 || static_cast<std::size_t>(step) >= log_.frames())
    throw std::out_of_range("step " + std::to_string(step) + " is beyond the log's " +
                            std::to_string(log_.frames()) + " frames");
  controller::MuscleLevels out;
  out.names = log_.muscle_names;
  for (std::size_t j = 0; j < log_.muscles(); ++j)
    out.levels.push_back(log_.level(static_cast<std::size_t>(step), j));
  return out;
}

std::string Replayer::summary() const {
  return std::to_string(log_.frames()) + " frames of " + std::to_string(log_.muscles()) +
         " muscles from " + log_.path;
}

}  // namespace tongue::replay
