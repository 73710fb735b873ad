// The Galerkin projection Phi^T A Phi against the dense product, on a mesh's tangent pattern with
// supports (prescribed dofs) and a mode count that is not a whole number of vectors.
#include "reduced/galerkin_projector.hpp"

#include <gtest/gtest.h>

#include <random>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::reduced {
namespace {

TEST(GalerkinProjector, EqualsTheDenseProduct) {
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.03, 0.02, 0.01}, 3, 2, 2);
  std::vector<fem::PrescribedDof> supports;
  for (int node : mesh.node_sets.at("x_min")) supports.push_back({node, 1, 0.0});
  supports.push_back({mesh.node_sets.at("x_max").front(), 2, 0.0});
  const fem::DofMap dofs(mesh.num_nodes(), supports);
  auto pattern =
      std::make_shared<const fem::SparsityPattern>(fem::build_assembly_pattern(mesh, dofs).pattern);

  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  fem::SymmetricMatrix a(pattern);
  for (double& v : a.values()) v = uniform(random);
  for (int modes : {1, 17, 32}) {
    Eigen::MatrixXd phi(dofs.num_dofs(), modes);
    for (Eigen::Index i = 0; i < phi.size(); ++i) phi.data()[i] = uniform(random);
    // The dense reference over the free dofs: the projector ignores Phi's prescribed rows.
    Eigen::MatrixXd phi_free(dofs.num_free(), modes);
    for (int j = 0; j < modes; ++j) phi_free.col(j) = dofs.gather_free(phi.col(j));
    const Eigen::MatrixXd expected = phi_free.transpose() * a.to_dense() * phi_free;

    const Eigen::MatrixXd p = GalerkinProjector(*pattern, dofs, phi).project(a);
    ASSERT_EQ(p.rows(), modes);
    ASSERT_EQ(p.cols(), modes);
    // The same sums in another order: each entry's rounding is bounded by n u times the sum of
    // its terms' sizes, |Phi|^T |A| |Phi| (Higham 2002, sec. 3.1), with n, the terms a sum
    // chains, below 500 here and u = 1.1e-16.
    const Eigen::MatrixXd sizes =
        phi_free.cwiseAbs().transpose() * a.to_dense().cwiseAbs() * phi_free.cwiseAbs();
    EXPECT_TRUE(((p - expected).cwiseAbs().array() <= 500 * 1.1e-16 * sizes.array()).all())
        << modes << " modes";
    EXPECT_EQ(p, p.transpose());
  }
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
