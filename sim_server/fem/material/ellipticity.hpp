#pragma once
// Strong ellipticity (the Legendre-Hadamard condition) of a hyperelastic law at a deformation
// F: a_i N_J A_iJkL a_k N_L > 0 for every amplitude a and reference direction N, i.e. the
// acoustic tensor Q(N)_ik = A_iJkL N_J N_L is positive definite for every unit N. Where it fails
// the equations of motion lose well-posedness: waves stop propagating in some direction, strain
// localizes in bands as thin as the mesh allows, and Newton's method stalls (Ogden 1984,
// sec. 6.2.7; Marsden & Hughes 1983, sec. 6.4). The test is exact on the sampled directions and
// refined locally around the weakest; it never reports a loss that is not there.
#include "fem/material/material.hpp"
#include "fem/types.hpp"

namespace tongue::fem {

struct EllipticityCheck {
  double min_eigenvalue = 0.0;     // smallest eigenvalue of Q(N) over the directions tried [Pa]
  Vec3 direction = Vec3::UnitX();  // the reference direction N where it occurs (unit)
  Vec3 amplitude = Vec3::UnitX();  // its eigenvector a (unit)
  bool elliptic() const { return min_eigenvalue > 0.0; }
};

// The acoustic tensor Q(N) of tangent A (first Piola form, types.hpp flattening).
Mat3 acoustic_tensor(const Mat9& A, const Vec3& N);

// Searches the unit sphere for the direction of least stiffness: 128 directions spread evenly
// over the half sphere (N and -N give the same Q), then a local refinement (Newton's method on
// the direction and the amplitude together) from the weakest few of their local minima.
EllipticityCheck check_ellipticity(const Material& material, const Mat3& F);

}  // namespace tongue::fem
