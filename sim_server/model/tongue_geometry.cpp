#include "model/tongue_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fem/mesh/mesh_quality.hpp"

namespace tongue::model {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Catmull-Rom interpolation of values given at equally spaced parameters 0, 1, ..., n - 1
// (end values repeated), evaluated at s in [0, n - 1]: smooth, and exact at the control points.
double catmull_rom(const std::vector<double>& v, double s) {
  const int n = static_cast<int>(v.size());
  const int i = std::clamp(static_cast<int>(std::floor(s)), 0, n - 2);
  const double t = s - i;
  const double p0 = v[std::max(i - 1, 0)], p1 = v[i], p2 = v[i + 1], p3 = v[std::min(i + 2, n - 1)];
  return 0.5 * (2 * p1 + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t * t +
                (-p0 + 3 * p1 - 3 * p2 + p3) * t * t * t);
}

// Lateral profile along the radius: wide in the body, a little narrower under the dorsum so the
// margins are rounded, and the insertion width at rho = 0.
double width_profile(double rho) {
  return std::sqrt(std::sin(0.5 * std::numbers::pi * rho)) * (1.0 - 0.2 * std::pow(rho, 6));
}

}  // namespace

TongueShape default_tongue_shape() {
  // Dorsum from the tip (50 deg) over the palatal and velar dorsum to the root (196 deg): the
  // tongue lies mostly above and behind the insertion, its tip up and forward of it, its root
  // down and back toward the hyoid (proportions after Gerard et al. 2003, sec. II.2: GGp 60 mm
  // long behind the insertion, GGa ending 8 mm behind the tip).
  TongueShape s;
  const int n = 8;
  for (int m = 0; m < n; ++m) s.control_angles.push_back((50.0 + m * (146.0 / (n - 1))) * kDegree);
  s.dorsum_radius = {0.035, 0.046, 0.055, 0.062, 0.067, 0.069, 0.068, 0.062};
  s.half_width = {0.014, 0.020, 0.024, 0.025, 0.025, 0.023, 0.020, 0.016};
  s.lateral_fractions = {0.0, 0.4, 0.6, 0.75, 0.88, 1.0};
  return s;
}

TongueGrid make_tongue_grid(const TongueShape& shape, int refinement) {
  const std::size_t n = shape.control_angles.size();
  if (n < 2 || shape.dorsum_radius.size() != n || shape.half_width.size() != n) {
    throw std::invalid_argument("tongue shape: control angles, radii and widths must match");
  }
  if (refinement < 1) throw std::invalid_argument("tongue refinement must be >= 1");
  const int per_side = static_cast<int>(shape.lateral_fractions.size()) - 1;
  TongueGrid grid;
  grid.refinement = refinement;
  grid.size = GridSize{12, 6, 2 * per_side}.refined(refinement);
  const GridSize& g = grid.size;

  // Lateral positions of the node layers, -1 (right surface) .. +1 (left surface); each layer
  // of the base grid is split evenly when refined.
  std::vector<double> zeta(g.lateral + 1);
  const int half = g.lateral / 2;
  for (int k = 0; k <= half; ++k) {
    const int layer = k / refinement, sub = k % refinement;
    const double a = shape.lateral_fractions[layer];
    const double b = sub == 0 ? a : shape.lateral_fractions[layer + 1];
    const double f = sub == 0 ? a : a + (b - a) * sub / static_cast<double>(refinement);
    zeta[half + k] = f;
    zeta[half - k] = -f;
  }

  auto position = [&](int i, int j, int k, double lateral_scale) {
    const double s = static_cast<double>(i) / g.angular * (n - 1);
    const double theta = catmull_rom(shape.control_angles, s);
    const double R = catmull_rom(shape.dorsum_radius, s);
    const double W = catmull_rom(shape.half_width, s);
    // Radial layers finer near the insertion, where the fan is narrow.
    const double rho = std::pow(static_cast<double>(j) / g.radial, 1.2);
    const double z = zeta[k];
    const double r0 = shape.insertion_radius;
    const double r = r0 + rho * (R - r0) * (1.0 - shape.dome * z * z);
    const double w0 = shape.insertion_half_width;
    const double width = w0 + (W * lateral_scale - w0) * width_profile(rho);
    return fem::Vec3(r * std::cos(theta), r * std::sin(theta), z * width);
  };

  fem::Mesh& mesh = grid.mesh;
  mesh.nodes.resize((g.angular + 1) * (g.radial + 1) * (g.lateral + 1));
  for (int k = 0; k < g.lateral; ++k) {
    for (int j = 0; j < g.radial; ++j) {
      for (int i = 0; i < g.angular; ++i) {
        // (j, i, k) is a right-handed order: radius x angle points along +z.
        mesh.elements.push_back({grid.node(i, j, k), grid.node(i, j + 1, k),
                                 grid.node(i + 1, j + 1, k), grid.node(i + 1, j, k),
                                 grid.node(i, j, k + 1), grid.node(i, j + 1, k + 1),
                                 grid.node(i + 1, j + 1, k + 1), grid.node(i + 1, j, k + 1)});
      }
    }
  }
  auto place = [&](double lateral_scale) {
    for (int k = 0; k <= g.lateral; ++k)
      for (int j = 0; j <= g.radial; ++j)
        for (int i = 0; i <= g.angular; ++i)
          mesh.nodes[grid.node(i, j, k)] = position(i, j, k, lateral_scale);
  };
  // The volume is an affine function of the dorsum widths (the insertion width stays), so
  // two evaluations give the width scale that meets the target exactly.
  place(1.0);
  const double v1 = fem::check_quality(mesh).total_volume;
  place(2.0);
  const double v2 = fem::check_quality(mesh).total_volume;
  grid.lateral_scale = 1.0 + (shape.volume - v1) / (v2 - v1);
  place(grid.lateral_scale);
  return grid;
}

}  // namespace tongue::model
