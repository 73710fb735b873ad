#pragma once
// Proper orthogonal decomposition of displacement snapshots (Holmes, Lumley & Berkooz 1996,
// Turbulence, Coherent Structures, Dynamical Systems and Symmetry, ch. 3): the thin singular
// value decomposition S = U Sigma V^T of the snapshot matrix S (one column per snapshot, each the
// displacement from the reduced model's origin), by Eigen's divide-and-conquer SVD. The basis
// is the first k left singular vectors, k the fewest whose energy sum_i<=k sigma_i^2 is at least
// the given fraction of the total: the snapshots' squared distance to their projection onto the
// basis, summed over the snapshots, is then sum_i>k sigma_i^2 <= (1 - fraction) ||S||_F^2.
#include "fem/types.hpp"

namespace tongue::reduced {

struct PodBasis {
  Eigen::MatrixXd modes;        // dofs x k, orthonormal columns
  fem::Vector singular_values;  // all of them, largest first
  double captured = 0.0;        // the energy fraction the k modes hold
};

// The fewest leading singular values (largest first) whose squares sum to at least the fraction
// of all the squares.
int modes_for(const fem::Vector& singular_values, double energy_fraction);

// Throws std::invalid_argument for an empty snapshot matrix, snapshots that are all zero, or a
// fraction outside (0, 1].
PodBasis pod_basis(const Eigen::MatrixXd& snapshots, double energy_fraction);

}  // namespace tongue::reduced
