#pragma once
// The reduced model's error indicator: the full model's dynamic residual at a reduced state,
// R = M a + C v + f_int - f_ext over the free dofs with every element, turned into the
// correction the full model's Newton method would make from there, S^-1 R with S the tangent of
// a step of dt at the basis' origin (c0 M + c1 C + K0, C = alpha M + beta_R K0), as its largest
// nodal component [m]: zero for a state of the full model, and what the basis cannot represent
// otherwise. Costs one full residual and one solve; S is factorized, in single precision, at
// the first call and when dt changes, or ahead of them (prepare).
#include <memory>
#include <optional>

#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/solver/cholmod_solver.hpp"

namespace tongue::reduced {

class FullModelCheck {
 public:
  // The system's loads are evaluated as they stand at each call (the muscles' activations: the
  // checked state's). origin: the basis' origin, full vector [m].
  FullModelCheck(const fem::MechanicalSystem& system, fem::Vector origin,
                 fem::DynamicSettings settings);
  ~FullModelCheck();

  // Assembles K0 and factorizes S for steps of dt [s], unless done already for that dt; false
  // where S cannot be had (an inverted element at the origin, S not positive definite).
  // correction() calls it; calling it ahead of the first check takes that cost off the check.
  bool prepare(double dt);

  // The correction [m] at displacement u, velocity v and acceleration a (full vectors) reached
  // by a step of dt [s]; infinity (never NaN) where the full model cannot judge the state: an
  // inverted element, a non-finite residual or S not positive definite.
  double correction(const fem::Vector& u, const fem::Vector& v, const fem::Vector& a, double dt);

 private:
  const fem::MechanicalSystem& system_;
  fem::Vector origin_;
  fem::DynamicSettings settings_;
  fem::SymmetricMatrix mass_;
  std::optional<fem::SymmetricMatrix> stiffness0_;  // K0 at the origin, over the free dofs
  std::unique_ptr<fem::CholmodSolver> solver_;      // S of dt_
  double dt_ = 0.0;
};

}  // namespace tongue::reduced
