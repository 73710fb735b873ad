// Obstacle files: OBJ with polygons and STL (ASCII and binary) read into triangle surfaces, and
// bad files refused with the file's name in the message.
#include "fem/contact/obstacle_file.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>

#include "support/temp_dir_test.hpp"

namespace tongue::fem {
namespace {

class ObstacleFile : public testing::TempDirTest {
 protected:
  void expect_error(const std::string& path, const std::string& says) const {
    try {
      read_triangle_surface(path);
      ADD_FAILURE() << "expected an error for " << path;
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      EXPECT_NE(msg.find(says), std::string::npos) << msg;
    }
  }
};

// A unit cube of six quads, outward normals, in a length unit of the file's own.
constexpr const char* kCubeObj =
    "# unit cube\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

TEST_F(ObstacleFile, ObjPolygonsBecomeAClosedSurface) {
  const TriangleSurface s = read_triangle_surface(write("cube.obj", kCubeObj));
  EXPECT_EQ(s.vertices.size(), 8u);
  EXPECT_EQ(s.triangles.size(), 12u);
  const Obstacle cube("cube", s);
  EXPECT_TRUE(cube.closed());
  EXPECT_NEAR(cube.closest(Vec3(0.5, 0.5, 0.25)).distance, -0.25, 1e-15);
  EXPECT_NEAR(cube.closest(Vec3(0.5, 0.5, 1.5)).distance, 0.5, 1e-15);
}

// A tetrahedron's four facets, each with its own three corners as STL writes them.
const Vec3 kTet[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
const int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TEST_F(ObstacleFile, AsciiAndBinaryStlShareTheirCorners) {
  std::string ascii = "solid tet\n";
  for (const auto& f : kTetFaces) {
    ascii += " facet normal 0 0 0\n  outer loop\n";
    for (int k : f) {
      ascii += "   vertex " + std::to_string(kTet[k].x()) + " " + std::to_string(kTet[k].y()) +
               " " + std::to_string(kTet[k].z()) + "\n";
    }
    ascii += "  endloop\n endfacet\n";
  }
  ascii += "endsolid tet\n";
  const std::string binary_path = (dir_ / "tet_binary.stl").string();
  {
    std::ofstream out(binary_path, std::ios::binary);
    const char header[80] = "binary tetrahedron";
    out.write(header, 80);
    const std::uint32_t count = 4;
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const auto& f : kTetFaces) {
      float values[12] = {0, 0, 0};
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) values[3 + 3 * k + i] = static_cast<float>(kTet[f[k]][i]);
      out.write(reinterpret_cast<const char*>(values), sizeof values);
      const std::uint16_t attributes = 0;
      out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
  }
  for (const std::string& path : {write("tet.stl", ascii), binary_path}) {
    const TriangleSurface s = read_triangle_surface(path);
    EXPECT_EQ(s.vertices.size(), 4u) << path;
    EXPECT_EQ(s.triangles.size(), 4u) << path;
    const Obstacle tet("tet", s);  // closed, consistently oriented, outward
    EXPECT_TRUE(tet.closed());
    EXPECT_LT(tet.closest(Vec3(0.1, 0.1, 0.1)).distance, 0.0);
  }
}

TEST_F(ObstacleFile, BadFilesNameTheFile) {
  expect_error((dir_ / "missing.obj").string(), "no such file");
  expect_error(write("palate.ply", "ply\n"), ".obj or an .stl");
  expect_error(write("words.obj", "this is not a mesh\nat all\n"), "not readable as a mesh");
  expect_error(write("empty.stl", ""), "not readable as a mesh");
  expect_error(write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "not readable as a mesh");
  expect_error(write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"), "line primitive");
}

}  // namespace
}  // namespace tongue::fem
