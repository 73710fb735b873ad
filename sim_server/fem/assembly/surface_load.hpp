#pragma once
// Nodal forces equivalent to a uniform traction on part of the boundary.
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

// Distributes total_force [N] as a uniform traction over the boundary faces whose four nodes all
// belong to `nodes`, with consistent nodal forces f_a = t int N_a dA on the reference surface
// (2x2 Gauss on each bilinear face). Returns a full 3 n vector. Throws std::invalid_argument when
// no boundary face lies in the set.
Vector uniform_surface_force(const Mesh& mesh, const std::vector<int>& nodes,
                             const Vec3& total_force);

}  // namespace tongue::fem
