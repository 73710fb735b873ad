#pragma once
// A symmetric matrix over the free dofs, stored for fast products with full (3 n) vectors:
// dense 3 x 3 blocks coupling two nodes, the upper triangle of blocks in compressed rows of
// nodes (block CSR; Saad 2003, sec. 3.4), each row starting with its diagonal block. Entries
// of prescribed dofs are zero in the blocks.
//
// Why a second storage: SymmetricMatrix keeps one triangle in compressed columns, the layout
// CHOLMOD factorizes, and its product reads one index per value and scatters into y. The
// constant matrices of a time step (mass, damping, their Newmark combination) are multiplied
// several times per step; in blocks each row of nodes gathers three entries of x per nine
// values, and each block off the diagonal serves both of its triangles.
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/assembly/sparse_matrix.hpp"

namespace tongue::fem {

class NodeBlockMatrix {
 public:
  NodeBlockMatrix() = default;
  // The same matrix as `matrix` (over dofs' free dofs), in node blocks.
  NodeBlockMatrix(const SymmetricMatrix& matrix, const DofMap& dofs);

  // y += A x, both full vectors (3 n entries); x at prescribed dofs is ignored and y there is
  // left as it is.
  void multiply_add(const Vector& x, Vector& y) const;

 private:
  std::vector<int> row_start_;  // num_nodes + 1 entries
  std::vector<int> column_node_;
  std::vector<double> blocks_;  // 9 per block, row-major
};

}  // namespace tongue::fem
