// Runs the real mesh_tool executable on small ANSYS meshes written by the test itself (not by
// the writer under test) and checks its exit codes, its report and the files it writes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fem/mesh/ansys_reader.hpp"
#include "fem/mesh/mesh_quality.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir_test.hpp"

#ifndef MESH_TOOL_PATH
#error "MESH_TOOL_PATH must name the mesh_tool executable"
#endif

namespace tongue::apps {
namespace {

namespace fs = std::filesystem;

using testing::RunResult;

// A 40 x 20 x 20 mm box of 4 x 2 x 2 cubes of 10 mm, in mm, node (i, j, k) with id
// 101 + i + 5 (j + 3 k) and element (i, j, k) with id 1001 + i + 4 (j + 2 k); material 2 for
// x < 20 mm, 3 beyond.
struct BoxFiles {
  std::string nodes, elements;
};

int node_index(int i, int j, int k) {
  return i + 5 * (j + 3 * k);
}

// With fold = true two interior nodes are pushed 6.3 mm along a cube diagonal, each through the
// plane of its three edge neighbours in one element (0.53 mm beyond it): node (1, 1, 1) into
// element (1, 1, 1) (id 1014) and node (3, 1, 1) back into element (2, 0, 0) (id 1003).
std::string node_text(bool fold) {
  std::string text;
  const double t = 6.3 / std::sqrt(3.0);  // mm per axis
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 4; ++i) {
        double x = 10.0 * i, y = 10.0 * j, z = 10.0 * k;
        const double shift = !fold || j != 1 || k != 1 ? 0.0 : i == 1 ? t : i == 3 ? -t : 0.0;
        x += shift;
        y += shift;
        z += shift;
        char line[128];
        std::snprintf(line, sizeof line, "%6d %.10g %.10g %.10g\n", 101 + node_index(i, j, k), x, y,
                      z);
        text += line;
      }
  return text;
}

std::string element_text() {
  std::string text;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) {
        const int n[8] = {node_index(i, j, k),
                          node_index(i + 1, j, k),
                          node_index(i + 1, j + 1, k),
                          node_index(i, j + 1, k),
                          node_index(i, j, k + 1),
                          node_index(i + 1, j, k + 1),
                          node_index(i + 1, j + 1, k + 1),
                          node_index(i, j + 1, k + 1)};
        for (int a : n) text += std::to_string(101 + a) + " ";
        text += (i < 2 ? "2" : "3");
        text += " 1 1 1 0 " + std::to_string(1001 + i + 4 * (j + 2 * k)) + "\n";
      }
  return text;
}

class MeshTool : public testing::TempDirTest {
 protected:
  BoxFiles write_box(bool fold) const {
    return {write("box.node", node_text(fold)), write("box.elem", element_text())};
  }

  RunResult run(const std::string& args) const {
    return testing::run_command(MESH_TOOL_PATH, args, dir_);
  }

  static bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  }
};

TEST_F(MeshTool, CheckOfRegularMeshExitsZero) {
  const BoxFiles box = write_box(false);
  const RunResult r = run("check '" + box.nodes + "' '" + box.elements + "' --scale 1e-3");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "nodes: 45")) << r.out;
  EXPECT_TRUE(contains(r.out, "elements: 16")) << r.out;
  EXPECT_TRUE(contains(r.out, "volume: 16 cm^3")) << r.out;  // 16 cubes of 1 cm^3
  EXPECT_TRUE(contains(r.out, "bounding box: 0.04 x 0.02 x 0.02 m")) << r.out;
  EXPECT_TRUE(contains(r.out, "irregular elements: 0 of 16")) << r.out;
  EXPECT_TRUE(contains(r.out, "worst element quality (min/max nodal det J): 1 ")) << r.out;
}

// The box's file is in mm: read with a scale for a file in metres already scaled to mm, it is
// 16e-9 cm^3, which only a wrong unit gives: an error (exit 1) with the bounding box in metres.
TEST_F(MeshTool, VanishingVolumeIsAnErrorNamingTheBoundingBox) {
  const BoxFiles box = write_box(false);
  const RunResult r = run("check '" + box.nodes + "' '" + box.elements + "' --scale 1e-6");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(contains(r.err,
                       "the mesh's volume is 1.6e-14 m^3 (less than 1 mm^3) in a bounding "
                       "box of 4e-05 x 2e-05 x 2e-05 m"))
      << r.err;
  EXPECT_TRUE(contains(r.err, "is its length unit right")) << r.err;
}

