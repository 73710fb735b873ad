// build_reduced_model end to end: the real executable trains on the built-in tongue (short
// sequences, so that it takes a few seconds), and its basis and snapshots are read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "reduced/reduced_basis_file.hpp"
#include "reduced/snapshot_file.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir_test.hpp"

#if !defined(BUILD_REDUCED_MODEL_PATH) || !defined(PROJECT_DIR)
#error "BUILD_REDUCED_MODEL_PATH and PROJECT_DIR must be defined"
#endif

namespace tongue {
namespace {

namespace fs = std::filesystem;

class BuildReducedModel : public testing::TempDirTest {
 protected:
  testing::RunResult run(const std::string& args) const {
    return testing::run_command(BUILD_REDUCED_MODEL_PATH, args, dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

// 80 ms per sequence (10 steps of scenes/tongue_ep.yaml's 8 ms), one pair, one mix.
TEST_F(BuildReducedModel, TheBasisReproducesTheTrainingSnapshotsToItsEnergyFraction) {
  const std::string scene = PROJECT_DIR "/scenes/tongue_ep.yaml";
  const testing::RunResult r = run(
      "'" + scene + "' --output '" + path("basis.h5") + "' --snapshots '" + path("snapshots.h5") +
      "' --duration 0.08 --pairs 1 --mixes 1 --energy 0.999 --sampling 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("22 training runs of 10 steps"), std::string::npos) << r.out;

  const reduced::ReducedBasis b = reduced::read_reduced_basis(path("basis.h5"));
  const reduced::SnapshotSet s = reduced::read_snapshots(path("snapshots.h5"));
  // 10 muscle groups stepped and ramped, one pair, one mix: 22 runs x 10 steps, all converged.
  ASSERT_EQ(s.snapshots.cols(), 220);
  EXPECT_EQ(b.snapshots, 220);
  EXPECT_EQ(b.runs, 22);
  ASSERT_GT(b.modes.cols(), 0);
  ASSERT_EQ(b.modes.rows(), s.snapshots.rows());
  // Orthonormal modes (the SVD's round-off), and the projection leaves out at most 1 - 0.999
  // of the snapshots' energy (what the POD guarantees; docs/reduced.md).
  EXPECT_LT(
      (b.modes.transpose() * b.modes - Eigen::MatrixXd::Identity(b.modes.cols(), b.modes.cols()))
          .norm(),
      1e-12);
  const Eigen::MatrixXd left = s.snapshots - b.modes * (b.modes.transpose() * s.snapshots);
  EXPECT_LE(left.squaredNorm(), (1.0 - 0.999) * s.snapshots.squaredNorm());
  EXPECT_GE(b.captured, 0.999);
  // A sample of the elements within the misfit asked (a loose one: the sampling's path is
  // longer the tighter it is), fewer than the mesh's 720, with positive weights.
  EXPECT_LE(b.sample_error, 0.2);
  EXPECT_EQ(b.sample_tolerance, 0.2);
  EXPECT_GT(b.sample_elements.size(), 0u);
  EXPECT_LT(b.sample_elements.size(), 720u);
  EXPECT_GT(b.sample_weights.minCoeff(), 0.0);
  // The tongue moves in the training runs (millimetres), from the settled origin.
  EXPECT_GT(s.snapshots.cwiseAbs().maxCoeff(), 1e-4);
  // The basis fits the scene's mesh, not another one.
  const scene::Scene sc = scene::read_scene(scene);
  const scene::BuiltScene built = scene::build_scene(sc);
  EXPECT_NO_THROW(reduced::check_fits(b, "basis.h5", built.solid->mesh(), b.material));
  EXPECT_NE(b.material.find("mooney_rivlin5"), std::string::npos) << b.material;
  EXPECT_EQ(b.scene, sc.text);
}

TEST_F(BuildReducedModel, AStaticSceneOrAMissingOutputIsABadCommand) {
  const std::string scene =
      write("static.yaml",
            "mesh: {tongue: {refinement: 1}}\n"
            "material: {type: neo_hookean, parameters: {shear_modulus: 1000}}\n"
            "constraints: [{set: mandible, components: [x, y, z]}]\n"
            "muscles: builtin\n"
            "analysis: {type: static}\n");
  testing::RunResult r = run("'" + scene + "' --output '" + path("basis.h5") + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("training needs a dynamic analysis"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("basis.h5")));
  r = run("'" + scene + "'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("usage: build_reduced_model"), std::string::npos) << r.err;
  r = run("'" + scene + "' --output x.h5 --energy 2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--energy must lie in (0, 1]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tongue
