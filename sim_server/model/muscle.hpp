#pragma once
// A muscle as plain data (Gerard et al. 2003 sec. III.3.2, after Payan & Perrier 1997): a set
// of elements plus fibres, each fibre an ordered polyline of mesh nodes that may start at a fixed
// bony attachment. The forces the fibres exert are in muscle_forces.hpp.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fem/mesh/mesh_numbering.hpp"
#include "fem/types.hpp"

namespace tongue::model {

struct Fibre {
  std::vector<int> nodes;           // mesh node indices, in order along the fibre
  std::optional<fem::Vec3> origin;  // fixed attachment before nodes[0] (bone) [m]
  double weight = 1.0;              // share of the muscle's force; a muscle's weights sum to 1
};

struct Muscle {
  std::string name;
  std::vector<int> elements;  // the muscle's volume, for output and display
  std::vector<Fibre> fibres;
  double max_force = 0.0;  // F_max [N]: total tension of all fibres at full activation
};

// Tolerance on the sum of a muscle's fibre weights.
inline constexpr double kWeightSumTolerance = 1e-9;

// Throws std::invalid_argument, naming the muscle and the fibre, when: the name is empty; there
// are no fibres; a fibre has fewer than 2 points counting its origin; a node or element index is
// outside [0, num_nodes) or [0, num_elements); a node repeats consecutively (a zero-length
// segment has no direction); an origin is not finite; a weight is not finite and positive; the
// weights do not sum to 1 within kWeightSumTolerance (see normalize_weights); max_force is
// negative or not finite. Nodes and elements are named as numbering has them (the mesh file's ids
// with their index, for an imported mesh).
void validate(const Muscle& muscle, int num_nodes, int num_elements,
              const fem::MeshNumbering& numbering = {});

// Scales the fibre weights so that they sum to 1. Throws std::invalid_argument naming the muscle
// when it has no fibres or a weight is not finite and positive.
void normalize_weights(Muscle& muscle);

// Every pair of consecutive fibre nodes (a, b) with a < b, sorted and without repeats: the
// couplings the fibre stiffness needs, to be passed as SolidModel's extra_node_pairs.
std::vector<std::pair<int, int>> fibre_node_pairs(const std::vector<Muscle>& muscles);

}  // namespace tongue::model
