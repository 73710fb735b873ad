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

// sum_i a[i] b[i], vectorized as a reduction (OpenMP's simd directive allows the reordering).
inline float dot(const float* __restrict a, const float* __restrict b, int n) {
  float sum = 0.0f;
#pragma omp simd reduction(+ : sum)
  for (int i = 0; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

// L y = y, supernode by supernode: the diagonal block's triangle, then its rows below gathered
// into `work` by a dense product and scattered into y.
TONGUE_VECTOR_CLONES void forward(const Layout& f, float* __restrict y, float* __restrict work) {
  for (int k = 0; k < f.num_super; ++k) {
    const int first = f.super[k], cols = f.super[k + 1] - first;
    const int height = f.row_start[k + 1] - f.row_start[k], below = height - cols;
    const float* block = f.values + f.value_start[k];
    float* __restrict yk = y + first;
    for (int c = 0; c < cols; ++c) {
      const float v = yk[c] * f.inverse_diagonal[first + c];
      yk[c] = v;
      const float* __restrict column = block + static_cast<long>(c) * height;
#pragma omp simd
      for (int i = c + 1; i < cols; ++i) yk[i] -= column[i] * v;
    }
    if (below == 0) continue;
    // work = L21 yk, four columns per pass over work.
    std::fill(work, work + below, 0.0f);
    const float* __restrict l21 = block + cols;
    int c = 0;
    for (; c + 4 <= cols; c += 4) {
      const float* __restrict c0 = l21 + static_cast<long>(c) * height;
      const float* __restrict c1 = c0 + height, * __restrict c2 = c1 + height, * __restrict c3 = c2 + height;
      const float v0 = yk[c], v1 = yk[c + 1], v2 = yk[c + 2], v3 = yk[c + 3];
#pragma omp simd
      for (int i = 0; i < below; ++i) work[i] += c0[i] * v0 + c1[i] * v1 + c2[i] * v2 + c3[i] * v3;
    }
    for (; c < cols; ++c) {
      const float v = yk[c];
      const float* __restrict column = l21 + static_cast<long>(c) * height;
#pragma omp simd
      for (int i = 0; i < below; ++i) work[i] += column[i] * v;
    }
    const int* rows = f.rows + f.row_start[k] + cols;
    for (int i = 0; i < below; ++i) y[rows[i]] -= work[i];
  }
}

// L^T y = y, supernodes in reverse order: the rows below gathered, one dot product per column,
// then the diagonal block's transposed triangle.
TONGUE_VECTOR_CLONES void backward(const Layout& f, float* __restrict y, float* __restrict work) {
  for (int k = f.num_super - 1; k >= 0; --k) {
    const int first = f.super[k], cols = f.super[k + 1] - first;
    const int height = f.row_start[k + 1] - f.row_start[k], below = height - cols;
    const float* block = f.values + f.value_start[k];
    float* yk = y + first;
    const int* rows = f.rows + f.row_start[k] + cols;
    for (int i = 0; i < below; ++i) work[i] = y[rows[i]];
    // yk -= L21^T work, four columns per pass over work.
    const float* __restrict l21 = block + cols;
    int c = 0;
    for (; c + 4 <= cols; c += 4) {
      const float* __restrict c0 = l21 + static_cast<long>(c) * height;
      const float* __restrict c1 = c0 + height, * __restrict c2 = c1 + height, * __restrict c3 = c2 + height;
      float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
#pragma omp simd reduction(+ : s0, s1, s2, s3)
      for (int i = 0; i < below; ++i) {
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
    for (; c < cols; ++c) yk[c] -= dot(l21 + static_cast<long>(c) * height, work, below);
    // The diagonal block's transpose, by columns: U = L11^T stored column-major, so that each
    // solved entry updates the ones above it with one contiguous axpy, as in forward().
    const float* upper = f.transposed + f.transposed_start[k];
    for (int c = cols - 1; c >= 0; --c) {
      const float v = yk[c] * f.inverse_diagonal[first + c];
      yk[c] = v;
      const float* __restrict column = upper + static_cast<long>(c) * cols;
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
  inverse_diagonal_.resize(n);
  int widest = 0;
  for (int k = 0; k < num_super; ++k) {
    const int height = pi[k + 1] - pi[k];
    widest = std::max(widest, height);
    for (int c = 0; c < super[k + 1] - super[k]; ++c)
      inverse_diagonal_[super[k] + c] = static_cast<float>(1.0 / x[px[k] + c * height + c]);
  }
  transposed_start_.assign(num_super + 1, 0);
  for (int k = 0; k < num_super; ++k) {
    const long cols = super[k + 1] - super[k];
    transposed_start_[k + 1] = transposed_start_[k] + cols * cols;
  }
  transposed_.assign(transposed_start_[num_super], 0.0f);
  for (int k = 0; k < num_super; ++k) {
    const int cols = super[k + 1] - super[k], height = pi[k + 1] - pi[k];
    float* upper = transposed_.data() + transposed_start_[k];
    for (int c = 0; c < cols; ++c)  // column c of U = L11^T ...
      for (int i = 0; i <= c; ++i)  // ... holds row c of L11
        upper[static_cast<long>(c) * cols + i] = static_cast<float>(x[px[k] + i * height + c]);
  }
  y_.resize(n);
  work_.resize(widest);
}

void SinglePrecisionFactor::solve(const double* b, double* x) const {
  if (empty()) throw std::logic_error("single-precision factor: solve() before assign()");
  const int n = size();
  for (int i = 0; i < n; ++i) y_[i] = static_cast<float>(b[perm_[i]]);
  const Layout layout{static_cast<int>(super_.size()) - 1,
                      super_.data(),
                      row_start_.data(),
                      value_start_.data(),
                      rows_.data(),
                      values_.data(),
                      inverse_diagonal_.data(),
                      transposed_start_.data(),
                      transposed_.data()};
  forward(layout, y_.data(), work_.data());
  backward(layout, y_.data(), work_.data());
  for (int i = 0; i < n; ++i) x[perm_[i]] = static_cast<double>(y_[i]);
}

}  // namespace tongue::fem
