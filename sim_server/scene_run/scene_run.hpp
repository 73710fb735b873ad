#pragma once
// The run of a built dynamic scene: the one place where a dynamic scene is started and stepped,
// used by sim_batch, the server, the benchmarks and the tests that run scenes.
//
// Start-up order (docs/design.md, "The initial acceleration with the muscles off"):
//  1. settle(): static equilibrium under the scene's loads with every muscle off, when the scene
//     asks for it (analysis.settle); the settled state is the initial state of every restart.
//  2. restart(): a fresh integrator at the initial state, at rest, time 0, step 0, muscles off.
//     The initial acceleration and the damping's K0 are taken there with every muscle off: a
//     step of force in a_0 would make the average-acceleration scheme's velocities flip sign
//     from step to step in the stiff modes that the fibre end forces excite.
//     The first step's tangent is factorized there too (NewmarkIntegrator::prepare), so that
//     the first step is as quick as the later ones, under the first step's levels when the
//     caller knows them (a scheduled run) and with every muscle off otherwise.
//  3. step(dt, levels): the muscles act from the first step on, with the levels given for it.
//     A first step whose levels are not those its factor was formed with (by more than
//     kFreshFirstFactor) forms it again with them: the run then reaches the same states whether
//     its levels were known at start-up (sim_batch) or arrive with the step (the server).
// Activations enter only as the argument of step(): nothing else sets them.
// A scene with `model: {reduced: FILE}` is stepped by the reduced model of that basis
// (reduced::ReducedIntegrator) from the same initial state, projected onto the basis; every
// model.check_every steps the full model's residual at the reduced state is evaluated, off the
// step's critical path (ReducedCheckWatch), and reported with the step that hands over the next
// check (or by finish_checks()); above model.warn_above it warns. With model.switch_to_full each
// check is waited for and reported with its own step, and the run goes on with the full model
// from the state that called for it (until the next restart).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "fem/integrator/static_solver.hpp"
#include "fem/integrator/time_integrator.hpp"
#include "reduced/reduced_basis_file.hpp"
#include "run_file/run_file_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"
#include "scene_run/ellipticity_watch.hpp"
#include "scene_run/reduced_check_watch.hpp"
#include "scene_run/step_clock.hpp"

namespace tongue::scene_run {

// What one step did and reached.
struct StepResult {
  // The solver's figures. When !report.converged the run stays at the last accepted state
  // (step(), time() and the state are unchanged) and report.message says why.
  fem::StepReport report;
  // Activations, lengths [m] and velocities [m/s] of the muscles at the new state (empty vectors
  // without muscles); computed once per step for every consumer (state message, run file).
  run_file::MuscleFrame muscles;
  // The first loss of strong ellipticity of the material, reported once per run (again after a
  // restart, at the same step when the run repeats). It is checked off the step's critical path
  // (EllipticityWatch), so it comes one step late: the result of step k + 1 (converged or not)
  // reports a loss in the state of step k, and finish_checks() one in the last state. A reduced
  // model's states are checked every kReducedEllipticityEvery-th step, each finding reported with
  // the next checked step's result. The finding names its step.
  std::optional<EllipticityFinding> ellipticity_loss;
  // With a reduced model, on the steps a check is reported: the error indicator of the state it
  // checked (that of step reduced_check->step, check_every steps back; this step's own with
  // model.switch_to_full); and, the first time in a run that it exceeds the scene's
  // model.warn_above, a warning that says so (of which state and by how much).
  std::optional<ReducedCheck> reduced_check;
  std::optional<std::string> reduced_warning;
};

// What the checks made off the step's critical path found in the last states, which no step
// reported (finish_checks()).
struct FinishedChecks {
  std::optional<EllipticityFinding> ellipticity_loss;
  std::optional<ReducedCheck> reduced_check;
  std::optional<std::string> reduced_warning;
};

class SceneRun {
 public:
  // Throws std::invalid_argument naming the scene file when its analysis is not dynamic, and
  // naming the basis file when the scene's reduced model was made for another mesh or
  // material (std::runtime_error when it cannot be read).
  SceneRun(const scene::Scene& scene, scene::BuiltScene built);
  ~SceneRun();
  SceneRun(const SceneRun&) = delete;
  SceneRun& operator=(const SceneRun&) = delete;

  // Settles (when the scene says so) and restarts. Call once before the first step; the report
  // has the settling's increments (none when the scene does not settle). When it says
  // !converged the run cannot start: the initial state is the last accepted increment.
  // first_levels: the first step's levels when the caller knows them (empty: all 0), see
  // restart().
  fem::StaticReport start(const fem::Vector& first_levels = {});
  // Back to the initial state (settled or rest), at rest, time 0, step 0, all activations 0.
  // Nothing that steers a run carries over (factorizations of the step, previous dt; a reduced
  // model keeps only what it made of the same initial state), so a run after a restart repeats
  // the first one exactly, its loss of ellipticity reported again; one found in the last state
  // before it is still reported, by the next step (its finding names its step), unless
  // finish_checks() took it. The first step's factor is formed here under first_levels (empty:
  // all 0; the acceleration is taken with all 0 regardless).
  // Throws std::invalid_argument for first_levels of the wrong size or out of [0, 1]
  // (check_first_levels), before anything is changed.
  void restart(const fem::Vector& first_levels = {});
  void check_first_levels(const fem::Vector& first_levels) const;

