#pragma once
// The tangent kernel of uncoupled materials (W = W_iso + U(J)), vectorized across elements like
// the residual kernel (hex8_batch.hpp, same batches and instruction sets): internal force, energy
// and the element stiffness of up to kBatchLanes elements at once. It gives what the scalar
// element (evaluate_element with want_stiffness) gives, to round-off.
#include <array>

#include "fem/element/hex8_batch.hpp"

namespace tongue::fem {

// The stiffness is stored as its 36 upper node blocks (a, b), b >= a, the lower ones being their
// transposes: block (a, b) is number upper_block(a, b), in the order (0,0), (0,1), ..., (0,7),
// (1,1), ..., (7,7), and its entry (i, k) = K(3a + i, 3b + k) sits at 9 upper_block(a, b) + 3i + k.
inline constexpr int kUpperBlocks = 36;
constexpr int upper_block(int a, int b) {
  return 8 * a - a * (a - 1) / 2 + (b - a);
}

struct ElementBatchTangent {
  ElementBatchResponse response;                       // force, energy, smallest det F, ok
  std::array<LaneValues, 9 * kUpperBlocks> stiffness;  // d(force)/dx [N/m], upper node blocks
};

// Force, energy and stiffness of every element of the batch; an element with ok false has an
// undefined force, energy and stiffness. Throws std::invalid_argument for a level above
// best_simd_level().
void evaluate_batch_tangent(const ElementBatchGeometry& geometry, const BatchCoords& x,
                            const UncoupledMaterial& material, Formulation formulation,
                            ElementBatchTangent& result, SimdLevel level = best_simd_level());

// The whole symmetric 24 x 24 stiffness of one lane.
ElementMatrix lane_stiffness(const ElementBatchTangent& result, int lane);

}  // namespace tongue::fem
