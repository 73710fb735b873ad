// Runs the real sim_batch executable on small scenes and reads its run file back with run_file's
// reader, the dataset names spelled out here rather than taken from the layout header, so that a
// renamed dataset fails.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene_reader.hpp"
#include "support/box_scenes.hpp"
#include "support/reduced_box.hpp"
#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_BATCH_PATH
#error "SIM_BATCH_PATH must name the sim_batch executable"
#endif

namespace tongue::apps {
namespace {

namespace fs = std::filesystem;

// A 40 x 10 x 10 mm block, 4 x 1 x 1 elements (20 nodes), clamped at x = 0, under gravity.
const char* const kHead = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material:
  type: mooney_rivlin5
  density: 1000
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
)";

const char* const kDynamic = R"(
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
output: {every: 3}
)";

using testing::RunFile;
using testing::RunResult;

class SimBatch : public testing::TempDirTest {
 protected:
  fs::path write_scene(const std::string& text) const { return write("scene.yaml", text); }

  RunResult run(const std::string& args) const {
    return testing::run_command(SIM_BATCH_PATH, args, dir_);
  }
  // 'path', for the shell (appended, not "'" + text: GCC 12 warns falsely about that, -Wrestrict).
  static std::string quoted(const fs::path& p) {
    std::string s = "'";
    s += p.string();
    s += "'";
    return s;
  }
};

