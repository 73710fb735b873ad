#include "reduced/galerkin_projector.hpp"

#include <cblas.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tongue::reduced {

namespace {

// Columns of the product accumulated at once: two AVX-512 vectors a row, six sums in flight
// (with one vector a row the kernel took 1.17 ms on the tongue's tangent, 49 modes; with two,
// 0.87-0.96 ms).
constexpr int kLanes = 16;

// y = A x for A in full rows of 3 x 3 node blocks and x, y row-major with `width` columns (a
// multiple of kLanes). Compiled for the vector widths of AVX-512, AVX2 and the SSE2 of every
// x86-64; the dynamic loader picks the best the CPU has (GCC function multiversioning).
__attribute__((target_clones("avx512f", "avx2", "default"))) void block_rows_times(
    int num_nodes, const int* row_start, const int* column_node, const double* blocks,
    const double* x, int width, double* y) {
  for (int a = 0; a < num_nodes; ++a) {
    for (int c = 0; c < width; c += kLanes) {
      double sum[3][kLanes] = {};
      for (int k = row_start[a]; k < row_start[a + 1]; ++k) {
        const double* b = blocks + 9 * k;
        const double* x0 = x + static_cast<long>(3 * column_node[k]) * width + c;
        const double* x1 = x0 + width;
        const double* x2 = x1 + width;
        for (int r = 0; r < 3; ++r)
          for (int l = 0; l < kLanes; ++l)
            sum[r][l] += b[3 * r] * x0[l] + b[3 * r + 1] * x1[l] + b[3 * r + 2] * x2[l];
      }
      double* out = y + static_cast<long>(3 * a) * width + c;
      for (int r = 0; r < 3; ++r)
        for (int l = 0; l < kLanes; ++l) out[r * width + l] = sum[r][l];
    }
  }
}

}  // namespace

GalerkinProjector::GalerkinProjector(const fem::SparsityPattern& pattern, const fem::DofMap& dofs,
                                     const Eigen::MatrixXd& phi)
    : modes_(static_cast<int>(phi.cols())),
      width_((static_cast<int>(phi.cols()) + kLanes - 1) / kLanes * kLanes) {
  if (phi.rows() != dofs.num_dofs() || pattern.size != dofs.num_free())
    throw std::invalid_argument("Galerkin projector: " + std::to_string(phi.rows()) +
                                " rows of modes, a pattern of " + std::to_string(pattern.size) +
                                " for " + std::to_string(dofs.num_dofs()) + " dofs (" +
                                std::to_string(dofs.num_free()) + " free)");
  const int num_nodes = dofs.num_dofs() / 3;
  const std::vector<int>& free = dofs.free_dofs();

  // Each node's row of blocks: the nodes the stored entries couple it to, in either triangle.
  const std::vector<std::vector<int>> coupled = fem::coupled_nodes(pattern, dofs);
  row_start_.assign(num_nodes + 1, 0);
  for (int a = 0; a < num_nodes; ++a) {
    column_node_.insert(column_node_.end(), coupled[a].begin(), coupled[a].end());
    row_start_[a + 1] = static_cast<int>(column_node_.size());
  }
  const auto entry = [&](int dof_row, int dof_col) {
    const int a = dof_row / 3, b = dof_col / 3;
    const auto begin = column_node_.begin() + row_start_[a];
    const auto end = column_node_.begin() + row_start_[a + 1];
    const int block = static_cast<int>(std::lower_bound(begin, end, b) - column_node_.begin());
    return 9 * block + 3 * (dof_row % 3) + dof_col % 3;
  };
  position_.resize(pattern.row_index.size());
  mirror_.resize(pattern.row_index.size());
  for (int col = 0; col < pattern.size; ++col) {
    for (int k = pattern.column_start[col]; k < pattern.column_start[col + 1]; ++k) {
      const int i = free[pattern.row_index[k]], j = free[col];
      position_[k] = entry(i, j);
      mirror_[k] = i == j ? -1 : entry(j, i);
    }
  }
  // Entries of prescribed dofs are never written: they stay zero.
  blocks_.assign(9 * column_node_.size(), 0.0);

  phi_.assign(static_cast<std::size_t>(dofs.num_dofs()) * width_, 0.0);
  for (int dof : free)
    for (int m = 0; m < modes_; ++m) phi_[static_cast<std::size_t>(dof) * width_ + m] = phi(dof, m);
  product_.assign(phi_.size(), 0.0);
}

Eigen::MatrixXd GalerkinProjector::project(const fem::SymmetricMatrix& a) const {
  const std::vector<double>& values = a.values();
  if (values.size() != position_.size())
    throw std::invalid_argument("Galerkin projector: a matrix of another pattern");
  for (std::size_t k = 0; k < values.size(); ++k) {
    blocks_[position_[k]] = values[k];
    if (mirror_[k] >= 0) blocks_[mirror_[k]] = values[k];
  }
  const int num_nodes = static_cast<int>(row_start_.size()) - 1;
  block_rows_times(num_nodes, row_start_.data(), column_node_.data(), blocks_.data(), phi_.data(),
                   width_, product_.data());
  // Phi^T (A Phi): both row-major 3 n x width, of which the first k columns count.
  Eigen::MatrixXd p(modes_, modes_);
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, modes_, modes_, 3 * num_nodes, 1.0,
              phi_.data(), width_, product_.data(), width_, 0.0, p.data(), modes_);
  return 0.5 * (p + p.transpose());
}

}  // namespace tongue::reduced
