#include "reduced/reduced_integrator.hpp"

#include <cblas.h>

#include <chrono>
#include <limits>
#include <stdexcept>

namespace tongue::reduced {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The displacement tolerance when the scene sets none [m]: far below the basis' own error.
constexpr double kDefaultTolerance = 1e-8;
// Largest entry of a unit mode at a dof no snapshot moves that counts as round-off.
constexpr double kPrescribedRoundOff = 1e-10;
// As the full solver: the first correction of a step is judged with at least this contraction.
// The factor is re-formed when the corrections contract by less than the scene's reform_ratio
// (the full solver compares the residuals' norms with it; here the corrections', which the
// error estimate takes anyway).
constexpr double kFirstContraction = 0.5;
// A BFGS pair is used when the residual's change along the correction is at least this share of
// what the Newton matrix predicts (update_tangent).
constexpr double kMinCurvature = 1e-3;

// y = beta y + A x, or A^T x, by OpenBLAS: it picks its kernels for the CPU when it loads, where
// Eigen's products here are compiled for the vector width every x86-64 has (2 doubles). The
// basis' products (2464 x 49 on the tongue, several a step) were a quarter of a reduced step.
void multiply(const Eigen::MatrixXd& A, bool transpose, const fem::Vector& x, double beta,
              fem::Vector& y) {
  cblas_dgemv(CblasColMajor, transpose ? CblasTrans : CblasNoTrans, static_cast<int>(A.rows()),
              static_cast<int>(A.cols()), 1.0, A.data(), static_cast<int>(A.rows()), x.data(), 1,
              beta, y.data(), 1);
}

// The same with the basis held in single precision (OpenBLAS's sgemv, 8-10 us against 16-18 us for
// dgemv on the tongue's 2464 x 65 free rows: half the bytes to read).
void multiply(const Eigen::MatrixXf& A, bool transpose, const fem::Vector& x, double beta,
              fem::Vector& y) {
  const Eigen::VectorXf xf = x.cast<float>();
  Eigen::VectorXf yf(transpose ? A.cols() : A.rows());
  cblas_sgemv(CblasColMajor, transpose ? CblasTrans : CblasNoTrans, static_cast<int>(A.rows()),
              static_cast<int>(A.cols()), 1.0f, A.data(), static_cast<int>(A.rows()), xf.data(), 1,
              0.0f, yf.data(), 1);
  if (beta == 0.0)
    y = yf.cast<double>();
  else
    y = beta * y + yf.cast<double>();
}

}  // namespace

// One step's Newmark updates in reduced coordinates (Bathe 1996, sec. 9.2.4).
struct ReducedIntegrator::Step {
  double dt, beta, gamma, c0, c1;
  const fem::Vector &q, &qd, &qdd;
  fem::Vector acceleration(const fem::Vector& x) const {
    return c0 * (x - q - dt * qd) - (0.5 / beta - 1.0) * qdd;
  }
  fem::Vector velocity(const fem::Vector& a) const {
    return qd + dt * ((1.0 - gamma) * qdd + gamma * a);
  }
};

ReducedIntegrator::ReducedIntegrator(const fem::MechanicalSystem& system, ReducedBasis basis,
                                     fem::DynamicSettings settings)
    : system_(system),
      settings_(settings),
      precision_(settings.newton.single_precision_solve ? Precision::single_precision
                                                        : Precision::double_precision),
      phi_(std::move(basis.modes)),
      origin_(std::move(basis.origin)),
      num_sampled_(static_cast<int>(basis.sample_elements.size())),
      mass_(system.solid().mass_matrix(settings.lumped_mass)) {
  if (settings_.newmark.alpha != 0.0)
    throw std::invalid_argument(
        "reduced model: the alpha method (newmark: {spectral_radius}) is not supported; the "
        "reduced model steps with beta and gamma only");
  const fem::SolidModel& solid = system.solid();
  const fem::DofMap& dofs = solid.dofs();
  if (phi_.rows() != solid.num_dofs() || origin_.size() != solid.num_dofs())
    throw std::invalid_argument("reduced model: the basis has " + std::to_string(phi_.rows()) +
                                " rows, the model " + std::to_string(solid.num_dofs()) + " dofs");
  // The snapshots never move a prescribed dof; what the SVD leaves there is round-off.
  for (int dof : dofs.prescribed_dofs()) {
    if (phi_.row(dof).cwiseAbs().maxCoeff() > kPrescribedRoundOff)
      throw std::invalid_argument("reduced model: a mode moves prescribed dof " +
                                  std::to_string(dof) + " (the basis was made for other supports)");
    phi_.row(dof).setZero();
  }
  phi_free_.resize(dofs.num_free(), phi_.cols());
  for (Eigen::Index j = 0; j < phi_.cols(); ++j) phi_free_.col(j) = dofs.gather_free(phi_.col(j));
  if (precision_ == Precision::single_precision) phi_free_single_ = phi_free_.cast<float>();
  projector_ = GalerkinProjector(*solid.pattern(), dofs, phi_);
  weights_.assign(static_cast<std::size_t>(solid.mesh().num_elements()), 0.0);
  for (std::size_t j = 0; j < basis.sample_elements.size(); ++j)
    weights_.at(static_cast<std::size_t>(basis.sample_elements[j])) =
        basis.sample_weights[static_cast<Eigen::Index>(j)];
  mass_r_ = projector_.project(mass_);
  // The sample's internal force differs from the mesh's by a little everywhere, also at the
  // origin, which is the full model's equilibrium: the difference there is added back, so that
  // the reduced model rests where the full one does.
  fem::Vector whole, sampled = fem::Vector::Zero(solid.num_dofs());
  if (!solid.assemble(origin_, whole, nullptr).ok ||
      !solid.add_weighted(origin_, weights_, sampled, nullptr).ok)
    throw std::invalid_argument("reduced model: the basis' origin inverts an element");
  // Projected as each iteration's residual is, so that the two cancel at the origin.
  origin_correction_ = fem::Vector::Zero(phi_.cols());
  project_free(dofs.gather_free(whole - sampled), origin_correction_);
  const int k = num_modes();
  q_ = qd_ = qdd_ = fem::Vector::Zero(k);
  reconstruct();
}

