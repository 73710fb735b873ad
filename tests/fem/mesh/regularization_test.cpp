#include "fem/mesh/regularization.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "fem/mesh/box_generator.hpp"
#include "fem/mesh/mesh_quality.hpp"
#include "support/finite_difference.hpp"

namespace tongue::fem {
namespace {

constexpr double kCell = 0.01;  // m, edge of the box cells (10 mm)

// A 60 x 40 x 40 mm box of 6 x 4 x 4 cubes of 10 mm.
Mesh regular_box() {
  return make_box(Vec3::Zero(), Vec3(6, 4, 4) * kCell, 6, 4, 4);
}

int count_irregular(const Mesh& mesh) {
  return check_quality(mesh).num_irregular;
}

double min_nodal_det(const Mesh& mesh, int element) {
  const auto d = nodal_jacobian_determinants(mesh, element);
  return *std::min_element(d.begin(), d.end());
}

// Perturbs randomly chosen nodes of the box until at least a tenth of the elements are
// irregular. Each node lands uniformly in a ball of 6 mm about its grid position; a draw is kept
// only when every element around the node keeps its nodal determinants above -depth times the
// undistorted (h / 2)^3. That bounds how deep the folds go, as in a hand-made mesh whose defects
// the paper repaired within 1 mm; a fold of any depth could not be undone within a bound.
// mt19937's raw output is fixed by the standard (its distributions are not), so the mesh is the
// same with every standard library.
Mesh perturbed_box(unsigned seed, double depth) {
  const Mesh grid = regular_box();
  Mesh mesh = grid;
  std::mt19937 rng(seed);
  const auto unit = [&rng] { return rng() * (2.0 / 4294967296.0) - 1.0; };  // [-1, 1)
  const double radius = 0.6 * kCell;
  const double floor = -depth * std::pow(kCell / 2, 3);
  std::vector<std::vector<int>> elements_of(mesh.num_nodes());
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int n : mesh.elements[e]) elements_of[n].push_back(e);
  }
  for (int draw = 0; draw < 100000 && 10 * count_irregular(mesh) < mesh.num_elements(); ++draw) {
    const int node = static_cast<int>(rng() % mesh.num_nodes());
    Vec3 offset;
    do {
      offset = Vec3(unit(), unit(), unit());
    } while (offset.squaredNorm() > 1.0);
    const Vec3 previous = mesh.nodes[node];
    mesh.nodes[node] = grid.nodes[node] + radius * offset;
    for (int e : elements_of[node]) {
      if (min_nodal_det(mesh, e) < floor) {
        mesh.nodes[node] = previous;
        break;
      }
    }
  }
  return mesh;
}

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

// A distorted element (no two faces parallel) with the given corner pulled through the opposite
// side of its corner tetrahedron, so that its determinant there is negative.
hex8::ElementCoords distorted_element() {
  hex8::ElementCoords X;
  X << 0.0, 0.0, 0.0,   //
      1.1, 0.1, -0.05,  //
      1.3, 0.9, 0.1,    //
      -0.1, 1.0, 0.05,  //
      0.1, -0.1, 0.9,   //
      1.0, 0.0, 1.2,    //
      0.7, 0.7, 0.3,    // node 6 pushed down and in: D_6 < 0
      0.0, 1.1, 1.0;
  return X;
}

TEST(Regularization, CornerNeighboursDifferInOneReferenceCoordinate) {
  for (int a = 0; a < 8; ++a) {
    const auto n = corner_neighbours(a);
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        const double s = hex8::kNodeCoords[a][j], t = hex8::kNodeCoords[n[k]][j];
        if (j == k) {
          EXPECT_EQ(t, -s) << "corner " << a << " direction " << k;
        } else {
          EXPECT_EQ(t, s) << "corner " << a << " direction " << k;
        }
      }
    }
  }
  EXPECT_THROW(corner_neighbours(8), std::out_of_range);
}

TEST(Regularization, ClosedFormDeterminantMatchesIsoparametricJacobian) {
  Mesh m;
  const hex8::ElementCoords X = distorted_element();
  for (int a = 0; a < 8; ++a) m.nodes.push_back(X.row(a).transpose());
  m.elements = {{0, 1, 2, 3, 4, 5, 6, 7}};
  const auto expected = nodal_jacobian_determinants(m, 0);
  for (int a = 0; a < 8; ++a) {
    EXPECT_NEAR(nodal_jacobian_determinant(X, a), expected[a], 1e-14) << "corner " << a;
  }
  EXPECT_LT(expected[6], 0.0);  // the element really is irregular
}

