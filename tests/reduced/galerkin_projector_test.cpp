// The Galerkin projection Phi^T A Phi against the dense product, on a mesh's tangent pattern with
// supports (prescribed dofs) and a mode count that is not a whole number of vectors, in double and
// single precision, with every block of A non-zero and with whole blocks of zeros.
#include "reduced/galerkin_projector.hpp"

#include <gtest/gtest.h>

#include <random>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::reduced {
namespace {

struct BoxPattern {
  fem::DofMap dofs;
  std::shared_ptr<const fem::SparsityPattern> pattern;
};

BoxPattern box_with_supports() {
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.03, 0.02, 0.01}, 3, 2, 2);
  std::vector<fem::PrescribedDof> supports;
  for (int node : mesh.node_sets.at("x_min")) supports.push_back({node, 1, 0.0});
  supports.push_back({mesh.node_sets.at("x_max").front(), 2, 0.0});
  fem::DofMap dofs(mesh.num_nodes(), supports);
  auto pattern =
      std::make_shared<const fem::SparsityPattern>(fem::build_assembly_pattern(mesh, dofs).pattern);
  return {std::move(dofs), std::move(pattern)};
}

// Compares the projection with the dense product for 1, 17 and 32 modes. `unit`: the precision's
// unit round-off.
void expect_dense_product(const BoxPattern& box, const fem::SymmetricMatrix& a, Precision precision,
                          double unit, std::mt19937& random) {
  const fem::DofMap& dofs = box.dofs;
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int modes : {1, 17, 32}) {
    Eigen::MatrixXd phi(dofs.num_dofs(), modes);
    for (Eigen::Index i = 0; i < phi.size(); ++i) phi.data()[i] = uniform(random);
    // The dense reference over the free dofs: the projector ignores Phi's prescribed rows.
    Eigen::MatrixXd phi_free(dofs.num_free(), modes);
    for (int j = 0; j < modes; ++j) phi_free.col(j) = dofs.gather_free(phi.col(j));
    const Eigen::MatrixXd expected = phi_free.transpose() * a.to_dense() * phi_free;

    const Eigen::MatrixXd p = GalerkinProjector(*box.pattern, dofs, phi).project(a, precision);
    ASSERT_EQ(p.rows(), modes);
    ASSERT_EQ(p.cols(), modes);
    // The same sums in another order: each entry's rounding is bounded by n u times the sum of
    // its terms' sizes, |Phi|^T |A| |Phi| (Higham 2002, sec. 3.1), with n, the terms a sum
    // chains, below 500 here, and u the precision's unit round-off; in single precision A and
    // Phi are rounded to it first, a relative u on each of the three factors of a term.
    const Eigen::MatrixXd sizes =
        phi_free.cwiseAbs().transpose() * a.to_dense().cwiseAbs() * phi_free.cwiseAbs();
    EXPECT_TRUE(((p - expected).cwiseAbs().array() <= (500 + 3) * unit * sizes.array()).all())
        << modes << " modes";
    EXPECT_EQ(p, p.transpose());
  }
}

constexpr double kDoubleUnit = 1.1e-16;  // 2^-53
constexpr double kFloatUnit = 6.0e-8;    // 2^-24

TEST(GalerkinProjector, EqualsTheDenseProduct) {
  const BoxPattern box = box_with_supports();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  fem::SymmetricMatrix a(box.pattern);
  for (double& v : a.values()) v = uniform(random);
  expect_dense_product(box, a, Precision::double_precision, kDoubleUnit, random);
  expect_dense_product(box, a, Precision::single_precision, kFloatUnit, random);
}

// Blocks without a non-zero entry are skipped: the same product, whichever blocks they are.
TEST(GalerkinProjector, EqualsTheDenseProductWithBlocksOfZeros) {
  const BoxPattern box = box_with_supports();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  // Every third node pair's block zero, and a row of blocks zero throughout (node 5's).
  fem::SymmetricMatrix a(box.pattern);
  const std::vector<int>& free = box.dofs.free_dofs();
  const fem::SparsityPattern& pattern = *box.pattern;
  for (int col = 0; col < pattern.size; ++col) {
    for (int k = pattern.column_start[col]; k < pattern.column_start[col + 1]; ++k) {
      const int row = pattern.row_index[k];
      const int node_i = free[row] / 3, node_j = free[col] / 3;
      const bool zero = (node_i + node_j) % 3 == 0 || node_i == 5 || node_j == 5;
      a.values()[k] = zero ? 0.0 : uniform(random);
    }
  }
  expect_dense_product(box, a, Precision::double_precision, kDoubleUnit, random);
  expect_dense_product(box, a, Precision::single_precision, kFloatUnit, random);

  // And all zero.
  fem::SymmetricMatrix zero(box.pattern);
  const Eigen::MatrixXd phi = Eigen::MatrixXd::Ones(box.dofs.num_dofs(), 3);
  EXPECT_TRUE(GalerkinProjector(pattern, box.dofs, phi).project(zero).isZero(0.0));
}

TEST(GalerkinProjector, RefusesMismatchedSizes) {
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.02, 0.01, 0.01}, 2, 1, 1);
  const fem::DofMap dofs(mesh.num_nodes(), {});
  const fem::SparsityPattern pattern = fem::build_assembly_pattern(mesh, dofs).pattern;
  EXPECT_THROW(GalerkinProjector(pattern, dofs, Eigen::MatrixXd::Zero(3, 2)),
               std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
