#pragma once
// The default tongue's shape: a fan-shaped structured hexahedral grid around the genioglossus
// insertion on the mandible (Gerard et al. 2003 sec. II.2; docs/physics.md). Grid directions:
//   i: angle around the insertion, from the tip (front, up) over the dorsum to the root (back,
//   down); j: radius, from a small arc around the insertion out to the dorsum surface; k: lateral,
//   from the right side (z < 0) through the midsagittal plane to the left (z > 0).
// Coordinates: origin at the insertion (superior mental spine), x anterior, y superior, z to the
// subject's left; SI units. The fan follows the genioglossus fibres, and the muscle layers of
// Gerard et al. 2003 (sec. II.2) are ranges of grid indices.
#include <array>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace tongue::model {

// The dorsum profile and widths, given at control angles around the insertion.
struct TongueShape {
  // Angles [rad] from +x (anterior) toward +y (superior), increasing from tip to root.
  std::vector<double> control_angles;
  std::vector<double> dorsum_radius;     // distance insertion -> dorsum surface [m]
  std::vector<double> half_width;        // half-width at the dorsum, before scaling [m]
  double insertion_radius = 0.006;       // radius of the inner arc around the insertion [m]
  double insertion_half_width = 0.0025;  // half-width at the insertion (GG: 5 mm wide) [m]
  double volume = 160e-6;                // m^3: 160 g at 1000 kg/m^3 (Gerard et al. 2003)
  // How much lower the lateral margins are than the midline dorsum (a domed top), relative.
  double dome = 0.15;
  // Lateral layer boundaries per side as fractions of the half-width, from the midline out;
  // the first layer is the genioglossus (GG 5 -> 25 mm wide, sec. II.2.1).
  std::vector<double> lateral_fractions;
};

TongueShape default_tongue_shape();

// Grid sizes: elements along i, j, k (k counts both sides).
struct GridSize {
  int angular = 12;
  int radial = 6;
  int lateral = 10;
  GridSize refined(int factor) const {
    return {factor * angular, factor * radial, factor * lateral};
  }
};

struct TongueGrid {
  fem::Mesh mesh;
  GridSize size;
  int refinement = 1;
  double lateral_scale = 1.0;  // applied to the widths so that the volume is the target one

  int node(int i, int j, int k) const {
    return i + (size.angular + 1) * (j + (size.radial + 1) * k);
  }
  int element(int i, int j, int k) const { return i + size.angular * (j + size.radial * k); }
  int midline() const { return size.lateral / 2; }  // k of the midsagittal node layer
};

// Builds the grid; refinement multiplies the element count along each direction.
TongueGrid make_tongue_grid(const TongueShape& shape, int refinement);

}  // namespace tongue::model
