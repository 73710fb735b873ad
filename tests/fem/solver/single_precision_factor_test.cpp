// CholmodSolver's single-precision solves (SinglePrecisionFactor) against Eigen's dense Cholesky
// in double precision, on a Newmark-like effective tangent of a box large enough for many
// supernodes with rows below their diagonal blocks.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "fem/solver/cholmod_solver.hpp"

namespace tongue::fem {
namespace {

// Float's unit round-off, 2^-24.
constexpr double kFloatRoundoff = 5.96e-8;

struct Problem {
  std::shared_ptr<const SolidModel> model;
  SymmetricMatrix A;
  Eigen::MatrixXd dense;
  Vector b;
  Vector exact;  // A^-1 b by Eigen's dense Cholesky in double precision
};

// An 8 x 5 x 5 box of 5 mm Mooney-Rivlin elements clamped at x = 0 and sheared; A = K + c0 M at
// dt = 4 ms, as a dynamic step factorizes.
Problem effective_tangent() {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.04, 0.025, 0.025), 8, 5, 5);
  std::vector<PrescribedDof> clamp;
  for (int n : mesh.node_set("x_min"))
    for (int c = 0; c < 3; ++c) clamp.push_back({n, c, 0.0});
  auto model =
      std::make_shared<const SolidModel>(std::move(mesh), make_material("mooney_rivlin5", {}),
                                         Formulation::mean_dilatation, 1000.0, clamp);
  Vector u = Vector::Zero(model->num_dofs());
  for (int n = 0; n < model->mesh().num_nodes(); ++n) {
    const Vec3& X = model->mesh().nodes[n];
    u.segment<3>(3 * n) = Vec3(0.0, 0.1 * X.x(), 0.02 * X.y());
  }
  SymmetricMatrix A(model->pattern());
  Vector f;
  EXPECT_TRUE(model->assemble(u, f, &A).ok);
  const double dt = 4e-3;
  A.scale_and_add(1.0, 1.0 / (0.25 * dt * dt), model->mass_matrix(false));
  Problem p{model, A, A.to_dense(), Vector(A.pattern().size), Vector()};
  for (int i = 0; i < p.b.size(); ++i) p.b[i] = std::cos(0.37 * i) + 0.1;
  p.exact = Eigen::LLT<Eigen::MatrixXd>(p.dense).solve(p.b);
  return p;
}

// A solver of p's pattern that solves in single precision, with A factorized.
std::unique_ptr<CholmodSolver> float_solver(const Problem& p) {
  auto solver = std::make_unique<CholmodSolver>(p.model->pattern());
  solver->set_single_precision(true);
  EXPECT_TRUE(solver->factorize(p.A).ok);
  return solver;
}

double condition_number(const Eigen::MatrixXd& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
}

TEST(SinglePrecisionFactor, SolvesToTheAccuracyOfAFloatFactor) {
  const Problem p = effective_tangent();
  const Vector x = float_solver(p)->solve(p.b);
  const double error = (x - p.exact).norm() / p.exact.norm();
  // A solve with a factor rounded to float has a relative error of at most about
  // cond(A) n u_float (Higham 2002, thm. 10.4 with the factor's rounding as the backward
  // error); in practice far less. It is not double precision's round-off either, which would
  // mean the float copy was not used.
  const double cond = condition_number(p.dense);
  EXPECT_LT(error, cond * kFloatRoundoff);
  EXPECT_LT(error, 1e-4);
  EXPECT_GT(error, 1e-12);
}

TEST(SinglePrecisionFactor, RefinementAgainstTheDoubleResidualConverges) {
  // Iterative refinement x += A^-1 (b - A x) with the float solve contracts the error by about
  // cond(A) u_float per step (Higham 2002, sec. 12.1): the property modified Newton relies on.
  // A wrong entry, row or permutation in the copy would stall it.
  const Problem p = effective_tangent();
  const auto solver = float_solver(p);
  Vector x = solver->solve(p.b);
  double error = (x - p.exact).norm() / p.exact.norm();
  for (int k = 0; k < 3; ++k) {
    x += solver->solve(p.b - p.dense * x);
    const double next = (x - p.exact).norm() / p.exact.norm();
    // Each step gains at least two digits until double's round-off (cond * 1e-16) is reached.
    EXPECT_LT(next, std::max(1e-2 * error, 1e-12));
    error = next;
  }
  EXPECT_LT(error, 1e-12);
}

