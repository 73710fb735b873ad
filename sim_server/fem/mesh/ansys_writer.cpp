#include "fem/mesh/ansys_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace tongue::fem {

namespace {

// ANSYS element attributes the reader does not keep; 1 is the first entry of each table.

constexpr long kDefaultMaterial = 1;

// External id of every index: from the import map, or index + 1 when there is none.
std::vector<long> ids_by_index(const std::map<long, int>& index_of_id, int count,
                               const char* what) {
  std::vector<long> ids(count, 0);
  if (index_of_id.empty()) {
    for (int i = 0; i < count; ++i) ids[i] = i + 1;
    return ids;
  }
  for (const auto& [id, index] : index_of_id) {
    if (id <= 0) {
      throw std::invalid_argument(std::string("write_ansys_mesh: ") + what + " id " +
                                  std::to_string(id) + " is not positive");
    }
    if (index < 0 || index >= count || ids[index] != 0) {
      throw std::invalid_argument(std::string("write_ansys_mesh: ") + what + " id " +
                                  std::to_string(id) + " maps to a bad or repeated index " +
                                  std::to_string(index));
    }
    ids[index] = id;
  }
  for (int i = 0; i < count; ++i) {
    if (ids[i] == 0) {
      throw std::invalid_argument(std::string("write_ansys_mesh: ") + what + " " +
                                  std::to_string(i) + " has no id");
    }
  }
  return ids;
}

// Material number of every element from the reader's "mat_<n>" element sets.
std::vector<long> materials_by_element(const Mesh& mesh) {
  std::vector<long> material(mesh.num_elements(), kDefaultMaterial);
  std::vector<char> seen(mesh.num_elements(), 0);
  const std::string prefix = "mat_";
  for (const auto& [name, elements] : mesh.element_sets) {
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    long n = 0;
    const char* first = name.data() + prefix.size();
    const char* last = name.data() + name.size();
    const auto [end, ec] = std::from_chars(first, last, n);
    if (ec != std::errc() || end != last) continue;  // e.g. "mat_tongue": not a material number
    for (int e : elements) {
      if (e < 0 || e >= mesh.num_elements()) {
        throw std::invalid_argument("write_ansys_mesh: element set '" + name +
                                    "' holds a bad element index " + std::to_string(e));
      }
      if (seen[e]) {
        throw std::invalid_argument("write_ansys_mesh: element " + std::to_string(e) +
                                    " is in two material sets (the second is '" + name + "')");
      }
      seen[e] = 1;
      material[e] = n;
    }
  }
  return material;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::string& path, const char* what) {
  File f(std::fopen(path.c_str(), "w"));
  if (!f) {
    throw std::runtime_error(path + ": cannot open " + what + " file for writing");
  }
  return f;
}

// fclose reports the errors of buffered writes, so it is checked rather than left to the deleter.
void close_checked(File f, const std::string& path, const char* what) {
  const bool write_failed = std::ferror(f.get()) != 0;
  if (std::fclose(f.release()) != 0 || write_failed) {
    throw std::runtime_error(path + ": error writing " + what + " file");
  }
}

}  // namespace

void write_ansys_mesh(const ImportedMesh& imported, const std::string& nodes_path,
                      const std::string& elements_path, double length_scale) {
  if (!(length_scale > 0) || !std::isfinite(length_scale)) {
    throw std::invalid_argument("write_ansys_mesh: length_scale must be positive and finite");
  }
  const Mesh& mesh = imported.mesh;
  const std::vector<long> node_ids =
      ids_by_index(imported.node_index_of_id, mesh.num_nodes(), "node");
  const std::vector<long> element_ids =
      ids_by_index(imported.element_index_of_id, mesh.num_elements(), "element");
  const std::vector<long> materials = materials_by_element(mesh);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int n : mesh.elements[e]) {
      if (n < 0 || n >= mesh.num_nodes()) {
        throw std::invalid_argument("write_ansys_mesh: element " + std::to_string(e) +
                                    " refers to a bad node index " + std::to_string(n));
      }
    }
  }

  // Columns as wide as NWRITE's I9 ids; %.16E (17 significant digits) restores every double.
  File nodes = open_for_writing(nodes_path, "node");
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const Vec3 x = mesh.nodes[i] / length_scale;
    std::fprintf(nodes.get(), "%9ld %24.16E %24.16E %24.16E\n", node_ids[i], x.x(), x.y(), x.z());
  }
  close_checked(std::move(nodes), nodes_path, "node");

  // A space before every field keeps ids of more than 8 digits apart.
  File elements = open_for_writing(elements_path, "element");
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int n : mesh.elements[e]) std::fprintf(elements.get(), " %8ld", node_ids[n]);
    std::fprintf(elements.get(), " %8ld", materials[e]);
    // type, real and secnum 1 (the first of each), esys 0 (the global Cartesian system).
    std::fprintf(elements.get(), " %8d %8d %8d %8d", 1, 1, 1, 0);
    std::fprintf(elements.get(), " %8ld\n", element_ids[e]);
  }
  close_checked(std::move(elements), elements_path, "element");
}

}  // namespace tongue::fem
