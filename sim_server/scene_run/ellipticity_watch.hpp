#pragma once
// The material's stability check (fem::EllipticityMonitor::first_loss) run on a thread of its
// own, so that a step does not wait for it (on the built-in tongue it costs about 0.5 ms a step,
// the searches of the elements strained beyond the monitor's screen).
//
// check(u, step, time) hands over a copy of the state and returns at once; that state's finding
// comes back from the next check() (or collect()), which first waits for the check to end. Each
// accepted state is checked once, in order, whatever the threads' timing, so the findings are
// those of first_loss called on the main thread, each delivered one call later: a loss in the
// state of step k is reported with step k + 1's result (or by collect() at the end of a run).
// With check_every(n), only the states of every n-th step are checked (and the last one handed
// over, by collect()), each finding delivered by the next checked step's call.
#include <cstdint>
#include <optional>
#include <string>

#include "fem/assembly/ellipticity_monitor.hpp"
#include "scene_run/background_task.hpp"

namespace tongue::scene_run {

// The first loss of strong ellipticity a run found, in an accepted state.
struct EllipticityFinding {
  std::int64_t step = 0;  // the state's step number
  double time = 0.0;      // s, the state's time
  fem::EllipticityLoss loss;
  std::string warning;  // fem::describe()'s line for the user
};

class EllipticityWatch {
 public:
  // numbering names the element of a warning (fem::describe).
  explicit EllipticityWatch(const fem::SolidModel& solid, fem::MeshNumbering numbering = {});
  EllipticityWatch(const EllipticityWatch&) = delete;
  EllipticityWatch& operator=(const EllipticityWatch&) = delete;

  // Waits for the check under way, then starts checking u (full displacement [m], the state of
  // `step` at `time` [s]); returns the finding of the check it waited for, if any (at most one
  // finding per run: first_loss reports once, and once it has, no state is checked until
  // rearm()).
  std::optional<EllipticityFinding> check(const fem::Vector& u, std::int64_t step, double time);
  // Waits for the check under way and returns its finding, if any; the last state handed over,
  // if check_every left it unchecked, is checked first (on the caller's thread).
  std::optional<EllipticityFinding> collect();
  // From now on check() checks only the states whose step is a multiple of n >= 1 (1, the
  // default: every state). For a model whose steps take less time than a check, which each step
  // would wait for.
  void check_every(int n);
  // For a new run: waits for the check under way (its finding, if any, is still delivered by the
  // next call) and makes the monitor report a loss again.
  void rearm();

 private:
  void check_state();    // the task's job
  void check_skipped();  // with no task under way: the state check() left unchecked, if any

  fem::EllipticityMonitor monitor_;  // the task's while a check is under way
  const fem::Material& material_;
  const fem::MeshNumbering numbering_;
  fem::Vector u_;  // the state being checked: the task's while a check is under way
  std::int64_t step_ = 0;
  double time_ = 0.0;
  int every_ = 1;
  fem::Vector skipped_u_;  // the last state handed over if check() left it unchecked
  std::int64_t skipped_step_ = 0;
  double skipped_time_ = 0.0;
  bool skipped_ = false;
  bool found_loss_ = false;                  // this run's finding made: nothing more to check
  std::optional<EllipticityFinding> found_;  // not yet collected
  BackgroundTask task_;                      // last: stopped first
};

}  // namespace tongue::scene_run
