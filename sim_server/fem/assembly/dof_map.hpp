#pragma once
// Degrees of freedom: three displacement components per node (global dof 3 n + c), some of them
// prescribed. The unknowns of the solvers are the free dofs only, numbered consecutively.
#include <vector>

#include "fem/types.hpp"

namespace tongue::fem {

// A Dirichlet condition on one component of one node: u_c(node) = value [m].
struct PrescribedDof {
  int node = 0;
  int component = 0;  // 0 = x, 1 = y, 2 = z
  double value = 0.0;
};

class DofMap {
 public:
  // Throws std::invalid_argument on a node or component out of range. A dof prescribed twice
  // keeps the last value.
  DofMap(int num_nodes, const std::vector<PrescribedDof>& prescribed);

  int num_dofs() const { return static_cast<int>(free_index_.size()); }
  int num_free() const { return num_free_; }
  // Index among the free dofs, or -1 when the dof is prescribed.
  int free_index(int dof) const { return free_index_[dof]; }
  bool is_free(int dof) const { return free_index_[dof] >= 0; }
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  const std::vector<int>& prescribed_dofs() const { return prescribed_dofs_; }
  // Prescribed value of every dof (zero for free dofs) [m].
  const Vector& prescribed_values() const { return prescribed_values_; }

  Vector gather_free(const Vector& full) const;               // full (3n) -> free
  void scatter_free(const Vector& free, Vector& full) const;  // writes the free entries only

 private:
  std::vector<int> free_index_;
  std::vector<int> free_dofs_;
  std::vector<int> prescribed_dofs_;
  Vector prescribed_values_;
  int num_free_ = 0;
};

}  // namespace tongue::fem