TEST(Regularization, GradientMatchesCentralDifferences) {
  const hex8::ElementCoords X0 = distorted_element();
  // The 24 coordinates as a vector, node-major (x0 y0 z0 x1 ...).
  Eigen::VectorXd x(24);
  for (int b = 0; b < 8; ++b) x.segment<3>(3 * b) = X0.row(b).transpose();
  for (int a = 0; a < 8; ++a) {
    const auto det = [a](const Eigen::VectorXd& v) {
      hex8::ElementCoords X;
      for (int b = 0; b < 8; ++b) X.row(b) = v.segment<3>(3 * b).transpose();
      return Eigen::VectorXd::Constant(1, nodal_jacobian_determinant(X, a));
    };
    const Eigen::MatrixXd fd = testing::central_difference_jacobian(det, x, 1e-6);
    const hex8::ElementCoords g = nodal_jacobian_gradient(X0, a);
    double worst = 0.0;
    for (int b = 0; b < 8; ++b) {
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(g(b, k) - fd(0, 3 * b + k)));
    }
    // D_a is affine in each coordinate, so central differences are exact up to round-off.
    EXPECT_LT(worst, 1e-9 * g.cwiseAbs().maxCoeff()) << "corner " << a;
    // Only the corner and its three neighbours enter D_a.
    const auto n = corner_neighbours(a);
    for (int b = 0; b < 8; ++b) {
      if (b != a && b != n[0] && b != n[1] && b != n[2]) {
        EXPECT_TRUE(g.row(b).isZero(0.0)) << "corner " << a << " node " << b;
      }
    }
  }
}

TEST(Regularization, MeshGradientIsTheElementGradient) {
  Mesh m = regular_box();
  m.nodes[m.elements[5][2]] += Vec3(0.002, -0.001, 0.003);
  hex8::ElementCoords X;
  for (int b = 0; b < 8; ++b) X.row(b) = m.nodes[m.elements[5][b]].transpose();
  EXPECT_TRUE(nodal_jacobian_gradient(m, 5, 3).isApprox(nodal_jacobian_gradient(X, 3)));
  EXPECT_THROW(nodal_jacobian_gradient(m, m.num_elements(), 0), std::out_of_range);
  EXPECT_THROW(nodal_jacobian_gradient(m, 0, -1), std::out_of_range);
}

TEST(Regularization, RegularMeshIsLeftUntouched) {
  Mesh m = regular_box();
  const std::vector<Vec3> start = m.nodes;
  const RegularizationReport r = regularize(m, {});
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.irregular_before, 0);
  EXPECT_EQ(r.irregular_after, 0);
  EXPECT_EQ(r.max_node_displacement, 0.0);
  EXPECT_EQ(m.nodes, start);
}

TEST(Regularization, RandomlyPerturbedBoxBecomesRegularWithinOneMillimetre) {
  Mesh m = perturbed_box(20030101, 0.25);
  const int irregular = count_irregular(m);
  ASSERT_GE(10 * irregular, m.num_elements()) << "perturbation left too few irregular elements";
  const std::vector<Vec3> start = m.nodes;
  const std::vector<int> folded = check_quality(m).irregular_elements;

  const RegularizationReport r = regularize(m, {});
  std::printf("perturbed box: %d of %d elements irregular; %s\n", irregular, m.num_elements(),
              r.message.c_str());
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.irregular_before, irregular);
  EXPECT_EQ(r.irregular_after, 0);
  EXPECT_TRUE(r.still_irregular.empty());
  EXPECT_GT(r.iterations, 0);
  EXPECT_LT(r.iterations, RegularizationSettings{}.max_iterations);
  for (int e = 0; e < m.num_elements(); ++e) EXPECT_TRUE(is_regular(m, e)) << "element " << e;
  // Regular with a margin, not by round-off: at least a tenth of min_det_ratio of a cell.
  for (int e : folded) EXPECT_GT(min_nodal_det(m, e), 0.005 * std::pow(kCell / 2, 3)) << e;
  const double moved = max_distance(m.nodes, start);
  EXPECT_LE(moved, 1e-3 + 1e-15);
  EXPECT_GT(moved, 0.0);
  EXPECT_DOUBLE_EQ(r.max_node_displacement, moved);
}

