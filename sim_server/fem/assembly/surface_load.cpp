#include "fem/assembly/surface_load.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "fem/mesh/boundary_faces.hpp"

namespace tongue::fem {

Vector uniform_surface_force(const Mesh& mesh, const std::vector<int>& nodes,
                             const Vec3& total_force) {
  std::unordered_set<int> in_set(nodes.begin(), nodes.end());
  std::vector<Quad4> faces;
  for (const Quad4& face : boundary_faces(mesh)) {
    if (std::all_of(face.begin(), face.end(), [&](int n) { return in_set.count(n) > 0; })) {
      faces.push_back(face);
    }
  }
  if (faces.empty()) throw std::invalid_argument("no boundary face has all its nodes in the set");

  // int N_a dA per face node on the bilinear quad: |dx/dxi x dx/deta| at 2x2 Gauss points.
  const double g = 1.0 / std::sqrt(3.0);
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  Vector weight = Vector::Zero(3 * mesh.num_nodes());  // per node, stored in component 0
  double area = 0.0;
  for (const Quad4& face : faces) {
    for (int q = 0; q < 4; ++q) {
      const double xi = corner[q][0] * g, eta = corner[q][1] * g;
      Vec3 dxi = Vec3::Zero(), deta = Vec3::Zero();
      double N[4];
      for (int a = 0; a < 4; ++a) {
        N[a] = 0.25 * (1 + corner[a][0] * xi) * (1 + corner[a][1] * eta);
        dxi += 0.25 * corner[a][0] * (1 + corner[a][1] * eta) * mesh.nodes[face[a]];
        deta += 0.25 * (1 + corner[a][0] * xi) * corner[a][1] * mesh.nodes[face[a]];
      }
      const double dA = dxi.cross(deta).norm();
      area += dA;
      for (int a = 0; a < 4; ++a) weight[3 * face[a]] += N[a] * dA;
    }
  }
  Vector f = Vector::Zero(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (weight[3 * n] != 0.0) f.segment<3>(3 * n) = (weight[3 * n] / area) * total_force;
  }
  return f;
}

}  // namespace tongue::fem
