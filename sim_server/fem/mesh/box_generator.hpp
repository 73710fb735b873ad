#pragma once
// Structured hexahedral meshes for tests and benchmarks: an axis-aligned box, and a
// bilinearly mapped quadrilateral extruded in z (e.g. Cook's membrane).
#include <array>
#include <functional>

#include "fem/mesh/mesh.hpp"
#include "fem/types.hpp"

namespace tongue::fem {

// A box [origin, origin + size] split into nx * ny * nz equal hex8 elements with positive
// Jacobian. Node (i, j, k), 0 <= i <= nx etc., has index i + (nx + 1) * (j + (ny + 1) * k).
// Node sets: "x_min", "x_max", "y_min", "y_max", "z_min", "z_max" (the six faces).
// Element set: "all". Throws std::invalid_argument for n < 1 or a non-positive size.
Mesh make_box(const Vec3& origin, const Vec3& size, int nx, int ny, int nz);

// Returns the mesh with every rest position replaced by f(position); connectivity and sets are
// kept. Useful to build distorted meshes; the caller is responsible for keeping Jacobians positive.
Mesh map_nodes(Mesh mesh, const std::function<Vec3(const Vec3&)>& f);

// A quadrilateral in the x-y plane, given by its corners counter-clockwise seen from +z
// (corners[0] at (xi, eta) = (0, 0), then (1, 0), (1, 1), (0, 1)), meshed by bilinear
// interpolation of an n_xi * n_eta grid and extruded over z in [0, thickness] in n_z layers.
// Node (i, j, k) has index i + (n_xi + 1) * (j + (n_eta + 1) * k).
// Node sets: "left" (xi = 0 edge), "right" (xi = 1), "bottom" (eta = 0), "top" (eta = 1),
// "z_min", "z_max", and "corner_bottom_left", "corner_bottom_right", "corner_top_right",
// "corner_top_left" holding the corner's node in every z layer. Element set: "all".
// Throws std::invalid_argument for n < 1, a non-positive thickness, or a quadrilateral that is
// not strictly convex and counter-clockwise (the bilinear map would then fold).
Mesh make_quad_extrusion(const std::array<Eigen::Vector2d, 4>& corners, double thickness, int n_xi,
                         int n_eta, int n_z);

}  // namespace tongue::fem
