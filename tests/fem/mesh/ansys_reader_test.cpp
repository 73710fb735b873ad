#include "fem/mesh/ansys_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fem/mesh/mesh_quality.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::fem {
namespace {

namespace fs = std::filesystem;

// Each test writes its files into its own fresh directory under the system temp dir.
class AnsysReader : public testing::TempDirTest {
 protected:
  // Reads and expects a MeshReadError whose message names the file and the line.
  void expect_error(const std::string& nodes, const std::string& elements,
                    const std::string& bad_file, int line) const {
    try {
      read_ansys_mesh(nodes, elements);
      ADD_FAILURE() << "expected MeshReadError for " << bad_file << " line " << line;
    } catch (const MeshReadError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(bad_file), std::string::npos) << msg;
      EXPECT_EQ(e.path(), bad_file);
      EXPECT_EQ(e.line(), line) << msg;
      if (line > 0) {
        EXPECT_NE(msg.find("line " + std::to_string(line) + ":"), std::string::npos) << msg;
      }
    }
  }
};

// Two unit cubes side by side in x, node ids 11..13 / 21..23 style (non-contiguous, unsorted),
// written in mm. Node 101 is at the origin with all coordinates omitted, as NWRITE does.
constexpr const char* kNodes =
    "       101\n"
    "       102  1.000000000000    \n"
    "\n"
    "       105  1.000000000000       1.000000000000\n"
    "       104  0.0                  1.000000000000\n"
    "       201  0.0                  0.0                  1.000000000000\n"
    "       202  1.0                  0.0                  1.000000000000\n"
    "       205  1.0                  1.0                  1.0\r\n"
    "       204  0.0                  1.0                  1.0      0.0  0.0  0.0\n"
    "       303  2.0\n"
    "       306  2.0                  1.0\n"
    "       403  0.2E+001             0.0                  1.0\n"
    "       406  2.0                  1.0                  +1.0\n";

constexpr const char* kElements =
    "   101   102   105   104   201   202   205   204     1     1     1     1     0     7\n"
    "\n"
    "   102   303   306   105   202   403   406   205     3     1     1     1     0     5\n";

constexpr const char* kCubeNodes =
    "1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n";

TEST_F(AnsysReader, ReadsTwoElementsWithNonContiguousIds) {
  const auto nodes = write("mesh.node", kNodes);
  const auto elements = write("mesh.elem", kElements);
  const ImportedMesh im = read_ansys_mesh(nodes, elements);
  const Mesh& m = im.mesh;
  ASSERT_EQ(m.num_nodes(), 12);
  ASSERT_EQ(m.num_elements(), 2);
  // Indices follow file order; missing trailing coordinates are zero.
  EXPECT_EQ(im.node_index_of_id.at(101), 0);
  EXPECT_EQ(im.node_index_of_id.at(105), 2);
  EXPECT_EQ(im.node_index_of_id.at(104), 3);
  EXPECT_TRUE(m.nodes[0].isApprox(Vec3(0, 0, 0)));
  EXPECT_EQ(m.nodes[0], Vec3::Zero());
  EXPECT_EQ(m.nodes[1], Vec3(1, 0, 0));
  EXPECT_EQ(m.nodes[im.node_index_of_id.at(105)], Vec3(1, 1, 0));
  EXPECT_EQ(m.nodes[im.node_index_of_id.at(306)], Vec3(2, 1, 0));
  EXPECT_EQ(m.nodes[im.node_index_of_id.at(403)], Vec3(2, 0, 1));
  EXPECT_EQ(m.nodes[im.node_index_of_id.at(406)], Vec3(2, 1, 1));

  EXPECT_EQ(im.element_index_of_id.at(7), 0);
  EXPECT_EQ(im.element_index_of_id.at(5), 1);
  const Hex8 expected = {im.node_index_of_id.at(102), im.node_index_of_id.at(303),
                         im.node_index_of_id.at(306), im.node_index_of_id.at(105),
                         im.node_index_of_id.at(202), im.node_index_of_id.at(403),
                         im.node_index_of_id.at(406), im.node_index_of_id.at(205)};
  EXPECT_EQ(m.elements[1], expected);

  EXPECT_EQ(m.element_set("all"), (std::vector<int>{0, 1}));
  EXPECT_EQ(m.element_set("mat_1"), (std::vector<int>{0}));
  EXPECT_EQ(m.element_set("mat_3"), (std::vector<int>{1}));
  EXPECT_EQ(m.element_sets.size(), 3u);
}

TEST_F(AnsysReader, LengthScaleMultipliesCoordinates) {
  const auto nodes = write("mm.node", kNodes);
  const auto elements = write("mm.elem", kElements);
  const ImportedMesh im = read_ansys_mesh(nodes, elements, 1e-3);
  EXPECT_TRUE(im.mesh.nodes[im.node_index_of_id.at(406)].isApprox(Vec3(2e-3, 1e-3, 1e-3)));
  EXPECT_THROW(read_ansys_mesh(nodes, elements, 0.0), std::invalid_argument);
  EXPECT_THROW(read_ansys_mesh(nodes, elements, -1.0), std::invalid_argument);
}

