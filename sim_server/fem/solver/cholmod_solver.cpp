#include "fem/solver/cholmod_solver.hpp"

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

// OpenBLAS's run-time thread setting (declared here: Debian's OpenBLAS installs cblas.h under a
// BLAS-alternatives path that other BLAS builds do not share).
extern "C" void openblas_set_num_threads(int num_threads);

namespace tongue::fem {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

struct CholmodSolver::Impl {
  cholmod_common common;
  cholmod_sparse* matrix = nullptr;
  cholmod_factor* factor = nullptr;
  cholmod_dense* rhs = nullptr;
};

CholmodSolver::CholmodSolver(std::shared_ptr<const SparsityPattern> pattern)
    : impl_(std::make_unique<Impl>()), pattern_(std::move(pattern)) {
  // One BLAS thread: at the tongue's sizes the supernodes are small, and idle OpenBLAS threads
  // spinning between calls cost more than the second core gains (docs/speed.md).
  openblas_set_num_threads(1);
  // CHOLMOD opens OpenMP regions with a fixed team of 4 for small loops (clearing workspace),
  // after which the idle team spins: on the tongue that made a factorization 18 ms instead of
  // 13 ms on a busy 2-core machine. No nested-active levels makes every region run on the
  // calling thread alone (the project's own threads are std::threads, not OpenMP).
  omp_set_max_active_levels(0);
  cholmod_common& c = impl_->common;
  cholmod_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.print = 0;  // failures are reported through FactorizationReport, not stderr
  const SparsityPattern& p = *pattern_;
  const int n = p.size;
  impl_->matrix = cholmod_allocate_sparse(n, n, p.nnz(), /*sorted=*/1, /*packed=*/1,
                                          /*stype=*/1, CHOLMOD_REAL, &c);
  impl_->rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &c);
  if (!impl_->matrix || !impl_->rhs) throw std::runtime_error("CHOLMOD could not allocate");
  std::copy(p.column_start.begin(), p.column_start.end(), static_cast<int*>(impl_->matrix->p));
  std::copy(p.row_index.begin(), p.row_index.end(), static_cast<int*>(impl_->matrix->i));

  // The fill-reducing ordering: the better of AMD (CHOLMOD's default) and nested dissection
  // with small leaves and no constrained minimum degree on them (CHOLMOD's method 6 when it
  // tries all). On the tongue the latter has 18 % fewer nonzeros in L and 40 % fewer flops
  // (docs/speed.md); the analysis, once per pattern, takes about 11 ms instead of 3.
  c.nmethods = 2;
  c.method[0].ordering = CHOLMOD_AMD;
  c.method[1].ordering = CHOLMOD_NESDIS;
  c.method[1].nd_small = 4;
  c.method[1].nd_camd = 0;
  const auto start = std::chrono::steady_clock::now();
  impl_->factor = cholmod_analyze(impl_->matrix, &c);
  analysis_seconds_ = seconds_since(start);
  if (!impl_->factor) throw std::runtime_error("CHOLMOD symbolic analysis failed");
}

CholmodSolver::~CholmodSolver() {
  cholmod_common& c = impl_->common;
  cholmod_free_factor(&impl_->factor, &c);
  cholmod_free_sparse(&impl_->matrix, &c);
  cholmod_free_dense(&impl_->rhs, &c);
  cholmod_finish(&c);
}

