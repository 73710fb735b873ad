#pragma once
// The boundary of a hexahedral mesh: element faces that belong to exactly one element.
#include <array>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

// Four node indices in cyclic order around the face.
using Quad4 = std::array<int, 4>;

std::vector<Quad4> boundary_faces(const Mesh& mesh);

// Sorted indices of the nodes on the boundary.
std::vector<int> boundary_nodes(const Mesh& mesh);

}  // namespace tongue::fem