TEST_F(MeshTool, CheckOfFoldedMeshExitsOneAndListsAnsysIds) {
  const BoxFiles box = write_box(true);
  const RunResult r = run("check '" + box.nodes + "' '" + box.elements + "' --scale 1e-3");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // irregular: bad input (was 3)
  EXPECT_TRUE(contains(r.out, "irregular elements: 2 of 16")) << r.out;
  EXPECT_TRUE(contains(r.out, "ANSYS ids: 1003 1014")) << r.out;
}

TEST_F(MeshTool, ReadErrorExitsOneNamingFileAndLine) {
  const BoxFiles box = write_box(false);
  std::string elements = element_text();
  elements.insert(elements.find('\n') + 1, "1 2 3\n");  // line 2: too few fields
  const std::string bad = write("bad.elem", elements);
  RunResult r = run("check '" + box.nodes + "' '" + bad + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, bad + ", line 2:")) << r.err;

  const std::string missing = (dir_ / "missing.node").string();
  r = run("check '" + missing + "' '" + box.elements + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, missing)) << r.err;
}

TEST_F(MeshTool, RegularizeWritesRegularMeshWithOriginalIds) {
  const BoxFiles box = write_box(true);
  const std::string out_nodes = (dir_ / "fixed.node").string();
  const std::string out_elements = (dir_ / "fixed.elem").string();
  const RunResult r = run("regularize '" + box.nodes + "' '" + box.elements + "' --out-nodes '" +
                          out_nodes + "' --out-elements '" + out_elements + "' --scale 1e-3");
  std::printf("%s", r.out.c_str());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "before: irregular elements: 2 of 16")) << r.out;
  EXPECT_TRUE(contains(r.out, "after: irregular elements: 0 of 16")) << r.out;
  const std::size_t at = r.out.find("largest node displacement: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double reported_mm = std::atof(r.out.c_str() + at + 27);
  EXPECT_GT(reported_mm, 0.0);
  EXPECT_LE(reported_mm, 1.0);

  const fem::ImportedMesh before = fem::read_ansys_mesh(box.nodes, box.elements, 1e-3);
  const fem::ImportedMesh after = fem::read_ansys_mesh(out_nodes, out_elements, 1e-3);
  EXPECT_EQ(after.node_index_of_id, before.node_index_of_id);
  EXPECT_EQ(after.element_index_of_id, before.element_index_of_id);
  EXPECT_EQ(after.mesh.elements, before.mesh.elements);
  EXPECT_EQ(after.mesh.element_sets, before.mesh.element_sets);  // mat_2, mat_3, all
  EXPECT_EQ(fem::check_quality(after.mesh).num_irregular, 0);
  double moved = 0.0;
  for (int i = 0; i < before.mesh.num_nodes(); ++i) {
    moved = std::max(moved, (after.mesh.nodes[i] - before.mesh.nodes[i]).norm());
  }
  EXPECT_LE(moved, 1e-3 + 1e-12);
  EXPECT_NEAR(moved * 1e3, reported_mm, 1e-4);  // printed to 4 decimals

  const RunResult again = run("check '" + out_nodes + "' '" + out_elements + "' --scale 1e-3");
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
}

TEST_F(MeshTool, RegularizeWithTooSmallBoundExitsOne) {
  const BoxFiles box = write_box(true);
  const RunResult r = run("regularize '" + box.nodes + "' '" + box.elements + "' --out-nodes '" +
                          (dir_ / "o.node").string() + "' --out-elements '" +
                          (dir_ / "o.elem").string() + "' --scale 1e-3 --max-displacement-mm 0.05");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // irregular: bad input (was 3)
  EXPECT_TRUE(contains(r.out, "largest node displacement: 0.0500 mm")) << r.out;
  EXPECT_TRUE(contains(r.err, "2 elements still irregular (ANSYS ids 1003 1014)")) << r.err;
}

TEST_F(MeshTool, BadCommandLineExitsOne) {
  const BoxFiles box = write_box(false);
  EXPECT_EQ(run("").exit_code, 1);
  EXPECT_EQ(run("inspect '" + box.nodes + "' '" + box.elements + "'").exit_code, 1);
  EXPECT_EQ(run("regularize '" + box.nodes + "' '" + box.elements + "'").exit_code, 1);
  EXPECT_EQ(run("check '" + box.nodes + "' '" + box.elements + "' --scale -1").exit_code, 1);
  const RunResult r = run("check '" + box.nodes + "' '" + box.elements + "' --frobnicate 2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "unknown option '--frobnicate'")) << r.err;
}

}  // namespace
}  // namespace tongue::apps