TEST_F(AnsysReader, AcceptsIrregularButNotInvertedElement) {
  // Node 5 pushed below the bottom face: irregular at one corner but positive volume.
  const auto nodes =
      write("n", "1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0.0 0.0 -0.3\n6 1 0 1\n7 1 1 1\n8 0 1 1\n");
  const auto elements = write("e", "1 2 3 4 5 6 7 8 1 1 1 1 0 1\n");
  const Mesh m = read_ansys_mesh(nodes, elements).mesh;
  ASSERT_EQ(m.num_elements(), 1);
  EXPECT_FALSE(is_regular(m, 0));
  EXPECT_NEAR(element_volume(m, 0), 1.0 - 1.3 / 4, 1e-14);  // dip of 1.3 times a hat of mean 1/4
}

TEST_F(AnsysReader, MalformedNodeLinesNameFileAndLine) {
  const auto elements = write("ok.elem", "1 2 3 4 5 6 7 8 1 1 1 1 0 1\n");
  expect_error(write("text.node", "1 0 0 0\n\n2 1.0 abc 0\n"), elements,
               (dir_ / "text.node").string(), 3);
  expect_error(write("many.node", "1 0 0 0\n2 1 0 0 0 0 0 0\n"), elements,
               (dir_ / "many.node").string(), 2);
  expect_error(write("realid.node", "1.5 0 0 0\n"), elements, (dir_ / "realid.node").string(), 1);
  expect_error(write("zeroid.node", "1 0 0 0\n0 1 0 0\n"), elements,
               (dir_ / "zeroid.node").string(), 2);
  expect_error(write("nan.node", "1 0 0 nan\n"), elements, (dir_ / "nan.node").string(), 1);
  expect_error(write("dup.node", std::string(kCubeNodes) + "3 5 5 5\n"), elements,
               (dir_ / "dup.node").string(), 9);
}

TEST_F(AnsysReader, MalformedElementLinesNameFileAndLine) {
  const auto nodes = write("cube.node", std::string(kCubeNodes) + "9 2 0 0\n");
  const auto check = [&](const std::string& name, const std::string& text, int line) {
    expect_error(nodes, write(name, text), (dir_ / name).string(), line);
  };
  const std::string good = "1 2 3 4 5 6 7 8 1 1 1 1 0 1\n";
  check("short.elem", good + "1 2 3 4 5 6 7 8 1 1 1 1 2\n", 2);
  check("real.elem", "\n1 2 3 4 5 6 7 8.0 1 1 1 1 0 1\n", 2);
  check("word.elem", "1 2 3 4 5 6 7 8 steel 1 1 1 0 1\n", 1);
  check("unknown.elem", "1 2 3 4 5 6 7 99 1 1 1 1 0 1\n", 1);
  check("dupid.elem", good + good, 2);
  check("repeated.elem", "1 2 3 3 5 6 7 8 1 1 1 1 0 1\n", 1);  // prism-style collapse
  check("inverted.elem", "5 6 7 8 1 2 3 4 1 1 1 1 0 1\n", 1);  // top and bottom swapped
  try {
    read_ansys_mesh(nodes, (dir_ / "inverted.elem").string());
  } catch (const MeshReadError& e) {
    EXPECT_NE(std::string(e.what()).find("inside out"), std::string::npos) << e.what();
  }
}

TEST_F(AnsysReader, FlatElementIsRejected) {
  // All 8 nodes in the plane z = 0.
  const auto nodes = write("flat.node",
                           "1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 0 0\n6 2 0\n7 2 2\n8 0 2\n"
                           "11 0 0 0\n");
  // Nodes 1 and 5 coincide in position but are distinct ids, so this passes the repeated-node
  // check and must be caught by the volume check.
  const auto elements = write("flat.elem", "\n\n1 2 3 4 5 6 7 8 1 1 1 1 0 1\n");
  expect_error(nodes, elements, elements, 3);
  try {
    read_ansys_mesh(nodes, elements);
  } catch (const MeshReadError& e) {
    EXPECT_NE(std::string(e.what()).find("no volume"), std::string::npos) << e.what();
  }
}

TEST_F(AnsysReader, MissingAndEmptyFilesNameThePath) {
  const auto nodes = write("cube.node", kCubeNodes);
  const auto elements = write("cube.elem", "1 2 3 4 5 6 7 8 1 1 1 1 0 1\n");
  const std::string missing = (dir_ / "no_such.node").string();
  expect_error(missing, elements, missing, 0);
  const std::string missing_elements = (dir_ / "no_such.elem").string();
  expect_error(nodes, missing_elements, missing_elements, 0);
  expect_error(dir_.string(), elements, dir_.string(), 0);
  const auto empty_nodes = write("empty.node", "");
  expect_error(empty_nodes, elements, empty_nodes, 0);
  const auto blank_elements = write("blank.elem", "\n   \n\t\n");
  expect_error(nodes, blank_elements, blank_elements, 0);
}

}  // namespace
}  // namespace tongue::fem
