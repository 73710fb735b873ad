#include "fem/element/hex8_shape.hpp"

#include <cmath>

namespace tongue::fem::hex8 {

ShapeValues values(const Vec3& xi) {
  ShapeValues N;
  for (int a = 0; a < 8; ++a) {
    const auto& c = kNodeCoords[a];
    N(a) = 0.125 * (1 + c[0] * xi(0)) * (1 + c[1] * xi(1)) * (1 + c[2] * xi(2));
  }
  return N;
}

ShapeGradients reference_gradients(const Vec3& xi) {
  ShapeGradients G;
  for (int a = 0; a < 8; ++a) {
    const auto& c = kNodeCoords[a];
    const double f0 = 1 + c[0] * xi(0), f1 = 1 + c[1] * xi(1), f2 = 1 + c[2] * xi(2);
    G(a, 0) = 0.125 * c[0] * f1 * f2;
    G(a, 1) = 0.125 * f0 * c[1] * f2;
    G(a, 2) = 0.125 * f0 * f1 * c[2];
  }
  return G;
}

const std::array<QuadraturePoint, 8>& gauss_2x2x2() {
  static const std::array<QuadraturePoint, 8> rule = [] {
    std::array<QuadraturePoint, 8> r{};
    const double g = 1.0 / std::sqrt(3.0);
    for (int a = 0; a < 8; ++a) {
      const auto& c = kNodeCoords[a];
      r[a] = {Vec3(c[0] * g, c[1] * g, c[2] * g), 1.0};
    }
    return r;
  }();
  return rule;
}

}  // namespace tongue::fem::hex8
