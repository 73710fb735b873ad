#pragma once
// Triangle surfaces with known exact geometry for the contact tests.
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "fem/contact/obstacle.hpp"

namespace tongue::fem::test {

// A sphere of radius r about c: an icosahedron whose triangles are split in four `level` times,
// new vertices pushed onto the sphere; outward normals.
inline TriangleSurface icosphere(const Vec3& c, double r, int level) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleSurface s;
  for (const Vec3& v : {Vec3(-1, g, 0), Vec3(1, g, 0), Vec3(-1, -g, 0), Vec3(1, -g, 0),
                        Vec3(0, -1, g), Vec3(0, 1, g), Vec3(0, -1, -g), Vec3(0, 1, -g),
                        Vec3(g, 0, -1), Vec3(g, 0, 1), Vec3(-g, 0, -1), Vec3(-g, 0, 1)})
    s.vertices.push_back(v.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      return middle[key] = static_cast<int>(s.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : s.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = std::move(finer);
  }
  for (Vec3& v : s.vertices) v = c + r * v;
  return s;
}

// A square of side 2 h centred at c, normal n, split into 2 n_div^2 triangles (open).
inline TriangleSurface square(const Vec3& c, const Vec3& n, double h, int n_div = 1) {
  const Vec3 normal = n.normalized();
  const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  TriangleSurface s;
  for (int j = 0; j <= n_div; ++j)
    for (int i = 0; i <= n_div; ++i)
      s.vertices.push_back(c + h * ((2.0 * i / n_div - 1.0) * e1 + (2.0 * j / n_div - 1.0) * e2));
  const auto id = [&](int i, int j) { return j * (n_div + 1) + i; };
  for (int j = 0; j < n_div; ++j)
    for (int i = 0; i < n_div; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

}  // namespace tongue::fem::test
