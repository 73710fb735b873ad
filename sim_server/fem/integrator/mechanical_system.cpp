#include "fem/integrator/mechanical_system.hpp"

#include <cmath>

namespace tongue::fem {

AssemblyStatus MechanicalSystem::residual(const Vector& u, double load_factor, Vector& r,
                                          SymmetricMatrix* stiffness, double* load_norm) const {
  // Loads that scale the solid's energy element by element ride along in one element pass.
  std::vector<double> weights;
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

}  // namespace tongue::fem
