// The XDMF sidecar of a run file: written next to it when the log closes, and checked against
// the HDF5 file by check_xdmf.py (Debian's python3: xml.etree and h5py), the way ParaView's
// Xdmf2 reader resolves it. ParaView itself is not needed.
#include "run_file/xdmf_sidecar.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fem/mesh/box_generator.hpp"
#include "run_file/run_file_writer.hpp"
#include "scene_run/scene_run_file.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SYSTEM_PYTHON3
#error "SYSTEM_PYTHON3 must name Debian's python3"
#endif

namespace tongue::run_file {
namespace {

namespace fs = std::filesystem;

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

class XdmfSidecar : public testing::TempDirTest {
 protected:
  // Runs check_xdmf.py on the sidecar; its output explains a failure.
  void expect_valid(const fs::path& xmf) {
    const testing::RunResult r =
        testing::run_command(SYSTEM_PYTHON3, "'" CHECK_XDMF_PY "' '" + xmf.string() + "'", dir_);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  }
};

TEST(XdmfSidecarPath, ReplacesTheExtension) {
  EXPECT_EQ(xdmf_sidecar_path("/a/b/run.h5"), "/a/b/run.xmf");
  EXPECT_EQ(xdmf_sidecar_path("run"), "run.xmf");
}

TEST(XdmfText, OneGridPerFrameWithExactTimesAndEscapedNames) {
  XdmfRun run;
  run.h5_file = "a&b.h5";
  run.times = {0.0, 0.1, 1.0 / 3.0};
  run.num_nodes = 12;
  run.num_elements = 2;
  const std::string text = xdmf_text(run);
  EXPECT_EQ(count(text, "GridType=\"Uniform\""), 3);
  EXPECT_EQ(count(text, "CollectionType=\"Temporal\""), 1);
  EXPECT_NE(text.find("<Time Value=\"0.33333333333333331\" />"), std::string::npos) << text;
  EXPECT_NE(text.find(">2 0 0 1 1 1 1 12 3<"), std::string::npos) << text;
  EXPECT_NE(text.find("Dimensions=\"3 12 3\""), std::string::npos) << text;
  EXPECT_EQ(count(text, "a&amp;b.h5:/positions"), 3);
  EXPECT_EQ(text.find("a&b"), std::string::npos);
}

TEST(XdmfText, WithoutFramesShowsTheRestPositions) {
  XdmfRun run;
  run.h5_file = "run.h5";
  run.num_nodes = 8;
  run.num_elements = 1;
  const std::string text = xdmf_text(run);
  EXPECT_EQ(count(text, "<Grid "), 1);
  EXPECT_NE(text.find("run.h5:/rest_positions"), std::string::npos) << text;
  EXPECT_EQ(text.find("<Time"), std::string::npos);
}

TEST_F(XdmfSidecar, RunFileWriterWritesAValidSidecarWhenItCloses) {
  const fem::Mesh mesh = fem::make_box({0, 0, 0}, {0.03, 0.02, 0.01}, 3, 2, 1);
  const fs::path h5 = dir_ / "sub dir" / "run.h5";
  constexpr int kFrames = 7;
  {
    RunFileWriter log(h5.string(), scene_run::mesh_description(mesh), "scene: text");
    fem::Vector x(3 * mesh.num_nodes());
    for (int k = 0; k < kFrames; ++k) {
      for (int i = 0; i < mesh.num_nodes(); ++i)
        for (int c = 0; c < 3; ++c) x[3 * i + c] = mesh.nodes[i][c] + 1e-4 * k * (c + 1);
      log.append(0.002 * k, x, SolverFigures{});
    }
    EXPECT_FALSE(fs::exists(dir_ / "sub dir" / "run.xmf"));  // written at close
  }
  const fs::path xmf = dir_ / "sub dir" / "run.xmf";
  ASSERT_TRUE(fs::exists(xmf));
  EXPECT_FALSE(fs::exists(dir_ / "sub dir" / "run.xmf.tmp"));
  EXPECT_EQ(count(testing::read_text(xmf), "<Time "), kFrames);
  expect_valid(xmf);
}

TEST_F(XdmfSidecar, SimBatchRunFileGetsAValidSidecar) {
  const std::string scene = write("scene.yaml", R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material: {type: mooney_rivlin5}
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
analysis: {type: dynamic, duration: 0.01, dt: 0.002}
)");
  const testing::RunResult r = testing::run_command(
      SIM_BATCH_PATH, "'" + scene + "' --output '" + (dir_ / "run.h5").string() + "' --quiet",
      dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir_ / "run.xmf"));
  expect_valid(dir_ / "run.xmf");
}

}  // namespace
}  // namespace tongue::run_file
