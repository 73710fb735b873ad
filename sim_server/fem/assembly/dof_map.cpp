#include "fem/assembly/dof_map.hpp"

#include <stdexcept>
#include <string>

namespace tongue::fem {

DofMap::DofMap(int num_nodes, const std::vector<PrescribedDof>& prescribed)
    : free_index_(3 * num_nodes, 0), prescribed_values_(Vector::Zero(3 * num_nodes)) {
  for (const PrescribedDof& p : prescribed) {
    if (p.node < 0 || p.node >= num_nodes) {
      throw std::invalid_argument("prescribed dof on node " + std::to_string(p.node) +
                                  ", outside 0.." + std::to_string(num_nodes - 1));
    }
    if (p.component < 0 || p.component > 2) {
      throw std::invalid_argument("prescribed dof component " + std::to_string(p.component) +
                                  " is not 0, 1 or 2");
    }
    const int dof = 3 * p.node + p.component;
    free_index_[dof] = -1;
    prescribed_values_[dof] = p.value;
  }
  for (int dof = 0; dof < num_dofs(); ++dof) {
    if (free_index_[dof] < 0) {
      prescribed_dofs_.push_back(dof);
    } else {
      free_index_[dof] = num_free_++;
      free_dofs_.push_back(dof);
    }
  }
}

Vector DofMap::gather_free(const Vector& full) const {
  Vector free(num_free_);
  for (int i = 0; i < num_free_; ++i) free[i] = full[free_dofs_[i]];
  return free;
}

void DofMap::scatter_free(const Vector& free, Vector& full) const {
  for (int i = 0; i < num_free_; ++i) full[free_dofs_[i]] = free[i];
}

}  // namespace tongue::fem
