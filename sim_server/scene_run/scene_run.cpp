#include "scene_run/scene_run.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include "fem/integrator/newmark_integrator.hpp"
#include "reduced/reduced_integrator.hpp"
#include "scene_run/scene_run_file.hpp"

namespace tongue::scene_run {

SceneRun::SceneRun(const scene::Scene& scene, scene::BuiltScene built)
    : scene_(scene), built_(std::move(built)), ellipticity_(*built_.solid, built_.numbering) {
  if (scene_.analysis.type != scene::AnalysisType::dynamic)
    throw std::invalid_argument(scene_.source +
                                ": a run needs a dynamic analysis (analysis.type: dynamic)");
  if (scene_.model.is_reduced()) {
    basis_ = reduced::read_reduced_basis(scene_.model.reduced);
    reduced::check_fits(*basis_, scene_.model.reduced, built_.solid->mesh(),
                        scene::material_text(scene_.material));
    if (scene_.model.check_every > 0)
      reduced_watch_ = std::make_unique<ReducedCheckWatch>(scene_, basis_->origin);
  }
  levels_ = fem::Vector::Zero(num_muscles());
  initial_u_ = fem::Vector::Zero(built_.solid->num_dofs());
  u_ = v_ = initial_u_;
  frame_ = scene_muscle_frame(built_, u_, &v_);
}

SceneRun::~SceneRun() = default;

int SceneRun::num_muscles() const {
  return built_.muscles ? built_.muscles->num_muscles() : 0;
}

fem::StaticReport SceneRun::start(const fem::Vector& first_levels) {
  fem::Vector u = fem::Vector::Zero(built_.solid->num_dofs());
  if (built_.muscles) built_.muscles->set_activations(fem::Vector::Zero(num_muscles()));
  fem::StaticReport report;
  report.converged = true;
  if (scene_.analysis.settle) report = fem::solve_static(*built_.system, u, built_.static_settings);
  initial_u_ = u;
  if (report.converged) restart(first_levels);
  return report;
}

void SceneRun::check_first_levels(const fem::Vector& first_levels) const {
  if (first_levels.size() != 0 && first_levels.size() != num_muscles())
    throw std::invalid_argument("SceneRun::restart: " + std::to_string(first_levels.size()) +
                                " first levels for " + std::to_string(num_muscles()) + " muscles");
  for (const double level : first_levels)
    if (!(level >= 0.0 && level <= 1.0))
      throw std::invalid_argument("SceneRun::restart: a first level of " + std::to_string(level) +
                                  ", outside [0, 1]");
}

void SceneRun::restart(const fem::Vector& first_levels) {
  check_first_levels(first_levels);
  levels_ = fem::Vector::Zero(num_muscles());
  factor_levels_ = first_levels.size() != 0 ? first_levels : levels_;
  if (built_.muscles) built_.muscles->set_activations(levels_);
  // A model already running is initialized again: its matrices, their orderings and, from the
  // same initial state, its damping (and a reduced model's projections and check) stay valid.
  if (basis_ && !reduced_now())
    integrator_ = std::make_unique<reduced::ReducedIntegrator>(*built_.system, *basis_,
                                                               built_.dynamic_settings);
  else if (!basis_ && !integrator_)
    integrator_ = std::make_unique<fem::NewmarkIntegrator>(*built_.system, built_.dynamic_settings);
  integrator_->initialize(initial_u_, fem::Vector::Zero(initial_u_.size()), 0.0);
  if (built_.muscles) built_.muscles->set_activations(factor_levels_);
  integrator_->prepare(scene::time_step_length(scene_.analysis, 0));
  if (built_.muscles) built_.muscles->set_activations(levels_);
  accept();
  time_ = 0.0;
  clock_ = StepClock{};
  step_ = 0;
  ellipticity_.rearm();
  ellipticity_.check_every(reduced_now() ? kReducedEllipticityEvery : 1);
  if (reduced_watch_) reduced_watch_->collect();  // the last run's, which finish_checks() takes
  reduced_warned_ = false;
  reduced_correction_ = 0.0;
}

void SceneRun::accept() {
  u_ = integrator_->displacement();
  v_ = integrator_->velocity();
  frame_ = scene_muscle_frame(built_, u_, &v_);
}

StepResult SceneRun::step(double dt, const fem::Vector& levels) {
  if (!integrator_) throw std::logic_error("SceneRun::step before start()");
  if (levels.size() != num_muscles())
    throw std::invalid_argument("SceneRun::step: " + std::to_string(levels.size()) +
                                " activation levels for " + std::to_string(num_muscles()) +
                                " muscles");
  StepResult result;
  if (levels == levels_ && integrator_->at_rest()) {
    // Nothing acts that did not act in the last step, and that one was in equilibrium: the
    // identity, with the state, its muscle frame and its stability unchanged.
    result.report = integrator_->hold(dt);
    time_ = result.report.time = clock_.advance(dt);
    ++step_;
    result.muscles = frame_;
    result.ellipticity_loss = ellipticity_.collect();  // the last moving state's check
    return result;
  }
  if (built_.muscles) built_.muscles->set_activations(levels);
  fem::StepReport prepared;
  if (step_ == 0 && num_muscles() > 0 &&
      (levels - factor_levels_).lpNorm<Eigen::Infinity>() > kFreshFirstFactor) {
    prepared = integrator_->prepare(dt);
    factor_levels_ = levels;
  }
  result.report = integrator_->step(dt);
  result.report.add_preparation(prepared);
  if (!result.report.converged) {
    // The state stays at the last accepted step, and so do the levels that led to it.
    if (built_.muscles) built_.muscles->set_activations(levels_);
    result.muscles = frame_;
    result.ellipticity_loss = ellipticity_.collect();
    return result;
  }
  levels_ = levels;
  accept();
  time_ = result.report.time = clock_.advance(dt);
  ++step_;
  result.muscles = frame_;
  result.ellipticity_loss = ellipticity_.check(u_, step_, time_);
  check_reduced(result, dt);
  return result;
}

void SceneRun::check_reduced(StepResult& result, double dt) {
  const scene::ModelSpec& model = scene_.model;
  auto* reduced = dynamic_cast<reduced::ReducedIntegrator*>(integrator_.get());
  if (!reduced || !reduced_watch_ || step_ % model.check_every != 0) return;
  result.reduced_check =
      reduced_watch_->check(u_, v_, reduced->acceleration(), levels_, dt, step_, time_);
  // A switch starts from the state that called for it: its check is waited for.
  if (model.switch_to_full) result.reduced_check = reduced_watch_->collect();
  if (!result.reduced_check) return;
  result.reduced_warning = take_reduced_check(*result.reduced_check);
  if (!result.reduced_warning || !model.switch_to_full) return;
  // The full model from the reduced state, its acceleration included, with the damping a full
  // run has (K0 at the initial state).
  const fem::Vector a = reduced->acceleration();
  auto full = std::make_unique<fem::NewmarkIntegrator>(*built_.system, built_.dynamic_settings);
  full->initialize(u_, v_, a, time_, initial_u_);
  full->prepare(scene_.analysis.dt);
  integrator_ = std::move(full);
  ellipticity_.check_every(1);
}

std::optional<std::string> SceneRun::take_reduced_check(const ReducedCheck& check) {
  const scene::ModelSpec& model = scene_.model;
  reduced_correction_ = check.correction;
  if (check.correction <= model.warn_above || reduced_warned_) return std::nullopt;
  reduced_warned_ = true;
  char text[320];
  std::snprintf(text, sizeof text,
                "at t = %.6g s (step %lld) the full model would move the reduced model's state "
                "by %.3g mm, more than model.warn_above (%.3g mm): the run has left what the "
                "basis was trained on%s",
                check.time, static_cast<long long>(check.step), 1e3 * check.correction,
                1e3 * model.warn_above,
                model.switch_to_full ? "; going on with the full model from this state" : "");
  return text;
}

FinishedChecks SceneRun::finish_checks() {
  FinishedChecks found;
  found.ellipticity_loss = ellipticity_.collect();
  if (reduced_watch_) found.reduced_check = reduced_watch_->collect();
  if (found.reduced_check) found.reduced_warning = take_reduced_check(*found.reduced_check);
  return found;
}

bool SceneRun::reduced_now() const {
  return dynamic_cast<const reduced::ReducedIntegrator*>(integrator_.get()) != nullptr;
}

fem::Vector SceneRun::positions() const {
  return built_.solid->rest_positions() + u_;
}

}  // namespace tongue::scene_run
