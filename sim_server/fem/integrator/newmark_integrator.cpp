#include "fem/integrator/newmark_integrator.hpp"

#include <chrono>
#include <stdexcept>

namespace tongue::fem {

// One Newmark step as a nonlinear problem in the free displacements x at t + dt. The inertia
// and damping forces are affine in x: with a(x) and v(x) the Newmark updates,
//   M a(x) + C v(x) = S (x - u_n) + M a_s + C v_s,  S = c0 M + c1 C,
// a_s = a(u_n), v_s = v(a_s), c0 = 1 / (beta dt^2), c1 = gamma / (beta dt) (Bathe 1996
// sec. 9.2.4). With C = (S - c0 M) / c1 the step's constant part needs M alone:
//   M a(x) + C v(x) = S (x - s) + b,  s = u_n - v_s / c1,  b = M (a_s - (c0 / c1) v_s):
// one product with S per residual and one with M per step. The alpha method's inertia
// M [(1 - alpha) a(x) + alpha a_n] is the same with c0 (1 - alpha) for c0 in S and b, and
// (1 - alpha) a_s + alpha a_n for a_s in b. The products run on full vectors
// in node blocks (NodeBlockMatrix), where the residual is assembled, before its free entries
// are gathered.
class NewmarkIntegrator::StepProblem : public NonlinearProblem {
 public:
  StepProblem(NewmarkIntegrator& integrator, double dt)
      : in_(integrator),
        dofs_(integrator.system_.solid().dofs()),
        dt_(dt),
        c0_(1.0 / (integrator.settings_.newmark.beta * dt * dt)),
        u_n_(dofs_.gather_free(integrator.u_)),
        v_n_(dofs_.gather_free(integrator.v_)),
        a_n_(dofs_.gather_free(integrator.a_)),
        u_full_(integrator.u_),
        S_(integrator.dynamic_matrix(dt)) {
    // s and b over all dofs: zero velocity and acceleration at prescribed dofs, so s holds the
    // prescribed values there, as x does, and the blocks' rows and columns there are zero.
    const double c1 = in_.settings_.newmark.gamma / (in_.settings_.newmark.beta * dt_);
    const Vector a_start = acceleration(u_n_);
    const Vector v_start = velocity(a_start);
    shift_full_ = in_.u_;
    dofs_.scatter_free(u_n_ - v_start / c1, shift_full_);
    Vector mass_operand = Vector::Zero(u_full_.size());
    const double alpha = in_.settings_.newmark.alpha;
    dofs_.scatter_free(
        (1.0 - alpha) * a_start + alpha * a_n_ - ((1.0 - alpha) * c0_ / c1) * v_start,
        mass_operand);
    b_full_ = Vector::Zero(u_full_.size());
    in_.mass_blocks_.multiply_add(mass_operand, b_full_);
  }

  std::shared_ptr<const SparsityPattern> pattern() const override {
    return in_.mass_.shared_pattern();
  }
  bool residual(const Vector& x, Vector& r) override { return evaluate(x, r, nullptr); }
  bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& K) override {
    if (!evaluate(x, r, &K)) return false;
    K.scale_and_add(1.0, 1.0, S_);  // d r / d u_{n+1} = K_T + c0 M + c1 C
    return true;
  }
  double force_scale() const override { return load_norm_; }
  void rank_one_terms(const Vector& x, std::vector<RankOneTerm>& terms) override {
    in_.system_.rank_one_terms(full(x), terms);
  }

  Vector acceleration(const Vector& x) const {
    const double beta = in_.settings_.newmark.beta;
    return c0_ * (x - u_n_ - dt_ * v_n_) - (0.5 / beta - 1.0) * a_n_;
  }
  Vector velocity(const Vector& a) const {
    const double gamma = in_.settings_.newmark.gamma;
    return v_n_ + dt_ * ((1.0 - gamma) * a_n_ + gamma * a);
  }
  const Vector& full(const Vector& x) {
    dofs_.scatter_free(x, u_full_);
    return u_full_;
  }

