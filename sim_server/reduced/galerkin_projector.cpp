#include "reduced/galerkin_projector.hpp"

#include <cblas.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tongue::reduced {

namespace {

// Columns of the product accumulated at once: two AVX-512 vectors a row of doubles, six sums in
// flight (with one vector a row the kernel took 1.17 ms on the tongue's tangent, 49 modes; with
// two, 0.87-0.96 ms); one vector a row of floats.
constexpr int kLanes = 16;

// y = A x for A in full rows of 3 x 3 node blocks and x, y row-major with `width` columns (a
// multiple of kLanes), over the blocks listed for each row: row a's are blocks + 9 block[k] for
// k in [row_start[a], row_start[a + 1]).
template <typename T>
[[gnu::always_inline]] inline void rows_times(int num_nodes, const int* row_start,
                                              const int* column_node, const int* block,
                                              const T* blocks, const T* x, int width, T* y) {
  for (int a = 0; a < num_nodes; ++a) {
    for (int c = 0; c < width; c += kLanes) {
      T sum[3][kLanes] = {};
      for (int k = row_start[a]; k < row_start[a + 1]; ++k) {
        const T* b = blocks + 9 * block[k];
        const T* x0 = x + static_cast<long>(3 * column_node[k]) * width + c;
        const T* x1 = x0 + width;
        const T* x2 = x1 + width;
        for (int r = 0; r < 3; ++r)
          for (int l = 0; l < kLanes; ++l)
            sum[r][l] += b[3 * r] * x0[l] + b[3 * r + 1] * x1[l] + b[3 * r + 2] * x2[l];
      }
      T* out = y + static_cast<long>(3 * a) * width + c;
      for (int r = 0; r < 3; ++r)
        for (int l = 0; l < kLanes; ++l) out[r * width + l] = sum[r][l];
    }
  }
}

// Compiled for the vector widths of AVX-512, AVX2 and the SSE2 of every x86-64; the dynamic
// loader picks the best the CPU has (GCC function multiversioning).
__attribute__((target_clones("avx512f", "avx2", "default"))) void block_rows_times(
    int num_nodes, const int* row_start, const int* column_node, const int* block,
    const double* blocks, const double* x, int width, double* y) {
  rows_times(num_nodes, row_start, column_node, block, blocks, x, width, y);
}
__attribute__((target_clones("avx512f", "avx2", "default"))) void block_rows_times(
    int num_nodes, const int* row_start, const int* column_node, const int* block,
    const float* blocks, const float* x, int width, float* y) {
  rows_times(num_nodes, row_start, column_node, block, blocks, x, width, y);
}

// C = A^T B for A, B row-major with `rows` rows of `width` (the first k columns counting), C
// k x k column-major, by the BLAS of the precision.
void transpose_times(int k, int rows, int width, const double* a, const double* b, double* c) {
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k, k, rows, 1.0, a, width, b, width, 0.0, c,
              k);
}
void transpose_times(int k, int rows, int width, const float* a, const float* b, float* c) {
  cblas_sgemm(CblasColMajor, CblasNoTrans, CblasTrans, k, k, rows, 1.0f, a, width, b, width, 0.0f,
              c, k);
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
  nonzero_.assign(column_node_.size(), 0);
  active_start_.assign(num_nodes + 1, 0);
  active_column_.reserve(column_node_.size());
  active_block_.reserve(column_node_.size());

  // Entries of prescribed dofs are never written: they stay zero.
  double_.blocks.assign(9 * column_node_.size(), 0.0);
  double_.phi.assign(static_cast<std::size_t>(dofs.num_dofs()) * width_, 0.0);
  for (int dof : free)
    for (int m = 0; m < modes_; ++m)
      double_.phi[static_cast<std::size_t>(dof) * width_ + m] = phi(dof, m);
  double_.product.assign(double_.phi.size(), 0.0);
}

Eigen::MatrixXd GalerkinProjector::project(const fem::SymmetricMatrix& a,
                                           Precision precision) const {
  if (a.values().size() != position_.size())
    throw std::invalid_argument("Galerkin projector: a matrix of another pattern");
  if (precision == Precision::double_precision) return project_in(a, double_);
  if (single_.phi.empty()) {
    single_.phi.assign(double_.phi.begin(), double_.phi.end());
    single_.blocks.assign(double_.blocks.size(), 0.0f);
    single_.product.assign(double_.product.size(), 0.0f);
  }
  return project_in(a, single_);
}

template <typename T>
Eigen::MatrixXd GalerkinProjector::project_in(const fem::SymmetricMatrix& a, Work<T>& work) const {
  const std::vector<double>& values = a.values();
  std::fill(nonzero_.begin(), nonzero_.end(), 0);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const T v = static_cast<T>(values[k]);
    work.blocks[position_[k]] = v;
    if (mirror_[k] >= 0) work.blocks[mirror_[k]] = v;
    if (v != T(0)) {
      nonzero_[position_[k] / 9] = 1;
      if (mirror_[k] >= 0) nonzero_[mirror_[k] / 9] = 1;
    }
  }
  const int num_nodes = static_cast<int>(row_start_.size()) - 1;
  active_column_.clear();
  active_block_.clear();
  for (int n = 0; n < num_nodes; ++n) {
    for (int k = row_start_[n]; k < row_start_[n + 1]; ++k) {
      if (!nonzero_[k]) continue;
      active_column_.push_back(column_node_[k]);
      active_block_.push_back(k);
    }
    active_start_[n + 1] = static_cast<int>(active_block_.size());
  }
  block_rows_times(num_nodes, active_start_.data(), active_column_.data(), active_block_.data(),
                   work.blocks.data(), work.phi.data(), width_, work.product.data());
  // Phi^T (A Phi): both row-major 3 n x width, of which the first k columns count.
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> p(modes_, modes_);
  transpose_times(modes_, 3 * num_nodes, width_, work.phi.data(), work.product.data(), p.data());
  const Eigen::MatrixXd result = p.template cast<double>();
  return 0.5 * (result + result.transpose());
}

}  // namespace tongue::reduced
