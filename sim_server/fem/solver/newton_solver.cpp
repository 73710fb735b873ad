#include "fem/solver/newton_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tongue::fem {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The contraction assumed for a solve's first correction at the least. One measured right after
// a factorization is full Newton's, far below what the reused factor gives steps later
// (0.002 against about 0.1 on the tongue): carried over alone it let corrections a hundred
// times the tolerance pass. With 1/2 the first correction passes only when it is itself
// within the tolerance.
constexpr double kFirstContraction = 0.5;

// Rank-one corrections of a reused factor, at most: each costs a sparse forward substitution
// and inner products with the others, and each solve with them an update of the capacitance
// system; beyond this many re-forming the factor (about 7 ms) is cheaper.
constexpr int kMaxCorrections = 96;
// A reused factor whose corrections contract by this or better is kept (see solve()): halving
// corrections meet the tolerance within a few more iterations, where a new factor costs about as
// much as ten. On scenes/tongue_i.yaml 0.5 saved a third of the factorizations and a sixth of the
// iterations; 0.8 (the default reform_ratio) saved as many there, but cost the /ai/ closed loop in
// the vocal tract 12 % more iterations and no factorization.
constexpr double kKeepContraction = 0.5;
// Rank-one terms this close count as the same: directions within 8 degrees, stiffnesses within
// a factor 4.
constexpr double kCloseDirection = 0.99;
constexpr double kCloseStiffness = 4.0;
// A reused column's direction may differ from the term's by this much (cosine: 0.8 degrees).
// On scenes/tongue_i.yaml with smooth normals, 0.9999 took 96 iterations and 5 factorizations,
// exact directions 121 and 8 with solves three times as long, 0.99 (8 degrees) 138 and 11.
constexpr double kSameColumn = 0.9999;
// An inner product of two columns not taken yet.
constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
// Rounds of engaging the springs a correction would carry into contact, each a solve more.
constexpr int kEngageRounds = 3;

// u^T y for the sparse u of a term or a column: its direction on its unknowns.
template <typename Sparse>
double along(const Sparse& t, const Vector& y) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c)
    if (t.index[c] >= 0) sum += t.direction[c] * y[t.index[c]];
  return sum;
}

// Whether two terms or columns act on the same unknowns, compared as three ints: std::array's
// == calls memcmp, which the searches over every term and column of a reused factor made
// 0.5-1 % of a contact scene's stepping.
bool same_unknowns(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

bool all_finite(const Vector& v) {
  return v.allFinite();
}

}  // namespace

bool NewtonSolver::Residuals::operator()(const Vector& at, Vector& out) const {
  const auto start = Clock::now();
  ++report.residual_evaluations;
  const bool ok = problem.residual(at, out) && all_finite(out);
  report.assembly_seconds += seconds_since(start);
  return ok;
}

NewtonSolver::NewtonSolver(std::shared_ptr<const SparsityPattern> pattern, NewtonSettings settings)
    : settings_(settings), tangent_(pattern), linear_solver_(pattern) {}

void NewtonSolver::forget_factor() {
  factor_age_ = -1;
  contraction_ = -1.0;
  updates_.clear();
  factored_terms_.clear();
  candidates_.clear();
  corrections_.clear();
  columns_.clear();
  gram_.clear();
}

void NewtonSolver::add_correction(const RankOneTerm& term, double stiffness) {
  // A column within kSameColumn of the term's direction stands in for it: a smooth obstacle's
  // normal turns a little at every iterate, and a column for each would be a forward
  // substitution and inner products with all the others every iteration.
  const auto known = std::find_if(columns_.begin(), columns_.end(), [&](const Column& c) {
    return same_unknowns(c.index, term.index) && c.direction.dot(term.direction) > kSameColumn;
  });
  const int column = static_cast<int>(known - columns_.begin());
  if (known == columns_.end()) {
    // Its inner products with the other columns are taken when a capacitance system needs them.
    gram_.emplace_back(columns_.size() + 1, kUnknown);
    columns_.push_back(
        {term.index, term.direction,
         linear_solver_.forward_sparse({term.index.begin(), term.index.end()},
                                       {term.direction.begin(), term.direction.end()})});
  }
  corrections_.push_back({column, stiffness});
}

