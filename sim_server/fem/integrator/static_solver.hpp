#pragma once
// Static equilibrium f_int(u) = f_ext(u) reached by load stepping: the loads and prescribed
// displacements are raised in equal increments of the load factor, each solved by Newton;
// an increment that fails is halved and retried.
#include <functional>
#include <vector>

#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/step_report.hpp"
#include "fem/solver/newton_solver.hpp"

namespace tongue::fem {

struct StaticSettings {
  int load_steps = 1;
  // Refuse a solid its Dirichlet conditions leave free to move rigidly (fem/assembly/
  // rigid_motions.hpp) before solving; off where something else may hold it (obstacles).
  bool require_held = true;
  int max_cuts = 6;  // an increment may be halved this many times in a row
  NewtonSettings newton;
};

struct StaticReport {
  bool converged = false;
  std::vector<StepReport> increments;  // one per accepted load increment ("time" = load factor)
  std::string message;
};

// Called after each accepted load increment with its report and the displacement reached.
using IncrementObserver = std::function<void(const StepReport&, const Vector& u)>;

// u: initial guess in, equilibrium out (full displacement vector). Prescribed dofs end at their
// prescribed values. On failure u holds the last accepted increment. A solid free to move as a
// rigid body (settings.require_held) fails at once, the report's message naming the motions.
StaticReport solve_static(const MechanicalSystem& system, Vector& u, const StaticSettings& settings,
                          const IncrementObserver& observer = {});

}  // namespace tongue::fem
