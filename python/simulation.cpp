#include "python/simulation.hpp"

#include <chrono>
#include <stdexcept>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run_file.hpp"

namespace tongue::python {
namespace {

std::string ellipticity_warning(const scene_run::EllipticityFinding& found) {
  return "at t = " + std::to_string(found.time) + " s " + found.warning;
}

}  // namespace

Simulation::Simulation(const std::string& scene_path) : scene_(scene::read_scene(scene_path)) {
  run_ = std::make_unique<scene_run::SceneRun>(scene_, scene::build_scene(scene_));
  const fem::StaticReport settled = run_->start();
  if (!settled.converged)
    throw std::runtime_error(scene_path + ": settling failed: " + settled.message);
  if (run_->built().muscles)
    for (const auto& m : run_->built().muscles->muscles()) muscle_names_.push_back(m.name);
}

Simulation::~Simulation() {
  close_run_file();
}

void Simulation::open_run_file(const std::string& path) {
  close_run_file();
  log_ = std::make_unique<run_file::RunFileQueue>(
      scene_run::open_scene_run_file(path, scene_, run_->built()));
  log_path_ = path;
  resets_ = 0;
  failure_.clear();
  write_frame({});
}

void Simulation::close_run_file() {
  if (!log_) return;
  try {
    log_->set_attribute("status", failure_.empty() ? "completed" : "failed: " + failure_);
    log_->close();
  } catch (...) {
    // The destructor's call: a write error was the caller's to see at the step that made it.
  }
  log_.reset();
  log_path_.clear();
}

void Simulation::write_frame(const run_file::SolverFigures& figures) {
  if (!log_) return;
  const scene::BuiltScene& built = run_->built();
  log_->append(run_->time(), built.solid->rest_positions() + run_->displacement(), figures,
               run_->muscle_frame(), scene_run::scene_contact_frame(built, run_->displacement()));
}

StepFigures Simulation::step(const fem::Vector& levels) {
  const auto start = std::chrono::steady_clock::now();
  const scene_run::StepResult r = run_->step(dt(), levels);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.report.converged) {
    failure_ =
        "step " + std::to_string(step_count() + 1) + " did not converge: " + r.report.message;
    throw std::runtime_error(failure_);
  }
  failure_.clear();
  write_frame({r.report.iterations, r.report.final_residual, r.report.wall_seconds, r.report.cuts,
               run_->reduced_correction()});
  StepFigures f;
  f.time = r.report.time;
  f.iterations = r.report.iterations;
  f.factorizations = r.report.factorizations;
  f.cuts = r.report.cuts;
  f.error_estimate = r.report.error_estimate;
  f.wall_seconds = seconds;
  f.held = r.report.held;
  if (r.ellipticity_loss) f.warnings.push_back(ellipticity_warning(*r.ellipticity_loss));
  if (r.reduced_warning) f.warnings.push_back(*r.reduced_warning);
  return f;
}

StepFigures Simulation::step(const std::map<std::string, double>& levels) {
  return step(with_named(run_->levels(), levels));
}

fem::Vector Simulation::with_named(fem::Vector base,
                                   const std::map<std::string, double>& levels) const {
  for (const auto& [name, level] : levels) {
    bool found = false;
    for (std::size_t m = 0; m < muscle_names_.size(); ++m) {
      const std::string& muscle = muscle_names_[m];
      if (muscle == name || muscle.rfind(name + "_", 0) == 0) {
        base[static_cast<Eigen::Index>(m)] = level;
        found = true;
      }
    }
    if (!found)
      throw std::invalid_argument("'" + name + "' is neither a muscle nor a group of " +
                                  scene_.source);
  }
  return base;
}

std::vector<std::string> Simulation::finish_checks() {
  std::vector<std::string> warnings;
  const scene_run::FinishedChecks last = run_->finish_checks();
  if (last.ellipticity_loss) warnings.push_back(ellipticity_warning(*last.ellipticity_loss));
  if (last.reduced_warning) warnings.push_back(*last.reduced_warning);
  return warnings;
}

std::vector<std::string> Simulation::reset(const fem::Vector& first_levels) {
  run_->check_first_levels(first_levels);  // before the run is touched
  std::vector<std::string> warnings = finish_checks();
  run_->restart(first_levels);
  if (!log_) return warnings;
  log_->set_attribute("resets", std::to_string(++resets_));
  write_frame({});
  return warnings;
}

std::vector<std::string> Simulation::reset(const std::map<std::string, double>& first_levels) {
  return reset(with_named(fem::Vector::Zero(run_->num_muscles()), first_levels));
}

Eigen::MatrixX3d Simulation::by_node(const fem::Vector& v) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      v.data(), v.size() / 3, 3);
}

Eigen::MatrixX3d Simulation::positions() const {
  return by_node(run_->positions());
}
Eigen::MatrixX3d Simulation::displacements() const {
  return by_node(run_->displacement());
}
Eigen::MatrixX3d Simulation::velocities() const {
  return by_node(run_->velocity());
}
const fem::Vector& Simulation::muscle_lengths() const {
  return run_->muscle_frame().lengths;
}
const fem::Vector& Simulation::muscle_velocities() const {
  return run_->muscle_frame().velocities;
}

fem::Vector Simulation::max_forces() const {
  fem::Vector f(static_cast<Eigen::Index>(muscle_names_.size()));
  if (run_->built().muscles) {
    const auto& muscles = run_->built().muscles->muscles();
    for (std::size_t m = 0; m < muscles.size(); ++m)
      f[static_cast<Eigen::Index>(m)] = muscles[m].max_force;
  }
  return f;
}

Eigen::MatrixX3d Simulation::rest_positions() const {
  return by_node(run_->built().solid->rest_positions());
}

Eigen::Matrix<int, Eigen::Dynamic, 8, Eigen::RowMajor> Simulation::elements() const {
  const auto& elements = run_->built().solid->mesh().elements;
  Eigen::Matrix<int, Eigen::Dynamic, 8, Eigen::RowMajor> e(elements.size(), 8);
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int k = 0; k < 8; ++k) e(static_cast<Eigen::Index>(i), k) = elements[i][k];
  return e;
}

const std::map<std::string, std::vector<int>>& Simulation::node_sets() const {
  return run_->built().solid->mesh().node_sets;
}

}  // namespace tongue::python
