#pragma once
// Running totals of step reports: how many steps, iterations, factorizations and residuals a run
// took and where the solver's time went (assembly, factorization, solves). The batch runner and
// the server print them; the server also writes them to its run file.
#include "fem/integrator/step_report.hpp"

namespace tongue::fem {

struct StepTotals {
  int steps = 0, iterations = 0, cuts = 0, factorizations = 0, residuals = 0, augmentations = 0;
  int constraints_unmet = 0;  // steps accepted with a constraint beyond its tolerance
  double assembly = 0.0, factorization = 0.0, solve = 0.0;  // s
  double wall = 0.0;                                        // s
  double residual = 0.0;                                    // the last step's final residual [N]

  void add(const StepReport& r) {
    ++steps;
    iterations += r.iterations;
    cuts += r.cuts;
    augmentations += r.augmentations;
    constraints_unmet += r.constraint_unmet ? 1 : 0;
    factorizations += r.factorizations;
    residuals += r.residual_evaluations;
    assembly += r.assembly_seconds;
    factorization += r.factorization_seconds;
    solve += r.solve_seconds;
    wall += r.wall_seconds;
    residual = r.final_residual;
  }
};

}  // namespace tongue::fem
