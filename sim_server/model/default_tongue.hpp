#pragma once
// The built-in tongue: the fan grid, its muscles, its boundary conditions (Gerard et al. 2003,
// sec. III.3.1) and named landmarks, ready for a scene or a test.
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "model/muscle.hpp"
#include "model/tongue_geometry.hpp"
#include "model/tongue_muscles.hpp"

namespace tongue::model {

// Node sets the mesh carries:
//   boundary conditions: "mandible" (fixed), "root_bottom" (no vertical motion), "hyoid" (moves
//   only along x, forward/backward);
//   landmarks, one node each on the midsagittal dorsum unless said: "tip", "blade",
//   "palatal_dorsum", "velar_dorsum", "root" (the back, pharyngeal), "gg_insertion" (on the
//   arc around the insertion, fixed);
//   "midsagittal": every node on z = 0.
// Element sets: "all", and one per muscle, named as the muscle.
struct TongueModel {
  fem::Mesh mesh;
  std::vector<Muscle> muscles;
  TongueGrid grid;  // the grid the mesh came from (indices, sizes)
};

inline const std::vector<std::string>& landmark_names() {
  static const std::vector<std::string> names = {"tip",          "blade", "palatal_dorsum",
                                                 "velar_dorsum", "root",  "gg_insertion"};
  return names;
}

TongueModel make_default_tongue(int refinement = 1);

// Dirichlet conditions from a mesh's "mandible", "root_bottom" and "hyoid" node sets.
std::vector<fem::PrescribedDof> tongue_boundary_conditions(const fem::Mesh& mesh);

}  // namespace tongue::model
