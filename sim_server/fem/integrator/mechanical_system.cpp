#include "fem/integrator/mechanical_system.hpp"

#include <cmath>

namespace tongue::fem {

AssemblyStatus MechanicalSystem::residual(const Vector& u, double load_factor, Vector& r,
                                          SymmetricMatrix* stiffness, double* load_norm,
                                          const std::vector<double>* element_weights) const {
  // Loads that scale the solid's energy element by element ride along in one element pass.
  std::vector<double> weights;
  if (element_weights) weights = *element_weights;
  std::vector<char> folded(loads_.size());
  for (std::size_t i = 0; i < loads_.size(); ++i)
    folded[i] = loads_[i]->add_element_weights(load_factor, weights);
  r.setZero(solid_->num_dofs());
  if (stiffness) stiffness->set_zero();
  const AssemblyStatus status = solid_->add_weighted(u, weights, r, stiffness);
  if (!status.ok) return status;
  Vector f_ext = Vector::Zero(r.size());
  for (std::size_t i = 0; i < loads_.size(); ++i)
    if (!folded[i]) loads_[i]->add(u, load_factor, f_ext, stiffness);
  r -= f_ext;
  if (load_norm) {
    double sum = 0.0;
    for (int dof : solid_->dofs().free_dofs()) sum += f_ext[dof] * f_ext[dof];
    *load_norm = std::sqrt(sum);
  }
  return status;
}

void MechanicalSystem::rank_one_terms(const Vector& u, std::vector<RankOneTerm>& terms) const {
  terms.clear();
  std::vector<NodeSpring> springs;
  for (const auto& load : loads_) load->add_springs(u, springs);
  const DofMap& dofs = solid_->dofs();
  for (const NodeSpring& s : springs) {
    RankOneTerm t;
    for (int c = 0; c < 3; ++c) t.index[c] = dofs.free_index(3 * s.node + c);
    t.direction = s.direction;
    t.stiffness = s.stiffness;
    t.gap = s.gap;
    terms.push_back(t);
  }
}

void MechanicalSystem::begin_step() {
  for (const auto& load : loads_) load->begin_step();
}

Augmentation MechanicalSystem::augment(const Vector& u) {
  Augmentation all = Augmentation::held;
  for (const auto& load : loads_) {
    const Augmentation a = load->augment(u);
    if (a == Augmentation::solve_again || (a == Augmentation::unmet && all == Augmentation::held))
      all = a;
  }
  return all;
}

}  // namespace tongue::fem
