// A reused factor corrected by rank-one terms (NewtonSolver with NonlinearProblem::rank_one_terms):
// a chain of springs pushed onto a floor, where penalty springs engage and release as nodes
// touch and leave it. The corrections make the stale factor exact for the springs, so the
// piecewise-linear problem is solved without forming the factor again, to the answer of a
// direct active-set solution.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>

#include "fem/solver/newton_solver.hpp"

namespace tongue::fem {
namespace {

// n nodes on a line between two walls, neighbours joined by springs k; node i carries the load
// b_i and may not go below the floor f_i, held there by a penalty spring kp.
class ChainOnFloor : public NonlinearProblem {
 public:
  static constexpr int n = 30;
  static constexpr double k = 100.0, kp = 1e5;  // N/m
  double chain_k = k;                           // the springs between the nodes [N/m]
  Vector b = Vector::Zero(n), floor = Vector::Zero(n);

  ChainOnFloor() {
    auto p = std::make_shared<SparsityPattern>();
    p->size = n;
    p->column_start.push_back(0);
    for (int j = 0; j < n; ++j) {
      if (j > 0) p->row_index.push_back(j - 1);
      p->row_index.push_back(j);
      p->column_start.push_back(static_cast<int>(p->row_index.size()));
    }
    pattern_ = p;
  }
  std::shared_ptr<const SparsityPattern> pattern() const override { return pattern_; }

  bool residual(const Vector& x, Vector& r) override {
    r = stiffness() * x - b;
    for (int i = 0; i < n; ++i)
      if (x[i] < floor[i]) r[i] -= kp * (floor[i] - x[i]);
    return true;
  }
  bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& K) override {
    residual(x, r);
    K.set_zero();
    for (int j = 0; j < n; ++j) {
      K.values()[pattern_->find(j, j)] = 2.0 * chain_k + (x[j] < floor[j] ? kp : 0.0);
      if (j > 0) K.values()[pattern_->find(j - 1, j)] = -chain_k;
    }
    return true;
  }
  void rank_one_terms(const Vector& x, std::vector<RankOneTerm>& terms) override {
    terms.clear();
    for (int i = 0; i < n; ++i) {
      const double gap = x[i] - floor[i];
      if (gap < 1.0) terms.push_back({{i, -1, -1}, Vec3::UnitX(), kp, std::max(gap, 0.0)});
    }
  }

  Eigen::MatrixXd stiffness() const {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      A(i, i) = 2.0 * chain_k;
      if (i > 0) A(i, i - 1) = A(i - 1, i) = -chain_k;
    }
    return A;
  }
  // The exact solution by active sets: solve with the springs of the nodes below the floor
  // until the set no longer changes.
  Vector exact() const {
    std::vector<bool> active(n, false);
    Vector x;
    for (int round = 0; round < 100; ++round) {
      Eigen::MatrixXd A = stiffness();
      Vector rhs = b;
      for (int i = 0; i < n; ++i)
        if (active[i]) A(i, i) += kp, rhs[i] += kp * floor[i];
      x = A.ldlt().solve(rhs);
      bool same = true;
      for (int i = 0; i < n; ++i) {
        same = same && active[i] == (x[i] < floor[i]);
        active[i] = x[i] < floor[i];
      }
      if (same) return x;
    }
    ADD_FAILURE() << "active set did not settle";
    return x;
  }

 private:
  std::shared_ptr<const SparsityPattern> pattern_;
};

NewtonSettings reused() {
  NewtonSettings s;
  s.max_tangent_reuse = 100;
  // Never re-form for a residual that grows (an engaged spring's node overshooting the floor a
  // little makes it jump): the test counts the factorizations the corrections save.
  s.reform_ratio = 1e9;
  s.residual_rtol = 1e-12;
  s.residual_atol = 1e-10;  // N; loads are ~1 N
  s.increment_rtol = 1e-12;
  s.max_iterations = 40;
  return s;
}

// A uniform load presses the chain's middle onto a floor 0.2 m below it: a factor formed with
// no spring engaged serves the whole solve.
TEST(RankOneCorrection, SpringsThatEngageNeedNoNewFactor) {
  ChainOnFloor chain;
  chain.b.setConstant(-1.0);
  chain.floor.setConstant(-0.2);
  NewtonSolver newton(chain.pattern(), reused());
  Vector x = Vector::Zero(ChainOnFloor::n);
  const NewtonReport report = newton.solve(chain, x);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_EQ(report.factorizations, 1);
  EXPECT_LE(report.iterations, 8);  // an active-set iteration: the set settles in a few
  const Vector exact = chain.exact();
  ASSERT_GT((exact.array() < chain.floor.array()).count(), 10);  // most of the chain touches
  // The corrected solve is exact for the springs; what is left is the solver's tolerance on a
  // system of condition ~1e5 (kp against k / n^2).
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-9);
}

