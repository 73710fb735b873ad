#pragma once
// What one step of a solver did: every step records it, so no unconverged or cut step goes
// unreported.
#include <algorithm>
#include <sstream>
#include <string>

#include "fem/solver/newton_solver.hpp"

namespace tongue::fem {

struct StepReport {
  double time = 0.0;  // simulated time at the end of the step [s]
  double dt = 0.0;    // requested step [s]
  bool converged = false;
  int substeps = 1;    // > 1 when the step was cut and retried in pieces
  int cuts = 0;        // how many times a (sub)step was halved
  int iterations = 0;  // Newton iterations over all substeps
  int factorizations = 0;
  int residual_evaluations = 0;
  double initial_residual = 0.0;  // of the first substep [N]
  double final_residual = 0.0;    // of the last substep [N]
  double max_shift = 0.0;         // largest regularizing shift of the tangent (0: none)
  double wall_seconds = 0.0;
  double assembly_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
  double error_estimate =
      0.0;              // Newton's estimate of the error left in u, largest over substeps [m]
  bool held = false;    // taken as the identity from a state at rest (nothing evaluated)
  std::string message;  // why a cut happened or why the step failed; empty when clean
  int newton_solves = 0;
  int augmentations = 0;  // solves repeated with a load's multipliers updated (contact)
  // Accepted with a load's constraint violated beyond its tolerance, its multipliers' updates
  // spent (contact deeper than its penetration_tolerance after max_augmentations).
  bool constraint_unmet = false;

  // Records a failed (sub)step of dt at time t [s]: with cuts left it counts a cut and says the
  // step is halved, and returns true (the caller retries in halves); otherwise says no cuts are
  // left and returns false.
  bool cut(double t, double dt, const std::string& failure, bool cuts_left) {
    std::string why = "t = " + number(t) + " s, dt = " + number(dt) + " s: " + failure;
    why += cuts_left ? ", step halved" : "; no cuts left";
    message += (message.empty() ? "" : "; ") + why;
    if (cuts_left) ++cuts;
    return cuts_left;
  }

  // Adds the work of an integrator's prepare() done within this step (TimeIntegrator::prepare).
  void add_preparation(const StepReport& prepared) {
    factorizations += prepared.factorizations;
    residual_evaluations += prepared.residual_evaluations;
    assembly_seconds += prepared.assembly_seconds;
    factorization_seconds += prepared.factorization_seconds;
    wall_seconds += prepared.wall_seconds;
    max_shift = std::max(max_shift, prepared.max_shift);
  }

  // Adds the figures of one Newton solve (a step, a substep or a retried increment).
  void add(const NewtonReport& newton) {
    if (newton_solves++ == 0) initial_residual = newton.initial_residual;
    iterations += newton.iterations;
    factorizations += newton.factorizations;
    residual_evaluations += newton.residual_evaluations;
    final_residual = newton.final_residual;
    error_estimate = std::max(error_estimate, newton.error_estimate);
    max_shift = std::max(max_shift, newton.max_shift);
    assembly_seconds += newton.assembly_seconds;
    factorization_seconds += newton.factorization_seconds;
    solve_seconds += newton.solve_seconds;
  }

 private:
  static std::string number(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
  }
};

}  // namespace tongue::fem
