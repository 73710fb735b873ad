#include "fem/solver/newton_solver.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace tongue::fem {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool all_finite(const Vector& v) {
  return v.allFinite();
}

}  // namespace

NewtonSolver::NewtonSolver(std::shared_ptr<const SparsityPattern> pattern, NewtonSettings settings)
    : settings_(settings), tangent_(pattern), linear_solver_(pattern) {}

void NewtonSolver::forget_factor() {
  factor_age_ = -1;
  updates_.clear();
}

Vector NewtonSolver::direction(const Vector& r) const {
  // Two-loop recursion: q = prod (I - rho y s^T) r, z = H_0 q, then back through the pairs.
  Vector q = r;
  std::vector<double> alpha(updates_.size());
  for (std::size_t i = updates_.size(); i-- > 0;) {
    alpha[i] = updates_[i].inverse_curvature * updates_[i].s.dot(q);
    q -= alpha[i] * updates_[i].y;
  }
  Vector z = linear_solver_.solve(q);
  for (std::size_t i = 0; i < updates_.size(); ++i) {
    const double beta = updates_[i].inverse_curvature * updates_[i].y.dot(z);
    z += (alpha[i] - beta) * updates_[i].s;
  }
  return -z;
}

NewtonReport NewtonSolver::solve(NonlinearProblem& problem, Vector& x) {
  NewtonReport report;
  const NewtonSettings& s = settings_;
  const Vector x0 = x;
  Vector r(x.size());

  auto evaluate = [&](const Vector& at, Vector& out) {
    const auto start = Clock::now();
    ++report.residual_evaluations;
    const bool ok = problem.residual(at, out) && all_finite(out);
    report.assembly_seconds += seconds_since(start);
    return ok;
  };

  if (!evaluate(x, r)) {
    report.failure = "residual not evaluable at the initial guess (inverted element or NaN)";
    return report;
  }
  double r_norm = r.norm();
  report.initial_residual = report.final_residual = r_norm;
  report.residual_history.push_back(r_norm);
  report.force_scale = problem.force_scale();
  // Already in equilibrium with the forces acting, to the tolerance an iterated solution meets.
  if (r_norm <= std::max(s.residual_rtol * report.force_scale, s.residual_atol)) {
    report.converged = true;
    return report;
  }
  const double residual_tolerance =
      std::max(s.residual_rtol * std::max(r_norm, report.force_scale), s.residual_atol);
  double previous_step = 0.0;  // ||eta dx|| of the previous iteration [m]

  bool reform = factor_age_ < 0 || s.max_tangent_reuse == 0;
  for (int k = 0; k < s.max_iterations; ++k) {
    report.iterations = k + 1;
    if (reform || factor_age_ >= s.max_tangent_reuse) {
      auto start = Clock::now();
      ++report.residual_evaluations;
      if (!problem.residual_and_tangent(x, r, tangent_) || !all_finite(r)) {
        report.failure = "tangent not evaluable";
        forget_factor();
        return report;
      }
      report.assembly_seconds += seconds_since(start);
      const FactorizationReport f = linear_solver_.factorize(tangent_);
      report.factorization_seconds += f.seconds;
      ++report.factorizations;
      report.max_shift = std::max(report.max_shift, f.shift);
      if (!f.ok) {
        report.failure = "tangent could not be factorized, even shifted";
        forget_factor();
        return report;
      }
      factor_age_ = 0;
      updates_.clear();
    }
    auto start = Clock::now();
    const Vector dx = direction(r);
    report.solve_seconds += seconds_since(start);
    if (!all_finite(dx)) {
      report.failure = "the linear solve gave a non-finite correction";
      forget_factor();
      return report;
    }
    ++factor_age_;

    // Secant line search on s(eta) = dx . r(x + eta dx): step back from configurations that
    // cannot be evaluated, and interpolate to the root of s when the full step overshoots.
    const double s0 = dx.dot(r);
    double eta = 1.0;
    Vector x_trial = x + dx, r_trial(x.size());
    bool evaluable = evaluate(x_trial, r_trial);
    for (int halvings = 0; !evaluable && halvings < 6; ++halvings) {
      eta *= 0.5;
      x_trial = x + eta * dx;
      evaluable = evaluate(x_trial, r_trial);
    }
    if (!evaluable) {
      report.failure = "every step along the Newton direction inverts an element";
      forget_factor();
      return report;
    }
    if (s.line_search) {
      for (int ls = 0; ls < 3; ++ls) {
        const double s_eta = dx.dot(r_trial);
        if (std::abs(s_eta) <= 0.8 * std::abs(s0) || s0 == s_eta) break;
        const double next = std::clamp(eta * s0 / (s0 - s_eta), 0.1 * eta, eta);
        if (next == eta) break;
        Vector x_next = x + next * dx, r_next(x.size());
        if (!evaluate(x_next, r_next)) break;
        eta = next;
        x_trial = std::move(x_next);
        r_trial = std::move(r_next);
      }
    }
    if (s.quasi_newton_updates > 0 && s.max_tangent_reuse > 0) {
      // The pair enters only with positive curvature y . s > 0, which keeps H positive definite.
      Update u{x_trial - x, r_trial - r, 0.0};
      const double curvature = u.y.dot(u.s);
      if (curvature > 0.0) {
        u.inverse_curvature = 1.0 / curvature;
        if (static_cast<int>(updates_.size()) == s.quasi_newton_updates)
          updates_.erase(updates_.begin());
        updates_.push_back(std::move(u));
      }
    }
    x = std::move(x_trial);
    r = std::move(r_trial);
    const double previous_norm = r_norm;
    r_norm = r.norm();
    report.final_residual = r_norm;
    const double step = eta * dx.norm();
    report.last_increment = step;
    report.residual_history.push_back(r_norm);

    // The corrections still to come form about a geometric series of ratio rho (modified Newton
    // contracts linearly; full Newton's rho falls towards 0), so the error left in x is about
    // step * rho / (1 - rho); no contraction yet (rho >= 1) leaves it unbounded.
    double remaining_error = step;
    if (k > 0 && previous_step > 0.0) {
      const double rho = step / previous_step;
      remaining_error =
          rho < 1.0 ? step * rho / (1.0 - rho) : std::numeric_limits<double>::infinity();
    }
    previous_step = step;
    const bool residual_small = r_norm <= residual_tolerance;
    const bool increment_small =
        remaining_error <= std::max(s.increment_rtol * (x - x0).norm(), s.increment_atol);
    if ((residual_small && increment_small) || r_norm <= s.residual_atol) {
      report.converged = true;
      return report;
    }
    reform = s.max_tangent_reuse == 0 || r_norm > s.reform_ratio * previous_norm;
  }
  report.failure = "no convergence in " + std::to_string(s.max_iterations) + " iterations";
  forget_factor();
  return report;
}

}  // namespace tongue::fem
