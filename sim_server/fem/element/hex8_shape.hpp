#pragma once
// Trilinear shape functions of the 8-node hexahedron on the reference cube [-1, 1]^3, and the
// 2x2x2 Gauss rule (Hughes 2000, sec. 3.5). Node order as in fem/mesh/mesh.hpp.
#include <array>

#include "fem/types.hpp"

namespace tongue::fem::hex8 {

// Reference coordinates (xi, eta, zeta) of the 8 nodes.
inline constexpr std::array<std::array<double, 3>, 8> kNodeCoords = {{
    {-1, -1, -1},
    {1, -1, -1},
    {1, 1, -1},
    {-1, 1, -1},
    {-1, -1, 1},
    {1, -1, 1},
    {1, 1, 1},
    {-1, 1, 1},
}};

using ShapeValues = Eigen::Matrix<double, 8, 1>;
using ShapeGradients = Eigen::Matrix<double, 8, 3>;  // row a: dN_a / d(xi, eta, zeta)

ShapeValues values(const Vec3& xi);
ShapeGradients reference_gradients(const Vec3& xi);

struct QuadraturePoint {
  Vec3 xi;
  double weight;
};
// The 2x2x2 Gauss-Legendre rule: points at +-1/sqrt(3), unit weights.
const std::array<QuadraturePoint, 8>& gauss_2x2x2();

// Nodal coordinates of one element as an 8x3 matrix (row a = node a).
using ElementCoords = Eigen::Matrix<double, 8, 3>;

// Jacobian dX/dxi (3x3, column k = d/dxi_k) of the isoparametric map at xi.
inline Mat3 jacobian(const ElementCoords& X, const Vec3& xi) {
  return X.transpose() * reference_gradients(xi);
}

}  // namespace tongue::fem::hex8
