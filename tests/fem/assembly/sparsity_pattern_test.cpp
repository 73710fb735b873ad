// The assembly pattern against a brute-force dense build: upper triangle, sorted, exactly the
// element couplings between free dofs; the element scatter map points at the right entries; and
// the symmetric matrix operations on it agree with their dense counterparts.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

using BoolMatrix = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

// A 3 x 2 x 2 box with the x_min face clamped and a few single components prescribed elsewhere,
// so that elements mix free and prescribed dofs within one node.
struct Fixture {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.03, 0.02, 0.02), 3, 2, 2);
  std::vector<PrescribedDof> prescribed = [this] {
    std::vector<PrescribedDof> p;
    for (int n : mesh.node_set("x_min")) {
      for (int c = 0; c < 3; ++c) p.push_back({n, c, 0.0});
    }
    p.push_back({mesh.node_set("x_max")[0], 2, 0.0});
    p.push_back({mesh.node_set("y_max")[5], 0, 0.0});
    p.push_back({mesh.node_set("z_max")[7], 1, 0.0});
    return p;
  }();
  DofMap dofs{mesh.num_nodes(), prescribed};
};

// Upper-triangular coupling of free dofs by brute force over nodes groups (elements, pairs).
void mark(const std::vector<int>& nodes, const DofMap& dofs, BoolMatrix& coupled) {
  for (int a : nodes) {
    for (int b : nodes) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const int r = dofs.free_index(3 * a + i), c = dofs.free_index(3 * b + j);
          if (r >= 0 && c >= 0 && r <= c) coupled(r, c) = true;
        }
      }
    }
  }
}

BoolMatrix dense_pattern(const SparsityPattern& p) {
  BoolMatrix d = BoolMatrix::Constant(p.size, p.size, false);
  for (int col = 0; col < p.size; ++col) {
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k)
      d(p.row_index[k], col) = true;
  }
  return d;
}

void expect_well_formed(const SparsityPattern& p) {
  ASSERT_EQ(static_cast<int>(p.column_start.size()), p.size + 1);
  EXPECT_EQ(p.column_start.front(), 0);
  EXPECT_EQ(p.column_start.back(), p.nnz());
  for (int col = 0; col < p.size; ++col) {
    ASSERT_LE(p.column_start[col], p.column_start[col + 1]);
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k) {
      EXPECT_GE(p.row_index[k], 0);
      EXPECT_LE(p.row_index[k], col) << "entry below the diagonal in column " << col;
      if (k > p.column_start[col]) {
        EXPECT_LT(p.row_index[k - 1], p.row_index[k]) << "unsorted or repeated in column " << col;
      }
    }
    // Every free dof couples with itself.
    EXPECT_GE(p.find(col, col), 0);
  }
}

TEST(SparsityPattern, IsExactlyTheUpperTriangleOfElementCouplingsBetweenFreeDofs) {
  const Fixture f;
  const AssemblyPattern assembly = build_assembly_pattern(f.mesh, f.dofs);
  const SparsityPattern& p = assembly.pattern;
  ASSERT_EQ(p.size, f.dofs.num_free());
  expect_well_formed(p);

  BoolMatrix expected = BoolMatrix::Constant(p.size, p.size, false);
  for (const Hex8& e : f.mesh.elements) mark({e.begin(), e.end()}, f.dofs, expected);
  EXPECT_TRUE(dense_pattern(p) == expected);
  EXPECT_EQ(p.nnz(), expected.count());
  // Not trivially dense: the far ends of the box do not couple.
  EXPECT_LT(p.nnz(), p.size * (p.size + 1) / 2);
}

TEST(SparsityPattern, FindLocatesEntriesAndRejectsAbsentOnes) {
  const Fixture f;
  const SparsityPattern p = build_assembly_pattern(f.mesh, f.dofs).pattern;
  const BoolMatrix present = dense_pattern(p);
  std::set<int> positions;
  for (int col = 0; col < p.size; ++col) {
    for (int row = 0; row <= col; ++row) {
      const int k = p.find(row, col);
      if (present(row, col)) {
        ASSERT_GE(k, 0);
        EXPECT_EQ(p.row_index[k], row);
        EXPECT_TRUE(p.column_start[col] <= k && k < p.column_start[col + 1]);
        positions.insert(k);
      } else {
        EXPECT_EQ(k, -1) << "(" << row << ", " << col << ")";
      }
    }
  }
  EXPECT_EQ(static_cast<int>(positions.size()), p.nnz());
}

