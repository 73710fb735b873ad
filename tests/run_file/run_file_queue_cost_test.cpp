// RunFileQueue's cost to its caller: once the worker has written as many frames as wait at once,
// append reuses their buffers and allocates nothing; and the worker takes the frames on its own
// (the caller never wakes it for a frame), within about its poll interval.
//
// malloc is counted on the calling thread by interposing it in this executable (the C library
// exports its own as __libc_malloc & co.): Eigen's vectors are allocated with malloc, not with
// operator new, so counting operator new alone would miss them.
#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <thread>

#include "run_file/run_file_queue.hpp"
#include "run_file/run_file_reader.hpp"
#include "run_file/run_file_writer.hpp"
#include "support/temp_dir_test.hpp"

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void __libc_free(void* p);
}

namespace {
thread_local bool counting = false;
thread_local long allocations = 0;
}  // namespace

extern "C" {
void* malloc(std::size_t size) {
  if (counting) ++allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  if (counting) ++allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  if (counting) ++allocations;
  return __libc_realloc(p, size);
}
void free(void* p) {
  __libc_free(p);
}
}

namespace tongue::run_file {
namespace {

namespace fs = std::filesystem;

constexpr int kNodes = 850;  // about the built-in tongue's

std::unique_ptr<RunFileWriter> writer(const fs::path& path) {
  MeshDescription mesh;
  for (int i = 0; i < kNodes; ++i) mesh.nodes.push_back({0.001 * i, 0.0, 0.0});
  std::vector<MuscleDescription> muscles{{"GGa", 10.0, {{{0, 1}, {}, 1.0}}}};
  return std::make_unique<RunFileWriter>(path.string(), mesh, "scene: text\n", RunFileOptions{},
                                         muscles);
}

MuscleFrame muscle_frame(int k) {
  MuscleFrame m;
  m.activations = Eigen::VectorXd::Constant(1, 0.01 * k);
  m.lengths = Eigen::VectorXd::Constant(1, 0.03);
  m.velocities = Eigen::VectorXd::Constant(1, 0.0);
  return m;
}

class RunFileQueueCost : public testing::TempDirTest {};

TEST_F(RunFileQueueCost, AppendReusesTheWrittenFramesBuffers) {
  const int batch = 40;
  const fs::path path = dir_ / "run.h5";
  const Eigen::VectorXd positions = Eigen::VectorXd::LinSpaced(3 * kNodes, 0.0, 1.0);
  const MuscleFrame muscles = muscle_frame(1);
  RunFileQueue q(writer(path));
  for (int k = 0; k < batch; ++k) q.append(0.004 * k, positions, {k, 0.0, 0.0, 0}, muscles);
  q.flush();  // every frame written: their buffers are spare

  counting = true;
  for (int k = batch; k < 2 * batch; ++k) q.append(0.004 * k, positions, {k, 0.0, 0.0, 0}, muscles);
  counting = false;
  EXPECT_EQ(allocations, 0);

  q.close();
  const RunFileReader r(path.string());
  const std::vector<double> time = r.doubles(layout::kTime);
  ASSERT_EQ(time.size(), static_cast<std::size_t>(2 * batch));
  EXPECT_EQ(time.back(), 0.004 * (2 * batch - 1));
  EXPECT_EQ(r.ints(layout::kIterations).back(), 2 * batch - 1);
}

// Three frames are far fewer than a batch (kDefaultCapacity / kBatchDivisor): the worker finds
// them on its poll. The 20 s limit is for a loaded machine, not a figure of the poll interval.
TEST_F(RunFileQueueCost, TheWorkerTakesFramesWithoutBeingWoken) {
  const Eigen::VectorXd positions = Eigen::VectorXd::Zero(3 * kNodes);
  RunFileQueue q(writer(dir_ / "run.h5"));
  ASSERT_GT(RunFileQueue::kDefaultCapacity / RunFileQueue::kBatchDivisor, 3u);
  for (int k = 0; k < 3; ++k) q.append(0.004 * k, positions, {}, muscle_frame(k));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (q.frames() < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(q.frames(), 3);
}

}  // namespace
}  // namespace tongue::run_file
