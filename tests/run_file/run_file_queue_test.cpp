// RunFileQueue: the run file written by a worker thread is the synchronous writer's, every frame
// kept under back-pressure, attributes and errors in their place among the frames.
#include "run_file/run_file_queue.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "run_file/run_file_reader.hpp"
#include "run_file/run_file_writer.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::run_file {
namespace {

namespace fs = std::filesystem;

// A row of `nodes` nodes in hexahedra of 8 consecutive nodes, with one node set.
MeshDescription mesh(int nodes) {
  MeshDescription m;
  for (int i = 0; i < nodes; ++i) m.nodes.push_back({0.001 * i, 0.002 * (i % 3), 0.0});
  for (int e = 0; e + 8 <= nodes; e += 8)
    m.elements.push_back({e, e + 1, e + 2, e + 3, e + 4, e + 5, e + 6, e + 7});
  m.node_sets["tip"] = {0, 1};
  m.element_sets["all"] = {0};
  return m;
}

std::vector<MuscleDescription> muscles() {
  FibreDescription with_origin{{0, 1, 2}, {0.1, 0.2, 0.3}, 0.5};
  FibreDescription without{{3, 4}, {}, 1.0};
  return {{"GGa", 10.0, {with_origin, without}}, {"SG", 5.0, {without}}};
}

// Two obstacles: a triangle and a square of two triangles.
std::vector<ObstacleDescription> obstacles() {
  return {
      {"ridge", {{0, 0, 0.01}, {0.01, 0, 0.01}, {0, 0.01, 0.01}}, {{0, 1, 2}}},
      {"wall", {{0, 0, 0}, {0, 0.01, 0}, {0, 0.01, 0.01}, {0, 0, 0.01}}, {{0, 1, 2}, {0, 2, 3}}}};
}

// Frame k: values that tell the frames apart (and a NaN-free, exactly representable pattern).
struct Frame {
  double time;
  Eigen::VectorXd positions;
  SolverFigures figures;
  MuscleFrame muscles;
  ContactFrame contact;
};
Frame frame(int k, int nodes) {
  Frame f;
  f.time = 0.004 * k;
  f.positions = Eigen::VectorXd::LinSpaced(3 * nodes, k, k + 1.0);
  f.figures = {k % 5, 1e-9 * k, 1e-3 * k, k % 2};
  f.muscles.activations = Eigen::Vector2d(0.01 * k, 0.5);
  f.muscles.lengths = Eigen::Vector2d(0.03, 0.04 + 1e-5 * k);
  f.muscles.velocities = Eigen::Vector2d(-1e-3 * k, 0.0);
  f.contact.node_forces = Eigen::VectorXd::Zero(3 * nodes);
  f.contact.node_forces[1] = 0.25 * k;
  f.contact.obstacle_forces = Eigen::VectorXd::LinSpaced(6, -k, k);
  f.contact.max_penetration = 1e-6 * k;
  return f;
}

std::unique_ptr<RunFileWriter> writer(const fs::path& path, int nodes) {
  return std::make_unique<RunFileWriter>(path.string(), mesh(nodes), "scene: text\n",
                                         RunFileOptions{}, muscles(), obstacles());
}

// Every object of the file, by name, and whether it is a dataset.
std::vector<std::pair<std::string, bool>> objects(const fs::path& path) {
  std::vector<std::pair<std::string, bool>> out;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << path;
  H5Ovisit(
      file, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
        static_cast<std::vector<std::pair<std::string, bool>>*>(data)->emplace_back(
            std::string("/") + (std::strcmp(name, ".") == 0 ? "" : name),
            info->type == H5O_TYPE_DATASET);
        return 0;
      },
      &out);
  H5Fclose(file);
  return out;
}