void NewtonSolver::update_capacitance() {
  const int k = static_cast<int>(corrections_.size());
  if (k == 0) return;
  // The inner products of the columns in use not taken yet: a column meets only those in use
  // with it, not every column solved for with the factor (on scenes/tongue_i.yaml about 60 in
  // use of up to 170).
  Eigen::MatrixXd C(k, k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j <= i; ++j) {
      const int a = std::max(corrections_[i].column, corrections_[j].column);
      const int b = std::min(corrections_[i].column, corrections_[j].column);
      double& product = gram_[a][b];
      if (std::isnan(product)) product = dot(columns_[a].w, columns_[b].w);
      C(i, j) = C(j, i) = product;
    }
    C(i, i) += 1.0 / corrections_[i].stiffness;
  }
  capacitance_.compute(C);
}

void NewtonSolver::split_terms() {
  candidates_.clear();
  std::erase_if(terms_, [&](const RankOneTerm& t) {
    if (!t.engaged()) candidates_.push_back(t);
    return !t.engaged();
  });
}

void NewtonSolver::take_terms(NonlinearProblem& problem, const Vector& x) {
  if (next_terms_known_) {
    terms_.swap(next_terms_);
    next_terms_known_ = false;
  } else {
    problem.rank_one_terms(x, terms_);
  }
}

bool NewtonSolver::correct_factor(NonlinearProblem& problem, const Vector& x,
                                  NewtonReport& report) {
  take_terms(problem, x);
  split_terms();
  // A term on the same unknowns and about the same direction as one of the factor's, with a
  // stiffness within a factor kCloseStiffness of it, is left to the iteration, as the rest of
  // the tangent's change is; one that changed more is corrected by the difference, a new one
  // added, and one that is gone taken out.
  const auto same_place = [](const RankOneTerm& a, const RankOneTerm& b) {
    return same_unknowns(a.index, b.index) && a.direction.dot(b.direction) > kCloseDirection;
  };
  std::vector<std::pair<RankOneTerm, double>> wanted;  // (term, change of stiffness)
  for (const RankOneTerm& t : terms_) {
    const auto f = std::find_if(factored_terms_.begin(), factored_terms_.end(),
                                [&](const RankOneTerm& o) { return same_place(t, o); });
    if (f == factored_terms_.end()) {
      wanted.push_back({t, t.stiffness});
    } else if (std::max(t.stiffness, f->stiffness) >
               kCloseStiffness * std::min(t.stiffness, f->stiffness)) {
      wanted.push_back({t, t.stiffness - f->stiffness});
    }
  }
  for (const RankOneTerm& t : factored_terms_) {
    const auto now = std::find_if(terms_.begin(), terms_.end(),
                                  [&](const RankOneTerm& o) { return same_place(t, o); });
    if (now == terms_.end()) wanted.push_back({t, -t.stiffness});
  }
  if (static_cast<int>(wanted.size()) > kMaxCorrections) return false;
  const bool same = wanted.size() == corrections_.size() &&
                    std::equal(wanted.begin(), wanted.end(), corrections_.begin(),
                               [&](const auto& w, const Correction& c) {
                                 const Column& col = columns_[c.column];
                                 return same_unknowns(w.first.index, col.index) &&
                                        w.first.direction == col.direction &&
                                        w.second == c.stiffness;
                               });
  if (same) return true;
  const auto start = Clock::now();
  corrections_.clear();
  for (const auto& [term, change] : wanted) add_correction(term, change);
  update_capacitance();
  report.solve_seconds += seconds_since(start);
  return true;
}

