#include "fem/mesh/mesh.hpp"

#include <stdexcept>

namespace tongue::fem {

namespace {

// Shared by node_set and element_set: the message lists what does exist, because a missing set
// is almost always a typo in a scene file.
const std::vector<int>& find_set(const std::map<std::string, std::vector<int>>& sets,
                                 const std::string& name, const char* kind) {
  const auto it = sets.find(name);
  if (it != sets.end()) return it->second;
  std::string available;
  for (const auto& [key, members] : sets) {
    if (!available.empty()) available += ", ";
    available += "'" + key + "'";
  }
  if (available.empty()) available = "(none)";
  throw std::invalid_argument(std::string("no ") + kind + " set named '" + name + "'; available " +
                              kind + " sets: " + available);
}

}  // namespace

const std::vector<int>& Mesh::node_set(const std::string& name) const {
  return find_set(node_sets, name, "node");
}

const std::vector<int>& Mesh::element_set(const std::string& name) const {
  return find_set(element_sets, name, "element");
}

std::vector<int> nodes_in_box(const Mesh& mesh, const Vec3& lo, const Vec3& hi, double tol) {
  std::vector<int> result;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3& x = mesh.nodes[n];
    if ((x.array() >= lo.array() - tol).all() && (x.array() <= hi.array() + tol).all()) {
      result.push_back(n);
    }
  }
  return result;  // ascending by construction
}

}  // namespace tongue::fem
