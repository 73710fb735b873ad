// NewtonSolver on a chain of nonlinear springs with a known root: quadratic convergence, counts
// of iterations and factorizations, modified Newton, and reported failures.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "fem/solver/newton_solver.hpp"
#include "fem/solver/nonlinear_problem.hpp"

namespace tongue::fem {
namespace {

// Four masses in a row, x_i their displacements, joined by springs to a wall and to each other:
// spring i (from node i - 1, or the wall, to node i) has tension t_i(e) = k_i e + c e^3 at
// elongation e. A load P pulls the last node. Every spring then carries P, so with the k_i
// chosen below the root has the elongations kElongation: x* = their partial sums.
class SpringChain : public NonlinearProblem {
 public:
  static constexpr int kSize = 4;
  static constexpr double kLoad = 2.0;                                            // N
  static constexpr double kCubic = 0.2;                                           // N/m^3
  static constexpr std::array<double, kSize> kElongation = {1.0, 0.5, 2.0, 1.5};  // m

  SpringChain() {
    auto p = std::make_shared<SparsityPattern>();
    // Tridiagonal: column j holds rows j - 1 (when j > 0) and j.
    p->size = kSize;
    p->column_start = {0, 1, 3, 5, 7};
    p->row_index = {0, 0, 1, 1, 2, 2, 3};
    pattern_ = p;
    for (int i = 0; i < kSize; ++i) {
      const double e = kElongation[i];
      k_[i] = (kLoad - kCubic * e * e * e) / e;  // so that t_i(e*_i) = P
    }
  }

  static Vector root() {
    Vector x(kSize);
    double sum = 0.0;
    for (int i = 0; i < kSize; ++i) x[i] = sum += kElongation[i];
    return x;
  }

  std::shared_ptr<const SparsityPattern> pattern() const override { return pattern_; }

  bool residual(const Vector& x, Vector& r) override {
    ++residual_calls;
    if (evaluable && !evaluable(x)) return false;
    r.setZero(kSize);
    for (int i = 0; i < kSize; ++i) {
      const double t = tension(i, x);
      r[i] += t;                 // spring i pulls node i back
      if (i > 0) r[i - 1] -= t;  // and node i - 1 forward
    }
    r[kSize - 1] -= kLoad;
    return true;
  }

  bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& K) override {
    ++tangent_calls;
    if (!residual(x, r)) return false;
    K.set_zero();
    std::vector<double>& v = K.values();
    for (int i = 0; i < kSize; ++i) {
      const double s = stiffness(i, x);
      v[pattern_->find(i, i)] += s;
      if (i > 0) {
        v[pattern_->find(i - 1, i - 1)] += s;
        v[pattern_->find(i - 1, i)] -= s;
      }
    }
    return true;
  }

  double force_scale() const override { return scale; }

  // When set, residual() fails wherever this returns false.
  std::function<bool(const Vector&)> evaluable;
  double scale = 0.0;  // what force_scale() reports [N]
  int residual_calls = 0, tangent_calls = 0;

 private:
  double elongation(int i, const Vector& x) const { return x[i] - (i > 0 ? x[i - 1] : 0.0); }
  double tension(int i, const Vector& x) const {
    const double e = elongation(i, x);
    return k_[i] * e + kCubic * e * e * e;
  }
  double stiffness(int i, const Vector& x) const {
    const double e = elongation(i, x);
    return k_[i] + 3.0 * kCubic * e * e;
  }

