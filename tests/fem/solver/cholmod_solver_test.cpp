// CholmodSolver against Eigen's dense Cholesky on tangent-like matrices of a small box: SPD
// solves, reuse of the symbolic analysis, the regularizing shift of indefinite matrices, and
// rejection of matrices on another pattern.
#include <gtest/gtest.h>

#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <memory>
#include <stdexcept>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "fem/solver/cholmod_solver.hpp"

namespace tongue::fem {
namespace {

// A 4 x 3 x 3 box of 5 mm elements (tongue-like Mooney-Rivlin, mean dilatation) clamped at
// x = 0: its stiffness at rest is symmetric positive definite, with the banded-but-not-trivial
// structure of a real tangent.
std::shared_ptr<const SolidModel> box_model() {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.015, 0.015), 4, 3, 3);
  std::vector<PrescribedDof> clamp;
  for (int n : mesh.node_set("x_min")) {
    for (int c = 0; c < 3; ++c) clamp.push_back({n, c, 0.0});
  }
  return std::make_shared<const SolidModel>(std::move(mesh), make_material("mooney_rivlin5", {}),
                                            Formulation::mean_dilatation, 1040.0, clamp);
}

SymmetricMatrix stiffness_at(const SolidModel& model, const Vector& u) {
  SymmetricMatrix K(model.pattern());
  Vector f;
  EXPECT_TRUE(model.assemble(u, f, &K).ok);
  return K;
}

// A moderate non-homogeneous deformation: the tangent keeps its pattern, changes its values.
// (Twice this much makes the Mooney-Rivlin tangent indefinite.)
Vector bent(const SolidModel& model) {
  Vector u = Vector::Zero(model.num_dofs());
  const Mesh& mesh = model.mesh();
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3& X = mesh.nodes[n];
    const double t = X.x() / 0.02;
    u.segment<3>(3 * n) = Vec3(0.05 * X.x() * X.y() / 0.015, 0.0, -1.5e-3 * t * t);
  }
  return u;
}

Vector right_hand_side(int n) {
  Vector b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.7 * i + 0.3) + 0.2;
  return b;
}

double condition_number(const Eigen::MatrixXd& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().cwiseAbs().maxCoeff() / eig.eigenvalues().cwiseAbs().minCoeff();
}

double relative_difference(const Vector& a, const Vector& b) {
  return (a - b).norm() / b.norm();
}

TEST(CholmodSolver, SolvesAnSpdTangentLikeDenseCholesky) {
  const auto model = box_model();
  const SymmetricMatrix K = stiffness_at(*model, Vector::Zero(model->num_dofs()));
  CholmodSolver solver(model->pattern());
  EXPECT_FALSE(solver.has_factor());
  EXPECT_GE(solver.analysis_seconds(), 0.0);

  const FactorizationReport report = solver.factorize(K);
  ASSERT_TRUE(report.ok);
  EXPECT_EQ(report.shift, 0.0);
  EXPECT_EQ(report.attempts, 1);
  EXPECT_TRUE(solver.has_factor());
  // The factor holds at least the lower triangle of A, and the count of flops is at least one
  // per entry of L.
  EXPECT_GE(solver.factor_nonzeros(), K.pattern().nnz());
  EXPECT_GE(solver.factorization_flops(), solver.factor_nonzeros());

  const Eigen::MatrixXd dense = K.to_dense();
  const Vector b = right_hand_side(K.pattern().size);
  const Eigen::LLT<Eigen::MatrixXd> llt(dense);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const Vector x_dense = llt.solve(b);
  const Vector x = solver.solve(b);
  // Both solutions carry a backward-stable error ~cond * eps; cond is checked to be ~1e4 or
  // less, so 1e-10 leaves a margin of ~1e2 and still catches any wrong entry.
  ASSERT_LT(condition_number(dense), 1e5);
  EXPECT_LT(relative_difference(x, x_dense), 1e-10);
  EXPECT_LT((dense * x - b).norm() / b.norm(), 1e-12);
}

TEST(CholmodSolver, ReusesTheAnalysisForNewValuesOnTheSamePattern) {
  const auto model = box_model();
  CholmodSolver solver(model->pattern());
  const Vector b = right_hand_side(model->pattern()->size);

  // First the stiffness at rest, then a Newmark-like effective tangent at a bent state.
  const SymmetricMatrix K0 = stiffness_at(*model, Vector::Zero(model->num_dofs()));
  SymmetricMatrix K1 = stiffness_at(*model, bent(*model));
  K1.scale_and_add(1.0, 4.0 / (2e-3 * 2e-3), model->mass_matrix(false));
  ASSERT_GT((K1.to_dense() - K0.to_dense()).norm(), 0.1 * K0.to_dense().norm());

  std::vector<double> factor_sizes;
  for (const SymmetricMatrix* K : std::vector<const SymmetricMatrix*>{&K0, &K1, &K0}) {
    const FactorizationReport report = solver.factorize(*K);
    ASSERT_TRUE(report.ok);
    EXPECT_EQ(report.shift, 0.0);
    factor_sizes.push_back(solver.factor_nonzeros());
    const Eigen::MatrixXd dense = K->to_dense();
    const Eigen::LLT<Eigen::MatrixXd> llt(dense);
    ASSERT_EQ(llt.info(), Eigen::Success);
    ASSERT_LT(condition_number(dense), 1e5);  // as above: 1e-10 is ~1e2 above cond * eps
    EXPECT_LT(relative_difference(solver.solve(b), llt.solve(b)), 1e-10);
  }
  // Same symbolic factor throughout.
  EXPECT_EQ(factor_sizes[0], factor_sizes[1]);
  EXPECT_EQ(factor_sizes[1], factor_sizes[2]);
}

