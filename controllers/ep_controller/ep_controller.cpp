#include "ep_controller/ep_controller.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/number_text.hpp"
#include "controller/input_error.hpp"
#include "controller/muscle_selection.hpp"
#include "ep_controller/muscle_rho.hpp"

namespace tongue::ep_controller {
namespace {

constexpr double kMmPerM = 1000.0;

}  // namespace

EpController::EpController(MotorPlanSpec plan, EpSettings settings)
    : spec_(std::move(plan)), settings_(settings) {
  if (!(settings_.delay_s >= 0.0) || !std::isfinite(settings_.delay_s))
    throw std::invalid_argument("the reflex delay must be a finite number >= 0 s");
  if (!(settings_.force_lag_s >= 0.0) || !std::isfinite(settings_.force_lag_s))
    throw std::invalid_argument("the force lag must be a finite number >= 0 s");
}

void EpController::start(const controller::Model& model) {
  if (!(model.dt > 0.0) || !std::isfinite(model.dt))
    throw std::runtime_error("the model's dt is " + common::number_text(model.dt) + " s, not > 0");
  dt_ = model.dt;
  names_ = model.muscle_names;
  plan_.emplace(spec_, names_);

  std::vector<std::pair<std::string, double>> overrides;
  for (const RhoEntry& r : spec_.rho) {
    if (controller::select_muscles(r.name, names_).empty())
      throw controller::InputError(
          spec_.source, r.key_path,
          "no muscle is named '" + r.name + "' or starts with '" + r.name +
              "_' (the server's muscles: " + controller::joined_names(names_) + ")",
          r.line);
    overrides.emplace_back(r.name, r.rho_n);
  }
  std::vector<double> rho;
  try {
    rho = muscle_rhos(names_, model.muscle_max_forces, overrides);
  } catch (const std::invalid_argument& e) {
    throw controller::InputError(spec_.source, "rho", e.what());
  }
  laws_.assign(names_.size(), MuscleLaw{});
  for (std::size_t m = 0; m < names_.size(); ++m) {
    laws_[m].rho_n = rho[m];
    laws_[m].max_force_n = model.muscle_max_forces[m];
  }
  history_.emplace(std::max(1.0, settings_.delay_s / dt_));
  lag_.emplace(names_.size(), settings_.force_lag_s, dt_);
}

void EpController::observe(const controller::State& state) {
  const std::size_t n = names_.size();
  if (state.muscle_lengths.size() != n || state.muscle_velocities.size() != n)
    throw std::runtime_error("the state of step " + std::to_string(state.step) + " has " +
                             std::to_string(state.muscle_lengths.size()) + " muscle lengths for " +
                             std::to_string(n) + " muscles");
  for (std::size_t m = 0; m < n; ++m) {
    const double l = state.muscle_lengths[m], v = state.muscle_velocities[m];
    if (!std::isfinite(l) || !(l > 0.0) || !std::isfinite(v))
      throw std::runtime_error("the state of step " + std::to_string(state.step) + " gives " +
                               names_[m] + " length " + common::number_text(l) + " m, velocity " +
                               common::number_text(v) + " m/s: not usable feedback");
  }
  if (!have_rest_lengths_) {
    for (std::size_t m = 0; m < n; ++m) laws_[m].rest_length_mm = state.muscle_lengths[m] * kMmPerM;
    have_rest_lengths_ = true;
  }
  history_->push(Feedback{state.step, state.muscle_lengths, state.muscle_velocities});
}

controller::MuscleLevels EpController::command(std::int64_t step) {
  const Feedback fb = history_->for_step(step);
  const double t = static_cast<double>(step) * dt_;
  last_.assign(names_.size(), MuscleCommand{});
  std::vector<double> law_levels(names_.size());
  for (std::size_t m = 0; m < names_.size(); ++m) {
    const int muscle = static_cast<int>(m);
    const double lambda_mm = laws_[m].rest_length_mm + plan_->delta_lambda_mm(muscle, t);
    last_[m] = muscle_command(laws_[m], lambda_mm, fb.lengths_m[m] * kMmPerM,
                              fb.velocities_m_s[m] * kMmPerM, settings_.velocity_factor,
                              settings_.constants);
    law_levels[m] = last_[m].level;
  }
  controller::MuscleLevels out;
  out.names = names_;
  out.levels = lag_->update(step, law_levels);
  for (std::size_t m = 0; m < names_.size(); ++m) {
    if (out.levels[m] > peak_level_) {
      peak_level_ = out.levels[m];
      peak_muscle_ = names_[m];
      peak_step_ = step;
    }
  }
  return out;
}

std::string EpController::summary() const {
  char text[200];
  std::snprintf(text, sizeof text,
                "delay %.3g steps (%.3g ms at dt %.3g ms), velocity factor %s, force lag %.3g ms",
                delay_steps(), delay_steps() * dt_ * 1e3, dt_ * 1e3,
                settings_.velocity_factor ? "on" : "off", settings_.force_lag_s * 1e3);
  std::string s = text;
  if (!peak_muscle_.empty()) {
    std::snprintf(text, sizeof text, "; highest level %.3g (%s, step %lld)", peak_level_,
                  peak_muscle_.c_str(), static_cast<long long>(peak_step_));
    s += text;
  } else {
    s += "; every level 0";
  }
  return s;
}

}  // namespace tongue::ep_controller