TEST(Regularization, FixedNodesDoNotMove) {
  // Shallower folds: the held nodes take away part of the room to undo them.
  Mesh m = perturbed_box(20030101, 0.1);
  const std::vector<Vec3> start = m.nodes;
  // The floor held, as a tongue mesh is held where it meets bone; some irregular elements have
  // nodes on it, so the held nodes are ones the free run would move.
  const std::vector<int> fixed = m.node_set("z_min");
  const std::vector<int> irregular = check_quality(m).irregular_elements;
  ASSERT_GE(10 * irregular.size(), static_cast<std::size_t>(m.num_elements()));
  const bool touches_floor = std::any_of(irregular.begin(), irregular.end(), [&](int e) {
    return std::any_of(m.elements[e].begin(), m.elements[e].end(),
                       [&](int n) { return std::binary_search(fixed.begin(), fixed.end(), n); });
  });
  ASSERT_TRUE(touches_floor);

  const RegularizationReport r = regularize(m, {}, fixed);
  std::printf("perturbed box, %zu nodes fixed: %s\n", fixed.size(), r.message.c_str());
  EXPECT_TRUE(r.success) << r.message;
  for (int n : fixed) EXPECT_EQ(m.nodes[n], start[n]) << "node " << n;
  EXPECT_LE(max_distance(m.nodes, start), 1e-3 + 1e-15);
}

TEST(Regularization, FoldDeeperThanTheBoundIsReportedAsFailure) {
  // Two cubes of 10 mm; their shared top node (10, 0, 10) mm pushed 5 mm below the floor.
  Mesh m = make_box(Vec3::Zero(), Vec3(2, 1, 1) * kCell, 2, 1, 1);
  const int node = m.elements[1][4];
  ASSERT_TRUE(m.nodes[node].isApprox(Vec3(kCell, 0, kCell)));
  m.nodes[node].z() = -0.005;
  const std::vector<Vec3> start = m.nodes;

  RegularizationSettings settings;
  settings.max_displacement = 1e-3;
  const RegularizationReport r = regularize(m, settings);
  std::printf("node pushed 5 mm through the floor: %s\n", r.message.c_str());
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.irregular_before, 2);
  EXPECT_EQ(r.irregular_after, 2);
  EXPECT_EQ(r.still_irregular, (std::vector<int>{0, 1}));
  EXPECT_LE(r.iterations, settings.max_iterations);
  EXPECT_LE(max_distance(m.nodes, start), 1e-3 + 1e-15);
  EXPECT_NE(r.message.find("still irregular"), std::string::npos) << r.message;
}

TEST(Regularization, IterationLimitIsReported) {
  Mesh m = perturbed_box(20030101, 0.25);
  RegularizationSettings settings;
  settings.max_iterations = 1;
  const RegularizationReport r = regularize(m, settings);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_EQ(r.irregular_after, static_cast<int>(r.still_irregular.size()));
  EXPECT_EQ(r.irregular_after, count_irregular(m));
}

// The step is relative to the element size, so a mesh scaled by a power of two (exact in
// floating point), with its bound scaled alike, takes the same iterations to the same shape.
TEST(Regularization, ResultDoesNotDependOnTheLengthUnit) {
  const double scale = 1024.0;
  Mesh small = perturbed_box(20030101, 0.25);
  Mesh large = small;
  for (Vec3& x : large.nodes) x *= scale;
  RegularizationSettings settings, scaled;
  scaled.max_displacement = settings.max_displacement * scale;
  const RegularizationReport a = regularize(small, settings);
  const RegularizationReport b = regularize(large, scaled);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.success, b.success);
  EXPECT_DOUBLE_EQ(a.max_node_displacement * scale, b.max_node_displacement);
  for (int n = 0; n < small.num_nodes(); ++n) {
    EXPECT_TRUE((small.nodes[n] * scale - large.nodes[n]).isZero(1e-12 * scale)) << "node " << n;
  }
}

TEST(Regularization, RejectsBadSettingsAndFixedNodes) {
  Mesh m = regular_box();
  RegularizationSettings s;
  s.step = 0.0;
  EXPECT_THROW(regularize(m, s), std::invalid_argument);
  s = {};
  s.max_displacement = -1e-3;
  EXPECT_THROW(regularize(m, s), std::invalid_argument);
  s = {};
  s.min_det_ratio = 0.0;
  EXPECT_THROW(regularize(m, s), std::invalid_argument);
  s = {};
  s.max_iterations = -1;
  EXPECT_THROW(regularize(m, s), std::invalid_argument);
  EXPECT_THROW(regularize(m, {}, {m.num_nodes()}), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::fem