FactorizationReport CholmodSolver::factorize(const SymmetricMatrix& matrix) {
  if (matrix.shared_pattern() != pattern_) {
    throw std::invalid_argument("matrix and solver have different sparsity patterns");
  }
  const auto start = std::chrono::steady_clock::now();
  cholmod_common& c = impl_->common;
  std::copy(matrix.values().begin(), matrix.values().end(), static_cast<double*>(impl_->matrix->x));

  FactorizationReport report;
  // CHOLMOD factorizes NaN entries without complaint, into a NaN factor: refuse them here.
  const bool finite = std::all_of(matrix.values().begin(), matrix.values().end(),
                                  [](double v) { return std::isfinite(v); });
  double max_diagonal = 0.0;
  for (int i = 0; i < pattern_->size; ++i)
    max_diagonal = std::max(max_diagonal, std::abs(matrix.diagonal(i)));

  // Shifts tried after a failure, relative to the largest diagonal entry, in steps of 10: the
  // smallest that works changes Newton's direction least. The last, 10x the largest diagonal,
  // exceeds the most negative eigenvalue of any tangent whose indefiniteness is not larger
  // than its own diagonal (Gershgorin bounds the eigenvalues by diagonal plus row sums).
  constexpr double kRelativeShifts[] = {0.0,  1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5,
                                        1e-4, 1e-3,  1e-2, 1e-1, 1.0,  10.0};
  for (double relative : kRelativeShifts) {
    if (!finite) break;
    ++report.attempts;
    double beta[2] = {relative * max_diagonal, 0.0};
    cholmod_factorize_p(impl_->matrix, beta, nullptr, 0, impl_->factor, &c);
    if (c.status == CHOLMOD_OK && impl_->factor->minor == impl_->factor->n) {
      report.ok = true;
      report.shift = beta[0];
      break;
    }
  }
  factored_ = report.ok;
  if (report.ok && single_precision_) single_factor_.assign(*impl_->factor);
  report.seconds = seconds_since(start);
  return report;
}

Vector CholmodSolver::solve(const Vector& b) const {
  if (!factored_) throw std::logic_error("solve() called without a successful factorization");
  if (single_precision_ && !single_factor_.empty()) {
    Vector x(b.size());
    single_factor_.solve(b.data(), x.data());
    return x;
  }
  return solve_system(b, CHOLMOD_A);
}

Vector CholmodSolver::forward(const Vector& b) const {
  if (!factored_) throw std::logic_error("forward() called without a successful factorization");
  Vector y(b.size());
  if (single_precision_ && !single_factor_.empty()) {
    single_factor_.forward(b.data(), y.data());
    return y;
  }
  return solve_system(solve_system(b, CHOLMOD_P), CHOLMOD_L);
}

Vector CholmodSolver::backward(const Vector& y) const {
  if (!factored_) throw std::logic_error("backward() called without a successful factorization");
  if (single_precision_ && !single_factor_.empty()) {
    Vector x(y.size());
    single_factor_.backward(y.data(), x.data());
    return x;
  }
  return solve_system(solve_system(y, CHOLMOD_Lt), CHOLMOD_Pt);
}

SparseColumn CholmodSolver::forward_sparse(const std::vector<int>& unknowns,
                                           const std::vector<double>& values) const {
  SparseColumn column;
  if (single_precision_ && !single_factor_.empty()) {
    single_factor_.forward_sparse(unknowns.data(), values.data(), static_cast<int>(unknowns.size()),
                                  column);
    return column;
  }
  // In double precision the whole forward substitution; the entries it does not reach stay
  // exactly 0.
  Vector b = Vector::Zero(pattern_->size);
  for (std::size_t i = 0; i < unknowns.size(); ++i)
    if (unknowns[i] >= 0) b[unknowns[i]] += values[i];
  const Vector y = forward(b);
  for (int i = 0; i < y.size(); ++i) column.append(i, y[i]);
  return column;
}

Vector CholmodSolver::solve_system(const Vector& b, int system) const {
  cholmod_common& c = impl_->common;
  std::copy(b.data(), b.data() + b.size(), static_cast<double*>(impl_->rhs->x));
  cholmod_dense* x = cholmod_solve(system, impl_->factor, impl_->rhs, &c);
  if (!x) throw std::runtime_error("CHOLMOD solve failed");
  Vector result = Eigen::Map<const Vector>(static_cast<const double*>(x->x), b.size());
  cholmod_free_dense(&x, &c);
  return result;
}

double CholmodSolver::factor_nonzeros() const {
  return impl_->common.lnz;
}
double CholmodSolver::factorization_flops() const {
  return impl_->common.fl;
}

}  // namespace tongue::fem