void ReducedIntegrator::reconstruct() {
  // One pass over the basis for the three (at a run's start: steps update them alongside).
  Eigen::MatrixXd coordinates(phi_.cols(), 3), full(phi_.rows(), 3);
  coordinates << q_, qd_, qdd_;
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, static_cast<int>(phi_.rows()), 3,
              static_cast<int>(phi_.cols()), 1.0, phi_.data(), static_cast<int>(phi_.rows()),
              coordinates.data(), static_cast<int>(phi_.cols()), 0.0, full.data(),
              static_cast<int>(phi_.rows()));
  u_ = origin_ + full.col(0);
  v_ = full.col(1);
  a_ = full.col(2);
}

void ReducedIntegrator::project_free(const fem::Vector& r_free, fem::Vector& f) const {
  if (precision_ == Precision::single_precision)
    multiply(phi_free_single_, true, r_free, 1.0, f);
  else
    multiply(phi_free_, true, r_free, 1.0, f);
}

fem::Vector ReducedIntegrator::expand_free(const fem::Vector& dq) const {
  fem::Vector change(phi_free_.rows());
  if (precision_ == Precision::single_precision)
    multiply(phi_free_single_, false, dq, 0.0, change);
  else
    multiply(phi_free_, false, dq, 0.0, change);
  return change;
}

fem::Vector ReducedIntegrator::displacement_of(const fem::Vector& q) const {
  fem::Vector u = origin_;
  multiply(phi_, false, q, 1.0, u);
  return u;
}

bool ReducedIntegrator::reduced_force(const fem::Vector& u, fem::Vector& f, fem::SymmetricMatrix* K,
                                      double* load_norm) const {
  fem::Vector r;
  if (!system_.residual(u, 1.0, r, K, load_norm, &weights_).ok) return false;
  // Over the free dofs only: the modes are zero at the prescribed ones.
  f = origin_correction_;
  project_free(system_.solid().dofs().gather_free(r), f);
  return f.allFinite();
}

void ReducedIntegrator::initialize(const fem::Vector& u0, const fem::Vector& v0, double t0) {
  q_ = phi_.transpose() * (u0 - origin_);
  qd_ = phi_.transpose() * v0;
  t_ = t0;
  reconstruct();
  const fem::SolidModel& solid = system_.solid();
  const fem::RayleighDamping& d = settings_.damping;
  // K0 and the damping made of it are kept when the state is the one they were taken at: a
  // restart of a run.
  const bool same_state = damping_state_.size() == u_.size() && damping_state_ == u_;
  if (!same_state) {
    damping_r_ = d.mass_coefficient * mass_r_;
    stiffness0_.reset();
  }
  if (!same_state && d.stiffness_coefficient != 0.0) {
    // K0 of the whole solid, loads left out, as the full integrator's damping has it.
    stiffness0_.emplace(solid.pattern());
    fem::Vector f;
    if (!solid.assemble(u_, f, &*stiffness0_).ok)
      throw std::runtime_error("initial state has an inverted element");
    damping_r_ += d.stiffness_coefficient * projector_.project(*stiffness0_);
  }
  damping_state_ = u_;
  fem::Vector f;
  if (!reduced_force(u_, f, nullptr, nullptr))
    throw std::runtime_error("initial state has an inverted element");
  qdd_ = mass_r_.ldlt().solve(-f - damping_r_ * qd_);
  reconstruct();
  tangent_dt_ = 0.0;
  contraction_ = -1.0;
  in_equilibrium_ = false;
  last_dt_ = 0.0;
}

