#pragma once
// Small dynamic box scenes with muscles, for tests that run a scene many steps in little time
// (the server's, through the bus or without it).

namespace tongue::testing {

// The smallest runnable scene: a 40 x 10 x 10 mm neo-Hookean box, 4 x 1 x 1 elements (5 x 2 x 2
// = 20 nodes, the corner at the origin), static, nothing acting on it; tests append sections or
// break one thing in a copy of it.
inline constexpr const char* kStaticBoxScene = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material:
  type: neo_hookean
  parameters: {shear_modulus: 5000}
analysis:
  type: static
)";

// A 40 x 10 x 10 mm block, 4 x 1 x 1 elements (20 nodes), clamped at x = 0, under gravity, with
// one listed muscle along the free end; dynamic, dt 2 ms: a step takes well under a millisecond.
inline constexpr const char* kBoxScene = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material:
  type: mooney_rivlin5
  density: 1000
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
muscles:
  - {name: flexor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [2, 3, 4]}]}
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
)";

// kBoxScene with a second muscle along the top edge (nodes 7, 8, 9: y = 10 mm, z = 0), so that
// two controllers can each drive their own muscle: "flexor" (bottom) and "extensor" (top).
inline constexpr const char* kTwoMuscleBoxScene = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material:
  type: mooney_rivlin5
  density: 1000
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
muscles:
  - {name: flexor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [2, 3, 4]}]}
  - {name: extensor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [7, 8, 9]}]}
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
)";

}  // namespace tongue::testing