  std::shared_ptr<const SparsityPattern> pattern_;
  std::array<double, kSize> k_{};
};

// Tight enough that several iterations lie in the quadratic regime before the round-off floor
// (~1e-15 N for O(1) N forces).
NewtonSettings tight() {
  NewtonSettings s;
  s.residual_rtol = 1e-13;
  s.residual_atol = 1e-13;  // N
  s.increment_rtol = 1e-12;
  s.increment_atol = 1e-14;  // m
  return s;
}

TEST(SpringChain, RootIsARoot) {
  SpringChain problem;
  Vector r;
  ASSERT_TRUE(problem.residual(SpringChain::root(), r));
  EXPECT_LT(r.norm(), 1e-14);  // N: a few O(1) operations
}

TEST(NewtonSolver, FullNewtonConvergesQuadratically) {
  SpringChain problem;
  NewtonSolver newton(problem.pattern(), tight());
  Vector x = Vector::Zero(SpringChain::kSize);
  const NewtonReport report = newton.solve(problem, x);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_TRUE(report.failure.empty());
  // Converged to the root to round-off: the tangent is O(1) N/m, so |dx| ~ |r|.
  EXPECT_LT((x - SpringChain::root()).norm(), 1e-12);

  const std::vector<double>& h = report.residual_history;
  ASSERT_EQ(static_cast<int>(h.size()), report.iterations + 1);
  EXPECT_EQ(h.front(), report.initial_residual);
  EXPECT_EQ(h.back(), report.final_residual);
  EXPECT_LE(report.final_residual, 1e-13);
  // Full Newton: one factorization per iteration; at least one residual per iteration besides.
  EXPECT_EQ(report.factorizations, report.iterations);
  EXPECT_GE(report.residual_evaluations, 2 * report.iterations + 1);
  EXPECT_EQ(report.max_shift, 0.0);
  EXPECT_GE(report.iterations, 4);  // far enough from the root to show the rate

  // Order of convergence p_k = log(r_k+1 / r_k) / log(r_k / r_k-1), which tends to 2 for
  // r_k+1 ~ C r_k^2 whatever C. Only steps whose result lies well above the round-off floor
  // (1e-10 N vs ~1e-15 N) count, and the last of them must show p > 1.8; linear convergence
  // gives p ~ 1.
  double last_order = 0.0;
  int measured = 0;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {
    if (h[k + 1] < 1e-10) break;
    last_order = std::log(h[k + 1] / h[k]) / std::log(h[k] / h[k - 1]);
    ++measured;
  }
  ASSERT_GE(measured, 1) << "no step in the quadratic regime";
  EXPECT_GT(last_order, 1.8);
  EXPECT_LT(last_order, 2.5);
}

TEST(NewtonSolver, StartingAtTheRootNeedsNoIteration) {
  SpringChain problem;
  NewtonSolver newton(problem.pattern(), tight());
  Vector x = SpringChain::root();
  const NewtonReport report = newton.solve(problem, x);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(report.factorizations, 0);
  EXPECT_EQ(x, SpringChain::root());
}

TEST(NewtonSolver, ReusedTangentNeedsFewerFactorizationsAndStillConverges) {
  SpringChain full_problem, reuse_problem;
  NewtonSolver full(full_problem.pattern(), tight());
  NewtonSettings settings = tight();
  settings.max_tangent_reuse = 10;
  NewtonSolver modified(reuse_problem.pattern(), settings);

  Vector x_full = Vector::Zero(SpringChain::kSize), x = x_full;
  const NewtonReport full_report = full.solve(full_problem, x_full);
  const NewtonReport report = modified.solve(reuse_problem, x);
  ASSERT_TRUE(full_report.converged) << full_report.failure;
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_LT((x - SpringChain::root()).norm(), 1e-12);  // m, as for full Newton
  EXPECT_GE(report.factorizations, 1);
  EXPECT_LT(report.factorizations, report.iterations);
  EXPECT_LT(report.factorizations, full_report.factorizations);
  EXPECT_EQ(reuse_problem.tangent_calls, report.factorizations);

  // The factor is kept across solves: a nearby start converges without a new factorization...
  Vector near = SpringChain::root() + Vector::Constant(SpringChain::kSize, 1e-3);
  const NewtonReport again = modified.solve(reuse_problem, near);
  ASSERT_TRUE(again.converged) << again.failure;
  EXPECT_EQ(again.factorizations, 0);
  EXPECT_GE(again.iterations, 1);
  EXPECT_LT((near - SpringChain::root()).norm(), 1e-12);
  // ...unless invalidated.
  modified.invalidate_factor();
  near = SpringChain::root() + Vector::Constant(SpringChain::kSize, 1e-3);
  EXPECT_GE(modified.solve(reuse_problem, near).factorizations, 1);
}

// A start whose residual is below residual_rtol of the forces acting is accepted with no
// iteration (a body at rest under unchanged loads); just above, it is iterated.
TEST(NewtonSolver, AcceptsAStartInEquilibriumWithTheForcesActingAndIteratesOtherwise) {
  SpringChain problem;
  problem.scale = SpringChain::kLoad;  // the load is the force acting [N]
  NewtonSettings settings = tight();
  settings.residual_rtol = 1e-6;
  NewtonSolver newton(problem.pattern(), settings);
  Vector r;
  // The tangent is O(1) N/m: a displacement of d moves the residual by about d N.
  for (double offset : {1e-8, 1e-4}) {
    const Vector start = SpringChain::root() + Vector::Constant(SpringChain::kSize, offset);
    Vector x = start;
    ASSERT_TRUE(problem.residual(start, r));
    const bool within = r.norm() <= settings.residual_rtol * problem.scale;
    EXPECT_EQ(within, offset < 1e-6) << "offset " << offset;
    const NewtonReport report = newton.solve(problem, x);
    ASSERT_TRUE(report.converged) << report.failure;
    EXPECT_EQ(report.force_scale, problem.scale);
    if (within) {
      EXPECT_EQ(report.iterations, 0);
      EXPECT_EQ(report.residual_evaluations, 1);
      EXPECT_EQ(x, start);
    } else {
      EXPECT_GE(report.iterations, 1);
      EXPECT_LE(report.final_residual, settings.residual_rtol * problem.scale);
    }
  }
}

// Judged by the displacement, a solve stops where the error left in x (the distance to the
// root, largest component) is within the tolerance: the estimate from the contraction of the
// corrections bounds the true error, for a reused factor (linear convergence) and across solves
// (the first correction of a solve judged with the contraction carried over, at least 1/2).
TEST(NewtonSolver, DisplacementToleranceBoundsTheErrorLeftInX) {
  for (const double tolerance : {1e-3, 1e-5, 1e-7, 1e-9}) {  // m
    SpringChain problem;
    NewtonSettings settings = tight();
    settings.displacement_tolerance = tolerance;
    settings.max_tangent_reuse = 100;
    settings.max_iterations = 100;
    NewtonSolver newton(problem.pattern(), settings);
    const auto error = [](const Vector& x) {
      return (x - SpringChain::root()).lpNorm<Eigen::Infinity>();
    };
    Vector x = Vector::Zero(SpringChain::kSize);
    const NewtonReport first = newton.solve(problem, x);
    ASSERT_TRUE(first.converged) << first.failure;
    EXPECT_LE(first.error_estimate, tolerance);
    EXPECT_LE(error(x), tolerance) << "tolerance " << tolerance;
    EXPECT_GT(error(x), 0.0);  // not to round-off: it stopped early, as asked

    // A nearby start on the same factor: the error is again within the tolerance, and fewer
    // corrections than from x = 0 were needed.
    for (const double offset : {10 * tolerance, 1e3 * tolerance}) {
      Vector near = SpringChain::root() + Vector::Constant(SpringChain::kSize, offset);
      const NewtonReport again = newton.solve(problem, near);
      ASSERT_TRUE(again.converged) << again.failure;
      EXPECT_EQ(again.factorizations, 0);
      EXPECT_LE(error(near), tolerance) << "tolerance " << tolerance << ", offset " << offset;
      EXPECT_LT(again.iterations, first.iterations);
    }
  }
}

// BFGS updates on a reused factor (Matthies & Strang 1979) reach the root in fewer iterations
// than the plain reused factor, and as accurately.
TEST(NewtonSolver, QuasiNewtonUpdatesSpeedUpAReusedFactor) {
  SpringChain plain_problem, bfgs_problem;
  NewtonSettings plain = tight();
  plain.max_tangent_reuse = 100;
  plain.reform_ratio = 1.0;    // never re-form for a slow rate: the factor from the start serves
  plain.max_iterations = 200;  // a factor from x = 0 contracts slowly on the cubic springs
  NewtonSettings bfgs = plain;
  bfgs.quasi_newton_updates = 5;
  NewtonSolver plain_newton(plain_problem.pattern(), plain),
      bfgs_newton(bfgs_problem.pattern(), bfgs);
  Vector x_plain = Vector::Zero(SpringChain::kSize), x_bfgs = x_plain;
  const NewtonReport p = plain_newton.solve(plain_problem, x_plain);
  const NewtonReport b = bfgs_newton.solve(bfgs_problem, x_bfgs);
  ASSERT_TRUE(p.converged) << p.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  EXPECT_LT((x_bfgs - SpringChain::root()).norm(), 1e-12);  // m, as full Newton
  EXPECT_LT(b.iterations, p.iterations);
  std::printf("  iterations: reused factor %d, with BFGS updates %d\n", p.iterations, b.iterations);
}

TEST(NewtonSolver, ReportsFailureWhenTheResidualCannotBeEvaluatedAwayFromTheStart) {
  SpringChain problem;
  const Vector start = Vector::Zero(SpringChain::kSize);
  problem.evaluable = [&](const Vector& x) { return x == start; };
  NewtonSolver newton(problem.pattern(), tight());
  Vector x = start;
  const NewtonReport report = newton.solve(problem, x);
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.failure.empty());
  EXPECT_EQ(x, start);                        // the last iterate is still the start
  EXPECT_GT(report.residual_evaluations, 2);  // the step was cut back several times

