#pragma once
// The total-Lagrangian trilinear hexahedron with 2x2x2 Gauss points (Bonet & Wood 2008, ch. 9),
// in two formulations:
//  - standard: W(F) integrated at every Gauss point; locks for nearly incompressible materials;
//  - mean dilatation (Q1/P0, Simo, Taylor & Pister 1985): for W = W_iso(C_bar) + U(J), the
//    volumetric energy uses the element's volume ratio J_bar = v / V, so the element energy is
//      E = sum_gp W_iso(F_gp) w_gp + V U(v / V),
//    and force and tangent are its exact first and second derivatives (the tangent stays
//    symmetric).
#include <array>

#include "fem/element/hex8_shape.hpp"
#include "fem/material/material.hpp"

namespace tongue::fem {

enum class Formulation { standard, mean_dilatation };

using ElementVector = Eigen::Matrix<double, 24, 1>;  // dof 3a + i: node a, component i
using ElementMatrix = Eigen::Matrix<double, 24, 24>;

// Reference-configuration data of one element, computed once.
struct ElementGeometry {
  std::array<hex8::ShapeGradients, 8> dN_dX;  // per Gauss point: row a = dN_a/dX
  std::array<double, 8> weight;               // Gauss weight x det(dX/dxi) [m^3]
  double volume = 0.0;                        // V [m^3]
};

// Throws std::invalid_argument when det(dX/dxi) <= 0 at a Gauss point.
ElementGeometry make_element_geometry(const hex8::ElementCoords& X);

struct ElementResponse {
  double energy = 0.0;      // strain energy [J]
  ElementVector force;      // internal force [N]
  ElementMatrix stiffness;  // d(force)/dx [N/m]; filled only when asked for
  double min_J = 0.0;       // smallest det F over the Gauss points
};

// Evaluates the element at current nodal positions x. Returns false, leaving the response
// undefined, when det F <= 0 at a Gauss point (an inverted element).
bool evaluate_element(const ElementGeometry& geometry, const hex8::ElementCoords& x,
                      const Material& material, Formulation formulation, bool want_stiffness,
                      ElementResponse& response);

// Consistent mass per unit density, M_ab = int N_a N_b dV (8x8; the 24x24 matrix is M_ab I_3).
Eigen::Matrix<double, 8, 8> element_mass_pattern(const hex8::ElementCoords& X);

// int N_a dV for each node (8), for body forces such as gravity.
Eigen::Matrix<double, 8, 1> element_shape_integrals(const ElementGeometry& geometry);

}  // namespace tongue::fem
