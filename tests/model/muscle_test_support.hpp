#pragma once
// Small solids carrying muscles, shared by the muscle tests.
#include <memory>
#include <utility>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/box_generator.hpp"
#include "model/muscle.hpp"

namespace tongue::model::testing {

// A solid on the mesh whose pattern couples the consecutive fibre nodes of the muscles.
inline std::shared_ptr<const fem::SolidModel> make_solid(
    fem::Mesh mesh, const std::vector<Muscle>& muscles,
    const std::vector<fem::PrescribedDof>& prescribed = {}) {
  return std::make_shared<fem::SolidModel>(
      std::move(mesh), fem::make_material("neo_hookean", {{"shear_modulus", 5e3}}),
      fem::Formulation::mean_dilatation, 1000.0, prescribed, fibre_node_pairs(muscles));
}

// A 4 x 2 x 2 box of 10 mm cubes: node (i, j, k) = i + 5 (j + 3 k) sits at 10 mm (i, j, k).
inline fem::Mesh grid_box() {
  return fem::make_box(fem::Vec3::Zero(), fem::Vec3(0.04, 0.02, 0.02), 4, 2, 2);
}
inline int grid_node(int i, int j, int k) {
  return i + 5 * (j + 3 * k);
}

inline Fibre fibre(std::vector<int> nodes, double weight = 1.0) {
  Fibre f;
  f.nodes = std::move(nodes);
  f.weight = weight;
  return f;
}

inline Muscle muscle(std::string name, std::vector<Fibre> fibres, double max_force) {
  Muscle m;
  m.name = std::move(name);
  m.fibres = std::move(fibres);
  m.max_force = max_force;
  return m;
}

}  // namespace tongue::model::testing