bool ReducedIntegrator::form_tangent(const fem::Vector& q, double dt) {
  const fem::NewmarkParameters& p = settings_.newmark;
  fem::SymmetricMatrix K(system_.solid().pattern());
  fem::Vector f;
  if (!reduced_force(displacement_of(q), f, &K, nullptr)) return false;
  // The tangent steers the corrections only: in the products' precision.
  newton_matrix_ = projector_.project(K, precision_) + mass_r_ / (p.beta * dt * dt) +
                   damping_r_ * (p.gamma / (p.beta * dt));
  tangent_.compute(newton_matrix_);
  if (tangent_.info() != Eigen::Success || !tangent_.isPositive()) return false;
  tangent_dt_ = dt;
  contraction_ = -1.0;
  return true;
}

void ReducedIntegrator::update_tangent(const fem::Vector& s, const fem::Vector& y) {
  // BFGS (Matthies & Strang 1979; Nocedal & Wright 2006, eq. 6.19) on the dense matrix:
  // J + y y^T / y^T s - (J s)(J s)^T / s^T J s, which is what the residual's change along s
  // says of the tangent, and positive definite when J is and y^T s > 0. A pair with little
  // curvature along s (y^T s at most kMinCurvature s^T J s) is skipped: it would make J nearly
  // singular there.
  const fem::Vector js = newton_matrix_ * s;
  const double sjs = s.dot(js), ys = y.dot(s);
  if (!(sjs > 0.0) || !(ys > kMinCurvature * sjs) || !y.allFinite()) return;
  // The factor updated by the two rank-one terms (Gill, Golub, Murray & Saunders 1974, Math.
  // Comp. 28; Eigen's LDLT::rankUpdate), O(k^2) against O(k^3) to factorize again: 3 us
  // against 13 us at 65 modes. Kept only when D stays positive (rankUpdate leaves
  // isPositive() as it was).
  Eigen::LDLT<Eigen::MatrixXd> factor = tangent_;
  factor.rankUpdate(y, 1.0 / ys);
  factor.rankUpdate(js, -1.0 / sjs);
  const fem::Vector d = factor.vectorD();
  if (!d.allFinite() || !(d.minCoeff() > 0.0)) return;
  newton_matrix_ += y * y.transpose() / ys - js * js.transpose() / sjs;
  tangent_ = std::move(factor);
}

fem::StepReport ReducedIntegrator::prepare(double dt) {
  const auto start = Clock::now();
  fem::StepReport report;
  report.dt = dt;
  report.time = t_;
  report.substeps = 0;
  report.converged = form_tangent(q_ + dt * qd_, dt);
  if (!report.converged) report.message = "the reduced tangent is not positive definite";
  report.residual_evaluations = 1;
  report.factorizations = report.converged ? 1 : 0;
  report.wall_seconds = report.factorization_seconds = seconds_since(start);
  return report;
}

fem::StepReport ReducedIntegrator::step(double dt) {
  const auto start = Clock::now();
  fem::StepReport report;
  report.dt = dt;
  report.substeps = 0;
  report.converged = advance(dt, report, 0);
  report.time = t_;
  if (report.converged) last_dt_ = dt;
  in_equilibrium_ = report.converged && report.iterations == 0;
  report.wall_seconds = seconds_since(start);
  return report;
}

bool ReducedIntegrator::at_rest() const {
  return in_equilibrium_ && v_.lpNorm<Eigen::Infinity>() <= fem::NewmarkIntegrator::kRestSpeed;
}

fem::StepReport ReducedIntegrator::hold(double dt) {
  if (!at_rest()) throw std::logic_error("ReducedIntegrator::hold: the state is not at rest");
  t_ += dt;
  fem::StepReport report;
  report.dt = dt;
  report.time = t_;
  report.converged = true;
  report.held = true;
  return report;
}