 private:
  bool evaluate(const Vector& x, Vector& r, SymmetricMatrix* K) {
    if (!in_.system_.residual(full(x), 1.0, r_full_, K, &load_norm_).ok) return false;
    increment_ = u_full_ - shift_full_;
    r_full_ += b_full_;
    in_.dynamic_blocks_.multiply_add(increment_, r_full_);
    r = dofs_.gather_free(r_full_);
    return true;
  }

  const NewmarkIntegrator& in_;
  const DofMap& dofs_;
  double dt_, c0_;
  Vector u_n_, v_n_, a_n_;
  Vector u_full_, r_full_, increment_, shift_full_, b_full_;
  const SymmetricMatrix& S_;
  double load_norm_ = 0.0;
};

const SymmetricMatrix& NewmarkIntegrator::dynamic_matrix(double dt) {
  if (!dynamic_matrix_ || dynamic_matrix_dt_ != dt) {
    const NewmarkParameters& p = settings_.newmark;
    if (!dynamic_matrix_) dynamic_matrix_.emplace(mass_.shared_pattern());
    dynamic_matrix_->scale_and_add(0.0, (1.0 - p.alpha) / (p.beta * dt * dt), mass_);
    if (damping_) dynamic_matrix_->scale_and_add(1.0, p.gamma / (p.beta * dt), *damping_);
    dynamic_blocks_ = NodeBlockMatrix(*dynamic_matrix_, system_.solid().dofs());
    dynamic_matrix_dt_ = dt;
  }
  return *dynamic_matrix_;
}

NewmarkParameters NewmarkParameters::bossak(double rho_inf) {
  if (!(rho_inf >= 0.5 && rho_inf <= 1.0))
    throw std::invalid_argument("the alpha method's spectral radius must lie in [0.5, 1]");
  const double alpha = (rho_inf - 1.0) / (rho_inf + 1.0);
  return {0.25 * (1.0 - alpha) * (1.0 - alpha), 0.5 - alpha, alpha};
}

NewmarkIntegrator::NewmarkIntegrator(MechanicalSystem& system, DynamicSettings settings)
    : system_(system),
      settings_(settings),
      mass_(system.solid().mass_matrix(settings.lumped_mass)),
      mass_blocks_(mass_, system.solid().dofs()),
      newton_(system.solid().pattern(), settings.newton) {
  const NewmarkParameters& p = settings_.newmark;
  if (!(p.beta > 0.0) || !(p.gamma >= 0.5)) {
    throw std::invalid_argument("Newmark needs beta > 0 and gamma >= 1/2 (implicit and stable)");
  }
  if (!(p.alpha <= 0.0 && p.alpha >= -1.0 / 3.0)) {
    throw std::invalid_argument("the alpha method needs -1/3 <= alpha <= 0");
  }
  const int n = system.solid().num_dofs();
  u_ = v_ = a_ = Vector::Zero(n);
}

NewmarkIntegrator::~NewmarkIntegrator() = default;

void NewmarkIntegrator::initialize(const Vector& u0, const Vector& v0, double t0) {
  const DofMap& dofs = system_.solid().dofs();
  u_ = u0;
  v_ = v0;
  for (int dof : dofs.prescribed_dofs()) {
    u_[dof] = dofs.prescribed_values()[dof];
    v_[dof] = 0.0;
  }
  t_ = t0;
  previous_dt_ = 0.0;
  system_.begin_step();  // multipliers of another state mean nothing here
  Vector r_full;
  if (!system_.residual(u_, 1.0, r_full, nullptr).ok) {
    throw std::runtime_error("initial state has an inverted element");
  }
  // Initialized again at the state of the last time (a run restarted), C is the same.
  if (!damping_state_ || *damping_state_ != u_) form_damping(u_);
  // M a0 = f_ext - f_int - C v0 over the free dofs.
  Vector rhs = -dofs.gather_free(r_full);
  if (damping_) rhs -= damping_->multiply(dofs.gather_free(v_));
  if (!mass_solver_) {
    mass_solver_ = std::make_unique<CholmodSolver>(mass_.shared_pattern());
    if (!mass_solver_->factorize(mass_).ok) {
      mass_solver_.reset();
      throw std::runtime_error("mass matrix is singular");
    }
  }
  a_ = Vector::Zero(u_.size());
  dofs.scatter_free(mass_solver_->solve(rhs), a_);
  newton_.invalidate_factor();
  held_before_.clear();
  held_ = settings_.held_nodes_follow_increment ? held_unknowns() : std::vector<char>();
  initialized_ = true;
  in_equilibrium_ = false;
}

