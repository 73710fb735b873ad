#pragma once
// Sparse Cholesky factorization of the symmetric tangent with CHOLMOD (Chen, Davis, Hager &
// Rajamanickam 2008). The fill-reducing ordering and symbolic analysis are done once per
// sparsity pattern; each factorize() is numeric only. Supernodal, so the dense kernels run in
// the BLAS the library is linked with.
#include <array>
#include <memory>
#include <vector>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/solver/single_precision_factor.hpp"
#include "fem/solver/sparse_column.hpp"

namespace tongue::fem {

struct FactorizationReport {
  bool ok = false;
  // 0 when the matrix was positive definite. Otherwise the factorization fell back to
  // A + shift I (a Levenberg-Marquardt regularization: the Newton direction stays a descent
  // direction and convergence is still judged on the true residual), with the smallest shift
  // tried that worked [same unit as A's diagonal].
  double shift = 0.0;
  int attempts = 0;
  double seconds = 0.0;
};

class CholmodSolver {
 public:
  explicit CholmodSolver(std::shared_ptr<const SparsityPattern> pattern);
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  FactorizationReport factorize(const SymmetricMatrix& matrix);
  // Solves A x = b with the last successful factorization.
  Vector solve(const Vector& b) const;
  // Its two halves, for low-rank corrections between them: with P A P^T = L L^T,
  // forward(b) = L^{-1} P b and backward(y) = P^T L^{-T} y, so solve(b) = backward(forward(b)).
  Vector forward(const Vector& b) const;
  Vector backward(const Vector& y) const;
  // forward() of the vector with `values` on the `unknowns` (entries < 0 skipped) and zeros
  // elsewhere, as its nonzeros. In single precision it visits only the part of L that such a
  // vector reaches (SinglePrecisionFactor::forward_sparse).
  SparseColumn forward_sparse(const std::vector<int>& unknowns,
                              const std::vector<double>& values) const;
  // Solves in single precision (single_precision_factor.hpp) from the next factorization on:
  // for iterations that judge their result on a double-precision residual.
  void set_single_precision(bool single) {
    single_precision_ = single;
    if (!single) single_factor_ = SinglePrecisionFactor();
  }
  bool single_precision() const { return single_precision_; }
  bool has_factor() const { return factored_; }

  double analysis_seconds() const { return analysis_seconds_; }
  double factor_nonzeros() const;      // nnz(L)
  double factorization_flops() const;  // floating-point operations of one numeric factorization

 private:
  // b through CHOLMOD's solve of one of its systems (CHOLMOD_A, CHOLMOD_P, CHOLMOD_L, ...).
  Vector solve_system(const Vector& b, int system) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<const SparsityPattern> pattern_;
  double analysis_seconds_ = 0.0;
  bool factored_ = false;
  bool single_precision_ = false;
  SinglePrecisionFactor single_factor_;  // empty until a factorization in single precision
};

}  // namespace tongue::fem
