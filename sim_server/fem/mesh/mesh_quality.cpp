#include "fem/mesh/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <Eigen/LU>  // determinant()

#include "fem/element/hex8_shape.hpp"

namespace tongue::fem {

hex8::ElementCoords element_coords(const Mesh& mesh, int element) {
  if (element < 0 || element >= mesh.num_elements()) {
    throw std::out_of_range("element index " + std::to_string(element) + " out of range [0, " +
                            std::to_string(mesh.num_elements()) + ")");
  }
  hex8::ElementCoords X;
  const Hex8& nodes = mesh.elements[element];
  for (int a = 0; a < 8; ++a) X.row(a) = mesh.nodes.at(nodes[a]).transpose();
  return X;
}

std::array<double, 8> nodal_jacobian_determinants(const Mesh& mesh, int element) {
  const hex8::ElementCoords X = element_coords(mesh, element);
  std::array<double, 8> dets{};
  for (int a = 0; a < 8; ++a) {
    const auto& c = hex8::kNodeCoords[a];
    dets[a] = hex8::jacobian(X, Vec3(c[0], c[1], c[2])).determinant();
  }
  return dets;
}

bool is_regular(const Mesh& mesh, int element) {
  const auto dets = nodal_jacobian_determinants(mesh, element);
  return std::all_of(dets.begin(), dets.end(), [](double d) { return d > 0; });
}

double element_volume(const Mesh& mesh, int element) {
  const hex8::ElementCoords X = element_coords(mesh, element);
  double volume = 0.0;
  for (const auto& qp : hex8::gauss_2x2x2()) {
    volume += qp.weight * hex8::jacobian(X, qp.xi).determinant();
  }
  return volume;
}

std::string bounding_box_text(const Mesh& mesh) {
  if (mesh.nodes.empty()) return "empty (no nodes)";
  Vec3 lo = mesh.nodes.front(), hi = lo;
  for (const Vec3& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const Vec3 size = hi - lo;
  char text[200];
  std::snprintf(text, sizeof text,
                "%.4g x %.4g x %.4g m (from (%.4g, %.4g, %.4g) to (%.4g, %.4g, %.4g) m)", size.x(),
                size.y(), size.z(), lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
  return text;
}

std::string implausible_size(const Mesh& mesh, double volume) {
  if (volume >= kSmallestPlausibleVolume) return {};
  char text[120];
  std::snprintf(text, sizeof text, "the mesh's volume is %.4g m^3 (less than 1 mm^3)", volume);
  return std::string(text) + " in a bounding box of " + bounding_box_text(mesh) +
         ": is its length unit right (metres per file unit: 1 for m, 0.001 for mm)?";
}

QualityReport check_quality(const Mesh& mesh) {
  QualityReport report;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto dets = nodal_jacobian_determinants(mesh, e);
    const auto [lo, hi] = std::minmax_element(dets.begin(), dets.end());
    // Scaling by the largest magnitude keeps the ratio meaningful (<= 0) when every nodal
    // determinant is negative, where min/max would be positive.
    const double scale = std::max(std::abs(*lo), std::abs(*hi));
    const double ratio = scale > 0 ? *lo / scale : 0.0;
    if (!(*lo > 0)) {
      ++report.num_irregular;
      report.irregular_elements.push_back(e);
    }
    if (report.worst_element < 0 || ratio < report.worst_ratio) {
      report.worst_ratio = ratio;
      report.worst_element = e;
    }
    report.total_volume += element_volume(mesh, e);
  }
  return report;
}

}  // namespace tongue::fem
