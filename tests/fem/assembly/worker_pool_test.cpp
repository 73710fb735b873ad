// WorkerPool: every index is visited once, exceptions reach the caller, and idle workers sleep
// (the reason it exists instead of a spinning OpenMP team).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <thread>
#include <vector>

#include "fem/assembly/worker_pool.hpp"

namespace tongue::fem {
namespace {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

TEST(WorkerPool, VisitsEveryIndexOnceInContiguousChunks) {
  for (int threads : {1, 2, 3}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (int count : {0, 1, 2, 5, 1000}) {
      std::vector<std::atomic<int>> visits(count);
      std::atomic<int> chunks = 0;
      pool.parallel_for(count, [&](int begin, int end) {
        ASSERT_LT(begin, end);
        ++chunks;
        for (int i = begin; i < end; ++i) ++visits[i];
      });
      for (int i = 0; i < count; ++i) EXPECT_EQ(visits[i], 1) << i;
      EXPECT_LE(chunks, threads);
    }
  }
}

TEST(WorkerPool, RethrowsAWorkersException) {
  WorkerPool pool(2);
  EXPECT_THROW(pool.parallel_for(10,
                                 [](int begin, int) {
                                   if (begin > 0) throw std::runtime_error("in the worker");
                                 }),
               std::runtime_error);
  // And stays usable.
  std::atomic<int> sum = 0;
  pool.parallel_for(10, [&](int begin, int end) { sum += end - begin; });
  EXPECT_EQ(sum, 10);
}

TEST(WorkerPool, RejectsLessThanOneThread) {
  EXPECT_THROW(WorkerPool(0), std::invalid_argument);
}

TEST(WorkerPool, IdleWorkersDoNotSpin) {
  WorkerPool pool(2);
  pool.parallel_for(2, [](int, int) {});  // the worker has run once and gone back to sleep
  const double cpu = process_cpu_seconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // A spinning worker would burn ~0.2 s of CPU here; a sleeping one next to nothing. 0.02 s
  // leaves room for the test process's own wake-up and any timer noise.
  EXPECT_LT(process_cpu_seconds() - cpu, 0.02);
}

}  // namespace
}  // namespace tongue::fem