TEST_F(SimBatch, DynamicSceneWritesARunFileThatMoves) {
  const std::string text = std::string(kHead) + kDynamic;
  const fs::path scene = write_scene(text);
  const fs::path h5 = dir_ / "out" / "run.h5";  // the missing directory is created
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("summary: completed, 10 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("real-time factor"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max displacement"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("volume change"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("residual [N]"), std::string::npos) << r.out;  // per-step table

  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  // Frames: t = 0, then steps 3, 6, 9 (every 3) and the last step 10.
  EXPECT_EQ(f.shape("/time"), (std::vector<std::size_t>{5}));
  EXPECT_EQ(f.shape("/positions"), (std::vector<std::size_t>{5, 20, 3}));
  EXPECT_EQ(f.shape("/rest_positions"), (std::vector<std::size_t>{20, 3}));
  EXPECT_EQ(f.shape("/elements"), (std::vector<std::size_t>{4, 8}));
  for (const char* name :
       {"/solver/iterations", "/solver/residual", "/solver/wall_time", "/solver/cuts"})
    EXPECT_EQ(f.shape(name), (std::vector<std::size_t>{5})) << name;

  const std::vector<double> time = f.doubles("/time");
  ASSERT_EQ(time.size(), 5u);
  const double expected[] = {0.0, 0.006, 0.012, 0.018, 0.02};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(time[i], expected[i], 1e-12) << i;

  const std::vector<double> rest = f.doubles("/rest_positions");
  const std::vector<double> positions = f.doubles("/positions");
  ASSERT_EQ(positions.size(), 5u * 60u);
  double first_change = 0.0, last_change = 0.0, min_y_change = 0.0;
  for (int k = 0; k < 60; ++k) {
    first_change = std::max(first_change, std::abs(positions[k] - rest[k]));
    const double d = positions[4 * 60 + k] - rest[k];
    last_change = std::max(last_change, std::abs(d));
    if (k % 3 == 1) min_y_change = std::min(min_y_change, d);
  }
  EXPECT_EQ(first_change, 0.0);    // starts at rest
  EXPECT_GT(last_change, 1e-6);    // and moves
  EXPECT_LT(min_y_change, -1e-6);  // down, under gravity

  const std::vector<int> iterations = f.ints("/solver/iterations");
  ASSERT_EQ(iterations.size(), 5u);
  EXPECT_EQ(iterations[0], 0);  // no settling
  for (int i = 1; i < 5; ++i) EXPECT_GT(iterations[i], 0) << i;

  EXPECT_EQ(f.int_attribute("format_version"), 1);
  EXPECT_EQ(f.string_attribute("/", "length_unit"), "m");
  EXPECT_EQ(f.string_attribute("/", "time_unit"), "s");
  EXPECT_EQ(f.string_attribute("/", "scene_text"), text);
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
  EXPECT_EQ(f.string_attribute("/time", "units"), "s");
  EXPECT_EQ(f.string_attribute("/positions", "units"), "m");
  EXPECT_EQ(f.string_attribute("/rest_positions", "units"), "m");
  EXPECT_EQ(f.string_attribute("/solver/residual", "units"), "N");
  EXPECT_EQ(f.string_attribute("/solver/wall_time", "units"), "s");

  // The mesh's sets, and no muscle datasets without muscles.
  EXPECT_EQ(f.ints("/mesh/node_sets/x_min"), (std::vector<int>{0, 5, 10, 15}));
  EXPECT_EQ(f.shape("/mesh/node_sets/all"), (std::vector<std::size_t>{20}));
  EXPECT_EQ(f.ints("/mesh/element_sets/all"), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(f.exists("/muscles"));
  EXPECT_FALSE(f.exists("/activations"));
  EXPECT_EQ(f.string_attribute("/", "initial_state").rfind("reference", 0), 0u);
}

TEST_F(SimBatch, OutputFileFromTheSceneAndQuiet) {
  const fs::path h5 = dir_ / "from_scene.h5";
  // output.file is relative to the working directory: give it absolute here.
  const fs::path scene = write_scene(std::string(kHead) + R"(
analysis: {type: dynamic, duration: 0.004, dt: 0.002}
output: {file: ')" + h5.string() + "'}\n");
  const RunResult r = run(quoted(scene) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("residual [N]"), std::string::npos) << r.out;  // no per-step table
  EXPECT_NE(r.out.find("summary:"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.shape("/positions"), (std::vector<std::size_t>{3, 20, 3}));
}

TEST_F(SimBatch, StaticSceneWritesRestAndEachLoadIncrement) {
  const fs::path scene = write_scene(std::string(kHead) + R"(
loads:
  - {set: x_max, total_force: [0, -0.001, 0]}
analysis: {type: static, load_steps: 2}
)");
  const fs::path h5 = dir_ / "static.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("summary: completed, 2 increments"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/time"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(f.string_attribute("/", "time_unit"), "1");  // load factor
  EXPECT_EQ(f.shape("/positions"), (std::vector<std::size_t>{3, 20, 3}));
  const std::vector<double> rest = f.doubles("/rest_positions");
  const std::vector<double> positions = f.doubles("/positions");
  double half = 0.0, full = 0.0;  // largest displacement at load factors 0.5 and 1 [m]
  for (int k = 0; k < 60; ++k) {
    half = std::max(half, std::abs(positions[60 + k] - rest[k]));
    full = std::max(full, std::abs(positions[120 + k] - rest[k]));
  }
  EXPECT_GT(half, 1e-6);
  EXPECT_GT(full, 1.5 * half);  // a small load: nearly proportional
}

// A 10 mm cube stretched to 1.8 times its length along x (symmetry planes on the min faces).
// mooney_rivlin5 loses strong ellipticity near a uniaxial stretch of 1.54 (fem/material
// ellipticity tests): the run says so, on stderr and in the run file, before Newton gives up
// there; the exponential law, elliptic throughout, completes without a warning.
std::string stretched_cube(const std::string& material) {
  return "mesh:\n  box: {size: [0.01, 0.01, 0.01], divisions: [2, 2, 2]}\nmaterial: {type: " +
         material + R"(}
constraints:
  - {set: x_min, components: [x]}
  - {set: y_min, components: [y]}
  - {set: z_min, components: [z]}
  - {set: x_max, components: [x], displacement: 0.008}
analysis: {type: static, load_steps: 8}
)";
}

TEST_F(SimBatch, LossOfEllipticityIsReported) {
  const fs::path h5 = dir_ / "stretch.h5";
  const RunResult mr5 =
      run(quoted(write_scene(stretched_cube("mooney_rivlin5"))) + " --output " + quoted(h5));
  EXPECT_NE(mr5.err.find("warning: at t = "), std::string::npos) << mr5.err;
  EXPECT_NE(mr5.err.find("mooney_rivlin5 is no longer strongly elliptic"), std::string::npos)
      << mr5.err;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_NE(f.string_attribute("/", "material_warning").find("no longer strongly elliptic"),
            std::string::npos);

  const RunResult exponential = run(quoted(write_scene(stretched_cube("exponential"))));
  EXPECT_EQ(exponential.exit_code, 0) << exponential.out << exponential.err;
  EXPECT_EQ(exponential.err.find("elliptic"), std::string::npos) << exponential.err;
}

TEST_F(SimBatch, AReducedModelRunsAndReportsItsIndicator) {
  // The test box with its flexor, stepped to 0.6 for 20 ms, run by a reduced model of itself
  // checked every 2 steps: the run file holds the indicator at each frame (0 until the first
  // check), and a threshold below it is warned once, on stderr and in the run file.
  const std::string body =
      std::string(testing::kBoxScene) + "activations:\n  - {muscles: [flexor], level: 0.6}\n";
  const fs::path basis = dir_ / "basis.h5";
  testing::write_reduced_basis_of(scene::parse_scene(body, "", "box.yaml"), 40, basis.string());
  const fs::path h5 = dir_ / "reduced.h5";
  RunResult r =
      run(quoted(write_scene(body + "model: {reduced: " + quoted(basis) + ", check_every: 2}\n")) +
          " --output " + quoted(h5));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find("reduced model"), std::string::npos) << r.err;
  {
    const RunFile f(h5);
    ASSERT_TRUE(f.ok());
    const std::vector<double> c = f.doubles("/solver/reduced_correction");
    ASSERT_EQ(c.size(), f.doubles("/time").size());
    ASSERT_GE(c.size(), 3u);
    EXPECT_EQ(c[0], 0.0);  // the initial state: not checked
    EXPECT_GT(*std::max_element(c.begin(), c.end()), 0.0);
    EXPECT_LT(*std::max_element(c.begin(), c.end()), 1e-4);  // m: far below the 1 mm default
    EXPECT_EQ(f.string_attribute("/", "reduced_model_warning"), "<missing>");
  }
  r = run(quoted(write_scene(body + "model: {reduced: " + quoted(basis) +
                             ", check_every: 2, warn_above: 1.0e-15}\n")) +
          " --output " + quoted(h5));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("warning: at t = 0.004 s (step 2) the full model would move the reduced "
                       "model's state by"),
            std::string::npos)
      << r.err;
  const RunFile f(h5);
  EXPECT_NE(f.string_attribute("/", "reduced_model_warning").find("model.warn_above"),
            std::string::npos);
}

TEST_F(SimBatch, BadSceneExitsNonZeroNamingTheKeyPath) {
  const fs::path scene = write_scene(std::string(kHead) + R"(
analysis: {type: dynamic, duration: 0.02, dt: -0.002}
)");
  const fs::path h5 = dir_ / "never.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(scene.string() + ": analysis.dt:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(h5));  // nothing is written for a scene that cannot run
}