TEST(SinglePrecisionFactor, FollowsEveryFactorizationAndCanBeSwitchedOff) {
  const Problem p = effective_tangent();
  const auto owner = float_solver(p);
  CholmodSolver& solver = *owner;
  // A new factorization (twice the matrix) replaces the float copy: the solution halves.
  SymmetricMatrix twice = p.A;
  twice.scale_and_add(2.0, 0.0, p.A);
  const Vector first = solver.solve(p.b);
  ASSERT_TRUE(solver.factorize(twice).ok);
  const Vector second = solver.solve(p.b);
  EXPECT_LT((2.0 * second - first).norm() / first.norm(), 1e-5);  // float round-off, above
  // Off: double precision again, at once.
  solver.set_single_precision(false);
  const Vector exact = Eigen::LLT<Eigen::MatrixXd>(twice.to_dense()).solve(p.b);
  EXPECT_LT((solver.solve(p.b) - exact).norm() / exact.norm(), 1e-10);
}

// The halves of a solve, for corrections applied between them: backward(forward(b)) is the
// solve, in single precision bit for bit (the same operations) and in double to round-off.
TEST(SinglePrecisionFactor, ItsHalvesMakeTheSolve) {
  const Problem p = effective_tangent();
  const auto solver = float_solver(p);
  EXPECT_EQ(solver->backward(solver->forward(p.b)), solver->solve(p.b));
  solver->set_single_precision(false);
  ASSERT_TRUE(solver->factorize(p.A).ok);
  EXPECT_LT((solver->backward(solver->forward(p.b)) - p.exact).norm() / p.exact.norm(), 1e-10);
}

// A node's unit vector through the forward substitution: the sparse substitution visits only
// the supernodes it reaches and gives exactly the nonzeros of the whole one; the inner products
// of two such columns are u_i^T A^-1 u_j (L^-1 P u_i . L^-1 P u_j), to the float factor's
// accuracy (the first test's bound).
TEST(SinglePrecisionFactor, ASparseForwardSubstitutionGivesTheNonzerosOfTheWholeOne) {
  const Problem p = effective_tangent();
  const int n = static_cast<int>(p.b.size());
  const double cond = condition_number(p.dense);
  for (const bool single : {true, false}) {
    CholmodSolver solver(p.model->pattern());
    solver.set_single_precision(single);
    ASSERT_TRUE(solver.factorize(p.A).ok);
    std::vector<SparseColumn> columns;
    std::vector<Vector> units;
    for (const int first : {0, n / 3 - n / 3 % 3, n - 3}) {
      const std::array<int, 3> index{first, first + 1, first + 2};
      const Vec3 direction = Vec3(0.48, -0.6, 0.64);  // unit
      Vector u = Vector::Zero(n);
      for (int c = 0; c < 3; ++c) u[index[c]] = direction[c];
      const Vector dense = solver.forward(u);
      const SparseColumn sparse =
          solver.forward_sparse({index.begin(), index.end()}, {direction.begin(), direction.end()});
      // The same nonzeros: every entry the sparse column leaves out is zero in the dense one.
      Vector spread = Vector::Zero(n);
      sparse.subtract_from(-1.0, spread);
      EXPECT_EQ(spread, dense) << "single " << single << ", unknown " << first;
      EXPECT_LT(static_cast<int>(sparse.values.size()), n) << "it reached every row";
      columns.push_back(sparse);
      units.push_back(u);
    }
    const Eigen::LLT<Eigen::MatrixXd> exact(p.dense);
    for (std::size_t i = 0; i < columns.size(); ++i) {
      for (std::size_t j = 0; j < columns.size(); ++j) {
        const double product = dot(columns[i], columns[j]);
        const double expected = units[i].dot(exact.solve(units[j]));
        const double scale =
            std::sqrt(units[i].dot(exact.solve(units[i])) * units[j].dot(exact.solve(units[j])));
        EXPECT_LT(std::abs(product - expected), (single ? cond * kFloatRoundoff : 1e-10) * scale);
      }
    }
  }
}

// Several nodes' entries through one sparse substitution (the pulls of the springs that engage
// together): it visits the union of their paths and gives exactly the nonzeros of the whole
// substitution of their sum; entries on the same unknown add up.
TEST(SinglePrecisionFactor, ASparseForwardSubstitutionOfSeveralNodesIsTheWholeOne) {
  const Problem p = effective_tangent();
  const int n = static_cast<int>(p.b.size());
  for (const bool single : {true, false}) {
    CholmodSolver solver(p.model->pattern());
    solver.set_single_precision(single);
    ASSERT_TRUE(solver.factorize(p.A).ok);
    const std::vector<int> unknowns{0, 2, n / 2, n / 2, -1, n - 1};
    const std::vector<double> values{0.5, -1.5, 2.0, 0.25, 7.0, -0.75};
    Vector b = Vector::Zero(n);
    for (std::size_t i = 0; i < unknowns.size(); ++i)
      if (unknowns[i] >= 0) b[unknowns[i]] += values[i];
    Vector spread = Vector::Zero(n);
    solver.forward_sparse(unknowns, values).subtract_from(-1.0, spread);
    EXPECT_EQ(spread, solver.forward(b)) << "single " << single;
  }
}

}  // namespace
}  // namespace tongue::fem
