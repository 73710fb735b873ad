// Loads: the body force and uniform surface traction distribute exactly their totals, the
// surface traction with the consistent 1:2:4 weights on a regular face; the boundary of a box.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fem/assembly/solid_model.hpp"
#include "fem/assembly/surface_load.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

Vec3 nodal_total(const Vector& f) {
  Vec3 total = Vec3::Zero();
  for (Eigen::Index n = 0; n < f.size() / 3; ++n) total += f.segment<3>(3 * n);
  return total;
}

TEST(BodyForce, SumsToDensityTimesVolumeTimesAcceleration) {
  const Mesh mesh =
      map_nodes(make_box(Vec3::Zero(), Vec3(0.04, 0.02, 0.03), 4, 2, 3), [](const Vec3& X) {
        return Vec3(X.x() + 0.1 * X.y() * X.z() / 0.03, X.y(), X.z() * (1.0 + 0.2 * X.x() / 0.04));
      });
  const double rho = 1040.0;
  // Clamped nodes still carry their share (the force is over all dofs).
  std::vector<PrescribedDof> clamp;
  for (int n : mesh.node_set("x_min")) clamp.push_back({n, 0, 0.0});
  const SolidModel model(mesh, make_material("mooney_rivlin5", {}), Formulation::standard, rho,
                         clamp);
  const Vec3 g(0.3, -1.2, -9.81);
  const Vector f = model.body_force(g);
  ASSERT_EQ(f.size(), model.num_dofs());
  const Vec3 expected = rho * model.reference_volume() * g;
  // Sum of ~200 terms of one sign per component: round-off ~1e-15 relative.
  EXPECT_LT((nodal_total(f) - expected).norm(), 1e-13 * expected.norm());
  // Every node carries load in the direction of g.
  for (int n = 0; n < mesh.num_nodes(); ++n) EXPECT_GT(f.segment<3>(3 * n).dot(g), 0.0);
}

TEST(UniformSurfaceForce, SumsToTheTotalWithCornerEdgeInteriorWeights124) {
  // The x_max face of a 2 x 3 x 3 box is a 3 x 3 grid of equal rectangles (5 mm x 4 mm).
  const Mesh mesh = make_box(Vec3(0.01, 0.0, -0.005), Vec3(0.02, 0.015, 0.012), 2, 3, 3);
  const Vec3 total(1.5, -0.25, 0.75);
  const Vector f = uniform_surface_force(mesh, mesh.node_set("x_max"), total);
  ASSERT_EQ(f.size(), 3 * mesh.num_nodes());
  EXPECT_LT((nodal_total(f) - total).norm(), 1e-15 * total.norm() * 16);

  // On a face of 9 equal quads, int N_a dA is A/36 at the 4 corners (one quad), A/18 on the 8
  // edge nodes (two quads) and A/9 at the 4 interior nodes (four quads).
  const std::vector<int>& face = mesh.node_set("x_max");
  ASSERT_EQ(face.size(), 16u);
  int corners = 0, edges = 0, interior = 0;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 fn = f.segment<3>(3 * n);
    if (!std::binary_search(face.begin(), face.end(), n)) {
      EXPECT_EQ(fn.norm(), 0.0) << "node " << n << " is off the loaded face";
      continue;
    }
    // Grid indices j, k within the face.
    const int j = (n / 3) % 4, k = n / 12;
    const int boundary_directions = (j == 0 || j == 3) + (k == 0 || k == 3);
    const double weight = boundary_directions == 2 ? 1.0 : boundary_directions == 1 ? 2.0 : 4.0;
    (boundary_directions == 2 ? corners : boundary_directions == 1 ? edges : interior)++;
    // Each value is a few products and sums of O(1) numbers: round-off ~1e-16.
    EXPECT_LT((fn - weight / 36.0 * total).norm(), 1e-14 * total.norm()) << "node " << n;
  }
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(edges, 8);
  EXPECT_EQ(interior, 4);
}

TEST(UniformSurfaceForce, OnACurvedFaceStillSumsToTheTotal) {
  const Mesh mesh = map_nodes(
      make_box(Vec3::Zero(), Vec3(0.02, 0.02, 0.02), 2, 3, 2),
      [](const Vec3& X) { return Vec3(X.x() * (1.0 + 10.0 * X.y() * X.z()), X.y(), X.z()); });
  const Vec3 total(0.0, 0.0, -2.0);
  const Vector f = uniform_surface_force(mesh, mesh.node_set("x_max"), total);
  EXPECT_LT((nodal_total(f) - total).norm(), 1e-14 * total.norm());
}

TEST(UniformSurfaceForce, RejectsASetWithNoWholeBoundaryFace) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.02, 0.02), 2, 2, 2);
  // Three of the four nodes of a face, and an interior node.
  EXPECT_THROW(uniform_surface_force(mesh, {0, 1, 3}, Vec3(1, 0, 0)), std::invalid_argument);
  EXPECT_THROW(uniform_surface_force(mesh, {13}, Vec3(1, 0, 0)), std::invalid_argument);
}

TEST(BoundaryFaces, BoxHasTwiceNmPlusMkPlusNkFaces) {
  for (const auto& [n, m, k] : {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{3, 2, 4},
                                std::array<int, 3>{5, 1, 2}, std::array<int, 3>{2, 3, 3}}) {
    const Mesh mesh = make_box(Vec3::Zero(), Vec3(1, 1, 1), n, m, k);
    const std::vector<Quad4> faces = boundary_faces(mesh);
    EXPECT_EQ(static_cast<int>(faces.size()), 2 * (n * m + m * k + n * k))
        << n << " x " << m << " x " << k;
    // Boundary nodes: all but the (n-1)(m-1)(k-1) interior ones.
    EXPECT_EQ(static_cast<int>(boundary_nodes(mesh).size()),
              (n + 1) * (m + 1) * (k + 1) - (n - 1) * (m - 1) * (k - 1));
  }
}

TEST(BoundaryFaces, FacesLieOnTheBoxSurfaceAndPointOutward) {
  const Vec3 size(0.03, 0.02, 0.01);
  const Mesh mesh = make_box(Vec3::Zero(), size, 3, 2, 2);
  const Vec3 centre = 0.5 * size;
  for (const Quad4& q : boundary_faces(mesh)) {
    const Vec3 a = mesh.nodes[q[0]], b = mesh.nodes[q[1]], c = mesh.nodes[q[2]],
               d = mesh.nodes[q[3]];
    const Vec3 normal = (c - a).cross(d - b);
    const Vec3 mid = 0.25 * (a + b + c + d);
    // Cyclic order with the normal pointing away from the box centre.
    EXPECT_GT(normal.dot(mid - centre), 0.0);
    // The face lies in one of the six bounding planes.
    int on_planes = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const auto on = [&](double value) {
        return std::abs(a[axis] - value) < 1e-15 && std::abs(b[axis] - value) < 1e-15 &&
               std::abs(c[axis] - value) < 1e-15 && std::abs(d[axis] - value) < 1e-15;
      };
      on_planes += on(0.0) + on(size[axis]);
    }
    EXPECT_EQ(on_planes, 1);
  }
}

}  // namespace
}  // namespace tongue::fem