TEST_F(SimBatch, MissingSceneFileExitsNonZero) {
  const RunResult r = run(quoted(dir_ / "absent.yaml"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("absent.yaml"), std::string::npos) << r.err;
}

TEST_F(SimBatch, BadCommandLineExitsNonZero) {
  const RunResult r = run("--frobnicate");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("usage"), std::string::npos) << r.err;
}

TEST_F(SimBatch, UnconvergedStepIsReportedAndWrittenFramesKept) {
  // One Newton iteration, an unreachable tolerance and no cuts: the first step must fail.
  const fs::path scene = write_scene(std::string(kHead) + R"(
analysis: {type: dynamic, duration: 0.02, dt: 0.002, max_cuts: 0}
solver: {max_iterations: 1, residual_rtol: 0, residual_atol: 0, increment_rtol: 0,
         increment_atol: 0, displacement_tolerance: 0}
)");
  const fs::path h5 = dir_ / "failed.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("failed to converge"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("FAILED"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.shape("/positions"), (std::vector<std::size_t>{1, 20, 3}));  // the initial frame
  EXPECT_EQ(f.string_attribute("/", "status").rfind("failed: ", 0), 0u);
}

// The built-in tongue, settled under gravity, then a step of 3 N on SG (the paper's first
// experiment), cut short to three 4 ms steps.
const char* const kTongueSg = R"(
mesh: {tongue: {refinement: 1}}
material: {type: mooney_rivlin5, parameters: {poisson_ratio: 0.49}, density: 1000}
constraints:
  - {set: mandible, components: [x, y, z]}
  - {set: root_bottom, components: [y]}
  - {set: hyoid, components: [y, z]}