std::vector<std::string> attribute_names(const fs::path& path, const std::string& object) {
  std::vector<std::string> out;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hsize_t index = 0;
  H5Aiterate_by_name(
      file, object.c_str(), H5_INDEX_NAME, H5_ITER_INC, &index,
      [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &out, H5P_DEFAULT);
  H5Fclose(file);
  return out;
}

// Type, chunks and filters of a dataset, as text.
std::string storage(const fs::path& path, const std::string& dataset) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t ds = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  const hid_t type = H5Dget_type(ds);
  const hid_t dcpl = H5Dget_create_plist(ds);
  std::string text = "class " + std::to_string(H5Tget_class(type)) + " size " +
                     std::to_string(H5Tget_size(type)) + " order " +
                     std::to_string(H5Tget_order(type));
  if (H5Pget_layout(dcpl) == H5D_CHUNKED) {
    hsize_t chunk[4] = {0, 0, 0, 0};
    const int rank = H5Pget_chunk(dcpl, 4, chunk);
    text += " chunk";
    for (int i = 0; i < rank; ++i) text += " " + std::to_string(chunk[i]);
    text += " filters " + std::to_string(H5Pget_nfilters(dcpl));
  }
  H5Pclose(dcpl);
  H5Tclose(type);
  H5Dclose(ds);
  H5Fclose(file);
  return text;
}

bool is_string_dataset(const fs::path& path, const std::string& dataset) {
  return storage(path, dataset).rfind("class " + std::to_string(H5T_STRING) + " ", 0) == 0;
}

// The same bytes (NaN origins included) after reading as double.
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_attributes(const fs::path& a, const fs::path& b, const std::string& object) {
  const std::vector<std::string> names = attribute_names(a, object);
  ASSERT_EQ(names, attribute_names(b, object)) << object;
  const RunFileReader ra(a.string()), rb(b.string());
  for (const std::string& name : names) {
    if (name == layout::kFormatVersionAttribute) {
      EXPECT_EQ(ra.int_attribute(object, name), rb.int_attribute(object, name));
    } else {
      EXPECT_EQ(ra.string_attribute(object, name), rb.string_attribute(object, name))
          << object << " " << name;
    }
  }
}

// Every object, dataset, attribute and storage choice of a equal to b's.
void expect_same_file(const fs::path& a, const fs::path& b) {
  const auto listed = objects(a);
  ASSERT_EQ(listed, objects(b));
  ASSERT_GT(listed.size(), 20u);
  const RunFileReader ra(a.string()), rb(b.string());
  for (const auto& [name, dataset] : listed) {
    expect_same_attributes(a, b, name);
    if (!dataset) continue;
    EXPECT_EQ(storage(a, name), storage(b, name)) << name;
    EXPECT_EQ(ra.shape(name), rb.shape(name)) << name;
    if (is_string_dataset(a, name))
      EXPECT_EQ(ra.strings(name), rb.strings(name)) << name;
    else
      EXPECT_TRUE(same_bits(ra.doubles(name), rb.doubles(name))) << name;
  }
}

class RunFileQueueTest : public testing::TempDirTest {};