void NewmarkIntegrator::form_damping(const Vector& at) {
  const RayleighDamping& d = settings_.damping;
  damping_.reset();
  dynamic_matrix_.reset();
  damping_state_ = at;
  if (!d.active()) return;
  damping_.emplace(system_.solid().pattern());
  damping_->scale_and_add(0.0, d.mass_coefficient, mass_);
  if (d.stiffness_coefficient != 0.0) {
    // K0 is the solid's own tangent: the loads' (e.g. active muscles') stiffness at the start
    // must not stay frozen in the damping for the whole run.
    SymmetricMatrix K0(system_.solid().pattern());
    Vector f_int;
    system_.solid().assemble(at, f_int, &K0);
    damping_->scale_and_add(1.0, d.stiffness_coefficient, K0);
  }
}

void NewmarkIntegrator::initialize(const Vector& u0, const Vector& v0, const Vector& a0, double t0,
                                   const Vector& damping_state) {
  initialize(u0, v0, t0);
  a_ = a0;
  for (int dof : system_.solid().dofs().prescribed_dofs()) a_[dof] = 0.0;
  form_damping(damping_state);
}

StepReport NewmarkIntegrator::step(double dt) {
  if (!initialized_) initialize(u_, v_, t_);
  const auto start = std::chrono::steady_clock::now();
  StepReport report;
  report.dt = dt;
  report.substeps = 0;
  report.converged = advance(dt, report, 0);
  report.time = t_;
  in_equilibrium_ = report.converged && report.iterations == 0;
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

bool NewmarkIntegrator::at_rest() const {
  return in_equilibrium_ && v_.lpNorm<Eigen::Infinity>() <= kRestSpeed;
}

StepReport NewmarkIntegrator::hold(double dt) {
  if (!at_rest()) throw std::logic_error("NewmarkIntegrator::hold: the state is not at rest");
  t_ += dt;
  previous_dt_ = 0.0;
  StepReport report;
  report.dt = dt;
  report.time = t_;
  report.converged = true;
  report.held = true;
  return report;
}

StepReport NewmarkIntegrator::prepare(double dt) {
  if (!initialized_) initialize(u_, v_, t_);
  const auto start = std::chrono::steady_clock::now();
  newton_.invalidate_factor();
  last_dt_ = dt;
  StepProblem problem(*this, dt);
  const DofMap& dofs = system_.solid().dofs();
  const NewtonReport newton =
      newton_.prepare(problem, dofs.gather_free(u_) + dt * dofs.gather_free(v_));
  StepReport report;
  report.dt = dt;
  report.time = t_;
  report.substeps = 0;
  report.converged = newton.converged;
  report.factorizations = newton.factorizations;
  report.residual_evaluations = newton.residual_evaluations;
  report.max_shift = newton.max_shift;
  report.assembly_seconds = newton.assembly_seconds;
  report.factorization_seconds = newton.factorization_seconds;
  report.message = newton.failure;
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::vector<char> NewmarkIntegrator::held_unknowns() const {
  std::vector<RankOneTerm> terms;
  system_.rank_one_terms(u_, terms);
  std::vector<char> held;
  for (const RankOneTerm& t : terms) {
    if (!t.engaged()) continue;
    held.resize(system_.solid().dofs().num_free(), 0);
    for (int i : t.index)
      if (i >= 0) held[i] = 1;
  }
  return held;
}

Vector NewmarkIntegrator::predictor(double dt) const {
  // The constant-velocity predictor u_n + dt v_n. On the tongue it starts a step about ten
  // times closer to the solution than u_n does; the second-order u_n + dt v_n + dt^2/2 a_n is
  // worse than u_n, because the average-acceleration rule leaves the acceleration of the stiff
  // modes alternating from step to step (it has no numerical damping; Hughes 2000, ch. 9).
  const DofMap& dofs = system_.solid().dofs();
  const Vector u_n = dofs.gather_free(u_);
  Vector x = u_n + dt * dofs.gather_free(v_);
  // A node held by a contact spring since the state before carries on its last step's
  // displacement instead, u_n + (u_n - u_n-1): its velocity holds the rebound off the obstacle
  // for several steps after it strikes, where its displacement follows the obstacle. (A node
  // that has just struck keeps its velocity: its last step's displacement went into the
  // obstacle.) On the tongue striking the palate (scenes/tongue_i.yaml, steps 6-9) the motion
  // along the contacts' normals predicted from the velocity is 0.32, 0.18, 0.12 and 0.075 mm
  // RMS over the nodes in contact, from the increment 0.19, 0.18, 0.043 and 0.012 mm
  // (docs/contact.md).
  if (!settings_.held_nodes_follow_increment || previous_dt_ != dt || held_.empty() ||
      held_before_.size() != held_.size())
    return x;
  const Vector previous = dofs.gather_free(previous_u_);
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (held_[i] && held_before_[i]) x[i] = 2.0 * u_n[i] - previous[i];
  return x;
}

bool NewmarkIntegrator::advance(double dt, StepReport& report, int depth) {
  if (dt != last_dt_) newton_.invalidate_factor();  // the effective tangent depends on dt
  last_dt_ = dt;
  system_.begin_step();
  StepProblem problem(*this, dt);
  const DofMap& dofs = system_.solid().dofs();
  // A prediction that inverts an element (a fast motion over a long step) gives way to u_n.
  const Vector u_n = dofs.gather_free(u_);
  Vector x = predictor(dt);
  NewtonReport newton = newton_.solve(problem, x, &u_n);
  if (!newton.start_evaluable) {
    x = u_n;
    report.residual_evaluations += newton.residual_evaluations;
    newton = newton_.solve(problem, x, &u_n);
  }
  report.add(newton);
  // A constraint held by an augmented Lagrangian (contact deeper than its tolerance): solved
  // again from here with the multipliers updated, until it holds or the load has no updates
  // left (then the step is accepted and says so).
  while (newton.converged) {
    const Augmentation constraint = system_.augment(problem.full(x));
    if (constraint == Augmentation::unmet) report.constraint_unmet = true;
    if (constraint != Augmentation::solve_again) break;
    ++report.augmentations;
    newton = newton_.solve(problem, x, &u_n);
    report.add(newton);
  }

  if (newton.converged) {
    const Vector a = problem.acceleration(x);
    const Vector v = problem.velocity(a);
    previous_u_ = std::move(u_);
    previous_dt_ = dt;
    u_ = problem.full(x);
    if (settings_.held_nodes_follow_increment) {
      held_before_ = std::move(held_);
      held_ = held_unknowns();
    }
    dofs.scatter_free(v, v_);
    dofs.scatter_free(a, a_);
    t_ += dt;
    ++report.substeps;
    return true;
  }
  if (!report.cut(t_, dt, newton.failure, depth < settings_.max_cuts)) return false;
  return advance(0.5 * dt, report, depth + 1) && advance(0.5 * dt, report, depth + 1);
}

}  // namespace tongue::fem
