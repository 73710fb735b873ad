#pragma once
// How the user's files number a mesh's nodes and elements, so that every message names them as
// the user knows them. An imported mesh keeps its file's ids (ANSYS node and element numbers);
// a generated mesh has none and is numbered by its 0-based indices.
#include <map>
#include <string>
#include <vector>

namespace tongue::fem {

struct MeshNumbering {
  std::vector<long> node_ids;     // node_ids[i]: the file's id of node index i; empty: none
  std::vector<long> element_ids;  // likewise for elements

  // From an importer's id -> index tables (fem::ImportedMesh).
  static MeshNumbering from_index_maps(const std::map<long, int>& node_index_of_id,
                                       const std::map<long, int>& element_index_of_id);

  // "node 89 (index 88)" with file ids, "node 88" without (likewise "element ...").
  std::string node(int index) const;
  std::string element(int index) const;
};

}  // namespace tongue::fem
