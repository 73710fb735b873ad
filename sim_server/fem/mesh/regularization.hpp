#pragma once
// Mesh regularization after Luboz et al. (2001), as applied to the tongue mesh in Gerard et al.
// (2003), sec. II.3: the nodes of irregular elements (nodal Jacobian determinant not positive at
// some of the 8 corners, see fem/mesh/mesh_quality.hpp) are moved step by step along the analytic
// gradient of that determinant until every element is regular, and never farther than a bound
// (1 mm in the paper) from where they started.
#include <array>
#include <string>
#include <vector>

#include "fem/element/hex8_shape.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

struct RegularizationSettings {
  double max_displacement = 1e-3;  // m, no node ends farther than this from where it started
  int max_iterations = 2000;
  // Relaxation: the fraction of the linearized correction (the step that would bring a corner's
  // determinant to twice its target were it linear) taken per iteration, in (0, 1].
  // Dimensionless, so the same value serves a mesh in any unit or size.
  double step = 0.5;
  // A corrected corner is driven to det J >= min_det_ratio * L1 L2 L3 / 8, where L_k is the mean
  // edge length of the element along reference direction k (L1 L2 L3 / 8 is every nodal
  // determinant of a box of those edges). In (0, 1). A positive margin, rather than just det > 0,
  // keeps the result regular after round-off (e.g. writing to text) and away from nearly
  // singular corners, which invert again at the first compression in a simulation.
  double min_det_ratio = 0.05;
  // Per iteration no node moves more than this fraction of the smallest edge scale min_k L_k of
  // the elements it is corrected for; keeps summed contributions of shared nodes from jumping.
  double max_step_ratio = 0.05;
};

struct RegularizationReport {
  bool success = false;  // every element regular at the end
  int iterations = 0;    // correction sweeps applied
  int irregular_before = 0, irregular_after = 0;
  double max_node_displacement = 0.0;  // m, max over nodes of |x_final - x_start|
  std::vector<int> still_irregular;    // element indices, ascending
  std::string message;
};

// Regularizes mesh.nodes in place; connectivity and sets are kept. Only elements that are, or
// became during the run, irregular are corrected; regular elements of the input are left as they
// are however poor. Nodes in fixed_nodes never move. A first phase makes the mesh regular with a
// tenth of the margin, a second raises the corrected corners to min_det_ratio with what is left
// of the bound (undone should it make an element irregular). Each phase stops when its target is
// reached, when no node can move (all held), after 200 sweeps without progress, or when the
// max_iterations sweeps of both phases are spent. success only says that every element is
// regular at the end. Throws std::invalid_argument for settings out of range or a fixed node
// index out of range, std::out_of_range for an element naming a node that does not exist.
RegularizationReport regularize(Mesh& mesh, const RegularizationSettings& settings = {},
                                const std::vector<int>& fixed_nodes = {});

// The element corners joined to corner a by an edge, along xi, eta and zeta in that order.
std::array<int, 3> corner_neighbours(int corner);

// Closed form of the nodal Jacobian determinant at a corner. At corner a (reference coordinates
// s = hex8::kNodeCoords[a]) only N_a and the shape function of the neighbour n_k along xi_k have a
// non-zero derivative along xi_k, so column k of dX/dxi is -s_k (X_{n_k} - X_a) / 2 and
//   D_a = -(s_1 s_2 s_3) / 8 * e_1 . (e_2 x e_3),   e_k = X_{n_k} - X_a,
// six times the signed volume of the tetrahedron of the corner and its three neighbours, times
// -(s_1 s_2 s_3) / 8. Equals nodal_jacobian_determinants()[a].
double nodal_jacobian_determinant(const hex8::ElementCoords& X, int corner);

// Gradient of D_a with respect to the 8 node positions of the element, row b = dD_a / dX_b.
// D_a is a triple product, so with c = -(s_1 s_2 s_3) / 8:
//   dD_a/dX_{n_1} = c e_2 x e_3,  dD_a/dX_{n_2} = c e_3 x e_1,  dD_a/dX_{n_3} = c e_1 x e_2,
//   dD_a/dX_a = -(sum of those three),
// and rows of the 4 corners not joined to a are zero. D_a is affine in each single node, so a
// node moved alone along its row changes D_a exactly linearly.
hex8::ElementCoords nodal_jacobian_gradient(const hex8::ElementCoords& X, int corner);
// The same for an element of a mesh; throws std::out_of_range for a bad element or corner.
hex8::ElementCoords nodal_jacobian_gradient(const Mesh& mesh, int element, int corner);

}  // namespace tongue::fem
