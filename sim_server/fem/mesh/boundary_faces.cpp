#include "fem/mesh/boundary_faces.hpp"

#include <algorithm>
#include <map>

namespace tongue::fem {

std::vector<Quad4> boundary_faces(const Mesh& mesh) {
  // Local node indices of the six faces, each cyclic (order as in mesh.hpp).
  static constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::map<Quad4, std::pair<Quad4, int>> seen;  // sorted nodes -> (cyclic nodes, count)
  for (const Hex8& element : mesh.elements) {
    for (const auto& local : kFaces) {
      Quad4 face{element[local[0]], element[local[1]], element[local[2]], element[local[3]]};
      Quad4 key = face;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = seen.try_emplace(key, face, 0);
      ++it->second.second;
    }
  }
  std::vector<Quad4> faces;
  for (const auto& [key, entry] : seen) {
    if (entry.second == 1) faces.push_back(entry.first);
  }
  return faces;
}

std::vector<int> boundary_nodes(const Mesh& mesh) {
  std::vector<int> nodes;
  for (const Quad4& face : boundary_faces(mesh))
    nodes.insert(nodes.end(), face.begin(), face.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace tongue::fem
