#pragma once
// Element quality of trilinear hexahedra by the Jacobian determinant at the 8 nodes
// (Luboz et al. 2001): an element is regular when all 8 nodal determinants are positive, which
// is the condition for the isoparametric map to be invertible at the nodes.
#include <array>
#include <string>
#include <vector>

#include "fem/element/hex8_shape.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

// The rest positions of one element's 8 nodes (row a = node a); throws std::out_of_range for a
// bad element index.
hex8::ElementCoords element_coords(const Mesh& mesh, int element);

// det(dX/dxi) at each corner xi = hex8::kNodeCoords[a], a = 0..7. For an undistorted cube of
// side h every entry is (h / 2)^3. Throws std::out_of_range for a bad element index.
std::array<double, 8> nodal_jacobian_determinants(const Mesh& mesh, int element);

// True when all 8 nodal Jacobian determinants are strictly positive.
bool is_regular(const Mesh& mesh, int element);

// Rest volume [m^3] by 2x2x2 Gauss quadrature, exact for a trilinear map because det J is at
// most quadratic in each reference coordinate. Negative for an inside-out element.
double element_volume(const Mesh& mesh, int element);

struct QualityReport {
  int num_irregular = 0;
  std::vector<int> irregular_elements;  // ascending
  // Minimum over elements of min_a det_a / max_a |det_a|: 1 for parallelepipeds, in (0, 1] for
  // regular elements and <= 0 for irregular ones (equals min/max det whenever max det > 0).
  // 1 for a mesh without elements.
  double worst_ratio = 1.0;
  int worst_element = -1;     // element attaining worst_ratio, -1 for a mesh without elements
  double total_volume = 0.0;  // sum of element_volume [m^3]
};

QualityReport check_quality(const Mesh& mesh);

// A rest volume below this [m^3] is taken for a wrong length unit, not a body: one cubic
// millimetre. The tongue is 1.6e-4 m^3; its file in metres read as if in millimetres would be
// 1.6e-13 m^3.
inline constexpr double kSmallestPlausibleVolume = 1e-9;

// "X x Y x Z m (from (x, y, z) to (x, y, z) m)": the mesh's bounding box, for messages about
// its size.
std::string bounding_box_text(const Mesh& mesh);

// Why a mesh of this volume [m^3] is not plausible (zero, negative, or below
// kSmallestPlausibleVolume), naming its bounding box; empty when it is.
std::string implausible_size(const Mesh& mesh, double volume);

}  // namespace tongue::fem
