// NodeBlockMatrix: the same product as SymmetricMatrix on full vectors, with some nodes fully
// and some partly prescribed.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "fem/assembly/node_block_matrix.hpp"
#include "fem/assembly/solid_model.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

TEST(NodeBlockMatrix, MultipliesAsTheSymmetricMatrixOnFullVectors) {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.015, 0.01), 4, 3, 2);
  std::vector<PrescribedDof> prescribed;
  for (int n : mesh.node_set("x_min"))
    for (int c = 0; c < 3; ++c) prescribed.push_back({n, c, 0.0});
  for (int n : mesh.node_set("y_min")) prescribed.push_back({n, 1, 1e-3});  // only y
  const SolidModel model(std::move(mesh), make_material("mooney_rivlin5", {}),
                         Formulation::standard, 1000.0, prescribed);
  // A tangent (full 3 x 3 blocks) plus a mass matrix (diagonal blocks).
  SymmetricMatrix A(model.pattern());
  Vector f;
  ASSERT_TRUE(model.assemble(Vector::Zero(model.num_dofs()), f, &A).ok);
  A.scale_and_add(1.0, 1e4, model.mass_matrix(false));
  const NodeBlockMatrix blocks(A, model.dofs());

  const DofMap& dofs = model.dofs();
  Vector x(model.num_dofs());
  for (int i = 0; i < x.size(); ++i) x[i] = std::sin(1.3 * i) + 0.5;
  Vector y(model.num_dofs());
  for (int i = 0; i < y.size(); ++i) y[i] = 0.25 * i;
  const Vector y0 = y;
  blocks.multiply_add(x, y);

  const Vector expected = A.multiply(dofs.gather_free(x));
  const Vector got = dofs.gather_free(y) - dofs.gather_free(y0);
  // The same products summed in another order: round-off of the sums, ~1e-16 of the largest
  // term; 1e-12 of the result's norm leaves a wide margin and catches any misplaced entry.
  EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm());
  for (int dof : dofs.prescribed_dofs()) EXPECT_EQ(y[dof], y0[dof]) << "dof " << dof;
}

}  // namespace
}  // namespace tongue::fem
