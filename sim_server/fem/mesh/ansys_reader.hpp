#pragma once
// Importer for hexahedral meshes written by ANSYS NWRITE (nodes) and EWRITE (elements) as text.
#include <stdexcept>
#include <string>

#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

// A malformed or unreadable mesh file. what() reads "<path>, line <n>: <reason>" for an error
// on a given line and "<path>: <reason>" for one concerning the whole file.
class MeshReadError : public std::runtime_error {
 public:
  MeshReadError(const std::string& path, int line, const std::string& reason);

  const std::string& path() const { return path_; }
  int line() const { return line_; }  // 1-based; 0 when the error concerns the whole file

 private:
  std::string path_;
  int line_;
};

// Reads an NWRITE node file and an EWRITE element file of 8-node hexahedra (SOLID185 order).
//
// Node lines: "id x y z [thxy thyz thzx]", whitespace separated. NWRITE leaves trailing zero
// fields blank, so missing trailing coordinates are 0; the nodal rotation angles only orient
// nodal degrees of freedom in ANSYS and are checked to be numeric, then ignored.
// Element lines: 14 integers "n1 .. n8 mat type real secnum esys id".
// Blank lines are skipped. Ids are positive and need be neither contiguous nor sorted; nodes and
// elements get indices in file order. Coordinates are multiplied by length_scale (e.g. 1e-3 for
// a file in mm) to give metres.
//
// The result has element sets "all" and "mat_<n>" for every material number n in the file.
// Throws MeshReadError for a missing, unreadable or empty file, a malformed line, a non-positive
// or duplicate id, an element naming an unknown node or the same node twice, and an element
// that has no volume or is inside out (negative volume, or Jacobian determinant non-positive at
// all 8 nodes).
// Elements that are merely irregular (some nodal determinants negative) are accepted; see
// fem/mesh/mesh_quality.hpp. Throws std::invalid_argument for a non-positive length_scale.
ImportedMesh read_ansys_mesh(const std::string& nodes_path, const std::string& elements_path,
                             double length_scale = 1.0);

}  // namespace tongue::fem
