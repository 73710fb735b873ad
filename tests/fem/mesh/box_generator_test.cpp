#include "fem/mesh/box_generator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "fem/mesh/mesh_quality.hpp"

namespace tongue::fem {
namespace {

constexpr double kTol = 1e-12;

bool sorted_unique(const std::vector<int>& v) {
  return std::adjacent_find(v.begin(), v.end(), std::greater_equal<int>()) == v.end();
}

TEST(MakeBox, CountsAndCoordinates) {
  const Vec3 origin(1, -2, 0.5), size(2, 3, 4);
  const Mesh m = make_box(origin, size, 2, 3, 4);
  EXPECT_EQ(m.num_nodes(), 3 * 4 * 5);
  EXPECT_EQ(m.num_elements(), 2 * 3 * 4);
  // Bounding box equals the requested box.
  Vec3 lo = m.nodes[0], hi = m.nodes[0];
  for (const Vec3& x : m.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  EXPECT_TRUE(lo.isApprox(origin));
  EXPECT_TRUE(hi.isApprox(origin + size));
  // All nodes are distinct and every one is used by some element.
  std::set<std::array<double, 3>> distinct;
  for (const Vec3& x : m.nodes) distinct.insert({x.x(), x.y(), x.z()});
  EXPECT_EQ(static_cast<int>(distinct.size()), m.num_nodes());
  std::set<int> used;
  for (const Hex8& h : m.elements) used.insert(h.begin(), h.end());
  EXPECT_EQ(static_cast<int>(used.size()), m.num_nodes());
}

TEST(MakeBox, ElementsAreUnitCellsWithPositiveJacobian) {
  const Mesh m = make_box(Vec3(0, 0, 0), Vec3(2, 3, 4), 2, 3, 4);  // 1 m cells
  for (int e = 0; e < m.num_elements(); ++e) {
    const Hex8& h = m.elements[e];
    // Node 0 at the minimum corner, node 6 at the maximum corner, node 4 above node 0.
    EXPECT_TRUE((m.nodes[h[6]] - m.nodes[h[0]]).isApprox(Vec3(1, 1, 1)));
    EXPECT_TRUE((m.nodes[h[4]] - m.nodes[h[0]]).isApprox(Vec3(0, 0, 1)));
    EXPECT_TRUE((m.nodes[h[1]] - m.nodes[h[0]]).isApprox(Vec3(1, 0, 0)));
    EXPECT_TRUE((m.nodes[h[3]] - m.nodes[h[0]]).isApprox(Vec3(0, 1, 0)));
    EXPECT_NEAR(element_volume(m, e), 1.0, kTol);
    for (double d : nodal_jacobian_determinants(m, e)) EXPECT_NEAR(d, 0.125, kTol);
  }
  const QualityReport q = check_quality(m);
  EXPECT_EQ(q.num_irregular, 0);
  EXPECT_NEAR(q.total_volume, 24.0, 1e-11);
  EXPECT_NEAR(q.worst_ratio, 1.0, kTol);
  EXPECT_EQ(m.element_set("all").size(), 24u);
}

TEST(MakeBox, FaceSetsHoldExactlyTheNodesOnEachFace) {
  const Vec3 origin(0.1, 0.2, 0.3), size(0.01, 0.02, 0.03);
  const int n[3] = {3, 2, 5};
  const Mesh m = make_box(origin, size, n[0], n[1], n[2]);
  const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
  for (int axis = 0; axis < 3; ++axis) {
    const int expected_count = (n[(axis + 1) % 3] + 1) * (n[(axis + 2) % 3] + 1);
    for (int side = 0; side < 2; ++side) {
      const auto& set = m.node_set(names[axis][side]);
      EXPECT_EQ(static_cast<int>(set.size()), expected_count) << names[axis][side];
      EXPECT_TRUE(sorted_unique(set));
      const double plane = origin[axis] + side * size[axis];
      for (int node = 0; node < m.num_nodes(); ++node) {
        const bool on_face = std::abs(m.nodes[node][axis] - plane) < 1e-12;
        EXPECT_EQ(on_face, std::binary_search(set.begin(), set.end(), node));
      }
    }
  }
}

TEST(MakeBox, RejectsBadArguments) {
  EXPECT_THROW(make_box(Vec3::Zero(), Vec3(1, 1, 1), 0, 1, 1), std::invalid_argument);
  EXPECT_THROW(make_box(Vec3::Zero(), Vec3(1, -1, 1), 1, 1, 1), std::invalid_argument);
}

TEST(MapNodes, AffineMapScalesVolumeByDeterminant) {
  Mat3 A;
  A << 2, 0.5, 0, 0, 1, 0.3, 0, 0, 1.5;  // det = 3
  const Vec3 b(1, 2, 3);
  const Mesh m = map_nodes(make_box(Vec3::Zero(), Vec3(1, 1, 1), 2, 2, 2),
                           [&](const Vec3& x) -> Vec3 { return A * x + b; });
  EXPECT_NEAR(check_quality(m).total_volume, 3.0, 1e-12);
  EXPECT_TRUE(m.nodes.back().isApprox(A * Vec3(1, 1, 1) + b));
  EXPECT_EQ(m.node_set("x_max").size(), 9u);
}

// Cook's membrane (Cook 1974): trapezoid (0,0), (48,44), (48,60), (0,44) mm.
std::array<Eigen::Vector2d, 4> cook_corners() {
  return {Eigen::Vector2d(0, 0), Eigen::Vector2d(48e-3, 44e-3), Eigen::Vector2d(48e-3, 60e-3),
          Eigen::Vector2d(0, 44e-3)};
}

TEST(MakeQuadExtrusion, CookMembraneVolumeAndRegularity) {
  const double t = 1e-3;
  const Mesh m = make_quad_extrusion(cook_corners(), t, 8, 6, 2);
  EXPECT_EQ(m.num_nodes(), 9 * 7 * 3);
  EXPECT_EQ(m.num_elements(), 8 * 6 * 2);
  // Trapezoid with parallel vertical sides 44 and 16 mm, 48 mm apart.
  const double area = 0.5 * (44e-3 + 16e-3) * 48e-3;
  const QualityReport q = check_quality(m);
  EXPECT_EQ(q.num_irregular, 0);
  EXPECT_NEAR(q.total_volume, area * t, 1e-15);
  EXPECT_GT(q.worst_ratio, 0.0);
  EXPECT_LT(q.worst_ratio, 1.0);  // the elements are not parallelepipeds
}

TEST(MakeQuadExtrusion, EdgeAndCornerSets) {
  const int n_xi = 4, n_eta = 3, n_z = 2;
  const double t = 2e-3;
  const Mesh m = make_quad_extrusion(cook_corners(), t, n_xi, n_eta, n_z);
  const auto& left = m.node_set("left");
  EXPECT_EQ(static_cast<int>(left.size()), (n_eta + 1) * (n_z + 1));
  for (int n : left) EXPECT_NEAR(m.nodes[n].x(), 0.0, kTol);
  const auto& right = m.node_set("right");
  EXPECT_EQ(static_cast<int>(right.size()), (n_eta + 1) * (n_z + 1));
  for (int n : right) {
    EXPECT_NEAR(m.nodes[n].x(), 48e-3, kTol);
    EXPECT_GE(m.nodes[n].y(), 44e-3 - kTol);
    EXPECT_LE(m.nodes[n].y(), 60e-3 + kTol);
  }
  // Bottom edge: the line from (0,0) to (48,44) mm.
  for (int n : m.node_set("bottom")) {
    EXPECT_NEAR(m.nodes[n].y(), m.nodes[n].x() * 44.0 / 48.0, kTol);
  }
  EXPECT_EQ(static_cast<int>(m.node_set("bottom").size()), (n_xi + 1) * (n_z + 1));
  EXPECT_EQ(static_cast<int>(m.node_set("top").size()), (n_xi + 1) * (n_z + 1));
  const int per_layer = (n_xi + 1) * (n_eta + 1);
  EXPECT_EQ(static_cast<int>(m.node_set("z_min").size()), per_layer);
  EXPECT_EQ(static_cast<int>(m.node_set("z_max").size()), per_layer);
  for (int n : m.node_set("z_max")) EXPECT_NEAR(m.nodes[n].z(), t, kTol);

  const auto& tip = m.node_set("corner_top_right");
  ASSERT_EQ(static_cast<int>(tip.size()), n_z + 1);
  for (int k = 0; k <= n_z; ++k) {
    EXPECT_TRUE(m.nodes[tip[k]].isApprox(Vec3(48e-3, 60e-3, t * k / n_z)));
  }
  EXPECT_TRUE(m.nodes[m.node_set("corner_bottom_right")[0]].isApprox(Vec3(48e-3, 44e-3, 0)));
  EXPECT_TRUE(m.nodes[m.node_set("corner_top_left")[0]].isApprox(Vec3(0, 44e-3, 0)));
  EXPECT_NEAR(m.nodes[m.node_set("corner_bottom_left")[1]].norm(), t / n_z, kTol);
}

TEST(MakeQuadExtrusion, RejectsClockwiseOrNonConvexQuads) {
  auto c = cook_corners();
  std::swap(c[1], c[3]);  // clockwise
  EXPECT_THROW(make_quad_extrusion(c, 1e-3, 2, 2, 1), std::invalid_argument);
  // Arrow-head: corner 2 pulled inside the triangle of the others.
  const std::array<Eigen::Vector2d, 4> arrow = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                                Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(0, 1)};
  EXPECT_THROW(make_quad_extrusion(arrow, 1e-3, 2, 2, 1), std::invalid_argument);
  EXPECT_THROW(make_quad_extrusion(cook_corners(), 0.0, 2, 2, 1), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::fem
