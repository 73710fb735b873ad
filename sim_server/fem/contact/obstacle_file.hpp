#pragma once
// Obstacle surfaces from files: Wavefront OBJ or STL (ASCII or binary), read with Assimp.
#include <string>

#include "fem/contact/obstacle.hpp"

namespace tongue::fem {

// The triangles of every mesh in the file, in the file's length unit, with any node transforms
// of the file applied; polygons are split into triangles and STL's repeated corners merged into
// shared vertices. Throws std::runtime_error naming the file when it is missing, not OBJ or STL,
// unreadable, or holds no triangles or other primitives than triangles.
TriangleSurface read_triangle_surface(const std::string& path);

}  // namespace tongue::fem
