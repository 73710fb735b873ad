#include "fem/mesh/mesh_quality.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

// One hexahedron spanning [0, h]^3 in SOLID185 order.
Mesh unit_cube(double h) {
  Mesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(h, 0, 0), Vec3(h, h, 0), Vec3(0, h, 0),
             Vec3(0, 0, h), Vec3(h, 0, h), Vec3(h, h, h), Vec3(0, h, h)};
  m.elements = {{0, 1, 2, 3, 4, 5, 6, 7}};
  return m;
}

TEST(MeshQuality, CubeNodalDeterminantsAreEighthOfVolume) {
  const double h = 0.02;
  const Mesh m = unit_cube(h);
  const double expected = (h / 2) * (h / 2) * (h / 2);
  for (double d : nodal_jacobian_determinants(m, 0)) EXPECT_NEAR(d, expected, 1e-18);
  EXPECT_NEAR(element_volume(m, 0), h * h * h, 1e-18);
  EXPECT_TRUE(is_regular(m, 0));
}

TEST(MeshQuality, ShearedParallelepipedHasEqualDeterminants) {
  Mesh m = unit_cube(1.0);
  for (Vec3& x : m.nodes) x.x() += 0.7 * x.z();  // simple shear keeps volume
  for (double d : nodal_jacobian_determinants(m, 0)) EXPECT_NEAR(d, 0.125, 1e-14);
  EXPECT_NEAR(check_quality(m).worst_ratio, 1.0, 1e-14);
}

TEST(MeshQuality, VolumeOfWarpedElementIsExact) {
  // Raise node 6 by d: the top surface becomes z = h + d x y / h^2 while x, y stay affine, so
  // the volume is the integral of that height over the square, h^3 + d h^2 / 4.
  const double h = 2.0, d = 0.6;
  Mesh m = unit_cube(h);
  m.nodes[6].z() += d;
  EXPECT_NEAR(element_volume(m, 0), h * h * h + d * h * h / 4, 1e-13);
  // Nodal determinant at node 6: dX/dxi = diag(h/2, h/2, (h + d)/2).
  EXPECT_NEAR(nodal_jacobian_determinants(m, 0)[6], h * h * (h + d) / 8, 1e-13);
  EXPECT_NEAR(nodal_jacobian_determinants(m, 0)[0], h * h * h / 8, 1e-13);
  EXPECT_TRUE(is_regular(m, 0));
}

TEST(MeshQuality, NodePushedThroughOppositeFaceMakesElementIrregular) {
  Mesh m = make_box(Vec3::Zero(), Vec3(2, 1, 1), 2, 1, 1);
  // Node 4 of element 1 is the node (1, 0, 1) shared by both elements; moving it below the
  // bottom face z = 0 folds both elements at that node.
  const int node = m.elements[1][4];
  ASSERT_TRUE(m.nodes[node].isApprox(Vec3(1, 0, 1)));
  m.nodes[node].z() = -0.5;
  EXPECT_FALSE(is_regular(m, 0));
  EXPECT_FALSE(is_regular(m, 1));
  EXPECT_LT(nodal_jacobian_determinants(m, 1)[4], 0.0);
  EXPECT_GT(nodal_jacobian_determinants(m, 1)[6], 0.0);
  const QualityReport q = check_quality(m);
  EXPECT_EQ(q.num_irregular, 2);
  EXPECT_EQ(q.irregular_elements, (std::vector<int>{0, 1}));
  EXPECT_LT(q.worst_ratio, 0.0);
}

TEST(MeshQuality, MildDistortionStaysRegularAndReportsRatio) {
  Mesh m = make_box(Vec3::Zero(), Vec3(2, 1, 1), 2, 1, 1);
  const int node = m.elements[1][4];
  m.nodes[node].z() = 0.5;  // halfway down, still above the bottom face
  EXPECT_TRUE(is_regular(m, 1));
  const QualityReport q = check_quality(m);
  EXPECT_EQ(q.num_irregular, 0);
  EXPECT_TRUE(q.irregular_elements.empty());
  // In both elements the moved node and the one below it see a vertical edge of 0.5, so their
  // nodal determinant is (1/2)(1/2)(0.5/2) = 1/16 (dX/dxi triangular); the undisturbed corner
  // diagonally opposite keeps 1/8. Ratio 1/16 / 1/8 = 0.5. The volume loss per element is the
  // integral of the 0.5 dip times a bilinear hat over the unit square, 0.5 / 4.
  EXPECT_NEAR(q.worst_ratio, 0.5, 1e-14);
  EXPECT_NEAR(q.total_volume, 2.0 - 2 * 0.5 / 4, 1e-14);
}

TEST(MeshQuality, InsideOutElementIsIrregularWithNegativeVolume) {
  Mesh m = unit_cube(1.0);
  m.elements[0] = {4, 5, 6, 7, 0, 1, 2, 3};  // top and bottom swapped
  EXPECT_NEAR(element_volume(m, 0), -1.0, 1e-14);
  EXPECT_FALSE(is_regular(m, 0));
  EXPECT_NEAR(check_quality(m).worst_ratio, -1.0, 1e-14);
}

TEST(MeshQuality, BadElementIndexThrows) {
  const Mesh m = unit_cube(1.0);
  EXPECT_THROW(nodal_jacobian_determinants(m, 1), std::out_of_range);
  EXPECT_THROW(element_volume(m, -1), std::out_of_range);
}

}  // namespace
}  // namespace tongue::fem