TEST(CholmodSolver, ShiftsAnIndefiniteMatrixAndSolvesTheShiftedSystem) {
  const auto model = box_model();
  const SymmetricMatrix K = stiffness_at(*model, Vector::Zero(model->num_dofs()));
  const int n = K.pattern().size;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K.to_dense(), Eigen::EigenvaluesOnly);
  const double lambda_min = eig.eigenvalues().minCoeff();
  ASSERT_GT(lambda_min, 0.0);

  // A - 1.5 lambda_min I has the eigenvalue -0.5 lambda_min: symmetric indefinite.
  SymmetricMatrix A = K;
  for (int i = 0; i < n; ++i) A.values()[A.pattern().find(i, i)] -= 1.5 * lambda_min;
  CholmodSolver solver(model->pattern());
  const FactorizationReport report = solver.factorize(A);
  ASSERT_TRUE(report.ok);
  EXPECT_GT(report.shift, 0.5 * lambda_min);  // anything less leaves A + shift I indefinite
  EXPECT_GT(report.attempts, 1);
  EXPECT_TRUE(solver.has_factor());

  const Eigen::MatrixXd shifted = A.to_dense() + report.shift * Eigen::MatrixXd::Identity(n, n);
  const Eigen::LLT<Eigen::MatrixXd> llt(shifted);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const Vector b = right_hand_side(n);
  const Vector x = solver.solve(b);
  // The shifted matrix may be worse conditioned than K: scale the round-off bound with it.
  const double tolerance = std::max(1e-10, 1e-14 * condition_number(shifted));
  EXPECT_LT(relative_difference(x, llt.solve(b)), tolerance);
  // And it is not the solution of the unshifted system.
  EXPECT_GT(relative_difference(x, A.to_dense().lu().solve(b)), 1e3 * tolerance);

  // The same solver still factorizes a definite matrix without shift afterwards.
  const FactorizationReport again = solver.factorize(K);
  ASSERT_TRUE(again.ok);
  EXPECT_EQ(again.shift, 0.0);
  EXPECT_LT(
      relative_difference(solver.solve(b), Eigen::LLT<Eigen::MatrixXd>(K.to_dense()).solve(b)),
      1e-10);
}

TEST(CholmodSolver, NegativeDefiniteMatrixGetsAShiftBeyondItsSpectrum) {
  const auto model = box_model();
  SymmetricMatrix A = stiffness_at(*model, Vector::Zero(model->num_dofs()));
  A.scale_and_add(-1.0, 0.0, A);  // negative definite
  const double most_negative =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A.to_dense()).eigenvalues().minCoeff();
  CholmodSolver solver(model->pattern());
  const FactorizationReport report = solver.factorize(A);
  ASSERT_TRUE(report.ok);
  EXPECT_GT(report.shift, -most_negative);  // A + shift I must be positive definite
}

TEST(CholmodSolver, ReportsFailureWhenNoShiftHelpsAndRefusesToSolve) {
  const auto model = box_model();
  SymmetricMatrix A = stiffness_at(*model, Vector::Zero(model->num_dofs()));
  // A NaN in the tangent (from a material evaluated beyond its range) defeats every shift.
  A.values()[A.pattern().find(0, 0)] = std::numeric_limits<double>::quiet_NaN();
  CholmodSolver solver(model->pattern());
  EXPECT_THROW(solver.solve(right_hand_side(A.pattern().size)), std::logic_error);
  const FactorizationReport report = solver.factorize(A);
  EXPECT_FALSE(report.ok);
  EXPECT_FALSE(solver.has_factor());
  EXPECT_THROW(solver.solve(right_hand_side(A.pattern().size)), std::logic_error);
}

TEST(CholmodSolver, RejectsAMatrixOnAnotherPattern) {
  const auto model = box_model();
  CholmodSolver solver(model->pattern());
  // The same box without constraints: a different pattern (and size).
  const SolidModel other(model->mesh(), make_material("mooney_rivlin5", {}), Formulation::standard,
                         1040.0, {});
  const SymmetricMatrix M = other.mass_matrix(false);
  EXPECT_THROW(solver.factorize(M), std::invalid_argument);
  EXPECT_FALSE(solver.has_factor());
}

}  // namespace
}  // namespace tongue::fem