  // Evaluable nowhere, not even at the start.
  problem.evaluable = [](const Vector&) { return false; };
  const NewtonReport none = newton.solve(problem, x);
  EXPECT_FALSE(none.converged);
  EXPECT_FALSE(none.failure.empty());
  EXPECT_EQ(none.iterations, 0);
}

TEST(NewtonSolver, ReportsFailureWhenOutOfIterations) {
  SpringChain problem;
  NewtonSettings settings = tight();
  settings.max_iterations = 2;
  NewtonSolver newton(problem.pattern(), settings);
  Vector x = Vector::Zero(SpringChain::kSize);
  const NewtonReport report = newton.solve(problem, x);
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.failure.empty());
  EXPECT_EQ(report.iterations, 2);
  EXPECT_EQ(report.residual_history.size(), 3u);
  EXPECT_GT(report.final_residual, 1e-13);  // N: not yet at the tolerance
}

// Two uncoupled equations, x0^3 - x0 = 6 (root 2) and 10 (x1 - 1) = 0: at x0 = 0.5 the tangent
// 3 x0^2 - 1 is negative, so the first factorization needs a shift.
class CubicAndLinear : public NonlinearProblem {
 public:
  CubicAndLinear() {
    auto p = std::make_shared<SparsityPattern>();
    p->size = 2;
    p->column_start = {0, 1, 2};
    p->row_index = {0, 1};
    pattern_ = p;
  }
  std::shared_ptr<const SparsityPattern> pattern() const override { return pattern_; }
  bool residual(const Vector& x, Vector& r) override {
    r = Vector(2);
    r << x[0] * x[0] * x[0] - x[0] - 6.0, 10.0 * (x[1] - 1.0);
    return true;
  }
  bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& K) override {
    residual(x, r);
    K.values() = {3.0 * x[0] * x[0] - 1.0, 10.0};
    return true;
  }

 private:
  std::shared_ptr<const SparsityPattern> pattern_;
};

TEST(NewtonSolver, ShiftsAnIndefiniteTangentAndStillConverges) {
  CubicAndLinear problem;
  NewtonSolver newton(problem.pattern(), tight());
  Vector x(2);
  x << 0.5, 0.0;
  const NewtonReport report = newton.solve(problem, x);
  ASSERT_TRUE(report.converged) << report.failure;
  // Any shift that makes diag(-0.25, 10) positive definite exceeds 0.25.
  EXPECT_GT(report.max_shift, 0.25);
  EXPECT_LT(std::abs(x[0] - 2.0), 1e-12);  // tangent ~11 near the root: |dx| ~ |r| / 11
  EXPECT_LT(std::abs(x[1] - 1.0), 1e-12);
}

}  // namespace
}  // namespace tongue::fem
