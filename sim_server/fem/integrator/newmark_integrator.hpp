#pragma once
// Implicit dynamics M a + C v + f_int(u) = f_ext(u) with the Newmark scheme (Newmark 1959;
// Bathe 1996, sec. 9.2.4):
//   u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}],
//   v_{n+1} = v_n + dt [(1 - gamma) a_n + gamma a_{n+1}],
// each step solved for u_{n+1} by Newton (the inertia optionally weighted as the alpha method of
// Wood, Bossak & Zienkiewicz weights it, below). beta = 1/4, gamma = 1/2 (average acceleration) is
// unconditionally stable and second-order accurate. Rayleigh damping C = alpha M + beta_R K0,
// with K0 the solid's tangent stiffness (without load stiffness) at the state the integrator is
// initialized in (for the tongue:
// the rest state under gravity): a constant C keeps the damping force linear in v and the
// Newton tangent exact.
#include <memory>
#include <optional>

#include "fem/assembly/node_block_matrix.hpp"
#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/step_report.hpp"
#include "fem/integrator/time_integrator.hpp"
#include "fem/solver/newton_solver.hpp"

namespace tongue::fem {

// beta, gamma and, for the alpha method of Wood, Bossak & Zienkiewicz (1980, Int. J. Numer.
// Meth. Eng. 15), the weight alpha <= 0 of a_n in the inertia, M [(1 - alpha) a_{n+1} +
// alpha a_n]: with gamma = 1/2 - alpha and beta = (1 - alpha)^2 / 4 the scheme stays
// second-order accurate and damps the modes that a step cannot resolve (omega dt -> infinity)
// by a factor rho_inf = (1 + alpha) / (1 - alpha) a step, where the average-acceleration rule
// (alpha = 0) keeps them forever (Hughes 2000, sec. 9.3.2).
struct NewmarkParameters {
  double beta = 0.25;
  double gamma = 0.5;
  double alpha = 0.0;
  // The alpha method's parameters for a spectral radius rho_inf in [1/2, 1] at infinite omega dt.
  static NewmarkParameters bossak(double rho_inf);
};

struct RayleighDamping {
  double mass_coefficient = 0.0;       // alpha [1/s]
  double stiffness_coefficient = 0.0;  // beta_R [s]
  bool active() const { return mass_coefficient != 0.0 || stiffness_coefficient != 0.0; }
};

struct DynamicSettings {
  NewmarkParameters newmark;
  RayleighDamping damping;
  bool lumped_mass = false;
  int max_cuts = 4;  // a step may be split into at most 2^max_cuts substeps
  NewtonSettings newton;
  // The nodes a load has held by a spring (in contact) for the last two states start a step
  // from their last step's displacement carried on, the others from their velocity
  // (NewmarkIntegrator::predictor). false: every node from its velocity.
  bool held_nodes_follow_increment = true;
};

class NewmarkIntegrator : public TimeIntegrator {
 public:
  NewmarkIntegrator(MechanicalSystem& system, DynamicSettings settings);
  ~NewmarkIntegrator() override;

  // Sets u, v (full vectors; prescribed dofs take their prescribed values and zero velocity)
  // and the consistent initial acceleration from M a = f_ext - f_int - C v; K0 for the damping
  // is formed here (kept when initialized again at the same u: a restarted run steps as a new
  // integrator's would, bit for bit). Throws std::runtime_error when f_int cannot be evaluated
  // at u. A first step() without it starts from rest at u = 0.
  void initialize(const Vector& u0, const Vector& v0, double t0 = 0.0) override;
  // The same mid-run, for a state another model hands over: the acceleration given instead of
  // the consistent one (a state that is not an equilibrium of this model would otherwise start
  // with its whole residual as acceleration), and K0 for the damping taken at damping_state
  // (the run's initial state, where the other model's damping took it: with the tongue's
  // stiffness-proportional damping, K0 taken 4 ms into a run moved the box test's free end by
  // a fifth of its motion).
  void initialize(const Vector& u0, const Vector& v0, const Vector& a0, double t0,
                  const Vector& damping_state);

  // Forms the constant matrices of a step of dt and factorizes that step's tangent at its
  // predictor, so that the first step() of dt, which starts with them, pays for neither: a
  // start-up cost (on the tongue the first numeric factorization, with the first touch of the
  // factor's memory, is about 9 ms). The factor holds the loads acting now, so a first step
  // whose activations differ starts from a slightly stale factor, as any later step whose
  // activations change does. Call after initialize(); a failure only leaves the work to the
  // first step.
  StepReport prepare(double dt) override;

  // Advances by dt; cuts and retries on failure. When the report says !converged the state is
  // left at the last accepted substep.
  StepReport step(double dt) override;

  // At rest: the last step was in equilibrium from its start (Newton accepted its predictor
  // without iterating: the residual, and with it M a, within the residual test) and no free node
  // moves faster than kRestSpeed. Under unchanged loads a step from such a state would move no
  // node by more than dt kRestSpeed (4 nm at dt 4 ms): hold(dt) takes it as the identity, only
  // the time advancing, without evaluating anything. Whether the loads are unchanged is the
  // caller's knowledge (e.g. the same muscle activations); any step() ends the rest.
  static constexpr double kRestSpeed = 1e-6;  // [m/s]
  bool at_rest() const override;
  // Throws std::logic_error when !at_rest().
  StepReport hold(double dt) override;

  const Vector& displacement() const override { return u_; }
  const Vector& velocity() const override { return v_; }
  const Vector& acceleration() const override { return a_; }
  double time() const override { return t_; }
  // Where Newton starts the next step of dt (the free dofs): u_n + dt v_n, but for the unknowns
  // of a node held by a spring in the last two states u_n + (u_n - u_n-1), when the last step
  // was one of dt (DynamicSettings::held_nodes_follow_increment).
  Vector predictor(double dt) const;
  const DynamicSettings& settings() const { return settings_; }
  NewtonSolver& newton() { return newton_; }

 private:
  class StepProblem;
  bool advance(double dt, StepReport& report, int depth);
  // C = alpha M + beta_R K0 with K0 the solid's tangent at `at`.
  void form_damping(const Vector& at);
  // c0 M + c1 C for this dt, formed again only when dt changes.
  const SymmetricMatrix& dynamic_matrix(double dt);
  // Marks the free unknowns of the nodes the loads hold by a spring at u_ (empty: none).
  std::vector<char> held_unknowns() const;

  MechanicalSystem& system_;
  DynamicSettings settings_;
  SymmetricMatrix mass_;
  std::optional<SymmetricMatrix> damping_;
  std::optional<Vector> damping_state_;         // the state K0 was taken at
  std::unique_ptr<CholmodSolver> mass_solver_;  // M factorized, for initial accelerations
  std::optional<SymmetricMatrix> dynamic_matrix_;
  // M and c0 M + c1 C in node blocks, for the steps' products (node_block_matrix.hpp).
  NodeBlockMatrix mass_blocks_, dynamic_blocks_;
  double dynamic_matrix_dt_ = 0.0;
  NewtonSolver newton_;
  Vector u_, v_, a_;  // full vectors
  double t_ = 0.0;
  double last_dt_ = 0.0;
  // The state before the last accepted step and that step's length (0: none since the last
  // initialize() or hold()); the unknowns held by a spring in that state and in u_.
  Vector previous_u_;
  double previous_dt_ = 0.0;
  std::vector<char> held_before_, held_;
  bool initialized_ = false;
  bool in_equilibrium_ = false;  // the last step() converged without a Newton iteration
};

}  // namespace tongue::fem