// The same load with the chain starting below the floor everywhere: the factor formed there
// holds every spring, and the springs of the nodes that rise off the floor are taken out.
TEST(RankOneCorrection, SpringsThatReleaseNeedNoNewFactor) {
  ChainOnFloor chain;
  chain.b.setConstant(-1.0);
  for (int i = 0; i < ChainOnFloor::n; ++i) chain.floor[i] = -0.05 - 0.002 * (i - 15) * (i - 15);
  NewtonSolver newton(chain.pattern(), reused());
  Vector x = Vector::Constant(ChainOnFloor::n, -1.0);
  const NewtonReport report = newton.solve(chain, x);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_EQ(report.factorizations, 1);
  const Vector exact = chain.exact();
  const auto touching = (exact.array() < chain.floor.array()).count();
  ASSERT_GT(touching, 0);
  ASSERT_LT(touching, ChainOnFloor::n);
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-9);
}

// With BFGS pairs on, the same solve as SpringsThatEngageNeedNoNewFactor. A pair whose step
// engaged springs would take the springs' jump of force for curvature of the rest of the problem
// and spoil every direction after it; such pairs are left out, so the iteration stays the
// active-set one of the corrections (measured: 5 iterations; with those pairs kept, no
// convergence in 40).
TEST(RankOneCorrection, BfgsPairsAcrossASpringThatEngagedAreLeftOut) {
  ChainOnFloor chain;
  chain.b.setConstant(-1.0);
  chain.floor.setConstant(-0.2);
  NewtonSettings settings = reused();
  settings.quasi_newton_updates = 8;
  NewtonSolver newton(chain.pattern(), settings);
  Vector x = Vector::Zero(ChainOnFloor::n);
  const NewtonReport report = newton.solve(chain, x);
  ASSERT_TRUE(report.converged) << report.failure;
  EXPECT_EQ(report.factorizations, 1);
  EXPECT_LE(report.iterations, 8);  // as many as without BFGS pairs
  EXPECT_LT((x - chain.exact()).cwiseAbs().maxCoeff(), 1e-9);
}

// Secant pairs gathered while no spring was engaged describe the chain without them: kept when
// an iteration engages springs in its linear model, they hold the correction along the springs'
// directions to the softer response they measured. Here the factor is formed for the chain at
// half its stiffness, a light load (no contact) gathers pairs that make up for it, and then a
// heavy load pushes the chain onto the floor.
TEST(RankOneCorrection, BfgsPairsFromBeforeSpringsEngagedAreNotUsedWithThem) {
  ChainOnFloor chain;
  chain.floor.setConstant(-0.2);
  NewtonSettings settings = reused();
  settings.quasi_newton_updates = 8;
  // On this linear chain the secant line search would find the exact step along the stale
  // factor's direction, and no pair would be needed.
  settings.line_search = false;
  NewtonSolver newton(chain.pattern(), settings);
  Vector x = Vector::Zero(ChainOnFloor::n);
  chain.b.setConstant(-0.01);
  ASSERT_TRUE(newton.solve(chain, x).converged);
  chain.chain_k = 2.0 * ChainOnFloor::k;
  chain.b.setConstant(-0.05);
  const NewtonReport light = newton.solve(chain, x);
  ASSERT_TRUE(light.converged) << light.failure;
  ASSERT_GT(light.iterations, 1);  // pairs were gathered
  EXPECT_GT(x.minCoeff(), -0.2);   // without touching the floor
  chain.b.setConstant(-1.0);
  const NewtonReport heavy = newton.solve(chain, x);
  ASSERT_TRUE(heavy.converged) << heavy.failure;
  EXPECT_EQ(heavy.factorizations, 0);
  // 11 measured; with the pairs kept the solve did not converge in 40.
  EXPECT_LE(heavy.iterations, 15);
  EXPECT_LT((x - chain.exact()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(x.minCoeff(), -0.2);  // springs engaged
}

}  // namespace
}  // namespace tongue::fem
