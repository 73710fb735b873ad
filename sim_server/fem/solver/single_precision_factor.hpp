#pragma once
// A single-precision copy of a supernodal Cholesky factor P A P^T = L L^T, with its own forward
// and backward substitutions.
//
// Why: the dynamic steps solve with one factor for many iterations and steps (modified Newton),
// and a solve reads all of L twice; on the tongue L is 3.7 MB in double, more than a core's L2
// cache, and CHOLMOD's supernodal solve calls the BLAS twice per supernode on blocks of a few
// columns. In float, L is half the bytes and the substitutions are plain loops the compiler
// vectorizes. The error this adds to a correction is of the order of cond(A) times float's
// rounding (2^-24), measured on the tongue's effective tangent in the tests; modified Newton
// iterates on the true double-precision residual, so it changes the contraction of the
// iterations, not the state they converge to (Higham 2002, sec. 12.1, on solving with a
// lower-precision factor).
//
// The layout is CHOLMOD's (Chen, Davis, Hager & Rajamanickam 2008): supernode k holds columns
// super[k] .. super[k+1]-1 of L as a dense column-major block whose rows are the row indices
// s[pi[k]] .. s[pi[k+1]-1], the first of them the supernode's own columns.
#include <vector>

#include "fem/solver/sparse_column.hpp"

struct cholmod_factor_struct;

namespace tongue::fem {

class SinglePrecisionFactor {
 public:
  // Copies a numerically factorized supernodal LL^T factor (int indices, real double values).
  // Throws std::invalid_argument for any other kind of factor.
  void assign(const cholmod_factor_struct& factor);
  bool empty() const { return super_.empty(); }
  int size() const { return static_cast<int>(perm_.size()); }

  // x = A^{-1} b (both of size(); x may alias b).
  void solve(const double* b, double* x) const;
  // The two halves of solve(), for corrections applied between them: y = L^{-1} P b, and
  // x = P^T L^{-T} y (y in the factor's order; x may alias y).
  void forward(const double* b, double* y) const;
  void backward(const double* y, double* x) const;
  // forward() of b = sum_i values[i] e_{unknowns[i]} (count entries; unknowns < 0 skipped) as
  // its nonzeros: `rows` ascending in the factor's order, `out` their values. Only the
  // supernodes on the paths from those unknowns to the root of the supernodal elimination tree
  // are visited, the only ones a sparse right-hand side reaches (Gilbert & Peierls 1988; Davis
  // 2006, *Direct Methods for Sparse Linear Systems*, sec. 3.2): on the tongue a few per cent of
  // L for one node's unknowns.
  void forward_sparse(const int* unknowns, const double* values, int count,
                      SparseColumn& out) const;

 private:
  // The arrays the substitutions read, as one view (its type is the .cpp's); throws
  // std::logic_error before assign().
  auto layout() const;

  std::vector<int> super_, row_start_, value_start_, rows_, perm_;
  std::vector<int> position_;   // of each unknown in the factor's order (perm_ inverted)
  std::vector<int> parent_;     // of each supernode in the elimination tree; -1 for a root
  std::vector<int> supernode_;  // of each column
  std::vector<float> values_;
  std::vector<float> inverse_diagonal_;  // 1 / L(j, j), per column
  // Each supernode's diagonal block transposed (column-major cols x cols), for the backward
  // substitution, and where each starts.
  std::vector<long> transposed_start_;
  std::vector<float> transposed_;
  mutable std::vector<float> y_, work_;
  mutable std::vector<float> sparse_y_;  // zero between forward_sparse() calls
  mutable std::vector<int> visit_;       // supernodes forward_sparse() visits
  mutable std::vector<char> visited_;    // per supernode, false between calls
};

}  // namespace tongue::fem
