#pragma once
// What the Newton solver needs from a problem: a residual r(x) over the unknowns and its
// symmetric tangent dr/dx. Statics, each Newmark step and any test system provide one.
#include <array>
#include <vector>

#include "fem/assembly/sparse_matrix.hpp"

namespace tongue::fem {

// A rank-one part k v v^T of a tangent on up to three unknowns: index[c] is the unknown that
// component c of the unit direction v acts on (-1: none), k the stiffness [N/m]. With gap > 0
// the term is not in the tangent yet: it enters once x has moved by `gap` [m] against v.
struct RankOneTerm {
  std::array<int, 3> index{-1, -1, -1};
  Vec3 direction = Vec3::Zero();
  double stiffness = 0.0;
  double gap = 0.0;
  bool operator==(const RankOneTerm& o) const {
    return index == o.index && direction == o.direction && stiffness == o.stiffness && gap == o.gap;
  }
  bool engaged() const { return gap <= 0.0; }
};

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
  // The rank-one terms of the tangent at x that may differ between nearby x (contact springs
  // engaging and releasing; part of what residual_and_tangent forms), and those about to enter
  // (gap > 0). A solver reusing a factor formed at x0 corrects it by the terms at x that it
  // lacks and those at x0 that x no longer has. Default: none.
  virtual void rank_one_terms(const Vector& /*x*/, std::vector<RankOneTerm>& terms) {
    terms.clear();
  }
};

}  // namespace tongue::fem