TEST(SparsityPattern, ElementScatterPointsAtTheUpperTriangleEntryOfFreeDofPairs) {
  const Fixture f;
  const AssemblyPattern assembly = build_assembly_pattern(f.mesh, f.dofs);
  ASSERT_EQ(assembly.element_scatter.size(), f.mesh.elements.size());
  for (int e = 0; e < f.mesh.num_elements(); ++e) {
    const Hex8& nodes = f.mesh.elements[e];
    for (int i = 0; i < 24; ++i) {
      for (int j = 0; j < 24; ++j) {
        const int row = f.dofs.free_index(3 * nodes[i / 3] + i % 3);
        const int col = f.dofs.free_index(3 * nodes[j / 3] + j % 3);
        const int expected =
            (row >= 0 && col >= 0 && row <= col) ? assembly.pattern.find(row, col) : -1;
        if (row >= 0 && col >= 0 && row <= col) {
          ASSERT_GE(expected, 0);
        }
        EXPECT_EQ(assembly.element_scatter[e][24 * i + j], expected)
            << "element " << e << " local (" << i << ", " << j << ")";
      }
    }
  }
}

TEST(SparsityPattern, ExtraNodePairsAddTheirCouplingsOnly) {
  const Fixture f;
  // Nodes two element layers apart share no element.
  const int a = 3, b = 33;  // grid nodes (3, 0, 0) and (1, 2, 2), both with free dofs
  const std::vector<std::pair<int, int>> pairs{{a, b}};
  const SparsityPattern p = build_assembly_pattern(f.mesh, f.dofs, pairs).pattern;
  expect_well_formed(p);
  BoolMatrix expected = BoolMatrix::Constant(p.size, p.size, false);
  for (const Hex8& e : f.mesh.elements) mark({e.begin(), e.end()}, f.dofs, expected);
  const BoolMatrix elements_only = expected;
  mark({a, b}, f.dofs, expected);
  ASSERT_FALSE(elements_only == expected) << "the pair should add couplings";
  EXPECT_TRUE(dense_pattern(p) == expected);
}

TEST(SymmetricMatrix, OperationsAgreeWithTheDenseMatrix) {
  const Fixture f;
  auto pattern =
      std::make_shared<const SparsityPattern>(build_assembly_pattern(f.mesh, f.dofs).pattern);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  SymmetricMatrix A(pattern), B(pattern);
  for (double& v : A.values()) v = uniform(rng);
  for (double& v : B.values()) v = uniform(rng);
  const Eigen::MatrixXd dA = A.to_dense(), dB = B.to_dense();
  EXPECT_EQ(dA, dA.transpose());
  // Zero exactly where the pattern has no entry (in either triangle).
  const BoolMatrix present = dense_pattern(*pattern);
  for (int r = 0; r < pattern->size; ++r) {
    for (int c = 0; c < pattern->size; ++c) {
      if (!present(std::min(r, c), std::max(r, c))) {
        EXPECT_EQ(dA(r, c), 0.0);
      }
    }
  }

  Vector x(pattern->size);
  for (int i = 0; i < x.size(); ++i) x[i] = uniform(rng);
  // Sums of ~100 products of O(1) numbers in a different order: round-off ~1e-14.
  EXPECT_LT((A.multiply(x) - dA * x).norm(), 1e-13 * (dA * x).norm());
  for (int i = 0; i < pattern->size; ++i) EXPECT_EQ(A.diagonal(i), dA(i, i));
  // Several vectors at once, added to what Y holds.
  SymmetricMatrix::RowMajorMatrix X(pattern->size, 5), Y(pattern->size, 5);
  for (double* v = X.data(); v != X.data() + X.size(); ++v) *v = uniform(rng);
  for (double* v = Y.data(); v != Y.data() + Y.size(); ++v) *v = uniform(rng);
  const Eigen::MatrixXd expected = Y + dA * X;
  A.multiply_add(X, Y);
  EXPECT_LT((Eigen::MatrixXd(Y) - expected).norm(), 1e-13 * expected.norm());

  A.scale_and_add(2.0, -3.0, B);
  EXPECT_LT((A.to_dense() - (2.0 * dA - 3.0 * dB)).norm(), 1e-15 * dA.norm());
  A.set_zero();
  EXPECT_EQ(A.to_dense().norm(), 0.0);
}

}  // namespace
}  // namespace tongue::fem