void NewtonSolver::engage_candidates(const Vector& r, Vector& dx, Vector forward_r) {
  // An engaged spring acts from its gap on: its force k (gap + v . dx) enters the linear model
  // of the residual as k gap v beside the tangent's k v v^T. While L^-1 P r is known (no BFGS
  // pairs in the first solve: 23 of the 27 rounds on scenes/tongue_i.yaml), the forward half
  // of the solve with the springs is that plus L^-1 P of their pulls, one sparse substitution
  // for all of them, and solving again costs about its backward half.
  std::vector<int> pulled;  // the unknowns of this round's pulls, and their values
  std::vector<double> pulls;
  for (int round = 0; round < kEngageRounds && !candidates_.empty(); ++round) {
    if (static_cast<int>(corrections_.size()) >= kMaxCorrections) break;
    pulled.clear();
    pulls.clear();
    for (auto c = candidates_.begin(); c != candidates_.end();) {
      if (c->gap + along(*c, dx) < 0.0 && static_cast<int>(corrections_.size()) < kMaxCorrections) {
        for (int i = 0; i < 3; ++i) {
          if (c->index[i] < 0) continue;
          pulled.push_back(c->index[i]);
          pulls.push_back(c->stiffness * c->gap * c->direction[i]);
        }
        add_correction(*c, c->stiffness);
        c = candidates_.erase(c);
      } else {
        ++c;
      }
    }
    if (pulled.empty()) break;
    // The secant pairs were gathered without these springs: H y = s holds them to the softer
    // response they measured along the springs' directions, and the correction, the springs'
    // pull from their gaps against it, came out 8 to 17 mm long after one of 0.4 to 2 mm
    // (scenes/tongue_i.yaml as the dorsum strikes the palate: line searches cut it to 2-5 %
    // and the factor was formed again). Dropped, the factor and its corrections alone
    // give the direction; the next pairs are gathered with the springs engaged. Correcting each
    // pair's y by the springs' k v (v . s) instead took more iterations and factorizations.
    updates_.clear();
    update_capacitance();
    if (forward_r.size() > 0) {
      linear_solver_.forward_sparse(pulled, pulls).subtract_from(-1.0, forward_r);
      dx = -corrected_backward(forward_r);
    } else {
      // Only in the first round: the solve below leaves L^-1 P r_model for the next ones.
      Vector r_model = r;
      for (std::size_t i = 0; i < pulled.size(); ++i) r_model[pulled[i]] += pulls[i];
      dx = direction(r_model, &forward_r);
    }
  }
}

Vector NewtonSolver::direction(const Vector& r, Vector* forward_r) const {
  // Two-loop recursion: q = prod (I - rho y s^T) r, z = H_0 q, then back through the pairs.
  Vector q = r;
  std::vector<double> alpha(updates_.size());
  for (std::size_t i = updates_.size(); i-- > 0;) {
    alpha[i] = updates_[i].inverse_curvature * updates_[i].s.dot(q);
    q -= alpha[i] * updates_[i].y;
  }
  Vector z;
  if (forward_r != nullptr) forward_r->resize(0);
  if (forward_r != nullptr && updates_.empty()) {
    *forward_r = linear_solver_.forward(q);
    z = corrected_backward(*forward_r);
  } else if (corrections_.empty()) {
    z = linear_solver_.solve(q);
  } else {
    z = corrected_backward(linear_solver_.forward(q));
  }
  for (std::size_t i = 0; i < updates_.size(); ++i) {
    const double beta = updates_[i].inverse_curvature * updates_[i].y.dot(z);
    z += (alpha[i] - beta) * updates_[i].s;
  }
  return -z;
}

Vector NewtonSolver::corrected_backward(Vector y) const {
  if (!corrections_.empty()) {
    Eigen::VectorXd w(corrections_.size());
    for (std::size_t j = 0; j < corrections_.size(); ++j)
      w[j] = columns_[corrections_[j].column].w.dot(y);
    const Eigen::VectorXd t = capacitance_.solve(w);
    for (std::size_t j = 0; j < corrections_.size(); ++j)
      columns_[corrections_[j].column].w.subtract_from(t[j], y);
  }
  return linear_solver_.backward(y);
}

