#pragma once
// Static equilibrium f_int(u) = f_ext(u) reached by load stepping: the loads and prescribed
// displacements are raised in equal increments of the load factor, each solved by Newton;
// an increment that fails is halved and retried.
#include <vector>

#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/step_report.hpp"
#include "fem/solver/newton_solver.hpp"

namespace tongue::fem {

struct StaticSettings {
  int load_steps = 1;
  int max_cuts = 6;  // an increment may be halved this many times in a row
  NewtonSettings newton;
};

struct StaticReport {
  bool converged = false;
  std::vector<StepReport> increments;  // one per accepted load increment ("time" = load factor)
  std::string message;
};

// u: initial guess in, equilibrium out (full displacement vector). Prescribed dofs end at their
// prescribed values.
StaticReport solve_static(const MechanicalSystem& system, Vector& u, const StaticSettings& settings);

}  // namespace tongue::fem