gravity: [0, -9.81, 0]
damping: {alpha: 0, beta: 0.028}
muscles: builtin
activations:
  - {group: SG, force: 3.0, start: 0, end: 0.12}
analysis: {type: dynamic, settle: true, duration: 0.012, dt: 0.004}
)";

TEST_F(SimBatch, TongueSceneLogsMusclesSetsAndLandmarks) {
  const fs::path scene = write_scene(kTongueSg);
  const fs::path h5 = dir_ / "tongue.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("19 muscles"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("summary: completed, 3 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("landmark displacement"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("velar_dorsum"), std::string::npos) << r.out;

  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  const std::size_t frames = 4, muscles = 19;  // t = 0 (settled) and 3 steps
  EXPECT_EQ(f.shape("/time"), (std::vector<std::size_t>{frames}));
  EXPECT_EQ(f.shape("/activations"), (std::vector<std::size_t>{frames, muscles}));
  EXPECT_EQ(f.shape("/muscles/length"), (std::vector<std::size_t>{frames, muscles}));
  EXPECT_EQ(f.shape("/muscles/velocity"), (std::vector<std::size_t>{frames, muscles}));
  EXPECT_EQ(f.shape("/muscles/max_force"), (std::vector<std::size_t>{muscles}));
  EXPECT_EQ(f.string_attribute("/activations", "units"), "1");
  EXPECT_EQ(f.string_attribute("/muscles/length", "units"), "m");
  EXPECT_EQ(f.string_attribute("/muscles/velocity", "units"), "m/s");
  EXPECT_EQ(f.string_attribute("/muscles/max_force", "units"), "N");
  EXPECT_EQ(f.string_attribute("/", "initial_state").rfind("settled", 0), 0u);

  const std::vector<std::string> names = f.strings("/muscles/names");
  ASSERT_EQ(names.size(), muscles);
  const auto find = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const int left = find("SG_left"), right = find("SG_right");
  ASSERT_LT(left, static_cast<int>(muscles));
  ASSERT_LT(right, static_cast<int>(muscles));
  const std::vector<double> max_force = f.doubles("/muscles/max_force");
  EXPECT_DOUBLE_EQ(max_force[left] + max_force[right], 24.0);

  // Frame 0 is the settled state, muscles off; during the step SG runs at 3 / 24 = 0.125.
  const std::vector<double> act = f.doubles("/activations");
  const std::vector<double> length = f.doubles("/muscles/length");
  ASSERT_EQ(act.size(), frames * muscles);
  for (std::size_t t = 0; t < frames; ++t) {
    for (std::size_t m = 0; m < muscles; ++m) {
      const bool sg = static_cast<int>(m) == left || static_cast<int>(m) == right;
      EXPECT_DOUBLE_EQ(act[t * muscles + m], sg && t > 0 ? 0.125 : 0.0) << t << " " << names[m];
      EXPECT_GT(length[t * muscles + m], 0.0) << names[m];
    }
  }
  EXPECT_LT(length[3 * muscles + left], length[left]);  // SG shortens

  // The fibres of every muscle, and where the run came from.
  const std::vector<int> fibre_muscle = f.ints("/muscles/fibres/muscle");
  const std::vector<int> offsets = f.ints("/muscles/fibres/node_offsets");
  const std::vector<int> fibre_nodes = f.ints("/muscles/fibres/nodes");
  ASSERT_FALSE(fibre_muscle.empty());
  ASSERT_EQ(offsets.size(), fibre_muscle.size() + 1);
  EXPECT_EQ(offsets.front(), 0);
  EXPECT_EQ(static_cast<std::size_t>(offsets.back()), fibre_nodes.size());
  for (int m : fibre_muscle) EXPECT_LT(static_cast<std::size_t>(m), muscles);
  EXPECT_EQ(f.shape("/muscles/fibres/origin"), (std::vector<std::size_t>{fibre_muscle.size(), 3}));
  // The built-in tongue has fibres with a bony origin and fibres without (NaN in the file).
  const std::vector<double> origins = f.doubles("/muscles/fibres/origin");
  std::size_t without_origin = 0;
  for (std::size_t k = 0; k < fibre_muscle.size(); ++k) without_origin += std::isnan(origins[3 * k]);
  EXPECT_GT(without_origin, 0u);
  EXPECT_LT(without_origin, fibre_muscle.size());
  EXPECT_EQ(f.string_attribute("/", "project_version"), "0.1.0");
  EXPECT_EQ(f.string_attribute("/", "start_time").size(), 20u);  // 2026-11-22T17:40:00Z

  // Sets for pictures: the muscle's elements and the landmarks.
  const std::vector<int> sg_elements = f.ints("/mesh/element_sets/SG_left");
  EXPECT_FALSE(sg_elements.empty());
  const std::vector<std::size_t> elements_shape = f.shape("/elements");
  ASSERT_EQ(elements_shape.size(), 2u);
  for (int e : sg_elements) EXPECT_LT(static_cast<std::size_t>(e), elements_shape[0]);
  for (const char* name :
       {"tip", "blade", "palatal_dorsum", "velar_dorsum", "root", "gg_insertion"}) {
    EXPECT_EQ(f.shape(std::string("/mesh/node_sets/") + name), (std::vector<std::size_t>{1}))
        << name;
  }
  EXPECT_FALSE(f.ints("/mesh/node_sets/mandible").empty());

  // SG lifts the velar dorsum (Gerard et al. 2003 sec. IV.2).
  const int velar = f.ints("/mesh/node_sets/velar_dorsum").at(0);
  const std::vector<std::size_t> pshape = f.shape("/positions");
  ASSERT_EQ(pshape.size(), 3u);
  const std::vector<double> positions = f.doubles("/positions");
  const std::size_t frame_size = pshape[1] * 3;
  EXPECT_GT(positions[3 * frame_size + 3 * velar + 1], positions[3 * velar + 1]);
}

