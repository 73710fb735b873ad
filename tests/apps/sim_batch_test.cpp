// Runs the real sim_batch executable on small scenes and reads its run file back with the HDF5
// C API, independently of the writer's code.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class SimBatch : public testing::TempDirTest {
 protected:
  fs::path write_scene(const std::string& text) const { return write("scene.yaml", text); }

  RunResult run(const std::string& args) const {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command = std::string("'") + SIM_BATCH_PATH + "' " + args + " >'" +
                                out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
  }
};

// Minimal read-only access to a run file.
class RunFile {
 public:
  explicit RunFile(const fs::path& p) : file_(H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~RunFile() {
    if (file_ >= 0) H5Fclose(file_);
  }
  bool ok() const { return file_ >= 0; }

  std::vector<hsize_t> shape(const std::string& name) const {
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    if (ds < 0) return {};
    const hid_t space = H5Dget_space(ds);
    std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(ds);
    return dims;
  }

  std::vector<double> doubles(const std::string& name) const {
    return read<double>(name, H5T_NATIVE_DOUBLE);
  }
  std::vector<int> ints(const std::string& name) const { return read<int>(name, H5T_NATIVE_INT); }

  // A string attribute of the root group (loc "/") or of a dataset.
  std::string string_attribute(const std::string& loc, const std::string& name) const {
    const hid_t attr = H5Aopen_by_name(file_, loc.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return "<missing>";
    const hid_t type = H5Aget_type(attr);
    std::string value;
    if (H5Tis_variable_str(type) > 0) {
      // Read with the stored type itself: HDF5 converts no strings between ASCII and UTF-8.
      char* s = nullptr;
      H5Aread(attr, type, &s);
      value = s ? s : "";
      H5free_memory(s);
    } else {
      std::vector<char> buf(H5Tget_size(type) + 1, '\0');
      H5Aread(attr, type, buf.data());
      value = buf.data();
    }
    H5Tclose(type);
    H5Aclose(attr);
    return value;
  }

  int int_attribute(const std::string& name) const {
    int v = -1;
    const hid_t attr = H5Aopen_by_name(file_, "/", name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0) return v;
    H5Aread(attr, H5T_NATIVE_INT, &v);
    H5Aclose(attr);
    return v;
  }

 private:
  template <typename T>
  std::vector<T> read(const std::string& name, hid_t mem_type) const {
    std::size_t count = 1;
    for (hsize_t d : shape(name)) count *= d;
    std::vector<T> v(count);
    const hid_t ds = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
    if (ds < 0) return {};
    if (count > 0) H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(ds);
    return v;
  }

  hid_t file_;
};

TEST_F(SimBatch, DynamicSceneWritesARunFileThatMoves) {
  const std::string text = std::string(kHead) + kDynamic;
  const fs::path scene = write_scene(text);
  const fs::path h5 = dir_ / "out" / "run.h5";  // the missing directory is created
  const RunResult r = run("'" + scene.string() + "' --output '" + h5.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("summary: completed, 10 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("real-time factor"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max displacement"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("volume change"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("residual [N]"), std::string::npos) << r.out;  // per-step table

  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  // Frames: t = 0, then steps 3, 6, 9 (every 3) and the last step 10.
  EXPECT_EQ(f.shape("/time"), (std::vector<hsize_t>{5}));
  EXPECT_EQ(f.shape("/positions"), (std::vector<hsize_t>{5, 20, 3}));
  EXPECT_EQ(f.shape("/rest_positions"), (std::vector<hsize_t>{20, 3}));
  EXPECT_EQ(f.shape("/elements"), (std::vector<hsize_t>{4, 8}));
  for (const char* name :
       {"/solver/iterations", "/solver/residual", "/solver/wall_time", "/solver/cuts"})
    EXPECT_EQ(f.shape(name), (std::vector<hsize_t>{5})) << name;

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
}

TEST_F(SimBatch, OutputFileFromTheSceneAndQuiet) {
  const fs::path h5 = dir_ / "from_scene.h5";
  // output.file is relative to the working directory: give it absolute here.
  const fs::path scene = write_scene(std::string(kHead) + R"(
analysis: {type: dynamic, duration: 0.004, dt: 0.002}
output: {file: ')" + h5.string() + "'}\n");
  const RunResult r = run("'" + scene.string() + "' --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("residual [N]"), std::string::npos) << r.out;  // no per-step table
  EXPECT_NE(r.out.find("summary:"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.shape("/positions"), (std::vector<hsize_t>{3, 20, 3}));
}

TEST_F(SimBatch, StaticSceneWritesRestAndEachLoadIncrement) {
  const fs::path scene = write_scene(std::string(kHead) + R"(
loads:
  - {set: x_max, total_force: [0, -0.001, 0]}
analysis: {type: static, load_steps: 2}
)");
  const fs::path h5 = dir_ / "static.h5";
  const RunResult r = run("'" + scene.string() + "' --output '" + h5.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("summary: completed, 2 increments"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/time"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(f.string_attribute("/", "time_unit"), "1");  // load factor
  EXPECT_EQ(f.shape("/positions"), (std::vector<hsize_t>{3, 20, 3}));
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

TEST_F(SimBatch, BadSceneExitsNonZeroNamingTheKeyPath) {
  const fs::path scene = write_scene(std::string(kHead) + R"(
analysis: {type: dynamic, duration: 0.02, dt: -0.002}
)");
  const fs::path h5 = dir_ / "never.h5";
  const RunResult r = run("'" + scene.string() + "' --output '" + h5.string() + "'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(scene.string() + ": analysis.dt:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(h5));  // nothing is written for a scene that cannot run
}

TEST_F(SimBatch, MissingSceneFileExitsNonZero) {
  const RunResult r = run("'" + (dir_ / "absent.yaml").string() + "'");
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
         increment_atol: 0}
)");
  const fs::path h5 = dir_ / "failed.h5";
  const RunResult r = run("'" + scene.string() + "' --output '" + h5.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("failed to converge"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("FAILED"), std::string::npos) << r.out;
  const RunFile f(h5);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.shape("/positions"), (std::vector<hsize_t>{1, 20, 3}));  // the initial frame
  EXPECT_EQ(f.string_attribute("/", "status").rfind("failed: ", 0), 0u);
}

}  // namespace
}  // namespace tongue::apps
