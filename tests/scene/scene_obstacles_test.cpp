// The obstacles and contact keys: what the reader refuses, the files placed as the scene says,
// a solid that starts behind an obstacle, bad files named, the built-in vocal tract.
#include <gtest/gtest.h>

#include <string>

#include "scene/scene_builder.hpp"
#include "scene/scene_error_expectations.hpp"
#include "scene/scene_reader.hpp"
#include "support/box_scenes.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::scene {
namespace {

using scene_test::expect_build_error;
using scene_test::expect_parse_error;

const char* const kBox = testing::kStaticBoxScene;

// A square of 100 x 100 file units in the plane z = 0, normal +z (a floor).
const char* const kFloorObj = "v -50 -50 0\nv 50 -50 0\nv 50 50 0\nv -50 50 0\nf 1 2 3\nf 1 3 4\n";

class SceneObstacles : public testing::TempDirTest {};

TEST_F(SceneObstacles, ReaderRefusesWhatItCannotPlace) {
  const std::string box = kBox;
  expect_parse_error(box + "contact: {penalty: 1e9}\n", "contact", "needs obstacles");
  expect_parse_error(box + "obstacles: vocal_tract\n", "obstacles", "built-in tongue");
  expect_parse_error(box + "obstacles: palate\n", "obstacles", "expected 'vocal_tract'");
  expect_parse_error(box + "obstacles: [{name: floor, file: missing.obj}]\n", "obstacles[0].file",
                     "obstacle file not found");
  const std::string floor = write("floor.obj", kFloorObj);
  expect_parse_error(box + "obstacles: [{name: floor, file: " + floor + ", size: 2}]\n",
                     "obstacles[0].size");
  expect_parse_error(
      box + "obstacles: [{name: a, file: " + floor + "}, {name: a, file: " + floor + "}]\n",
      "obstacles[1].name", "defined twice");
  expect_parse_error(box + "obstacles: [{name: a, file: " + floor + ", normals: round}]\n",
                     "obstacles[0].normals", "unknown normals 'round' (known: faceted, smooth)");
  expect_parse_error(box + "obstacles: [{name: a, file: " + floor + "}]\ncontact: {penalty: -1}\n",
                     "contact.penalty");
  expect_parse_error(box + "obstacles: [{name: a, file: " + floor +
                         "}]\ncontact: {penetration_tolerance: -1e-4}\n",
                     "contact.penetration_tolerance");
  expect_parse_error(
      box + "obstacles: [{name: a, file: " + floor + "}]\ncontact: {max_augmentations: -1}\n",
      "contact.max_augmentations");
}

TEST_F(SceneObstacles, FileIsScaledRotatedAndTranslated) {
  // The floor in mm, turned by 90 degrees about x ((x, y, z) -> (x, -z, y): the plane z = 0
  // becomes y = 0 and its normal +z becomes -y) and moved to 5 mm above the box (y = 0.015),
  // facing it.
  const std::string floor = write("floor.obj", kFloorObj);
  const BuiltScene built = build_scene(
      parse_scene(std::string(kBox) + "obstacles:\n  - {name: lid, file: " + floor +
                      ", length_scale: 0.001, rotate: [90, 0, 0], translate: [0, 0.015, 0]}\n",
                  "", "test.yaml"));
  ASSERT_TRUE(built.contact);
  EXPECT_EQ(built.system->loads().back()->name(), "contact");
  const fem::Obstacle& lid = *built.contact->obstacles().at(0);
  EXPECT_EQ(lid.name(), "lid");
  EXPECT_NEAR(lid.box_min().y(), 0.015, 1e-15);
  EXPECT_NEAR(lid.box_max().y(), 0.015, 1e-15);
  EXPECT_NEAR(lid.box_max().x(), 0.05, 1e-15);
  const fem::SurfacePoint below = lid.closest(fem::Vec3(0.02, 0.01, 0.005));
  EXPECT_NEAR(below.distance, 0.005, 1e-15);  // in front of the lid: its normal faces the box
  EXPECT_LT((below.normal - fem::Vec3(0, -1, 0)).norm(), 1e-15);
  EXPECT_EQ(lid.normals(), fem::Normals::faceted);  // unless the scene says otherwise
  const BuiltScene smooth = build_scene(
      parse_scene(std::string(kBox) + "obstacles:\n  - {name: lid, file: " + floor +
                      ", length_scale: 0.001, rotate: [90, 0, 0], translate: [0, 0.015, 0],"
                      " normals: smooth}\n",
                  "", "test.yaml"));
  EXPECT_EQ(smooth.contact->obstacles().at(0)->normals(), fem::Normals::smooth);
}

TEST_F(SceneObstacles, SolidStartingBehindAnObstacleIsRefused) {
  // The floor at y = 0.005 facing -y cuts the box (0 <= y <= 0.01): its upper nodes are behind.
  const std::string floor = write("floor.obj", kFloorObj);
  expect_build_error(std::string(kBox) + "obstacles:\n  - {name: floor, file: " + floor +
                         ", length_scale: 0.001, rotate: [90, 0, 0], translate: [0, 0.005, 0]}\n",
                     "obstacles (floor)", "start behind obstacle 'floor'");
}

TEST_F(SceneObstacles, BadFilesAreNamed) {
  const std::string words = write("words.obj", "not a mesh\n");
  expect_build_error(std::string(kBox) + "obstacles: [{name: w, file: " + words + "}]\n",
                     "obstacles (w)", words);
  // A closed cube with every face turned inward.
  const std::string inside_out =
      write("cube.obj",
            "v 1 1 1\nv 2 1 1\nv 2 2 1\nv 1 2 1\nv 1 1 2\nv 2 1 2\nv 2 2 2\nv 1 2 2\n"
            "f 1 2 3 4\nf 8 7 6 5\nf 5 6 2 1\nf 6 7 3 2\nf 7 8 4 3\nf 8 5 1 4\n");
  expect_build_error(std::string(kBox) + "obstacles: [{name: cube, file: " + inside_out + "}]\n",
                     "obstacles (cube)", "inward normals");
  // A triangle whose corners lie on one line.
  const std::string flat = write("flat.obj", "v 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 3\n");
  expect_build_error(std::string(kBox) + "obstacles: [{name: flat, file: " + flat + "}]\n",
                     "obstacles (flat)", "degenerate");
  expect_build_error(std::string(kBox) + "obstacles: [{name: flat, file: " + flat + "}]\n",
                     "obstacles (flat)", flat);
}

TEST(SceneVocalTract, BuiltInTongueGetsItsFourSurfaces) {
  const BuiltScene built = build_scene(parse_scene(R"(
mesh: {tongue: {refinement: 1}}
material: {type: mooney_rivlin5}
obstacles: vocal_tract
contact: {penalty: 2.0e8, smoothing: 1.0e-5, penetration_tolerance: 5.0e-5, max_augmentations: 2}
analysis: {type: static}
)",
                                                   "", "test.yaml"));
  ASSERT_TRUE(built.contact);
  std::vector<std::string> names;
  for (const auto& o : built.contact->obstacles()) names.push_back(o->name());
  EXPECT_EQ(names,
            (std::vector<std::string>{"hard_palate", "upper_teeth", "velum", "pharyngeal_wall"}));
  for (const auto& o : built.contact->obstacles()) EXPECT_EQ(o->normals(), fem::Normals::smooth);
  EXPECT_EQ(built.contact->settings().penalty, 2.0e8);
  EXPECT_EQ(built.contact->settings().smoothing, 1.0e-5);
  EXPECT_EQ(built.contact->settings().penetration_tolerance, 5.0e-5);
  EXPECT_EQ(built.contact->settings().max_augmentations, 2);
  // No node starts in contact (the builder would have refused it) and some are candidates.
  EXPECT_TRUE(built.contact->report(fem::Vector::Zero(built.solid->num_dofs())).contacts.empty());
  EXPECT_GT(built.contact->nodes().size(), 300u);
}

}  // namespace
}  // namespace tongue::scene
