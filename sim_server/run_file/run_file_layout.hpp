#pragma once
// The names in an HDF5 run file, shared by its writer and its reader (format_version 1):
//
//   /time               [T]          double  s (or "1" for the load factor of a static run)
//   /positions          [T x N x 3]  double  m, current node positions
//   /rest_positions     [N x 3]      double  m
//   /elements           [E x 8]      int32   0-based node indices, ANSYS SOLID185 node order
//   /solver/iterations  [T]          int32   Newton iterations since the previous frame
//   /solver/residual    [T]          double  N, final residual norm of the frame's step
//   /solver/wall_time   [T]          double  s, wall-clock time since the previous frame
//   /solver/cuts        [T]          int32   step halvings since the previous frame
//   /solver/reduced_correction [T]   double  m, a reduced model's error indicator at its last
//                                            check (0 for the full model)
// (When every step is logged, "since the previous frame" is simply "of the step".)
//   /mesh/node_sets/<name>     [n]   int32   0-based node indices, one dataset per node set
//   /mesh/element_sets/<name>  [e]   int32   0-based element indices, one per element set
//   /mesh/node_ids      [N]          int64   imported meshes only: the mesh file's id of each
//   /mesh/element_ids   [E]          int64   node / element, by 0-based index
// With M > 0 muscles (omitted without muscles):
//   /muscles/names      [M]          string  UTF-8, the muscles' order in the datasets below
//   /muscles/max_force  [M]          double  N, tension at full activation
//   /activations        [T x M]      double  1, activation level of each muscle
//   /muscles/length     [T x M]      double  m, weighted mean fibre length
//   /muscles/velocity   [T x M]      double  m/s, its rate of change (> 0: lengthening)
//   /muscles/fibres/muscle        [F]      int32   index of the fibre's muscle
//   /muscles/fibres/weight        [F]      double  1, share of the muscle's tension
//   /muscles/fibres/origin        [F x 3]  double  m, fixed bony attachment, NaN when none
//   /muscles/fibres/node_offsets  [F + 1]  int32   fibre f is nodes[node_offsets[f] ..
//   /muscles/fibres/nodes         [sum]    int32   node_offsets[f + 1]), 0-based, in order
// With O > 0 obstacles (omitted without):
//   /obstacles/names                 [O]          string  the obstacles' order below
//   /obstacles/<name>/vertices       [V x 3]      double  m
//   /obstacles/<name>/triangles      [F x 3]      int32   0-based vertex indices, normals (right-
//                                                         hand rule) toward the solid
//   /contact/node_force              [T x N x 3]  double  N, force of the obstacles on each node
//   /contact/obstacle_force          [T x O x 3]  double  N, force of the solid on each obstacle
//   /contact/max_penetration         [T]          double  m, deepest penetration of a node
//   root attributes: format_version (int), length_unit = "m", time_unit, scene_text (the YAML),
//                    plus string attributes set while running (status, resets, ...).
// Every dataset has a "units" and a "description" attribute. The time-indexed datasets are
// chunked along time and deflate-compressed, extended on each append; /time is extended last,
// so that a reader that sees T times finds T frames in every other dataset.
#include <string>

namespace tongue::run_file::layout {

inline constexpr int kFormatVersion = 1;

inline constexpr const char* kTime = "/time";
inline constexpr const char* kPositions = "/positions";
inline constexpr const char* kRestPositions = "/rest_positions";
inline constexpr const char* kElements = "/elements";

inline constexpr const char* kSolver = "/solver";
inline constexpr const char* kIterations = "/solver/iterations";
inline constexpr const char* kResidual = "/solver/residual";
inline constexpr const char* kWallTime = "/solver/wall_time";
inline constexpr const char* kCuts = "/solver/cuts";
inline constexpr const char* kReducedCorrection = "/solver/reduced_correction";

inline constexpr const char* kMesh = "/mesh";
inline constexpr const char* kNodeSets = "/mesh/node_sets";
inline constexpr const char* kElementSets = "/mesh/element_sets";
inline constexpr const char* kNodeIds = "/mesh/node_ids";
inline constexpr const char* kElementIds = "/mesh/element_ids";

inline constexpr const char* kMuscles = "/muscles";
inline constexpr const char* kMuscleNames = "/muscles/names";
inline constexpr const char* kMaxForce = "/muscles/max_force";
inline constexpr const char* kActivations = "/activations";
inline constexpr const char* kMuscleLength = "/muscles/length";
inline constexpr const char* kMuscleVelocity = "/muscles/velocity";

inline constexpr const char* kFibres = "/muscles/fibres";
inline constexpr const char* kFibreMuscle = "/muscles/fibres/muscle";
inline constexpr const char* kFibreWeight = "/muscles/fibres/weight";
inline constexpr const char* kFibreOrigin = "/muscles/fibres/origin";
inline constexpr const char* kFibreNodeOffsets = "/muscles/fibres/node_offsets";
inline constexpr const char* kFibreNodes = "/muscles/fibres/nodes";

inline constexpr const char* kObstacles = "/obstacles";
inline constexpr const char* kObstacleNames = "/obstacles/names";
inline constexpr const char* kContact = "/contact";
inline constexpr const char* kContactNodeForce = "/contact/node_force";
inline constexpr const char* kContactObstacleForce = "/contact/obstacle_force";
inline constexpr const char* kContactMaxPenetration = "/contact/max_penetration";

// Attributes of the root group ("/").
inline constexpr const char* kRoot = "/";
inline constexpr const char* kFormatVersionAttribute = "format_version";
inline constexpr const char* kLengthUnitAttribute = "length_unit";
inline constexpr const char* kTimeUnitAttribute = "time_unit";
inline constexpr const char* kSceneTextAttribute = "scene_text";
inline constexpr const char* kStatusAttribute = "status";
inline constexpr const char* kResetsAttribute = "resets";  // server runs: times reset
// Attributes of every dataset.
inline constexpr const char* kUnitsAttribute = "units";
inline constexpr const char* kDescriptionAttribute = "description";

inline std::string node_set(const std::string& name) {
  return std::string(kNodeSets) + "/" + name;
}
inline std::string element_set(const std::string& name) {
  return std::string(kElementSets) + "/" + name;
}

inline std::string obstacle_vertices(const std::string& name) {
  return std::string(kObstacles) + "/" + name + "/vertices";
}
inline std::string obstacle_triangles(const std::string& name) {
  return std::string(kObstacles) + "/" + name + "/triangles";
}

}  // namespace tongue::run_file::layout
