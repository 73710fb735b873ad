#pragma once
// Runs a dynamic scene through its SceneRun as sim_batch does (steps of dt with the schedule's
// activations at each step's end time), without a run file, and times the stepping alone: the
// settling is a one-off start-up, not part of the real-time budget.
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <stdexcept>
#include <string>

#include "scene/scene_builder.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::benchmarks {

struct DynamicRun {
  int steps = 0, iterations = 0, factorizations = 0, residual_evaluations = 0;
  double simulated_seconds = 0.0;
  double wall_seconds = 0.0;  // of the stepping
  // The integrator's own steps (StepReport::wall_seconds, what sim_batch's "stepping" sums): the
  // stepping less the scene run's work around them (the muscles' frame, the contact report,
  // the wait for the material's stability check).
  double integrator_seconds = 0.0;
  double cpu_seconds = 0.0;  // process CPU time of the stepping (all threads)
  double real_time_factor() const { return simulated_seconds / wall_seconds; }
};

inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// on_state(t, positions) is called with the settled state (t = 0) and after every step.
// Throws std::runtime_error when settling or a step fails to converge.
inline DynamicRun run_dynamic_scene(
    const scene::Scene& scene,
    const std::function<void(double, const fem::Vector&)>& on_state = {}) {
  scene_run::SceneRun run(scene, scene::build_scene(scene));
  const scene::BuiltScene& built = run.built();
  const fem::StaticReport settled = run.start(
      built.muscles ? built.activations.levels_at(scene::time_step_length(scene.analysis, 0))
                    : fem::Vector());
  if (!settled.converged) throw std::runtime_error("settling failed: " + settled.message);
  if (on_state) on_state(0.0, run.positions());

  DynamicRun figures;
  const int count = scene::time_step_count(scene.analysis);
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  for (int s = 0; s < count; ++s) {
    const double dt = scene::time_step_length(scene.analysis, s);
    const fem::Vector levels =
        built.muscles ? built.activations.levels_at(run.time() + dt) : fem::Vector();
    const fem::StepReport r = run.step(dt, levels).report;
    if (!r.converged)
      throw std::runtime_error("step " + std::to_string(s + 1) + " failed: " + r.message);
    ++figures.steps;
    figures.integrator_seconds += r.wall_seconds;
    figures.iterations += r.iterations;
    figures.factorizations += r.factorizations;
    figures.residual_evaluations += r.residual_evaluations;
    if (on_state) {
      // Observers are not part of the simulation's cost.
      const auto pause = std::chrono::steady_clock::now();
      const double cpu_pause = process_cpu_seconds();
      on_state(run.time(), run.positions());
      figures.wall_seconds -=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - pause).count();
      figures.cpu_seconds -= process_cpu_seconds() - cpu_pause;
    }
  }
  figures.wall_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  figures.cpu_seconds += process_cpu_seconds() - cpu_start;
  figures.simulated_seconds = run.time();
  return figures;
}

}  // namespace tongue::benchmarks
