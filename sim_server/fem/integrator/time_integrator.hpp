#pragma once
// What a run steps: a model of the dynamics that advances its state by a time step, whether the
// full finite-element model (NewmarkIntegrator) or a reduced one (reduced::ReducedIntegrator).
// The loads acting during a step are the system's at the time of the call (a caller sets the
// muscles' activations first).
#include "fem/integrator/step_report.hpp"
#include "fem/types.hpp"

namespace tongue::fem {

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;

  // The state u0, v0 (full vectors) at time t0 [s], with the consistent acceleration.
  virtual void initialize(const Vector& u0, const Vector& v0, double t0) = 0;
  // Start-up work for steps of dt [s], so that the first step costs what later ones do: the
  // first step's factor formed at its predictor under the loads acting now. The report has the
  // work's figures (factorizations, residual evaluations, their times, wall_seconds) and
  // converged = whether the factor is ready (when not, the first step forms its own).
  virtual StepReport prepare(double dt) = 0;
  // Advances by dt [s]; cuts and retries on failure. When the report says !converged the state is
  // left at the last accepted substep.
  virtual StepReport step(double dt) = 0;
  // At rest: a step under unchanged loads would be the identity; hold(dt) takes it as such
  // (throws std::logic_error when !at_rest()).
  virtual bool at_rest() const = 0;
  virtual StepReport hold(double dt) = 0;

  // The state, full vectors: m, m/s, m/s^2; s.
  virtual const Vector& displacement() const = 0;
  virtual const Vector& velocity() const = 0;
  virtual const Vector& acceleration() const = 0;
  virtual double time() const = 0;
};

}  // namespace tongue::fem
