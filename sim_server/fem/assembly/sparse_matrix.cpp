#include "fem/assembly/sparse_matrix.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tongue::fem {

int SparsityPattern::find(int row, int col) const {
  const auto begin = row_index.begin() + column_start[col];
  const auto end = row_index.begin() + column_start[col + 1];
  const auto it = std::lower_bound(begin, end, row);
  return (it != end && *it == row) ? static_cast<int>(it - row_index.begin()) : -1;
}

namespace {

// Free dofs of a group of nodes, in local order 3 a + c (-1 where prescribed).
template <size_t N>
std::array<int, 3 * N> local_free_dofs(const std::array<int, N>& nodes, const DofMap& dofs) {
  std::array<int, 3 * N> out{};
  for (size_t a = 0; a < N; ++a) {
    for (int c = 0; c < 3; ++c) out[3 * a + c] = dofs.free_index(3 * nodes[a] + c);
  }
  return out;
}

template <size_t N>
void add_couplings(const std::array<int, N>& free, std::vector<std::vector<int>>& rows_of_column) {
  for (int col : free) {
    if (col < 0) continue;
    for (int row : free) {
      if (row >= 0 && row <= col) rows_of_column[col].push_back(row);
    }
  }
}

}  // namespace

std::vector<std::vector<int>> coupled_nodes(const SparsityPattern& pattern, const DofMap& dofs) {
  const std::vector<int>& free = dofs.free_dofs();
  std::vector<std::vector<int>> nodes(static_cast<std::size_t>(dofs.num_dofs() / 3));
  for (int col = 0; col < pattern.size; ++col) {
    for (int k = pattern.column_start[col]; k < pattern.column_start[col + 1]; ++k) {
      const int a = free[pattern.row_index[k]] / 3, b = free[col] / 3;
      nodes[a].push_back(b);
      nodes[b].push_back(a);
    }
  }
  for (std::vector<int>& n : nodes) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nodes;
}

AssemblyPattern build_assembly_pattern(const Mesh& mesh, const DofMap& dofs,
                                       const std::vector<std::pair<int, int>>& extra_node_pairs) {
  const int n = dofs.num_free();
  std::vector<std::vector<int>> rows_of_column(n);
  for (const Hex8& element : mesh.elements) {
    add_couplings(local_free_dofs(element, dofs), rows_of_column);
  }
  for (const auto& [a, b] : extra_node_pairs) {
    add_couplings(local_free_dofs(std::array<int, 2>{a, b}, dofs), rows_of_column);
  }

  AssemblyPattern result;
  SparsityPattern& p = result.pattern;
  p.size = n;
  p.column_start.assign(n + 1, 0);
  for (int col = 0; col < n; ++col) {
    auto& rows = rows_of_column[col];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    p.column_start[col + 1] = p.column_start[col] + static_cast<int>(rows.size());
  }
  p.row_index.reserve(p.column_start[n]);
  for (auto& rows : rows_of_column) {
    p.row_index.insert(p.row_index.end(), rows.begin(), rows.end());
    std::vector<int>().swap(rows);
  }

  result.element_scatter.resize(mesh.elements.size());
  for (size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto free = local_free_dofs(mesh.elements[e], dofs);
    auto& scatter = result.element_scatter[e];
    for (int i = 0; i < 24; ++i) {
      for (int j = 0; j < 24; ++j) {
        const int row = free[i], col = free[j];
        scatter[24 * i + j] = (row >= 0 && col >= 0 && row <= col) ? p.find(row, col) : -1;
      }
    }
  }
  return result;
}

SymmetricMatrix::SymmetricMatrix(std::shared_ptr<const SparsityPattern> pattern)
    : pattern_(std::move(pattern)), values_(pattern_->nnz(), 0.0) {}

void SymmetricMatrix::set_zero() {
  std::fill(values_.begin(), values_.end(), 0.0);
}

Vector SymmetricMatrix::multiply(const Vector& x) const {
  Vector y = Vector::Zero(pattern_->size);
  multiply_add(x, y);
  return y;
}

void SymmetricMatrix::multiply_add(const Vector& x, Vector& y) const {
  const SparsityPattern& p = *pattern_;
  for (int col = 0; col < p.size; ++col) {
    const double x_col = x[col];
    double y_col = 0.0;  // the lower triangle's contributions to y[col], summed in a register
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k) {
      const int row = p.row_index[k];
      y[row] += values_[k] * x_col;
      if (row != col) y_col += values_[k] * x[row];
    }
    y[col] += y_col;
  }
}

void SymmetricMatrix::multiply_add(const RowMajorMatrix& X, RowMajorMatrix& Y) const {
  const SparsityPattern& p = *pattern_;
  for (int col = 0; col < p.size; ++col) {
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k) {
      const int row = p.row_index[k];
      Y.row(row) += values_[k] * X.row(col);
      if (row != col) Y.row(col) += values_[k] * X.row(row);
    }
  }
}

double SymmetricMatrix::diagonal(int i) const {
  const int k = pattern_->find(i, i);
  return k >= 0 ? values_[k] : 0.0;
}

void SymmetricMatrix::scale_and_add(double a, double b, const SymmetricMatrix& other) {
  for (size_t k = 0; k < values_.size(); ++k) values_[k] = a * values_[k] + b * other.values_[k];
}

Eigen::MatrixXd SymmetricMatrix::to_dense() const {
  const SparsityPattern& p = *pattern_;
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(p.size, p.size);
  for (int col = 0; col < p.size; ++col) {
    for (int k = p.column_start[col]; k < p.column_start[col + 1]; ++k) {
      d(p.row_index[k], col) = values_[k];
      d(col, p.row_index[k]) = values_[k];
    }
  }
  return d;
}

void add_node_block(SymmetricMatrix& K, const DofMap& dofs, int node_a, int node_b,
                    const Mat3& block) {
  const SparsityPattern& p = K.pattern();
  std::vector<double>& values = K.values();
  for (int c = 0; c < 3; ++c) {
    const int i = dofs.free_index(3 * node_a + c);
    if (i < 0) continue;
    // On the diagonal block, d < c would be the lower triangle (free numbering follows dof order).
    for (int d = node_a == node_b ? c : 0; d < 3; ++d) {
      const int j = dofs.free_index(3 * node_b + d);
      if (j < 0) continue;
      // Entry (i, j) and its mirror (j, i) share one stored value; for a != b every stored entry
      // of the coupling is reached exactly once, from whichever side lies in the upper triangle.
      const int k = p.find(std::min(i, j), std::max(i, j));
      if (k < 0) {
        throw std::logic_error("add_node_block: nodes " + std::to_string(node_a) + " and " +
                               std::to_string(node_b) +
                               " are not coupled in the sparsity pattern (share no element and "
                               "are not in extra_node_pairs)");
      }
      values[k] += block(c, d);
    }
  }
}

}  // namespace tongue::fem