  // How far [1] a first step's levels may be from those its factor was formed with before the
  // step forms it again. A factor formed without a step of activation converges to the step's
  // tolerance but not, as a fresh one does, far inside it: SG 3 N + relaxation at dt 4 ms was
  // 0.0457 mm RMS from its reference with the muscles-off factor, 0.0420 mm with a fresh one
  // (SG's step is a level of 0.125). A closed loop's controller starts from rest with small
  // levels (/ai/'s first step: 0.002 at most), which the start-up factor serves as well as a
  // fresh one; forming it again there would cost a factorization (about 7 ms) per run.
  static constexpr double kFreshFirstFactor = 0.01;

  // Every how many steps a reduced model's state has its material checked. A check takes about
  // 40 us on its thread, but a reduced step (about 0.13 ms on the tongue) handing over every
  // state waited for that thread to get the second core, which the error check (0.8 ms every
  // 10 steps) and the run file's writer share: 80 us of a 210 us step on a run that stays
  // elliptic. A loss is found at most this many steps late.
  static constexpr int kReducedEllipticityEvery = 4;

  // Advances by dt [s] with the activation levels [1] of every muscle (num_muscles() entries,
  // each in [0, 1]; callers validate them with their own messages first) acting during the step.
  // A step with the last step's levels from a state at rest is the identity and costs nothing
  // (fem::NewmarkIntegrator::at_rest; report.held). Throws std::invalid_argument for levels of the
  // wrong size or out of range, std::logic_error before start().
  StepResult step(double dt, const fem::Vector& levels);
  // The checks under way, which step() reports with a later step's result: waits for them and
  // returns what they found. For the end of a run, so that a loss of ellipticity in the last
  // state, or the error indicator of the last reduced state checked, is not left unsaid.
  FinishedChecks finish_checks();

  const scene::Scene& scene() const { return scene_; }
  const scene::BuiltScene& built() const { return built_; }
  int num_muscles() const;

  // The last accepted state (before start(): the rest state).
  std::int64_t step_count() const { return step_; }       // accepted steps since the last restart
  double time() const { return time_; }                   // s
  const fem::Vector& displacement() const { return u_; }  // m, full vector
  const fem::Vector& velocity() const { return v_; }      // m/s, full vector
  fem::Vector positions() const;                          // m, rest positions + displacement
  const fem::Vector& levels() const { return levels_; }   // [1], of the last step (0 at step 0)
  const fem::Vector& initial_displacement() const { return initial_u_; }  // m, of step 0
  // The integrator, read-only, for diagnostics that look inside a step (its acceleration);
  // valid after start().
  const fem::TimeIntegrator& integrator() const { return *integrator_; }
  // The reduced model's error indicator at its last check reported [m]
  // (StepResult::reduced_check); 0 for the full model and before the first report of a run.
  double reduced_correction() const { return reduced_correction_; }
  // Whether the reduced model steps the run now (false for the full model, and after a switch
  // to it, model.switch_to_full, until the next restart).
  bool reduced_now() const;
  // The reduced model's basis; null for the full model.
  const reduced::ReducedBasis* reduced_basis() const { return basis_ ? &*basis_ : nullptr; }
  // The muscles' frame at the current state (what step() returns; at step 0: all activations 0),
  // computed once per accepted state.
  const run_file::MuscleFrame& muscle_frame() const { return frame_; }

 private:
  const scene::Scene& scene_;
  scene::BuiltScene built_;
  std::optional<reduced::ReducedBasis> basis_;
  std::unique_ptr<fem::TimeIntegrator> integrator_;
  EllipticityWatch ellipticity_;
  void accept();  // the integrator's state becomes the last accepted one
  // A reduced model's check handed over on the steps it is due, the result of the one before
  // taken, and the switch to the full model when the scene asks for it.
  void check_reduced(StepResult& result, double dt);
  // A check's result becomes the run's indicator; returns the warning when it is the run's
  // first above model.warn_above.
  std::optional<std::string> take_reduced_check(const ReducedCheck& check);
  std::unique_ptr<ReducedCheckWatch> reduced_watch_;  // with a reduced model that checks

  fem::Vector initial_u_;
  fem::Vector u_, v_;  // m, m/s: the last accepted state (a failed step may leave the
                       // integrator at a substep)
  double time_ = 0.0;  // s
  StepClock clock_;    // time_ as a count of steps
  fem::Vector levels_;
  fem::Vector factor_levels_;    // the levels the first step's factor was formed with
  run_file::MuscleFrame frame_;  // of u_, v_ and levels_
  std::int64_t step_ = 0;
  bool reduced_warned_ = false;  // in this run (since the last restart)
  double reduced_correction_ = 0.0;
};

}  // namespace tongue::scene_run
