#pragma once
// Runs a dynamic scene as sim_batch does (settled under its loads with every muscle off, then
// steps of dt with the activations at each step's end time), without a run file, and times the
// stepping alone: the settling is a one-off start-up, not part of the real-time budget.
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <stdexcept>
#include <string>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "scene/scene_builder.hpp"

namespace tongue::benchmarks {

struct DynamicRun {
  int steps = 0, iterations = 0, factorizations = 0, residual_evaluations = 0;
  double simulated_seconds = 0.0;
  double wall_seconds = 0.0;  // of the stepping
  double cpu_seconds = 0.0;   // process CPU time of the stepping (all threads)
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
  scene::BuiltScene built = scene::build_scene(scene);
  const int n = built.solid->num_dofs();
  fem::Vector u = fem::Vector::Zero(n);
  if (scene.analysis.settle) {
    const fem::StaticReport settled = fem::solve_static(*built.system, u, built.static_settings);
    if (!settled.converged) throw std::runtime_error("settling failed: " + settled.message);
  }
  if (built.muscles)
    built.muscles->set_activations(fem::Vector::Zero(built.muscles->num_muscles()));
  fem::NewmarkIntegrator integrator(*built.system, built.dynamic_settings);
  integrator.initialize(u, fem::Vector::Zero(n), 0.0);
  const fem::Vector& rest = built.solid->rest_positions();
  if (on_state) on_state(0.0, rest + integrator.displacement());

  DynamicRun run;
  const int count = scene::time_step_count(scene.analysis);
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  for (int s = 0; s < count; ++s) {
    const double dt = scene::time_step_length(scene.analysis, s);
    if (built.muscles)
      built.muscles->set_activations(built.activations.levels_at(integrator.time() + dt));
    const fem::StepReport r = integrator.step(dt);
    if (!r.converged)
      throw std::runtime_error("step " + std::to_string(s + 1) + " failed: " + r.message);
    ++run.steps;
    run.iterations += r.iterations;
    run.factorizations += r.factorizations;
    run.residual_evaluations += r.residual_evaluations;
    if (on_state) {
      // Observers are not part of the simulation's cost.
      const auto pause = std::chrono::steady_clock::now();
      const double cpu_pause = process_cpu_seconds();
      on_state(integrator.time(), rest + integrator.displacement());
      run.wall_seconds -=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - pause).count();
      run.cpu_seconds -= process_cpu_seconds() - cpu_pause;
    }
  }
  run.wall_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  run.cpu_seconds += process_cpu_seconds() - cpu_start;
  run.simulated_seconds = integrator.time();
  return run;
}

}  // namespace tongue::benchmarks
