#include "fem/assembly/node_block_matrix.hpp"

#include <algorithm>
#include <stdexcept>

namespace tongue::fem {

NodeBlockMatrix::NodeBlockMatrix(const SymmetricMatrix& matrix, const DofMap& dofs) {
  const SparsityPattern& p = matrix.pattern();
  if (p.size != dofs.num_free())
    throw std::invalid_argument("node block matrix: matrix and dof map differ in size");
  const int num_nodes = dofs.num_dofs() / 3;
  const std::vector<int>& full = dofs.free_dofs();

  // Each node's row: the diagonal block, zero or not, then the nodes after it that it is
  // coupled to (the upper triangle of blocks).
  const std::vector<std::vector<int>> coupled = coupled_nodes(p, dofs);
  row_start_.assign(num_nodes + 1, 0);
  for (int a = 0; a < num_nodes; ++a) {
    const std::vector<int>& n = coupled[a];
    column_node_.push_back(a);
    for (auto it = std::upper_bound(n.begin(), n.end(), a); it != n.end(); ++it)
      column_node_.push_back(*it);
    row_start_[a + 1] = static_cast<int>(column_node_.size());
  }
  blocks_.assign(9 * column_node_.size(), 0.0);

  const auto block = [&](int a, int b) {
    const auto begin = column_node_.begin() + row_start_[a];
    const auto end = column_node_.begin() + row_start_[a + 1];
    return 9 * static_cast<int>(std::lower_bound(begin, end, b) - column_node_.begin());
  };
  const std::vector<double>& values = matrix.values();
  for (int col = 0; col < p.size; ++col) {
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k) {
      const int i = full[p.row_index[k]], j = full[col];
      const int a = i / 3, b = j / 3;
      if (a < b) {
        blocks_[block(a, b) + 3 * (i % 3) + j % 3] = values[k];
      } else if (a > b) {
        blocks_[block(b, a) + 3 * (j % 3) + i % 3] = values[k];
      } else {  // the diagonal block, both of its triangles
        blocks_[block(a, a) + 3 * (i % 3) + j % 3] = values[k];
        blocks_[block(a, a) + 3 * (j % 3) + i % 3] = values[k];
      }
    }
  }
}

void NodeBlockMatrix::multiply_add(const Vector& x, Vector& y) const {
  const int num_nodes = static_cast<int>(row_start_.size()) - 1;
  const double* b = blocks_.data();
  const double* xv = x.data();
  double* yv = y.data();
  for (int a = 0; a < num_nodes; ++a) {
    const double x0 = xv[3 * a], x1 = xv[3 * a + 1], x2 = xv[3 * a + 2];
    // The diagonal block first, then the blocks right of it and their transposes below it.
    double y0 = b[0] * x0 + b[1] * x1 + b[2] * x2;
    double y1 = b[3] * x0 + b[4] * x1 + b[5] * x2;
    double y2 = b[6] * x0 + b[7] * x1 + b[8] * x2;
    b += 9;
    for (int k = row_start_[a] + 1; k < row_start_[a + 1]; ++k, b += 9) {
      const double* xb = xv + 3 * column_node_[k];
      double* yb = yv + 3 * column_node_[k];
      y0 += b[0] * xb[0] + b[1] * xb[1] + b[2] * xb[2];
      y1 += b[3] * xb[0] + b[4] * xb[1] + b[5] * xb[2];
      y2 += b[6] * xb[0] + b[7] * xb[1] + b[8] * xb[2];
      yb[0] += b[0] * x0 + b[3] * x1 + b[6] * x2;
      yb[1] += b[1] * x0 + b[4] * x1 + b[7] * x2;
      yb[2] += b[2] * x0 + b[5] * x1 + b[8] * x2;
    }
    // Rows of prescribed dofs are zero: adding 0 leaves y there as it was.
    yv[3 * a] += y0;
    yv[3 * a + 1] += y1;
    yv[3 * a + 2] += y2;
  }
}

}  // namespace tongue::fem