TEST_F(RunFileQueueTest, WritesTheFileTheWriterWrites) {
  const int nodes = 40, count = 300;
  const fs::path direct = dir_ / "direct.h5", queued = dir_ / "queued.h5";
  {
    const auto w = writer(direct, nodes);
    w->set_attribute("status", "running");
    for (int k = 0; k < count; ++k) {
      const Frame f = frame(k, nodes);
      w->append(f.time, f.positions, f.figures, f.muscles, f.contact);
      if (k == 100) w->set_attribute("material_warning", "step 100: lost");
    }
    w->set_attribute("status", "completed");
    w->flush();
  }
  {
    auto w = writer(queued, nodes);
    w->set_attribute("status", "running");
    RunFileQueue q(std::move(w), 16);
    for (int k = 0; k < count; ++k) {
      Frame f = frame(k, nodes);
      q.append(f.time, std::move(f.positions), f.figures, std::move(f.muscles), f.contact);
      if (k == 100) q.set_attribute("material_warning", "step 100: lost");
    }
    q.set_attribute("status", "completed");
    q.flush();
    EXPECT_EQ(q.frames(), count);
  }
  expect_same_file(direct, queued);
  const RunFileReader read(queued.string());
  EXPECT_EQ(read.shape(layout::kPositions), (std::vector<std::size_t>{count, nodes, 3}));
  // The obstacles as described, the contact frames as appended.
  EXPECT_EQ(read.strings(layout::kObstacleNames), (std::vector<std::string>{"ridge", "wall"}));
  EXPECT_EQ(read.ints(layout::obstacle_triangles("wall")), (std::vector<int>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(read.doubles(layout::obstacle_vertices("ridge"))[3], 0.01);
  EXPECT_EQ(read.shape(layout::kContactNodeForce), (std::vector<std::size_t>{count, nodes, 3}));
  EXPECT_EQ(read.shape(layout::kContactObstacleForce), (std::vector<std::size_t>{count, 2, 3}));
  const Frame last = frame(count - 1, nodes);
  EXPECT_EQ(read.doubles(layout::kContactNodeForce)[(count - 1) * nodes * 3 + 1],
            last.contact.node_forces[1]);
  EXPECT_EQ(read.doubles(layout::kContactMaxPenetration).back(), last.contact.max_penetration);
  EXPECT_TRUE(fs::exists(dir_ / "queued.xmf"));
}

TEST_F(RunFileQueueTest, AFullQueueBlocksTheProducerAndLosesNothing) {
  const int nodes = 16, count = 3000;
  const std::size_t capacity = 2;
  const fs::path path = dir_ / "run.h5";
  {
    RunFileQueue q(writer(path, nodes), capacity);
    for (int k = 0; k < count; ++k) {
      Frame f = frame(k, nodes);
      q.append(f.time, std::move(f.positions), f.figures, std::move(f.muscles), f.contact);
      // At most `capacity` frames wait and one is being written: the producer was held back.
      ASSERT_GE(q.frames(), k + 1 - static_cast<int>(capacity) - 1) << k;
    }
  }
  const RunFileReader r(path.string());
  const std::vector<double> time = r.doubles(layout::kTime);
  ASSERT_EQ(time.size(), static_cast<std::size_t>(count));
  const std::vector<double> positions = r.doubles(layout::kPositions);
  for (int k = 0; k < count; ++k) {
    ASSERT_EQ(time[k], frame(k, nodes).time) << k;
    ASSERT_EQ(positions[static_cast<std::size_t>(k) * 3 * nodes], k) << k;
  }
  EXPECT_EQ(r.ints(layout::kIterations).back(), (count - 1) % 5);
}

TEST_F(RunFileQueueTest, AnErrorOnTheWorkerReachesTheCallerOnceAsTheWritersError) {
  const int nodes = 8;
  const fs::path path = dir_ / "run.h5";
  std::string expected;
  {
    const auto w = writer(path, nodes);
    try {
      w->set_attribute("", "no name");  // HDF5 refuses an empty attribute name
    } catch (const RunFileError& e) {
      expected = e.what();
    }
  }
  ASSERT_FALSE(expected.empty());
  RunFileQueue q(writer(path, nodes));              // the same file again, so the same message
  EXPECT_NO_THROW(q.set_attribute("", "no name"));  // queued: the worker fails later
  try {
    q.flush();
    ADD_FAILURE() << "flush did not rethrow the worker's error";
  } catch (const RunFileError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
  EXPECT_NO_THROW(q.flush());  // reported once
  const Frame f = frame(0, nodes);
  q.append(f.time, f.positions, f.figures, f.muscles, f.contact);  // the file still takes frames
  q.set_attribute("", "again");
  EXPECT_THROW(q.close(), RunFileError);
  EXPECT_THROW(q.append(f.time, f.positions, f.figures, f.muscles, f.contact), std::logic_error);
  EXPECT_EQ(RunFileReader(path.string()).shape(layout::kTime), std::vector<std::size_t>{1});
}

TEST_F(RunFileQueueTest, AFrameOfTheWrongSizeIsRefusedAtOnceAsByTheWriter) {
  const int nodes = 8;
  RunFileQueue q(writer(dir_ / "run.h5", nodes));
  const Frame f = frame(0, nodes);
  EXPECT_THROW(q.append(f.time, Eigen::VectorXd::Zero(5), f.figures, f.muscles, f.contact),
               std::invalid_argument);
  EXPECT_THROW(q.append(f.time, f.positions, f.figures, MuscleFrame{}, f.contact),
               std::invalid_argument);
  EXPECT_THROW(q.append(f.time, f.positions, f.figures, f.muscles, ContactFrame{}),
               std::invalid_argument);
  q.flush();
  EXPECT_EQ(q.frames(), 0);
}

// The error of an attribute queued after slow frames surfaces only once they are written.
TEST_F(RunFileQueueTest, AttributesLandAfterTheFramesQueuedBeforeThem) {
  const int nodes = 60000, count = 8;  // about 1.4 MB of positions per frame
  const fs::path path = dir_ / "run.h5";
  RunFileQueue q(writer(path, nodes), 64);
  for (int k = 0; k < count; ++k) {
    Frame f = frame(k, nodes);
    q.append(f.time, std::move(f.positions), f.figures, std::move(f.muscles), f.contact);
  }
  q.set_attribute("", "fails on the worker");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool raised = false;
  while (!raised && std::chrono::steady_clock::now() < deadline) {
    try {
      q.set_attribute("probe", "p");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    } catch (const RunFileError&) {
      raised = true;
      EXPECT_EQ(q.frames(), count);
    }
  }
  EXPECT_TRUE(raised);
  q.set_attribute("status", "completed");
  q.close();
  const RunFileReader r(path.string());
  EXPECT_EQ(r.shape(layout::kTime), std::vector<std::size_t>{count});
  EXPECT_EQ(r.string_attribute(layout::kRoot, "status"), "completed");
}

TEST_F(RunFileQueueTest, TheDestructorDrainsTheQueueAndClosesTheFile) {
  const int nodes = 24, count = 500;
  const fs::path path = dir_ / "run.h5";
  {
    RunFileQueue q(writer(path, nodes), 1000);
    for (int k = 0; k < count; ++k) {
      Frame f = frame(k, nodes);
      q.append(f.time, std::move(f.positions), f.figures, std::move(f.muscles), f.contact);
    }
    q.set_attribute("status", "completed");
  }
  const RunFileReader r(path.string());
  EXPECT_EQ(r.shape(layout::kPositions), (std::vector<std::size_t>{count, nodes, 3}));
  EXPECT_EQ(r.doubles(layout::kTime).back(), frame(count - 1, nodes).time);
  EXPECT_EQ(r.string_attribute(layout::kRoot, "status"), "completed");
  EXPECT_TRUE(fs::exists(dir_ / "run.xmf"));  // written when the writer closed
}

// An imported mesh's file ids by index, so that index i can be named as the user's files do.
TEST_F(RunFileQueueTest, ImportedMeshIdsAreWrittenByIndex) {
  MeshDescription m = mesh(8);
  m.node_ids = {101, 102, 103, 104, 105, 106, 107, 1000};
  m.element_ids = {89};
  const fs::path path = dir_ / "ids.h5";
  { RunFileWriter w(path.string(), m, "scene: text\n", RunFileOptions{}, {}, {}); }
  const hid_t file = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const auto read = [&](const char* name, std::size_t n) {
    std::vector<long> values(n, -1);
    const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
    EXPECT_GE(ds, 0) << name;
    const hid_t space = H5Dget_space(ds);
    EXPECT_EQ(H5Sget_simple_extent_npoints(space), static_cast<hssize_t>(n)) << name;
    H5Sclose(space);
    EXPECT_GE(H5Dread(ds, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(ds);
    return values;
  };
  EXPECT_EQ(read("/mesh/node_ids", 8), m.node_ids);
  EXPECT_EQ(read("/mesh/element_ids", 1), m.element_ids);
  H5Fclose(file);
  // A generated mesh has none.
  { RunFileWriter w((dir_ / "plain.h5").string(), mesh(8), "", RunFileOptions{}, {}, {}); }
  const hid_t plain = H5Fopen((dir_ / "plain.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Lexists(plain, "/mesh/node_ids", H5P_DEFAULT), 0);
  H5Fclose(plain);
}

}  // namespace
}  // namespace tongue::run_file
