// Muscles imported from ANSYS macros in a scene (muscles: {ansys_macros: ...}) and node sets read
// from node list files: the scene builds the same muscles, sets and activations as the same
// scene written by hand.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "scene/activation_schedule.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::scene {
namespace {

// CRLF line ends and Latin-1 comments ("\xe9": e acute), as in the Grenoble files.
const char* const kElements =
    "! Cr\xe9"
    "ation des muscles\r\n"
    "ESEL,S,ELEM,,1,4\r\n"
    "CM,STY_L,ELEM\r\n"
    "ESEL,S,ELEM,,5,7,2\r\n"
    "ESEL,A,ELEM,,8\r\n"
    "CM,STY_R,ELEM\r\n"
    "ESEL,S,ELEM,,2,3\r\n"
    "CM,SL,ELEM\r\n"
    "ESEL,NONE\r\n"
    "CM,REST,ELEM\r\n";

const char* const kFibres =
    "/COM, fibres \xe9\r\n"
    "NB_NODES_FIBER(1,1)=4\r\n"
    "FIBER(1,1,1)=1\r\nFIBER(2,1,1)=2\r\nFIBER(3,1,1)=3\r\nFIBER(4,1,1)=4037\r\n"
    "NB_NODES_FIBER(2,1)=3\r\n"
    "FIBER(1,2,1)=4037\r\nFIBER(2,2,1)=6\r\nFIBER(3,2,1)=7\r\n"
    "NB_NODES_FIBER(1,2)=3\r\n"
    "FIBER(1,1,2)=11\r\nFIBER(2,1,2)=12\r\nFIBER(3,1,2)=13\r\n"
    "NB_NODES_FIBER(1,3)=2\r\n"
    "FIBER(1,1,3)=16\r\nFIBER(2,1,3)=17\r\n";

const char* const kForces = "STY_L 12\r\nSTY_R 12\r\nSL 9.5 \r\n";

// The same muscles written by hand: the fibre ending at the styloid (4037) reversed.
const char* const kHandWritten = R"(
muscles:
  - {name: STY_L, max_force: 12, elements: [1, 2, 3, 4],
     fibres: [{nodes: [3, 2, 1], origin: [-0.07, 0.075, 0.04]},
              {nodes: [6, 7], origin: [-0.07, 0.075, 0.04]}]}
  - {name: STY_R, max_force: 12, elements: [5, 7, 8], fibres: [{nodes: [11, 12, 13]}]}
  - {name: SL, max_force: 9.5, elements: [2, 3], fibres: [{nodes: [16, 17]}]}
node_sets:
  jaw: {ids: [1, 6, 11, 16]}
constraints:
  - {set: jaw, components: [x, y, z]}
activations:
  - {muscles: [STY_L, STY_R], force: 3.0, start: 0, end: 0.1}
  - {muscles: [SL], level: 0.5, start: 0.05}
)";

const char* const kImported = R"(
muscles:
  ansys_macros:
    elements: CreateMuscles.mac
    fibres: Fibers.mac
    max_force: MuscleMaxForce.txt
    external_points: {4037: [-0.07, 0.075, 0.04]}   # the styloid process, m
    groups: {SG: [STY_L, STY_R]}
node_sets:
  jaw: {file: jaw.txt, numbering: one_based}
constraints:
  - {set: jaw, components: [x, y, z]}
activations:
  - {group: SG, force: 3.0, start: 0, end: 0.1}
  - {group: SL, level: 0.5, start: 0.05}
)";

