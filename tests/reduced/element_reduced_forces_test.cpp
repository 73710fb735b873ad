// The elements' reduced internal forces: with every weight 1 their columns add up to the reduced
// internal force of the whole mesh, Phi^T f_int(u), at every snapshot.
#include "reduced/element_reduced_forces.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <string>

#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::reduced {
namespace {

void expect_columns_add_up(const std::string& material, const std::map<std::string, double>& p) {
  SCOPED_TRACE(material);
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.03, 0.02, 0.02}, 3, 2, 2);
  const fem::SolidModel solid(mesh, fem::make_material(material, p),
                              fem::Formulation::mean_dilatation, 1000.0, {});
  const Eigen::Index n = 3 * mesh.num_nodes();
  std::srand(13);
  const fem::Vector origin = 1e-4 * fem::Vector::Random(n);
  const Eigen::MatrixXd snapshots = 5e-4 * Eigen::MatrixXd::Random(n, 3);  // 0.5 mm: 2.5 % strain
  const Eigen::MatrixXd modes = Eigen::MatrixXd::Random(n, 5).householderQr().householderQ() *
                                Eigen::MatrixXd::Identity(n, 5);
  const Eigen::MatrixXd g = element_reduced_forces(solid, origin, modes, snapshots);
  ASSERT_EQ(g.rows(), 3 * 5);
  ASSERT_EQ(g.cols(), mesh.num_elements());
  for (Eigen::Index s = 0; s < snapshots.cols(); ++s) {
    fem::Vector f = fem::Vector::Zero(n);
    ASSERT_TRUE(solid.assemble(origin + snapshots.col(s), f, nullptr).ok);
    const fem::Vector whole = modes.transpose() * f;
    const fem::Vector summed = g.middleRows(s * 5, 5).rowwise().sum();
    // The same element forces summed in another order (and, for the uncoupled law, by the
    // batched kernels in the assembly): equal to round-off of the elements' forces.
    const double scale = g.middleRows(s * 5, 5).cwiseAbs().sum();
    EXPECT_LT((summed - whole).cwiseAbs().maxCoeff(), 1e-12 * scale)
        << "snapshot " << s << ": " << summed.transpose() << " against " << whole.transpose();
    EXPECT_GT(whole.norm(), 1e-6);  // the snapshots load the mesh
  }
}

TEST(ElementReducedForces, ColumnsAddUpToTheReducedInternalForce) {
  expect_columns_add_up("mooney_rivlin5", {});
  expect_columns_add_up("neo_hookean", {{"shear_modulus", 5000.0}, {"poisson_ratio", 0.49}});
}

TEST(ElementReducedForces, RefusesSizesThatDoNotFitTheSolid) {
  const fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.01, 0.01, 0.01}, 1, 1, 1);
  const fem::SolidModel solid(mesh, fem::make_material("mooney_rivlin5", {}),
                              fem::Formulation::mean_dilatation, 1000.0, {});
  const Eigen::Index n = 3 * mesh.num_nodes();
  EXPECT_THROW(element_reduced_forces(solid, fem::Vector::Zero(n + 3), Eigen::MatrixXd::Zero(n, 2),
                                      Eigen::MatrixXd::Zero(n, 1)),
               std::invalid_argument);
  EXPECT_THROW(element_reduced_forces(solid, fem::Vector::Zero(n), Eigen::MatrixXd::Zero(n, 2),
                                      Eigen::MatrixXd::Zero(n - 1, 1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
