#include "fem/solver/single_precision_factor.hpp"

#include <cholmod.h>

#include <algorithm>
#include <stdexcept>

namespace tongue::fem {

namespace {

// The substitutions, compiled for the vector widths of AVX-512, AVX2 and the SSE2 of every
// x86-64; the dynamic loader picks the best the CPU has (GCC function multiversioning).
#define TONGUE_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))

struct Layout {
  int num_super;
  const int *super, *row_start, *value_start, *rows;
  const float *values, *inverse_diagonal;
  const long* transposed_start;
  const float* transposed;
};

// Supernode k of a layout: columns first .. first + cols - 1 of L, its block (height rows,
// column-major), the `below` rows under its diagonal block and their indices.
struct Supernode {
  int first, cols, height, below;
  const float* block;
  const float* l21;  // the rows below the diagonal block, column c at l21 + c height
  const int* rows_below;
  const float* upper;  // the diagonal block transposed, column-major cols x cols
};

inline Supernode supernode(const Layout& f, int k) {
  Supernode s;
  s.first = f.super[k];
  s.cols = f.super[k + 1] - s.first;
  s.height = f.row_start[k + 1] - f.row_start[k];
  s.below = s.height - s.cols;
  s.block = f.values + f.value_start[k];
  s.l21 = s.block + s.cols;
  s.rows_below = f.rows + f.row_start[k] + s.cols;
  s.upper = f.transposed + f.transposed_start[k];
  return s;
}

// sum_i a[i] b[i], vectorized as a reduction (OpenMP's simd directive allows the reordering).
inline float dot(const float* __restrict a, const float* __restrict b, int n) {
  float sum = 0.0f;
#pragma omp simd reduction(+ : sum)
  for (int i = 0; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

// L y = y, supernode by supernode: the diagonal block's triangle, then its rows below gathered
// into `work` by a dense product and scattered into y. Every supernode in order, or only the
// `count` ascending ones of `visit` (those a sparse y reaches).
TONGUE_VECTOR_CLONES void forward(const Layout& f, float* __restrict y, float* __restrict work,
                                  const int* visit = nullptr, int count = 0) {
  const int n = visit ? count : f.num_super;
  for (int v = 0; v < n; ++v) {
    const Supernode s = supernode(f, visit ? visit[v] : v);
    float* __restrict yk = y + s.first;
    const float* inverse = f.inverse_diagonal + s.first;
    // A sparse y enters the first supernode of its path part way: the columns before its first
    // nonzero leave the rest as it is (on the tongue a correction column's path covers a third
    // of L; skipping them took a seventh off the substitutions' samples in the contact scenes).
    int first = 0;
    while (first < s.cols && yk[first] == 0.0f) ++first;
    if (first == s.cols) continue;
    // The diagonal block's triangle four columns at a time: their 4 x 4 triangle, then one pass
    // over the rows under it for all four (a quarter of the loads and stores of yk).
    int c = first;
    for (; c + 4 <= s.cols; c += 4) {
      const float* __restrict c0 = s.block + static_cast<long>(c) * s.height;
      const float* __restrict c1 = c0 + s.height;
      const float* __restrict c2 = c1 + s.height;
      const float* __restrict c3 = c2 + s.height;
      const float v0 = yk[c] * inverse[c];
      const float v1 = (yk[c + 1] - c0[c + 1] * v0) * inverse[c + 1];
      const float v2 = (yk[c + 2] - c0[c + 2] * v0 - c1[c + 2] * v1) * inverse[c + 2];
      const float v3 =
          (yk[c + 3] - c0[c + 3] * v0 - c1[c + 3] * v1 - c2[c + 3] * v2) * inverse[c + 3];
      yk[c] = v0;
      yk[c + 1] = v1;
      yk[c + 2] = v2;
      yk[c + 3] = v3;
#pragma omp simd
      for (int i = c + 4; i < s.cols; ++i)
        yk[i] -= c0[i] * v0 + c1[i] * v1 + c2[i] * v2 + c3[i] * v3;
    }
    for (; c < s.cols; ++c) {
      const float v = yk[c] * inverse[c];
      yk[c] = v;
      const float* __restrict column = s.block + static_cast<long>(c) * s.height;
#pragma omp simd
      for (int i = c + 1; i < s.cols; ++i) yk[i] -= column[i] * v;
    }
    if (s.below == 0) continue;
    // work = L21 yk, four columns per pass over work.
    std::fill(work, work + s.below, 0.0f);
    c = first;
    for (; c + 4 <= s.cols; c += 4) {
      const float* __restrict c0 = s.l21 + static_cast<long>(c) * s.height;
      const float* __restrict c1 = c0 + s.height;
      const float* __restrict c2 = c1 + s.height;
      const float* __restrict c3 = c2 + s.height;
      const float v0 = yk[c], v1 = yk[c + 1], v2 = yk[c + 2], v3 = yk[c + 3];
#pragma omp simd
      for (int i = 0; i < s.below; ++i)
        work[i] += c0[i] * v0 + c1[i] * v1 + c2[i] * v2 + c3[i] * v3;
    }
    for (; c < s.cols; ++c) {
      const float v = yk[c];
      const float* __restrict column = s.l21 + static_cast<long>(c) * s.height;
#pragma omp simd
      for (int i = 0; i < s.below; ++i) work[i] += column[i] * v;
    }
    for (int i = 0; i < s.below; ++i) y[s.rows_below[i]] -= work[i];
  }
}

// L^T y = y, supernodes in reverse order: the rows below gathered, one dot product per column,
// then the diagonal block's transposed triangle.
TONGUE_VECTOR_CLONES void backward(const Layout& f, float* __restrict y, float* __restrict work) {
  for (int k = f.num_super - 1; k >= 0; --k) {
    const Supernode s = supernode(f, k);
    float* __restrict yk = y + s.first;
    for (int i = 0; i < s.below; ++i) work[i] = y[s.rows_below[i]];
    // yk -= L21^T work, four columns per pass over work.
    int c = 0;
    for (; c + 4 <= s.cols; c += 4) {
      const float* __restrict c0 = s.l21 + static_cast<long>(c) * s.height;
      const float* __restrict c1 = c0 + s.height;
      const float* __restrict c2 = c1 + s.height;
      const float* __restrict c3 = c2 + s.height;
      float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
#pragma omp simd reduction(+ : s0, s1, s2, s3)
      for (int i = 0; i < s.below; ++i) {
        s0 += c0[i] * work[i];
        s1 += c1[i] * work[i];
        s2 += c2[i] * work[i];
        s3 += c3[i] * work[i];
      }
      yk[c] -= s0;
      yk[c + 1] -= s1;
      yk[c + 2] -= s2;
      yk[c + 3] -= s3;
    }
    for (; c < s.cols; ++c) yk[c] -= dot(s.l21 + static_cast<long>(c) * s.height, work, s.below);
    // The diagonal block's transpose, by columns: U = L11^T stored column-major, so that solved
    // entries update the ones above them with contiguous loops, four columns at a time as in
    // forward().
    const float* inverse = f.inverse_diagonal + s.first;
    c = s.cols - 1;
    for (; c >= 3; c -= 4) {
      const float* __restrict u0 = s.upper + static_cast<long>(c) * s.cols;
      const float* __restrict u1 = u0 - s.cols;
      const float* __restrict u2 = u1 - s.cols;
      const float* __restrict u3 = u2 - s.cols;
      const float v0 = yk[c] * inverse[c];
      const float v1 = (yk[c - 1] - u0[c - 1] * v0) * inverse[c - 1];
      const float v2 = (yk[c - 2] - u0[c - 2] * v0 - u1[c - 2] * v1) * inverse[c - 2];
      const float v3 =
          (yk[c - 3] - u0[c - 3] * v0 - u1[c - 3] * v1 - u2[c - 3] * v2) * inverse[c - 3];
      yk[c] = v0;
      yk[c - 1] = v1;
      yk[c - 2] = v2;
      yk[c - 3] = v3;
#pragma omp simd
      for (int i = 0; i < c - 3; ++i) yk[i] -= u0[i] * v0 + u1[i] * v1 + u2[i] * v2 + u3[i] * v3;
    }
    for (; c >= 0; --c) {
      const float v = yk[c] * inverse[c];
      yk[c] = v;
      const float* __restrict column = s.upper + static_cast<long>(c) * s.cols;
#pragma omp simd
      for (int i = 0; i < c; ++i) yk[i] -= column[i] * v;
    }
  }
}

}  // namespace

void SinglePrecisionFactor::assign(const cholmod_factor& factor) {
  if (!factor.is_super || !factor.is_ll || factor.xtype != CHOLMOD_REAL ||
      factor.itype != CHOLMOD_INT || factor.dtype != CHOLMOD_DOUBLE) {
    throw std::invalid_argument(
        "single-precision factor: needs a numeric supernodal LL^T factor with int indices");
  }
  const int n = static_cast<int>(factor.n);
  const int num_super = static_cast<int>(factor.nsuper);
  const auto* super = static_cast<const int*>(factor.super);
  const auto* pi = static_cast<const int*>(factor.pi);
  const auto* px = static_cast<const int*>(factor.px);
  super_.assign(super, super + num_super + 1);
  row_start_.assign(pi, pi + num_super + 1);
  value_start_.assign(px, px + num_super + 1);
  rows_.assign(static_cast<const int*>(factor.s),
               static_cast<const int*>(factor.s) + pi[num_super]);
  perm_.assign(static_cast<const int*>(factor.Perm), static_cast<const int*>(factor.Perm) + n);
  const auto* x = static_cast<const double*>(factor.x);
  values_.assign(x, x + px[num_super]);
  // Per supernode: 1 / L(j, j) of its columns and its diagonal block transposed (U = L11^T,
  // column c of U holding row c of L11).
  inverse_diagonal_.resize(n);
  transposed_start_.assign(num_super + 1, 0);
  transposed_.clear();
  int widest = 0;
  for (int k = 0; k < num_super; ++k) {
    const int cols = super[k + 1] - super[k], height = pi[k + 1] - pi[k];
    widest = std::max(widest, height);
    transposed_start_[k + 1] = transposed_start_[k] + static_cast<long>(cols) * cols;
    transposed_.resize(transposed_start_[k + 1], 0.0f);
    float* upper = transposed_.data() + transposed_start_[k];
    const double* block = x + px[k];
    for (int c = 0; c < cols; ++c) {
      inverse_diagonal_[super[k] + c] = static_cast<float>(1.0 / block[c * height + c]);
      for (int i = 0; i <= c; ++i)
        upper[static_cast<long>(c) * cols + i] = static_cast<float>(block[i * height + c]);
    }
  }
  y_.resize(n);
  work_.resize(widest);
  // The elimination tree of the supernodes: a supernode's parent holds the first row below its
  // diagonal block (its rows are ascending).
  position_.resize(n);
  for (int i = 0; i < n; ++i) position_[perm_[i]] = i;
  supernode_.resize(n);
  parent_.assign(num_super, -1);
  for (int k = 0; k < num_super; ++k) {
    for (int j = super[k]; j < super[k + 1]; ++j) supernode_[j] = k;
    const int cols = super[k + 1] - super[k];
    if (pi[k + 1] - pi[k] > cols) parent_[k] = rows_[pi[k] + cols];
  }
  for (int& p : parent_)
    if (p >= 0) p = supernode_[p];
  sparse_y_.assign(n, 0.0f);
  visited_.assign(num_super, 0);
  visit_.reserve(num_super);
}

auto SinglePrecisionFactor::layout() const {
  if (empty()) throw std::logic_error("single-precision factor: used before assign()");
  return Layout{static_cast<int>(super_.size()) - 1,
                super_.data(),
                row_start_.data(),
                value_start_.data(),
                rows_.data(),
                values_.data(),
                inverse_diagonal_.data(),
                transposed_start_.data(),
                transposed_.data()};
}

void SinglePrecisionFactor::solve(const double* b, double* x) const {
  const Layout f = layout();
  const int n = size();
  for (int i = 0; i < n; ++i) y_[i] = static_cast<float>(b[perm_[i]]);
  tongue::fem::forward(f, y_.data(), work_.data());
  tongue::fem::backward(f, y_.data(), work_.data());
  for (int i = 0; i < n; ++i) x[perm_[i]] = static_cast<double>(y_[i]);
}

void SinglePrecisionFactor::forward(const double* b, double* y) const {
  const Layout f = layout();
  const int n = size();
  for (int i = 0; i < n; ++i) y_[i] = static_cast<float>(b[perm_[i]]);
  tongue::fem::forward(f, y_.data(), work_.data());
  for (int i = 0; i < n; ++i) y[i] = static_cast<double>(y_[i]);
}

void SinglePrecisionFactor::backward(const double* y, double* x) const {
  const Layout f = layout();
  const int n = size();
  for (int i = 0; i < n; ++i) y_[i] = static_cast<float>(y[i]);
  tongue::fem::backward(f, y_.data(), work_.data());
  for (int i = 0; i < n; ++i) x[perm_[i]] = static_cast<double>(y_[i]);
}

void SinglePrecisionFactor::forward_sparse(const int* unknowns, const double* values, int count,
                                           SparseColumn& out) const {
  const Layout f = layout();
  visit_.clear();
  for (int i = 0; i < count; ++i) {
    if (unknowns[i] < 0) continue;
    const int p = position_[unknowns[i]];
    sparse_y_[p] += static_cast<float>(values[i]);
    for (int k = supernode_[p]; k >= 0 && !visited_[k]; k = parent_[k]) {
      visited_[k] = 1;
      visit_.push_back(k);
    }
  }
  // A parent comes after its children, so ascending order is an order of elimination.
  std::sort(visit_.begin(), visit_.end());
  tongue::fem::forward(f, sparse_y_.data(), work_.data(), visit_.data(),
                       static_cast<int>(visit_.size()));
  out = SparseColumn{};
  for (int k : visit_) {
    visited_[k] = 0;
    for (int j = super_[k]; j < super_[k + 1]; ++j) {
      out.append(j, static_cast<double>(sparse_y_[j]));
      sparse_y_[j] = 0.0f;
    }
  }
}

}  // namespace tongue::fem
