#pragma once
// A hexahedral mesh: rest positions, 8-node elements, and named node and element sets.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::fem {

// Node order of a trilinear hexahedron: the bottom face (zeta = -1) counter-clockwise seen from
// above, then the top face (zeta = +1) in the same order; this is the ANSYS SOLID185 order.
using Hex8 = std::array<int, 8>;

struct Mesh {
  std::vector<Vec3> nodes;                               // rest positions [m]
  std::vector<Hex8> elements;                            // indices into nodes
  std::map<std::string, std::vector<int>> node_sets;     // sorted, unique node indices
  std::map<std::string, std::vector<int>> element_sets;  // sorted, unique element indices

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }

  // Looks a set up by name; throws std::invalid_argument naming the set when it is missing.
  const std::vector<int>& node_set(const std::string& name) const;
  const std::vector<int>& element_set(const std::string& name) const;
};

// Node indices whose rest position lies in the closed box [lo, hi] (inclusive, with tolerance
// tol [m] on every side), sorted.
std::vector<int> nodes_in_box(const Mesh& mesh, const Vec3& lo, const Vec3& hi, double tol = 1e-12);

// A mesh read from an external file together with the file's own node and element ids, so that
// scenes can refer to imported entities by the ids shown in the meshing tool.
struct ImportedMesh {
  Mesh mesh;
  std::map<long, int> node_index_of_id;     // external node id -> index into mesh.nodes
  std::map<long, int> element_index_of_id;  // external element id -> index into mesh.elements
};

}  // namespace tongue::fem
