#pragma once
// What the Newton solver needs from a problem: a residual r(x) over the unknowns and its
// symmetric tangent dr/dx. Statics, each Newmark step and any test system provide one.
#include "fem/assembly/sparse_matrix.hpp"

namespace tongue::fem {

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  virtual std::shared_ptr<const SparsityPattern> pattern() const = 0;
  // Each returns false when the residual cannot be evaluated at x (an inverted element).
  virtual bool residual(const Vector& x, Vector& r) = 0;
  virtual bool residual_and_tangent(const Vector& x, Vector& r, SymmetricMatrix& tangent) = 0;
  // A norm of the forces acting at the last state evaluated (e.g. the external loads) [N], the
  // scale against which the residual is judged small; 0 when the problem has none (the
  // residual is then judged against its own initial value alone).
  virtual double force_scale() const { return 0.0; }
};

}  // namespace tongue::fem
