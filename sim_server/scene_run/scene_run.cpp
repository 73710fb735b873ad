#include "scene_run/scene_run.hpp"

#include <stdexcept>
#include <utility>

#include "scene_run/scene_run_file.hpp"

namespace tongue::scene_run {

SceneRun::SceneRun(const scene::Scene& scene, scene::BuiltScene built)
    : scene_(scene), built_(std::move(built)), ellipticity_(*built_.solid) {
  if (scene_.analysis.type != scene::AnalysisType::dynamic)
    throw std::invalid_argument(scene_.source +
                                ": a run needs a dynamic analysis (analysis.type: dynamic)");
  levels_ = fem::Vector::Zero(num_muscles());
  initial_u_ = fem::Vector::Zero(built_.solid->num_dofs());
  u_ = v_ = initial_u_;
  frame_ = scene_muscle_frame(built_, u_, &v_);
}

SceneRun::~SceneRun() = default;

int SceneRun::num_muscles() const {
  return built_.muscles ? built_.muscles->num_muscles() : 0;
}

fem::StaticReport SceneRun::start() {
  fem::Vector u = fem::Vector::Zero(built_.solid->num_dofs());
  if (built_.muscles) built_.muscles->set_activations(fem::Vector::Zero(num_muscles()));
  fem::StaticReport report;
  report.converged = true;
  if (scene_.analysis.settle) report = fem::solve_static(*built_.system, u, built_.static_settings);
  initial_u_ = u;
  if (report.converged) restart();
  return report;
}

void SceneRun::restart() {
  levels_ = fem::Vector::Zero(num_muscles());
  if (built_.muscles) built_.muscles->set_activations(levels_);
  integrator_ = std::make_unique<fem::NewmarkIntegrator>(*built_.system, built_.dynamic_settings);
  integrator_->initialize(initial_u_, fem::Vector::Zero(initial_u_.size()), 0.0);
  integrator_->prepare(scene::time_step_length(scene_.analysis, 0));
  accept();
  step_ = 0;
}

void SceneRun::accept() {
  u_ = integrator_->displacement();
  v_ = integrator_->velocity();
  time_ = integrator_->time();
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
    time_ = integrator_->time();
    ++step_;
    result.muscles = frame_;
    result.ellipticity_loss = ellipticity_.collect();  // the last moving state's check
    return result;
  }
  if (built_.muscles) built_.muscles->set_activations(levels);
  result.report = integrator_->step(dt);
  if (!result.report.converged) {
    // The state stays at the last accepted step, and so do the levels that led to it.
    if (built_.muscles) built_.muscles->set_activations(levels_);
    result.muscles = frame_;
    result.ellipticity_loss = ellipticity_.collect();
    return result;
  }
  levels_ = levels;
  accept();
  ++step_;
  result.muscles = frame_;
  result.ellipticity_loss = ellipticity_.check(u_, step_, time_);
  return result;
}

std::optional<EllipticityFinding> SceneRun::finish_checks() {
  return ellipticity_.collect();
}

fem::Vector SceneRun::positions() const {
  return built_.solid->rest_positions() + u_;
}

}  // namespace tongue::scene_run
