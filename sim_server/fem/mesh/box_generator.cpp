#include "fem/mesh/box_generator.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace tongue::fem {

namespace {

void check_counts(int n0, int n1, int n2) {
  if (n0 < 1 || n1 < 1 || n2 < 1) {
    throw std::invalid_argument("structured mesh needs at least one element per direction, got " +
                                std::to_string(n0) + " x " + std::to_string(n1) + " x " +
                                std::to_string(n2));
  }
}

// A structured (n0 + 1) x (n1 + 1) x (n2 + 1) node grid. position(i, j, k) must be a map with
// positive Jacobian so that the SOLID185 node order below gives positive element volumes.
class Grid {
 public:
  Grid(int n0, int n1, int n2) : n_{n0, n1, n2} {}

  int node(int i, int j, int k) const { return i + (n_[0] + 1) * (j + (n_[1] + 1) * k); }

  template <class Position>
  Mesh build(Position&& position) const {
    Mesh mesh;
    mesh.nodes.reserve(static_cast<std::size_t>(n_[0] + 1) * (n_[1] + 1) * (n_[2] + 1));
    for (int k = 0; k <= n_[2]; ++k)
      for (int j = 0; j <= n_[1]; ++j)
        for (int i = 0; i <= n_[0]; ++i) mesh.nodes.push_back(position(i, j, k));

    std::vector<int> all;
    for (int k = 0; k < n_[2]; ++k)
      for (int j = 0; j < n_[1]; ++j)
        for (int i = 0; i < n_[0]; ++i) {
          // Bottom face counter-clockwise seen from +k, then the top face in the same order.
          mesh.elements.push_back({node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                                   node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                                   node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
          all.push_back(mesh.num_elements() - 1);
        }
    mesh.element_sets["all"] = std::move(all);
    return mesh;
  }

  // Nodes with grid index `value` in direction `axis`, ascending (the index grows fastest in i).
  std::vector<int> layer(int axis, int value) const {
    std::vector<int> result;
    for (int k = 0; k <= n_[2]; ++k)
      for (int j = 0; j <= n_[1]; ++j)
        for (int i = 0; i <= n_[0]; ++i) {
          const int ijk[3] = {i, j, k};
          if (ijk[axis] == value) result.push_back(node(i, j, k));
        }
    return result;
  }

  // The nodes (i, j, k) for k = 0..n2, ascending.
  std::vector<int> column(int i, int j) const {
    std::vector<int> result;
    for (int k = 0; k <= n_[2]; ++k) result.push_back(node(i, j, k));
    return result;
  }

  int n(int axis) const { return n_[axis]; }

 private:
  std::array<int, 3> n_;
};

// Fraction i / n, exactly 1 at i == n so that far faces land exactly on origin + size.
double fraction(int i, int n) {
  return i == n ? 1.0 : static_cast<double>(i) / n;
}

}  // namespace

Mesh make_box(const Vec3& origin, const Vec3& size, int nx, int ny, int nz) {
  check_counts(nx, ny, nz);
  if (!(size.array() > 0).all()) {
    throw std::invalid_argument("box size must be positive in x, y and z");
  }
  const Grid grid(nx, ny, nz);
  Mesh mesh = grid.build([&](int i, int j, int k) {
    return Vec3(origin.x() + size.x() * fraction(i, nx), origin.y() + size.y() * fraction(j, ny),
                origin.z() + size.z() * fraction(k, nz));
  });
  const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
  for (int axis = 0; axis < 3; ++axis) {
    mesh.node_sets[names[axis][0]] = grid.layer(axis, 0);
    mesh.node_sets[names[axis][1]] = grid.layer(axis, grid.n(axis));
  }
  return mesh;
}

Mesh map_nodes(Mesh mesh, const std::function<Vec3(const Vec3&)>& f) {
  for (Vec3& x : mesh.nodes) x = f(x);
  return mesh;
}

Mesh make_quad_extrusion(const std::array<Eigen::Vector2d, 4>& corners, double thickness, int n_xi,
                         int n_eta, int n_z) {
  check_counts(n_xi, n_eta, n_z);
  if (!(thickness > 0)) throw std::invalid_argument("extrusion thickness must be positive");
  // The bilinear map has positive Jacobian everywhere iff it is positive at the four corners
  // (its determinant is bilinear in (xi, eta)), i.e. iff every corner turns left.
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector2d a = corners[(c + 1) % 4] - corners[c];
    const Eigen::Vector2d b = corners[(c + 3) % 4] - corners[c];
    if (!(a.x() * b.y() - a.y() * b.x() > 0)) {
      throw std::invalid_argument(
          "quadrilateral corners must be strictly convex and counter-clockwise (corner " +
          std::to_string(c) + ")");
    }
  }
  const Grid grid(n_xi, n_eta, n_z);
  Mesh mesh = grid.build([&](int i, int j, int k) {
    const double s = fraction(i, n_xi), t = fraction(j, n_eta);
    const Eigen::Vector2d p = (1 - s) * (1 - t) * corners[0] + s * (1 - t) * corners[1] +
                              s * t * corners[2] + (1 - s) * t * corners[3];
    return Vec3(p.x(), p.y(), thickness * fraction(k, n_z));
  });
  mesh.node_sets["left"] = grid.layer(0, 0);
  mesh.node_sets["right"] = grid.layer(0, n_xi);
  mesh.node_sets["bottom"] = grid.layer(1, 0);
  mesh.node_sets["top"] = grid.layer(1, n_eta);
  mesh.node_sets["z_min"] = grid.layer(2, 0);
  mesh.node_sets["z_max"] = grid.layer(2, n_z);
  mesh.node_sets["corner_bottom_left"] = grid.column(0, 0);
  mesh.node_sets["corner_bottom_right"] = grid.column(n_xi, 0);
  mesh.node_sets["corner_top_right"] = grid.column(n_xi, n_eta);
  mesh.node_sets["corner_top_left"] = grid.column(0, n_eta);
  return mesh;
}

}  // namespace tongue::fem
