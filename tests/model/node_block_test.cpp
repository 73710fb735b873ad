// add_node_block (fem/assembly/sparse_matrix): a node-pair coupling lands in the upper-triangle
// storage once, with its transpose implied, prescribed dofs skipped, and missing pattern
// entries reported. (Kept with the muscle tests, its only caller so far.)
#include <gtest/gtest.h>

#include <stdexcept>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/mesh/box_generator.hpp"

namespace tongue::fem {
namespace {

// Dense matrix over all 3 n dofs holding block at (a, b) and block^T at (b, a) (or block at
// (a, a)), restricted to the free dofs.
Eigen::MatrixXd expected_free(const DofMap& dofs, int a, int b, const Mat3& block) {
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(dofs.num_dofs(), dofs.num_dofs());
  full.block<3, 3>(3 * a, 3 * b) += block;
  if (a != b) full.block<3, 3>(3 * b, 3 * a) += block.transpose();
  Eigen::MatrixXd free(dofs.num_free(), dofs.num_free());
  for (int i = 0; i < dofs.num_free(); ++i) {
    for (int j = 0; j < dofs.num_free(); ++j)
      free(i, j) = full(dofs.free_dofs()[i], dofs.free_dofs()[j]);
  }
  return free;
}

struct Fixture {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.01, 0.01), 2, 1, 1);  // 12 nodes
  // Node 1 has y prescribed, node 5 has x and z prescribed.
  DofMap dofs{mesh.num_nodes(), {{1, 1, 0.0}, {5, 0, 0.0}, {5, 2, 0.0}}};
  // 0 and 11 share no element: coupled through extra_node_pairs only.
  AssemblyPattern pattern = build_assembly_pattern(mesh, dofs, {{11, 0}});
  std::shared_ptr<const SparsityPattern> shared =
      std::make_shared<SparsityPattern>(pattern.pattern);
  Mat3 block = (Mat3() << 1, 2, 3, 4, 5, 6, 7, 8, 9).finished();
};

TEST(AddNodeBlock, OffDiagonalBlockAddsItsTransposeAsWell) {
  Fixture fx;
  for (auto [a, b] : {std::pair{1, 5}, std::pair{5, 1}, std::pair{11, 0}, std::pair{0, 11}}) {
    SymmetricMatrix K(fx.shared);
    add_node_block(K, fx.dofs, a, b, fx.block);
    EXPECT_EQ(K.to_dense(), expected_free(fx.dofs, a, b, fx.block)) << a << ", " << b;
  }
}

TEST(AddNodeBlock, DiagonalBlockReadsItsUpperTriangle) {
  Fixture fx;
  const Mat3 symmetric = fx.block + fx.block.transpose();
  for (int node : {0, 1, 5}) {
    SymmetricMatrix K(fx.shared);
    add_node_block(K, fx.dofs, node, node, symmetric);
    EXPECT_EQ(K.to_dense(), expected_free(fx.dofs, node, node, symmetric)) << node;
  }
}

TEST(AddNodeBlock, AccumulatesIntoExistingValues) {
  Fixture fx;
  SymmetricMatrix K(fx.shared);
  add_node_block(K, fx.dofs, 2, 4, fx.block);
  add_node_block(K, fx.dofs, 2, 4, fx.block);
  EXPECT_EQ(K.to_dense(), 2.0 * expected_free(fx.dofs, 2, 4, fx.block));
}

TEST(AddNodeBlock, ThrowsWhenThePairIsNotInThePattern) {
  Fixture fx;
  SymmetricMatrix K(fx.shared);
  EXPECT_THROW(add_node_block(K, fx.dofs, 0, 8, fx.block), std::logic_error);
  // Fully prescribed nodes need no entry.
  const DofMap clamped(fx.mesh.num_nodes(), {{8, 0, 0.0}, {8, 1, 0.0}, {8, 2, 0.0}});
  const auto p =
      std::make_shared<SparsityPattern>(build_assembly_pattern(fx.mesh, clamped).pattern);
  SymmetricMatrix K2(p);
  EXPECT_NO_THROW(add_node_block(K2, clamped, 0, 8, fx.block));
}

}  // namespace
}  // namespace tongue::fem
