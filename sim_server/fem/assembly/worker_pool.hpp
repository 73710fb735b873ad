#pragma once
// A small fixed pool of threads for the element loops. Idle workers sleep on a condition
// variable: nothing spins between jobs, so a second process on a 2-core machine (ctest -j2,
// another server) keeps its core (docs/speed.md: a spinning OpenMP attempt made the test suite 5x
// slower).
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tongue::fem {

class WorkerPool {
 public:
  // threads >= 1 in total, the calling thread included: threads - 1 workers are started.
  // Throws std::invalid_argument for threads < 1.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // Splits [0, count) into threads() contiguous chunks of nearly equal size and calls
  // body(begin, end) once per chunk, the calling thread taking the first; returns when every
  // chunk is done. The first exception thrown by a chunk is rethrown here. One job at a time:
  // concurrent callers are served one after the other.
  void parallel_for(int count, const std::function<void(int, int)>& body);

 private:
  void work(int chunk);
  void run_chunk(int chunk) noexcept;

  std::vector<std::thread> workers_;
  std::mutex job_mutex_;  // one job at a time
  std::mutex mutex_;      // guards everything below
  std::condition_variable start_;
  std::condition_variable done_;
  std::uint64_t generation_ = 0;
  bool stopping_ = false;
  int pending_ = 0;
  int count_ = 0;
  const std::function<void(int, int)>* body_ = nullptr;
  std::exception_ptr error_;
};

}  // namespace tongue::fem
