#pragma once
// Where the wall time of the server's steps goes, as running totals on the steady clock: the
// physics (SceneRun::step), writing the run-file frame, building and publishing the state
// message, and the loop's own work on the messages that led to the step (receiving is not
// counted: in lock-step its wait is the controller's turn and the bus round trip). Summed per
// step, so that the max of a part is that of one step; a step's parts close with end_step().
// The span from the first step to the last, against the steps' own time, gives the time the
// steps waited for. The solver's own figures (iterations, factorizations, and the physics time
// split into assembly, factorization and solves) are summed beside them.
#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fem/integrator/step_totals.hpp"

namespace tongue::server {

class StepTiming {
 public:
  enum class Part { physics, run_file, state_message, loop };
  static constexpr int kParts = 4;
  using Clock = std::chrono::steady_clock;

  // A step's physics starts at `at` (the first one starts the span).
  void start_step(Clock::time_point at);
  // Adds the time from start to now to part of the current step; returns now, the start of
  // what follows.
  Clock::time_point add(Part part, Clock::time_point start);
  // The current step, ended at `at`, is counted and its parts' times checked for the max.
  void end_step(Clock::time_point at);
  // Adds the solver's figures of a step taken.
  void add_solver(const fem::StepReport& report) { solver_.add(report); }

  std::int64_t count() const { return count_; }
  double mean_ms(Part part) const;  // 0 before the first step
  double max_ms(Part part) const;
  // s from the first step's start to the last one's end: the steps and, in lock-step, the
  // waits for the controller between them (0 before the first step).
  double span_s() const;

  // "per step (N steps): physics 5.61 ms, ... (mean; max physics 9.02 ms, ...); ...; solver
  // per step: 1.41 iterations, 0.08 factorizations, assembly 0.31 ms, ...".
  std::string summary() const;
  // The run file's root attributes: timing_steps, timing_span_s, then timing_<part>_ms and
  // timing_<part>_max_ms, then the solver's means per step: timing_iterations,
  // timing_factorizations, timing_assembly_ms, timing_factorization_ms, timing_solve_ms.
  std::vector<std::pair<std::string, std::string>> attributes() const;

 private:
  struct SolverMeans {
    double iterations = 0.0, factorizations = 0.0;             // per step
    double assembly_ms = 0.0, factorization_ms = 0.0, solve_ms = 0.0;  // per step
  };
  SolverMeans solver_means() const;

  std::array<double, kParts> current_{};  // s, of the step under way
  std::array<double, kParts> total_{};    // s, of the counted steps
  std::array<double, kParts> max_{};      // s
  std::int64_t count_ = 0;
  fem::StepTotals solver_;
  Clock::time_point first_start_, last_end_;
};

// "physics", "run_file", "state_message", "loop": the attributes' names.
const char* part_name(StepTiming::Part part);

}  // namespace tongue::server
