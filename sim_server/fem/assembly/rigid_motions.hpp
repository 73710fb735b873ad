#pragma once
// The rigid-body motions a solid's Dirichlet conditions leave free. A static solve (or the
// settling of a dynamic run) of a body that can translate or rotate freely has a singular
// tangent, and Newton's method fails without saying why; this says it before solving.
#include <string>
#include <vector>

#include "fem/assembly/dof_map.hpp"

namespace tongue::fem {

// The rigid motions that move no prescribed dof, for a user: each of the translations along x,
// y, z and rotations about the axes through the nodes' centroid that is free ("translation along
// x", "rotation about z through (x, y, z) m"), then how many free motions combine them (a hinge
// off the centroid); empty when the conditions hold the body. Free: in the null space of the
// six rigid modes restricted to the prescribed dofs (rank by Eigen's SVD, to 1e-9).
std::vector<std::string> free_rigid_motions(const std::vector<Vec3>& nodes,
                                            const std::vector<PrescribedDof>& prescribed);

}  // namespace tongue::fem