bool NewtonSolver::refactorize(NonlinearProblem& problem, const Vector& x, Vector& r,
                               NewtonReport& report) {
  const auto start = Clock::now();
  ++report.residual_evaluations;
  if (!problem.residual_and_tangent(x, r, tangent_) || !all_finite(r)) {
    report.failure = "tangent not evaluable";
    return false;
  }
  report.assembly_seconds += seconds_since(start);
  linear_solver_.set_single_precision(settings_.single_precision_solve);
  const FactorizationReport f = linear_solver_.factorize(tangent_);
  report.factorization_seconds += f.seconds;
  ++report.factorizations;
  report.max_shift = std::max(report.max_shift, f.shift);
  if (!f.ok) {
    report.failure = "tangent could not be factorized, even shifted";
    return false;
  }
  factor_age_ = 0;
  contraction_ = -1.0;
  updates_.clear();
  corrections_.clear();
  columns_.clear();
  gram_.clear();
  take_terms(problem, x);
  split_terms();
  factored_terms_ = terms_;
  return true;
}

NewtonReport NewtonSolver::prepare(NonlinearProblem& problem, const Vector& x) {
  NewtonReport report;
  next_terms_known_ = false;
  Vector r(x.size());
  report.converged = refactorize(problem, x, r, report);
  if (!report.converged) forget_factor();
  return report;
}

bool NewtonSolver::same_engaged_terms(NonlinearProblem& problem, const Vector& at) {
  // terms_ holds the terms engaged at the iterate the step started from (split_terms); those at
  // `at`, the next iterate, are kept for its correction of the factor (take_terms).
  problem.rank_one_terms(at, next_terms_);
  next_terms_known_ = true;
  auto engaged = terms_.begin();
  for (const RankOneTerm& t : next_terms_) {
    if (!t.engaged()) continue;
    if (engaged == terms_.end() || !same_unknowns(engaged->index, t.index)) return false;
    ++engaged;
  }
  return engaged == terms_.end();
}

void NewtonSolver::remember(Vector s, Vector y) {
  // The pair enters only with positive curvature y . s > 0, which keeps H positive definite.
  const double curvature = y.dot(s);
  if (!(curvature > 0.0)) return;
  if (static_cast<int>(updates_.size()) == settings_.quasi_newton_updates)
    updates_.erase(updates_.begin());
  updates_.push_back({std::move(s), std::move(y), 1.0 / curvature});
}

