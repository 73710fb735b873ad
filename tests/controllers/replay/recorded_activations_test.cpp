// Run files read for a replay (controllers/replay/recorded_activations.hpp) and checked against a
// server's model (replayer.hpp), without a bus; the run files are sim_batch's on small box scenes.
#include "replay/recorded_activations.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <string>

#include "controller/input_error.hpp"
#include "replay/replayer.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_BATCH_PATH
#error "SIM_BATCH_PATH must name the sim_batch executable"
#endif

namespace tongue::replay {
namespace {

namespace fs = std::filesystem;

constexpr double kDt = 0.002;  // s, the scene's

// One muscle switched on to 0.3 from 4 ms; 10 steps.
std::string box_scene(const std::string& output_every = "1", bool muscles = true) {
  std::string s = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material: {type: mooney_rivlin5, density: 1000}
constraints:
  - {set: x_min, components: [x, y, z]}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
output: {every: )" +
                  output_every + "}\n";
  if (muscles)
    s += R"(muscles:
  - {name: flexor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [2, 3, 4]}]}
activations:
  - {muscles: [flexor], level: 0.3, start: 0.004}
)";
  return s;
}

class RecordedActivationsTest : public tongue::testing::TempDirTest {
 protected:
  fs::path batch(const std::string& scene, const std::string& name) {
    const fs::path out = dir_ / (name + ".h5");
    const auto r = tongue::testing::run_command(
        SIM_BATCH_PATH,
        "'" + write(name + ".yaml", scene) + "' --quiet --output '" + out.string() + "'", dir_);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }

  static controller::Model box_model() {
    controller::Model m;
    m.muscle_names = {"flexor"};
    m.muscle_max_forces = {0.01};
    m.num_muscles = 1;
    m.dt = kDt;
    return m;
  }

  // start() must throw an InputError naming the file and the dataset.
  static void expect_misfit(RecordedActivations log, const controller::Model& model,
                            const std::string& dataset, const std::string& also) {
    const std::string path = log.path;
    Replayer replayer(std::move(log));
    try {
      replayer.start(model);
      ADD_FAILURE() << "accepted";
    } catch (const controller::InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.key_path(), dataset) << e.what();
      EXPECT_NE(std::string(e.what()).find(also), std::string::npos) << e.what();
    }
  }
};

TEST_F(RecordedActivationsTest, ReadsTimesNamesForcesAndLevels) {
  const RecordedActivations log = read_recorded_activations(batch(box_scene(), "run").string());
  ASSERT_EQ(log.frames(), 11u);
  EXPECT_EQ(log.muscle_names, (std::vector<std::string>{"flexor"}));
  EXPECT_EQ(log.max_forces_n, (std::vector<double>{0.01}));
  EXPECT_EQ(log.resets, 0);
  for (std::size_t k = 0; k < log.frames(); ++k) {
    EXPECT_NEAR(log.time_s[k], k * kDt, 1e-12);
    // The scene's schedule: a step to t uses the levels at t (0.3 from 4 ms on; frame 0 off).
    EXPECT_EQ(log.level(k, 0), k >= 2 ? 0.3 : 0.0) << "frame " << k;
  }
}

TEST_F(RecordedActivationsTest, ReplayerSendsRowKForStepKAndEndsWithTheLog) {
  Replayer replayer(read_recorded_activations(batch(box_scene(), "run").string()));
  replayer.start(box_model());
  EXPECT_EQ(replayer.last_step(), 10);
  const controller::MuscleLevels l = replayer.command(5);
  EXPECT_EQ(l.names, (std::vector<std::string>{"flexor"}));
  EXPECT_EQ(l.levels, (std::vector<double>{0.3}));
  EXPECT_EQ(replayer.command(1).levels, (std::vector<double>{0.0}));
  EXPECT_THROW(replayer.command(11), std::out_of_range);
}

TEST_F(RecordedActivationsTest, LogThatDoesNotFitTheServerIsRejected) {
  const std::string path = batch(box_scene(), "run").string();
  controller::Model other = box_model();
  other.muscle_names = {"extensor"};
  expect_misfit(read_recorded_activations(path), other, "/muscles/names", "(flexor)");
  controller::Model stronger = box_model();
  stronger.muscle_max_forces = {0.02};
  expect_misfit(read_recorded_activations(path), stronger, "/muscles/max_force",
                "0.01 N in the log, 0.02 N");
  controller::Model finer = box_model();
  finer.dt = 0.001;
  expect_misfit(read_recorded_activations(path), finer, "/time", "frame 1 is at 0.002 s");
  // Every second step logged: frame 1 is step 2.
  expect_misfit(read_recorded_activations(batch(box_scene("2"), "every2").string()), box_model(),
                "/time", "every step");
}

TEST_F(RecordedActivationsTest, ResetRunIsRejected) {
  const std::string path = batch(box_scene(), "run").string();
  {  // what the server writes after a reset command
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(file, "resets", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* value = "1";
    H5Awrite(attr, type, &value);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(file);
  }
  const RecordedActivations log = read_recorded_activations(path);
  EXPECT_EQ(log.resets, 1);
  expect_misfit(log, box_model(), "resets", "reset 1 time");
}

TEST_F(RecordedActivationsTest, UnreadableFilesNameTheFileAndTheDataset) {
  const std::string text = write("not_hdf5.h5", "hello");
  try {
    read_recorded_activations(text);
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_EQ(e.file(), text);
  }
  const std::string no_muscles = batch(box_scene("1", false), "no_muscles").string();
  try {
    read_recorded_activations(no_muscles);
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_EQ(e.file(), no_muscles);
    EXPECT_EQ(e.key_path(), "/muscles/names") << e.what();
  }
  EXPECT_THROW(read_recorded_activations((dir_ / "missing.h5").string()), controller::InputError);
}

}  // namespace
}  // namespace tongue::replay
