#pragma once
// The residual kernel of uncoupled materials (W = W_iso + U(J)), vectorized across elements:
// a batch holds up to kBatchLanes elements as structure of arrays, lane l being element l of the
// batch, so that an operation at a Gauss point works on several elements at once (2, 4 or 8, the
// CPU's vector width; docs/speed.md). Same formulas as the tangent path and the reference element
// of the tests.
#include <array>
#include <span>

#include "fem/element/hex8_element.hpp"

namespace tongue::fem {

inline constexpr int kBatchLanes = 8;

// One value per element of a batch; 64-byte aligned, the width of one AVX-512 register.
struct alignas(64) LaneValues {
  std::array<double, kBatchLanes> lane;
};

// Reference-configuration data of a batch, computed once. Lanes past `count` repeat the first
// element, so that they compute something finite; their results are ignored.
struct ElementBatchGeometry {
  int count = 0;  // elements in the batch, 1..kBatchLanes
  // gradient[q][8 J + a] = dN_a/dX_J at Gauss point q
  std::array<std::array<LaneValues, 24>, 8> gradient;
  std::array<LaneValues, 8> weight;  // Gauss weight x det(dX/dxi) [m^3] at Gauss point q
  LaneValues volume;                 // V [m^3]
};

// Throws std::invalid_argument unless 1 <= elements.size() <= kBatchLanes.
ElementBatchGeometry make_batch_geometry(std::span<const ElementGeometry> elements);

// Current nodal positions of a batch: x[3 a + i] is component i of node a [m].
using BatchCoords = std::array<LaneValues, 24>;

struct ElementBatchResponse {
  std::array<LaneValues, 24> force;  // internal force [N], dof 3 a + i
  LaneValues energy;                 // strain energy [J]
  LaneValues min_J;                  // smallest det F over the Gauss points
  std::array<bool, kBatchLanes> ok;  // false: det F <= 0 (or NaN) at a Gauss point
};

// The instruction sets the kernel is compiled for, each with its own vector width, so that one
// binary runs on any x86-64 and uses what the CPU has.
enum class SimdLevel { sse2, avx2, avx512 };
// The best one this CPU runs (AVX2 means x86-64-v3, with FMA; AVX-512 means x86-64-v4).
SimdLevel best_simd_level();

// Internal force and energy of every element of the batch; an element with ok false has an
// undefined force and energy. Every level gives the same results to round-off (their sums differ
// in fused multiply-adds). Throws std::invalid_argument for a level above best_simd_level().
void evaluate_batch_force(const ElementBatchGeometry& geometry, const BatchCoords& x,
                          const UncoupledMaterial& material, Formulation formulation,
                          ElementBatchResponse& response, SimdLevel level = best_simd_level());

}  // namespace tongue::fem
