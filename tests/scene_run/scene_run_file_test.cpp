// The run file of a scene is compressed as the scene's output.compression says: deflate level 4
// by default for the full model, none for a reduced model (whose steps outpace deflate), and
// the level given whatever the model. Read back from the file's own filter pipeline.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run_file.hpp"
#include "support/box_scenes.hpp"
#include "support/reduced_box.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::scene_run {
namespace {

scene::Scene box(const std::string& extra) {
  std::string text = testing::kBoxScene;
  const std::string analysis = "dt: 0.002}";
  text.replace(text.find(analysis), analysis.size(), "dt: 0.002, settle: true}");
  return scene::parse_scene(text + extra, "", "box.yaml");
}

// The deflate level of /positions in the file at path; 0 when it has no deflate filter, -1 when
// the file or the dataset does not open.
int positions_deflate_level(const std::string& path) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return -1;
  const hid_t set = H5Dopen2(file, "/positions", H5P_DEFAULT);
  int level = set < 0 ? -1 : 0;
  if (set >= 0) {
    const hid_t plist = H5Dget_create_plist(set);
    for (int i = 0; i < H5Pget_nfilters(plist); ++i) {
      unsigned flags = 0, values[8] = {};
      std::size_t count = 8;
      if (H5Pget_filter2(plist, static_cast<unsigned>(i), &flags, &count, values, 0, nullptr,
                         nullptr) == H5Z_FILTER_DEFLATE)
        level = count > 0 ? static_cast<int>(values[0]) : -1;
    }
    H5Pclose(plist);
    H5Dclose(set);
  }
  H5Fclose(file);
  return level;
}

class SceneRunFile : public testing::TempDirTest {
 protected:
  int level_of(const scene::Scene& scene) {
    const std::string path = (dir_ / "run.h5").string();
    {
      const scene::BuiltScene built = scene::build_scene(scene);
      auto log = open_scene_run_file(path, scene, built);
      log->append(0.0, built.solid->rest_positions(), {},
                  scene_muscle_frame(built, fem::Vector::Zero(built.solid->num_dofs()), nullptr));
    }
    return positions_deflate_level(path);
  }
};

TEST_F(SceneRunFile, TheFullModelsRunFileIsDeflatedAtLevel4UnlessTheSceneSaysOtherwise) {
  EXPECT_EQ(level_of(box("")), 4);
  EXPECT_EQ(level_of(box("output: {compression: 0}\n")), 0);
  EXPECT_EQ(level_of(box("output: {compression: 9}\n")), 9);
}

TEST_F(SceneRunFile, AReducedModelsRunFileIsNotCompressedUnlessTheSceneSaysSo) {
  const std::string basis = (dir_ / "basis.h5").string();
  testing::write_reduced_basis_of(box(""), 20, basis);
  const std::string model = "model: {reduced: " + basis + "}\n";
  EXPECT_EQ(level_of(box(model)), 0);
  EXPECT_EQ(level_of(box(model + "output: {compression: 1}\n")), 1);
}

}  // namespace
}  // namespace tongue::scene_run
