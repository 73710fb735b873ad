#include "fem/assembly/worker_pool.hpp"

#include <stdexcept>
#include <string>

namespace tongue::fem {

WorkerPool::WorkerPool(int threads) {
  if (threads < 1) {
    throw std::invalid_argument("worker pool: at least 1 thread needed, got " +
                                std::to_string(threads));
  }
  workers_.reserve(threads - 1);
  for (int chunk = 1; chunk < threads; ++chunk)
    workers_.emplace_back([this, chunk] { work(chunk); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void WorkerPool::run_chunk(int chunk) noexcept {
  const int n = threads();
  const int begin = static_cast<int>(static_cast<long long>(count_) * chunk / n);
  const int end = static_cast<int>(static_cast<long long>(count_) * (chunk + 1) / n);
  if (begin >= end) return;
  try {
    (*body_)(begin, end);
  } catch (...) {
    const std::lock_guard lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

void WorkerPool::work(int chunk) {
  std::uint64_t seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    start_.wait(lock, [&] { return stopping_ || generation_ != seen; });
    if (stopping_) return;
    seen = generation_;
    lock.unlock();
    run_chunk(chunk);
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
}

void WorkerPool::parallel_for(int count, const std::function<void(int, int)>& body) {
  if (count <= 0) return;
  if (workers_.empty()) {
    body(0, count);
    return;
  }
  const std::lock_guard job(job_mutex_);
  {
    const std::lock_guard lock(mutex_);
    body_ = &body;
    count_ = count;
    pending_ = static_cast<int>(workers_.size());
    error_ = nullptr;
    ++generation_;
  }
  start_.notify_all();
  run_chunk(0);
  std::exception_ptr error;
  {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
    body_ = nullptr;
    error = error_;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace tongue::fem