class SceneAnsysMacros : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    // 4 x 2 x 1 elements of 10 mm; node ids 1 + i + 5 (j + 3 k), element ids 1 + i + 4 j.
    std::ostringstream nodes, elements;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 5; ++i)
          nodes << id(i, j, k) << " " << 10 * i << " " << 10 * j << " " << 10 * k << "\r\n";
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 2; ++k)
          elements << id(i, j, k) << " " << id(i + 1, j, k) << " " << id(i + 1, j + 1, k) << " "
                   << id(i, j + 1, k) << " ";
        elements << "1 1 1 0 0 " << 1 + i + 4 * j << "\r\n";
      }
    write("t.node", nodes.str());
    write("t.elem", elements.str());
    write("CreateMuscles.mac", kElements);
    write("Fibers.mac", kFibres);
    write("MuscleMaxForce.txt", kForces);
    write("jaw.txt",
          "1 6\r\n11, 16 ! m\xe2"
          "choire\r\n");
  }
  static int id(int i, int j, int k) { return 1 + i + 5 * (j + 3 * k); }

  Scene scene(const std::string& extra) const {
    return parse_scene(R"(
mesh: {ansys: {nodes: t.node, elements: t.elem, length_scale: 0.001}}
material: {type: neo_hookean, parameters: {shear_modulus: 5000}}
analysis: {type: dynamic, duration: 0.1, dt: 0.01}
)" + extra,
                       dir_.string(), "test.yaml");
  }

  void expect_error(const std::string& extra, const std::string& key_path, const std::string& also,
                    bool when_building = false) const {
    try {
      if (when_building) {
        build_scene(scene(extra));
      } else {
        scene(extra);
      }
      ADD_FAILURE() << "no SceneError for " << key_path;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key_path(), key_path) << e.what();
      EXPECT_NE(std::string(e.what()).find(also), std::string::npos) << e.what();
    }
  }
};

TEST_F(SceneAnsysMacros, BuildsTheSameMusclesAsTheHandWrittenScene) {
  const BuiltScene by_hand = build_scene(scene(kHandWritten));
  const BuiltScene imported = build_scene(scene(kImported));
  const auto& a = by_hand.muscles->muscles();
  const auto& b = imported.muscles->muscles();
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t m = 0; m < a.size(); ++m) {
    SCOPED_TRACE(a[m].name);
    EXPECT_EQ(b[m].name, a[m].name);
    EXPECT_EQ(b[m].elements, a[m].elements);
    EXPECT_EQ(b[m].max_force, a[m].max_force);
    ASSERT_EQ(b[m].fibres.size(), a[m].fibres.size());
    for (std::size_t f = 0; f < a[m].fibres.size(); ++f) {
      EXPECT_EQ(b[m].fibres[f].nodes, a[m].fibres[f].nodes);
      EXPECT_EQ(b[m].fibres[f].origin.has_value(), a[m].fibres[f].origin.has_value());
      if (a[m].fibres[f].origin) {
        EXPECT_EQ(*b[m].fibres[f].origin, *a[m].fibres[f].origin);
      }
      EXPECT_EQ(b[m].fibres[f].weight, a[m].fibres[f].weight);
    }
  }
  // Sets and constraints alike: the attachment file's one_based numbers are the node ids here.
  const fem::Mesh& ma = by_hand.solid->mesh();
  const fem::Mesh& mb = imported.solid->mesh();
  EXPECT_EQ(mb.node_sets, ma.node_sets);
  EXPECT_EQ(mb.element_sets, ma.element_sets);
  EXPECT_EQ(imported.prescribed.size(), by_hand.prescribed.size());
  // The declared group SG is the two styloglossus halves: the same schedule as by name.
  ASSERT_EQ(imported.activations.steps().size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(imported.activations.steps()[s].muscles, by_hand.activations.steps()[s].muscles);
    EXPECT_EQ(imported.activations.steps()[s].level, by_hand.activations.steps()[s].level);
  }
  EXPECT_DOUBLE_EQ(imported.activations.steps()[0].level, 3.0 / 24.0);
}

// external_points may name a file of "id x y z" lines (m) instead of listing them.
TEST_F(SceneAnsysMacros, ExternalPointsFromAFile) {
  write("bone.txt", "# id x y z [m]\r\n4037, -0.07, 0.075, 0.04 ! the styloid\r\n\r\n");
  std::string from_file = kImported;
  const std::string listed = "external_points: {4037: [-0.07, 0.075, 0.04]}";
  from_file.replace(from_file.find(listed), listed.size(), "external_points: bone.txt");
  const BuiltScene a = build_scene(scene(kImported));
  const BuiltScene b = build_scene(scene(from_file));
  ASSERT_EQ(b.muscles->muscles().size(), a.muscles->muscles().size());
  const auto& fa = a.muscles->muscles()[0].fibres;
  const auto& fb = b.muscles->muscles()[0].fibres;
  ASSERT_EQ(fb.size(), fa.size());
  for (std::size_t f = 0; f < fa.size(); ++f) {
    ASSERT_TRUE(fb[f].origin.has_value());
    EXPECT_EQ(*fb[f].origin, *fa[f].origin);
    EXPECT_EQ(fb[f].nodes, fa[f].nodes);
  }
  write("bad_bone.txt", "4037 -0.07 0.075\n");
  from_file.replace(from_file.find("bone.txt"), 8, "bad_bone.txt");
  expect_error(from_file, "muscles.ansys_macros.external_points",
               "bad_bone.txt, line 1: expected 'id x y z'");
}

