#include "fem/mesh/mesh_numbering.hpp"

namespace tongue::fem {

namespace {

std::vector<long> ids_by_index(const std::map<long, int>& index_of_id) {
  std::vector<long> ids(index_of_id.size(), 0);
  for (const auto& [id, index] : index_of_id)
    if (index >= 0 && static_cast<std::size_t>(index) < ids.size()) ids[index] = id;
  return ids;
}

std::string label(const char* what, const std::vector<long>& ids, int index) {
  if (index >= 0 && static_cast<std::size_t>(index) < ids.size())
    return std::string(what) + " " + std::to_string(ids[index]) + " (index " +
           std::to_string(index) + ")";
  return std::string(what) + " " + std::to_string(index);
}

}  // namespace

MeshNumbering MeshNumbering::from_index_maps(const std::map<long, int>& node_index_of_id,
                                             const std::map<long, int>& element_index_of_id) {
  return {ids_by_index(node_index_of_id), ids_by_index(element_index_of_id)};
}

std::string MeshNumbering::node(int index) const {
  return label("node", node_ids, index);
}

std::string MeshNumbering::element(int index) const {
  return label("element", element_ids, index);
}

}  // namespace tongue::fem
