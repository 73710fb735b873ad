#include "fem/mesh/ansys_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/mesh/ansys_reader.hpp"
#include "fem/mesh/box_generator.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::fem {
namespace {

class AnsysWriter : public testing::TempDirTest {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

// Two hexahedra side by side in x, in mm, with non-contiguous unsorted ids, two materials and
// coordinates that need all 17 digits.
constexpr const char* kNodes =
    "  11 0 0 0\n"
    "  12 10.123456789012345 0 0\n"
    "  13 10.123456789012345 9.8765432109876543 0\n"
    "  14 0 9.8765432109876543 0\n"
    "  15 0 0 10.000000000000002\n"
    "  16 10.123456789012345 0 10.000000000000002\n"
    "  17 10.123456789012345 9.8765432109876543 10.000000000000002\n"
    "  18 0 9.8765432109876543 10.000000000000002\n"
    "   3 20.2 0.1 0\n"
    "   2 20.3 10.1 0\n"
    "   9 20.2 0.1 10.1\n"
    "   1 20.3 10.1 10.1\n";
constexpr const char* kElements =
    "11 12 13 14 15 16 17 18 4 1 1 1 0 77\n"
    "12 3 2 13 16 9 1 17 2 1 1 1 0 5\n";

std::vector<std::vector<std::string>> tokens_of_lines(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::vector<std::string> tokens;
    for (std::string t; s >> t;) tokens.push_back(t);
    lines.push_back(tokens);
  }
  return lines;
}

TEST_F(AnsysWriter, RoundTripKeepsNodesIdsAndMaterials) {
  const ImportedMesh original =
      read_ansys_mesh(write("in.node", kNodes), write("in.elem", kElements), 1e-3);
  write_ansys_mesh(original, path("out.node"), path("out.elem"), 1e-3);
  const ImportedMesh back = read_ansys_mesh(path("out.node"), path("out.elem"), 1e-3);

  ASSERT_EQ(back.mesh.num_nodes(), original.mesh.num_nodes());
  for (int i = 0; i < original.mesh.num_nodes(); ++i) {
    const Vec3& a = original.mesh.nodes[i];
    const Vec3& b = back.mesh.nodes[i];
    EXPECT_LE((a - b).norm(), 1e-12 * a.norm()) << "node " << i;
  }
  EXPECT_EQ(back.node_index_of_id, original.node_index_of_id);
  EXPECT_EQ(back.element_index_of_id, original.element_index_of_id);
  EXPECT_EQ(back.mesh.elements, original.mesh.elements);
  EXPECT_EQ(back.mesh.element_sets, original.mesh.element_sets);
  EXPECT_EQ(back.mesh.element_set("mat_4"), std::vector<int>{0});
  EXPECT_EQ(back.mesh.element_set("mat_2"), std::vector<int>{1});
}

TEST_F(AnsysWriter, ElementLinesHoldFourteenIntegers) {
  const ImportedMesh original =
      read_ansys_mesh(write("in.node", kNodes), write("in.elem", kElements), 1e-3);
  write_ansys_mesh(original, path("out.node"), path("out.elem"), 1e-3);
  const auto lines = tokens_of_lines(path("out.elem"));
  ASSERT_EQ(lines.size(), 2u);
  const std::vector<std::string> first = {"11", "12", "13", "14", "15", "16", "17",
                                          "18", "4",  "1",  "1",  "1",  "0",  "77"};
  EXPECT_EQ(lines[0], first);
  EXPECT_EQ(lines[1].size(), 14u);
  EXPECT_EQ(lines[1][8], "2");
  EXPECT_EQ(lines[1][13], "5");
  const auto nodes = tokens_of_lines(path("out.node"));
  ASSERT_EQ(nodes.size(), 12u);
  EXPECT_EQ(nodes[8][0], "3");  // file order and ids kept
  EXPECT_EQ(nodes[8].size(), 4u);
}

TEST_F(AnsysWriter, GeneratedMeshGetsIdsFromOneAndMaterialOne) {
  ImportedMesh generated;
  generated.mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.01, 0.01), 2, 1, 1);
  write_ansys_mesh(generated, path("box.node"), path("box.elem"));
  const ImportedMesh back = read_ansys_mesh(path("box.node"), path("box.elem"));
  EXPECT_EQ(back.mesh.nodes, generated.mesh.nodes);  // scale 1: exact
  EXPECT_EQ(back.mesh.elements, generated.mesh.elements);
  for (int i = 0; i < back.mesh.num_nodes(); ++i) EXPECT_EQ(back.node_index_of_id.at(i + 1), i);
  EXPECT_EQ(back.element_index_of_id.at(2), 1);
  EXPECT_EQ(back.mesh.element_set("mat_1"), (std::vector<int>{0, 1}));
}

TEST_F(AnsysWriter, RejectsAmbiguousMaterialsPartialIdsAndBadScale) {
  ImportedMesh m;
  m.mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.01, 0.01), 2, 1, 1);
  EXPECT_THROW(write_ansys_mesh(m, path("a.node"), path("a.elem"), 0.0), std::invalid_argument);

  ImportedMesh two_materials = m;
  two_materials.mesh.element_sets["mat_1"] = {0, 1};
  two_materials.mesh.element_sets["mat_2"] = {1};
  EXPECT_THROW(write_ansys_mesh(two_materials, path("a.node"), path("a.elem")),
               std::invalid_argument);

  ImportedMesh partial = m;
  partial.node_index_of_id = {{5, 0}};
  EXPECT_THROW(write_ansys_mesh(partial, path("a.node"), path("a.elem")), std::invalid_argument);
}

TEST_F(AnsysWriter, UnwritableFileIsNamed) {
  ImportedMesh m;
  m.mesh = make_box(Vec3::Zero(), Vec3(0.01, 0.01, 0.01), 1, 1, 1);
  const std::string bad = (dir_ / "no_such_dir" / "out.node").string();
  try {
    write_ansys_mesh(m, bad, path("out.elem"));
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tongue::fem