bool ReducedIntegrator::advance(double dt, fem::StepReport& report, int depth) {
  const fem::NewmarkParameters& p = settings_.newmark;
  const fem::NewtonSettings& ns = settings_.newton;
  const Step s{dt, p.beta, p.gamma, 1.0 / (p.beta * dt * dt), p.gamma / (p.beta * dt),
               q_, qd_,    qdd_};
  const double tolerance =
      ns.displacement_tolerance > 0.0 ? ns.displacement_tolerance : kDefaultTolerance;
  fem::Vector x = q_ + dt * qd_;  // the constant-velocity predictor, as the full model's
  // origin + Phi x, kept along with x from the state's u and v and the corrections' Phi dq,
  // which the error estimate takes anyway: one product with the basis an iteration, not two.
  fem::Vector u = u_ + dt * v_;
  fem::Vector f, r, last_r, dq;
  std::string failure;
  double previous = 0.0, load_norm = 0.0;
  bool converged = false, predicted = true;
  fem::NewtonReport newton;
  for (int k = 0; k < ns.max_iterations && failure.empty(); ++k) {
    auto started = Clock::now();
    ++newton.residual_evaluations;
    if (!reduced_force(u, f, nullptr, &load_norm)) {
      if (k == 0 && predicted) {
        // As in the full model: a prediction that inverts an element (a fast motion over a
        // long step) gives way to the last state.
        x = q_;
        u = u_;
        predicted = false;
        --k;
        continue;
      }
      failure = "an element inverted";
      break;
    }
    const fem::Vector a = s.acceleration(x);
    r = mass_r_ * a + damping_r_ * s.velocity(a) + f;
    newton.assembly_seconds += seconds_since(started);
    if (k == 0) {
      newton.initial_residual = r.norm();
      // Already in equilibrium: the predictor stands, as in the full solver's residual test.
      if (newton.initial_residual <= std::max(ns.residual_rtol * load_norm, ns.residual_atol)) {
        converged = true;
        break;
      }
    }
    newton.final_residual = r.norm();
    // With BFGS updates, the first pair of a step updates the matrix rather than a contraction
    // carried over from earlier steps re-forming it: it is re-formed when a correction made
    // with the updated matrix still contracts too slowly.
    const bool updates = ns.quasi_newton_updates > 0;
    if (k > 0 && updates && tangent_dt_ == dt) update_tangent(dq, r - last_r);
    if (tangent_dt_ != dt || (k > (updates ? 1 : 0) && contraction_ > ns.reform_ratio)) {
      started = Clock::now();
      if (!form_tangent(x, dt)) {
        failure = "the reduced tangent is not positive definite";
        break;
      }
      ++newton.factorizations;
      newton.factorization_seconds += seconds_since(started);
      previous = 0.0;
    }
    started = Clock::now();
    dq = tangent_.solve(-r);
    last_r = r;
    newton.solve_seconds += seconds_since(started);
    newton.iterations = k + 1;
    if (!dq.allFinite()) {
      failure = "the reduced solve gave a non-finite correction";
      break;
    }
    x += dq;
    // The error left, as the full solver estimates it (newton_solver.hpp), in the nodes'
    // displacement.
    const fem::Vector change = expand_free(dq);
    const std::vector<int>& free = system_.solid().dofs().free_dofs();
    for (std::size_t i = 0; i < free.size(); ++i)
      u[free[i]] += change[static_cast<Eigen::Index>(i)];
    const double size = change.lpNorm<Eigen::Infinity>();
    if (previous > 0.0) contraction_ = size / previous;
    const double rho = previous > 0.0 ? contraction_ : std::max(contraction_, kFirstContraction);
    newton.error_estimate =
        rho < 1.0 ? size * rho / (1.0 - rho) : std::numeric_limits<double>::infinity();
    previous = size;
    if (newton.error_estimate <= tolerance) {
      converged = true;
      break;
    }
  }
  newton.converged = converged;
  report.add(newton);
  if (converged) {
    // The state's full vectors by the same Newmark update, which is linear: Phi times the
    // coordinates' update to round-off, without a pass over the basis.
    const Step full{dt, p.beta, p.gamma, s.c0, s.c1, u_, v_, a_};
    fem::Vector full_a = full.acceleration(u);
    fem::Vector full_v = full.velocity(full_a);
    u_ = std::move(u);
    v_ = std::move(full_v);
    a_ = std::move(full_a);
    const fem::Vector a = s.acceleration(x);
    qd_ = s.velocity(a);
    qdd_ = a;
    q_ = x;
    t_ += dt;
    ++report.substeps;
    return true;
  }
  if (failure.empty())
    failure = "no convergence in " + std::to_string(ns.max_iterations) + " iterations";
  tangent_dt_ = 0.0;
  if (!report.cut(t_, dt, "reduced model: " + failure, depth < settings_.max_cuts)) return false;
  return advance(0.5 * dt, report, depth + 1) && advance(0.5 * dt, report, depth + 1);
}

double ReducedIntegrator::full_model_correction() {
  if (last_dt_ <= 0.0) return 0.0;  // no step yet: the state is the initial one
  if (!check_) check_ = std::make_unique<FullModelCheck>(system_, origin_, settings_);
  return check_->correction(u_, v_, a_, last_dt_);
}

}  // namespace tongue::reduced