TEST_F(SimBatch, StaticSceneWithListedMuscleLogsItsLevelAndLength) {
  const fs::path scene = write_scene(std::string(kHead) + R"(
muscles:
  - {name: flexor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [2, 3, 4]}]}
activations:
  - {muscles: [flexor], level: 0.5}
muscle_stiffening: 1   # the plain fibre model: this test is about the logging of a listed muscle
analysis: {type: static, load_steps: 2}
)");
  const fs::path h5 = dir_ / "muscle_static.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.strings("/muscles/names"), (std::vector<std::string>{"flexor"}));
  EXPECT_EQ(f.doubles("/activations"), (std::vector<double>{0.5, 0.5, 0.5}));
  EXPECT_EQ(f.doubles("/muscles/velocity"), (std::vector<double>{0.0, 0.0, 0.0}));
  const std::vector<double> length = f.doubles("/muscles/length");
  ASSERT_EQ(length.size(), 3u);
  EXPECT_DOUBLE_EQ(length[0], 0.02);  // two 10 mm segments at rest
  EXPECT_LT(length[2], length[0]);    // the muscle pulls its end in
  EXPECT_EQ(f.ints("/mesh/element_sets/flexor"), (std::vector<int>{2, 3}));
}

TEST_F(SimBatch, UnknownMuscleGroupIsASceneError) {
  std::string text = kTongueSg;
  text.replace(text.find("group: SG"), 9, "group: SK");
  const fs::path scene = write_scene(text);
  const fs::path h5 = dir_ / "never.h5";
  const RunResult r = run(quoted(scene) + " --output " + quoted(h5));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("activations[0].group: no muscle is named 'SK'"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(h5));
}

}  // namespace
}  // namespace tongue::apps
