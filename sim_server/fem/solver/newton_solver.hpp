#pragma once
// Newton-Raphson with a secant line search (Crisfield 1991, sec. 9.3; the scheme ANSYS and FEBio
// use) and optional reuse of the factorized tangent (modified Newton), re-formed as soon as the
// residual stops falling fast enough.
#include <memory>
#include <string>
#include <vector>

#include "fem/solver/cholmod_solver.hpp"
#include "fem/solver/nonlinear_problem.hpp"

namespace tongue::fem {

struct NewtonSettings {
  // Converged when ||r|| <= max(residual_rtol ||r_0||, residual_atol) and the last correction
  // ||dx|| <= max(increment_rtol ||x - x_0||, increment_atol); or at once when
  // ||r|| <= residual_atol.
  double residual_rtol = 1e-6;
  double residual_atol = 1e-9;  // [N]
  double increment_rtol = 1e-6;
  double increment_atol = 1e-12;  // [m]
  int max_iterations = 25;
  bool line_search = true;
  // Modified Newton: a factorization may serve up to this many iterations (0: full Newton),
  // across steps, and is re-formed when ||r_k+1|| > reform_ratio ||r_k||.
  int max_tangent_reuse = 0;
  double reform_ratio = 0.5;
  // With a reused factor, the direction is corrected by up to this many BFGS updates built from
  // the last corrections and residual changes (Matthies & Strang 1979; the inverse update in
  // the two-loop form of Nocedal & Wright 2006, alg. 7.4, with the factor as H_0). They are
  // dropped with the factor. 0: plain modified Newton.
  int quasi_newton_updates = 0;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  int factorizations = 0;
  int residual_evaluations = 0;
  double initial_residual = 0.0;  // ||r_0|| [N]
  double force_scale = 0.0;       // F of the convergence test [N]
  double final_residual = 0.0;    // [N]
  double last_increment = 0.0;    // [m]
  double max_shift = 0.0;         // largest tangent shift the factorization needed (0: none)
  std::vector<double> residual_history;
  std::string failure;  // why it did not converge
  double assembly_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
};

class NewtonSolver {
 public:
  NewtonSolver(std::shared_ptr<const SparsityPattern> pattern, NewtonSettings settings);

  // Iterates from x (updated in place; on failure x holds the last iterate).
  NewtonReport solve(NonlinearProblem& problem, Vector& x);
  // Forces a fresh tangent at the next iteration (the problem's tangent changed, e.g. new dt).
  void invalidate_factor() { forget_factor(); }

  const NewtonSettings& settings() const { return settings_; }
  NewtonSettings& settings() { return settings_; }

 private:
  NewtonSettings settings_;
  SymmetricMatrix tangent_;
  CholmodSolver linear_solver_;
  int factor_age_ = -1;  // iterations served by the current factor; -1 when none
  // BFGS pairs since the last factorization: s = x_k+1 - x_k, y = r_k+1 - r_k, 1 / (y . s).
  struct Update {
    Vector s, y;
    double inverse_curvature;
  };
  std::vector<Update> updates_;
  // -H r: the factor's solve, corrected by the BFGS updates.
  Vector direction(const Vector& r) const;
  void forget_factor();
};

}  // namespace tongue::fem
