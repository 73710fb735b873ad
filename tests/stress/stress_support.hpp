#pragma once
// Shared by the stability stress tests: the built-in tongue's scene with the paper's material
// and boundary conditions, and an independent check that a deformed state has no inverted
// element (det dx/dxi > 0 at every Gauss point, computed here from the positions alone).
#include <cmath>
#include <string>
#include <vector>

#include "fem/element/hex8_shape.hpp"

namespace tongue::testing {

// The head of a tongue scene (paper sec. III): mesh, material (the paper's by default) at
// Poisson's ratio nu,
// constraints, gravity, Rayleigh damping, the built-in muscles. The caller adds activations,
// analysis, solver and output.
inline std::string tongue_scene_head(double nu = 0.49,
                                     const std::string& material = "mooney_rivlin5") {
  return R"(mesh:
  tongue: {refinement: 1}
material:
  type: )" +
         material + R"(
  parameters: {poisson_ratio: )" +
         std::to_string(nu) + R"(}
constraints:
  - {set: mandible, components: [x, y, z]}
  - {set: root_bottom, components: [y]}
  - {set: hyoid, components: [y, z]}
gravity: [0, -9.81, 0]
damping: {beta: 0.028}
muscles: builtin
)";
}

// The smallest det(dx/dxi) over all Gauss points of all elements at positions x (3 per node),
// relative to the same element's value at rest: <= 0 means an inverted element; also false for
// a position that is not finite.
inline double min_relative_jacobian(const std::vector<double>& rest, const std::vector<double>& x,
                                    const std::vector<int>& elements) {
  double worst = 1e300;
  for (std::size_t e = 0; e + 8 <= elements.size(); e += 8) {
    fem::hex8::ElementCoords X, Y;
    for (int a = 0; a < 8; ++a) {
      for (int c = 0; c < 3; ++c) {
        X(a, c) = rest[3 * elements[e + a] + c];
        Y(a, c) = x[3 * elements[e + a] + c];
      }
    }
    for (const auto& q : fem::hex8::gauss_2x2x2()) {
      const double ratio =
          fem::hex8::jacobian(Y, q.xi).determinant() / fem::hex8::jacobian(X, q.xi).determinant();
      if (!std::isfinite(ratio)) return -1.0;
      worst = std::min(worst, ratio);
    }
  }
  return worst;
}

}  // namespace tongue::testing