NewtonReport NewtonSolver::solve(NonlinearProblem& problem, Vector& x, const Vector* origin) {
  NewtonReport report;
  next_terms_known_ = false;
  const NewtonSettings& s = settings_;
  const bool judge_displacement = s.displacement_tolerance > 0.0;
  const Vector x0 = origin ? *origin : x;
  Vector r(x.size());
  const Residuals evaluate{problem, report};

  auto fail = [&](std::string why) {
    report.failure = std::move(why);
    forget_factor();
    return report;
  };
  if (!evaluate(x, r)) {
    report.start_evaluable = false;
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
  double previous_step = 0.0;  // ||eta dx|| of the previous iteration, in the test's norm [m]

  bool reform = factor_age_ < 0 || s.max_tangent_reuse == 0;
  for (int k = 0; k < s.max_iterations; ++k) {
    report.iterations = k + 1;
    if (!reform && factor_age_ < s.max_tangent_reuse && !correct_factor(problem, x, report))
      reform = true;
    if ((reform || factor_age_ >= s.max_tangent_reuse) && !refactorize(problem, x, r, report))
      return fail(report.failure);
    auto start = Clock::now();
    Vector forward_r;
    Vector dx = direction(r, candidates_.empty() ? nullptr : &forward_r);
    engage_candidates(r, dx, std::move(forward_r));  // timed with the solve
    report.solve_seconds += seconds_since(start);
    if (!all_finite(dx)) return fail("the linear solve gave a non-finite correction");
    ++factor_age_;

    // The corrections still to come form about a geometric series of ratio rho (modified Newton
    // contracts linearly; full Newton's rho falls towards 0), so the error left after this one
    // is about ||dx|| rho / (1 - rho); no contraction yet (rho >= 1) leaves it unbounded.
    // The first correction of a solve has no contraction of its own: when the displacement
    // decides it is judged with the one carried over from the previous solve, but at least
    // kFirstContraction; otherwise by its own size.
    auto error_left = [&](double step) {
      if (k > 0 && previous_step > 0.0)
        contraction_ = step / previous_step;
      else if (!judge_displacement)
        return step;
      const double rho = k == 0 ? std::max(contraction_, kFirstContraction) : contraction_;
      return rho >= 0.0 && rho < 1.0 ? step * rho / (1.0 - rho)
                                     : std::numeric_limits<double>::infinity();
    };
    if (judge_displacement) {
      // Judged before the residual after dx is evaluated: the estimate needs only the corrections.
      const double step = dx.lpNorm<Eigen::Infinity>();
      report.error_estimate = error_left(step);
      report.last_increment = step;
      previous_step = step;
      if (report.error_estimate <= s.displacement_tolerance) {
        x += dx;
        report.converged = true;
        return report;
      }
    }

    Vector x_trial, r_trial;
    const double eta = line_search(evaluate, x, dx, r, x_trial, r_trial);
    if (eta == 0.0) return fail("every step along the Newton direction inverts an element");
    if (s.quasi_newton_updates > 0 && s.max_tangent_reuse > 0 &&
        same_engaged_terms(problem, x_trial))
      remember(x_trial - x, r_trial - r);
    x = std::move(x_trial);
    r = std::move(r_trial);
    const double previous_norm = r_norm;
    r_norm = r.norm();
    report.final_residual = r_norm;
    report.residual_history.push_back(r_norm);
    if (judge_displacement) {
      if (eta != 1.0) previous_step *= eta;
    } else {
      const double step = eta * dx.norm();
      report.last_increment = step;
      report.error_estimate = error_left(step);
      previous_step = step;
      const bool residual_small = r_norm <= residual_tolerance;
      const bool increment_small =
          report.error_estimate <= std::max(s.increment_rtol * (x - x0).norm(), s.increment_atol);
      if (residual_small && increment_small) {
        report.converged = true;
        return report;
      }
    }
    if (r_norm <= s.residual_atol) {
      report.converged = true;
      return report;
    }
    reform = s.max_tangent_reuse == 0 || r_norm > s.reform_ratio * previous_norm;
    // Where the displacement decides, so does the factor's own measure of quality: corrections
    // that at least halve keep it, even when the residual does not fall (stiff contact springs
    // make its norm swing with micrometres of their nodes).
    if (reform && judge_displacement && k > 0 && contraction_ >= 0.0 &&
        contraction_ < kKeepContraction)
      reform = false;
  }
  return fail("no convergence in " + std::to_string(s.max_iterations) + " iterations");
}

double NewtonSolver::line_search(const Residuals& evaluate, const Vector& x, const Vector& dx,
                                 const Vector& r, Vector& x_trial, Vector& r_trial) const {
  // Secant line search on s(eta) = dx . r(x + eta dx): step back from configurations that
  // cannot be evaluated, and interpolate to the root of s when the full step overshoots.
  const double s0 = dx.dot(r);
  double eta = 1.0;
  x_trial = x + dx;
  r_trial.resize(x.size());
  bool evaluable = evaluate(x_trial, r_trial);
  for (int halvings = 0; !evaluable && halvings < 6; ++halvings) {
    eta *= 0.5;
    x_trial = x + eta * dx;
    evaluable = evaluate(x_trial, r_trial);
  }
  if (!evaluable) return 0.0;
  if (!settings_.line_search) return eta;
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
  return eta;
}

}  // namespace tongue::fem
