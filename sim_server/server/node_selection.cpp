#include "server/node_selection.hpp"

#include <cstddef>
#include <numeric>
#include <stdexcept>

#include "fem/mesh/boundary_faces.hpp"
#include "model/default_tongue.hpp"

namespace tongue::server {

std::vector<int> select_nodes(const fem::Mesh& mesh, Nodes nodes, const std::string& source) {
  std::vector<int> indices;
  switch (nodes) {
    case Nodes::all:
      indices.resize(static_cast<std::size_t>(mesh.num_nodes()));
      std::iota(indices.begin(), indices.end(), 0);
      break;
    case Nodes::surface:
      indices = fem::boundary_nodes(mesh);
      break;
    case Nodes::midsagittal: {
      const auto it = mesh.node_sets.find("midsagittal");
      if (it == mesh.node_sets.end() || it->second.empty())
        throw std::invalid_argument(source +
                                    ": the mesh has no \"midsagittal\" node set (the node subset "
                                    "midsagittal needs one; the built-in tongue has it)");
      indices = it->second;
      break;
    }
    case Nodes::landmarks:
      for (const std::string& name : model::landmark_names()) {
        const auto it = mesh.node_sets.find(name);
        if (it != mesh.node_sets.end() && !it->second.empty())
          indices.push_back(it->second.front());
      }
      if (indices.empty())
        throw std::invalid_argument(source +
                                    ": the mesh has none of the landmark node sets (tip, blade, "
                                    "palatal_dorsum, velar_dorsum, root, gg_insertion) the node "
                                    "subset landmarks needs; the built-in tongue has them");
      break;
  }
  return indices;
}

}  // namespace tongue::server
