#pragma once
// A solid with the loads that act on it: the residual r(u) = f_int(u) - lambda f_ext(u) that both
// the static and the dynamic solvers drive to zero.
#include <memory>
#include <vector>

#include "fem/assembly/loads.hpp"
#include "fem/assembly/solid_model.hpp"
#include "fem/solver/nonlinear_problem.hpp"

namespace tongue::fem {

class MechanicalSystem {
 public:
  explicit MechanicalSystem(std::shared_ptr<const SolidModel> solid) : solid_(std::move(solid)) {}

  void add_load(std::shared_ptr<ForceContribution> load) { loads_.push_back(std::move(load)); }
  const std::vector<std::shared_ptr<ForceContribution>>& loads() const { return loads_; }
  const SolidModel& solid() const { return *solid_; }

  // r = f_int(u) - load_factor f_ext(u) over all dofs (loads that scale the solid's elements
  // are folded into one element pass, ForceContribution::add_element_weights) (the entries at
  // prescribed dofs are the negated reactions); when stiffness is given, dr/du over the free dofs.
  // When load_norm is given it receives ||load_factor f_ext(u)|| over the free dofs [N], a scale
  // for r. With element_weights (one per element) the solid's own elements count with those
  // weights instead of 1, elements of weight 0 not evaluated (hyper-reduction integrates over a
  // weighted sample of them), and the folded loads scale those weights.
  AssemblyStatus residual(const Vector& u, double load_factor, Vector& r,
                          SymmetricMatrix* stiffness, double* load_norm = nullptr,
                          const std::vector<double>* element_weights = nullptr) const;
  // The loads' springs at u (ForceContribution::add_springs) as rank-one terms of the tangent
  // over the free dofs, in the loads' order.
  void rank_one_terms(const Vector& u, std::vector<RankOneTerm>& terms) const;
  // The loads' augmented-Lagrangian multipliers (ForceContribution::begin_step, augment): set to
  // zero; updated at a converged u: solve_again when some load asks for it, else unmet when
  // some load's constraint is violated beyond its tolerance, else held.
  void begin_step();
  Augmentation augment(const Vector& u);

 private:
  std::shared_ptr<const SolidModel> solid_;
  std::vector<std::shared_ptr<ForceContribution>> loads_;
};

}  // namespace tongue::fem
