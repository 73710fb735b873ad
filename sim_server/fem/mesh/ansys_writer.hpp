#pragma once
// Writer for hexahedral meshes in the ANSYS NWRITE (nodes) and EWRITE (elements) text format
// that fem/mesh/ansys_reader.hpp reads, so a mesh can be repaired here and read back anywhere.
#include <string>

#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

// Writes node lines "id x y z" (coordinates divided by length_scale, e.g. 1e-3 for a file in mm,
// 17 significant digits so that reading back with the same scale gives the same doubles up to
// the rounding of the scale) and element lines of 14 integers "n1 .. n8 mat type real secnum
// esys id" in SOLID185 order.
// Ids are those of node_index_of_id and element_index_of_id; when a map is empty the ids are
// index + 1 (a generated mesh), when it is partial the mesh is rejected. mat is n from the
// element set "mat_<n>" holding the element (as the reader makes them), 1 if none does. The
// reader keeps neither type, real, secnum nor esys: they are written as 1, 1, 1 and 0 (the first
// type, real constant and section, in the global Cartesian system).
// Throws std::invalid_argument for a non-positive length_scale, incomplete or duplicate ids, or
// an element in two mat_<n> sets, and std::runtime_error naming the file when it cannot be written.
void write_ansys_mesh(const ImportedMesh& mesh, const std::string& nodes_path,
                      const std::string& elements_path, double length_scale = 1.0);

}  // namespace tongue::fem
