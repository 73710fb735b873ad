#pragma once
// The reduced model's error indicator (reduced::FullModelCheck) run on a thread of its own, so
// that the steps do not wait for it (a full residual and a sparse solve, about 0.8 ms on the
// tongue, four reduced steps' worth).
//
// The check needs the full model's loads at the checked state's activations while the run goes
// on with the next ones, so the watch checks on a build of the scene of its own. check() hands
// over a copy of the state and returns at once; its result comes back from the next check()
// (or collect()), which first waits for it to end. Each state handed over is checked, in order,
// whatever the threads' timing: the results are those of FullModelCheck on the run's own
// thread, each delivered one call later.
#include <cstdint>
#include <memory>
#include <optional>

#include "reduced/full_model_check.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"
#include "scene_run/background_task.hpp"

namespace tongue::scene_run {

// The error indicator of a reduced state.
struct ReducedCheck {
  std::int64_t step = 0;    // the state's step number
  double time = 0.0;        // s, the state's time
  double correction = 0.0;  // m (reduced::FullModelCheck::correction)
};

class ReducedCheckWatch {
 public:
  // origin: the basis' origin, full vector [m].
  ReducedCheckWatch(const scene::Scene& scene, const fem::Vector& origin);

  // Waits for the check under way, then starts checking the state reached by a step of dt [s]
  // under the activation levels [1] (displacement u [m], velocity v [m/s], acceleration a
  // [m/s^2], full vectors; the state of `step` at `time` [s]); returns the result of the check
  // it waited for, if any.
  std::optional<ReducedCheck> check(const fem::Vector& u, const fem::Vector& v,
                                    const fem::Vector& a, const fem::Vector& levels, double dt,
                                    std::int64_t step, double time);
  // Waits for the check under way and returns its result, if any.
  std::optional<ReducedCheck> collect();

 private:
  void check_state();  // the task's job

  scene::BuiltScene built_;  // the watch's own: its muscles take the checked state's levels
  reduced::FullModelCheck full_;
  // The state being checked, and then its result: the task's while a check is under way.
  fem::Vector u_, v_, a_, levels_;
  double dt_ = 0.0;
  ReducedCheck checked_;
  std::optional<ReducedCheck> result_;  // not yet collected
  BackgroundTask task_;                 // last: stopped first
};

}  // namespace tongue::scene_run