TEST_F(SceneAnsysMacros, NodeListNumberings) {
  write("jaw0.txt", "0 5 10 15\n");
  write("jaw_ids.txt", "# ids\n1\n6\n11\n16\n");
  const BuiltScene built = build_scene(scene(R"(
node_sets:
  a: {file: jaw.txt, numbering: one_based}
  b: {file: jaw0.txt, numbering: zero_based}
  c: {file: jaw_ids.txt, numbering: ids}
)"));
  const fem::Mesh& mesh = built.solid->mesh();
  EXPECT_EQ(mesh.node_set("a"), (std::vector<int>{0, 5, 10, 15}));
  EXPECT_EQ(mesh.node_set("b"), mesh.node_set("a"));
  EXPECT_EQ(mesh.node_set("c"), mesh.node_set("a"));
}

TEST_F(SceneAnsysMacros, Errors) {
  // A fibre through an id that is neither a node nor an external point: named by file and line.
  expect_error(
      R"(
muscles: {ansys_macros: {elements: CreateMuscles.mac, fibres: Fibers.mac,
                         max_force: MuscleMaxForce.txt}}
)",
      "muscles.ansys_macros (" + (dir_ / "Fibers.mac").string() + ", line 2, fibre 1 of STY_L)",
      "no node with id 4037 in the mesh file (an external point?", true);
  expect_error(R"(
muscles: {ansys_macros: {elements: CreateMuscles.mac, fibres: Fibers.mac,
                         max_force: MuscleMaxForce.txt, external_points: {4037: [0, 0, 0]},
                         groups: {SG: [STY_L, STY_X]}}}
)",
               "muscles.ansys_macros.groups.SG[1]", "no imported muscle 'STY_X'");
  write("bad.mac", "ESEL,S,ELEM,,1\r\nCM,A,ELEM\r\nESEL,S,NODE,,1\r\n");
  expect_error(R"(
muscles: {ansys_macros: {elements: bad.mac, fibres: Fibers.mac, max_force: MuscleMaxForce.txt}}
)",
               "muscles.ansys_macros.elements", "bad.mac, line 3: expected ESEL,S,ELEM");
  expect_error("node_sets:\n  jaw: {file: jaw.txt}\n", "node_sets.jaw", "needs 'numbering'");
  write("far.txt", "1\n2\n31\n");
  expect_error("node_sets:\n  far: {file: far.txt, numbering: one_based}\n",
               "node_sets.far.file (" + (dir_ / "far.txt").string() + ", line 3)",
               "outside the mesh's 30 nodes", true);
  write("bytes.txt", "1 2 \xe9\n");
  expect_error("node_sets:\n  b: {file: bytes.txt, numbering: ids}\n", "node_sets.b.file",
               "bytes.txt, line 1: byte 0xE9 outside a comment");
  try {
    parse_scene(R"(
mesh: {box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 5000}}
analysis: {type: static}
muscles: {ansys_macros: {elements: a.mac, fibres: b.mac, max_force: c.txt}}
)",
                dir_.string(), "test.yaml");
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "muscles.ansys_macros") << e.what();
    EXPECT_NE(std::string(e.what()).find("need mesh: ansys"), std::string::npos) << e.what();
  }
}

// Messages and the run file's tables name an imported mesh's nodes by the file's ids.
TEST_F(SceneAnsysMacros, OneNumbering) {
  const BuiltScene built = build_scene(scene(""));
  ASSERT_EQ(built.numbering.node_ids.size(), 30u);
  EXPECT_EQ(built.numbering.node_ids[6], 7);
  ASSERT_EQ(built.numbering.element_ids.size(), 8u);
  EXPECT_EQ(built.numbering.element(5), "element 6 (index 5)");
  expect_error(R"(
node_sets:
  a: {ids: [7]}
constraints:
  - {set: a, components: [x]}
  - {set: a, components: [x], displacement: 0.001}
)",
               "constraints[1]", "node 7 (index 6) component x is prescribed", true);
}

}  // namespace
}  // namespace tongue::scene
