#include "run_file/run_file_queue.hpp"

#include <pthread.h>
#include <signal.h>

#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>

namespace tongue::run_file {

namespace {

struct Frame {
  double time = 0.0;
  Eigen::VectorXd positions;
  SolverFigures figures;
  MuscleFrame muscles;
};
struct Attribute {
  std::string name, value;
};
struct Flush {};
using Item = std::variant<Frame, Attribute, Flush>;

}  // namespace

struct RunFileQueue::State {
  std::unique_ptr<RunFileWriter> writer;  // the worker's alone
  std::size_t capacity = 1;

  mutable std::mutex mutex;
  std::condition_variable to_worker;  // an item queued, or closing
  std::condition_variable to_caller;  // room in the queue, or an item done
  std::deque<Item> items;
  std::uint64_t queued = 0;  // items ever queued
  std::uint64_t done = 0;    // items the worker has finished
  int written = 0;           // the writer's frames()
  std::exception_ptr error;  // the first one not yet rethrown
  bool closing = false;
  bool closed = false;  // close has been called
  std::thread worker;

  void run() {
    std::unique_lock lock(mutex);
    while (true) {
      to_worker.wait(lock, [&] { return !items.empty() || closing; });
      if (items.empty()) break;  // closing, and drained
      Item item = std::move(items.front());
      items.pop_front();
      to_caller.notify_all();
      lock.unlock();
      std::exception_ptr failed;
      try {
        apply(item);
      } catch (...) {
        failed = std::current_exception();
      }
      const int frames = writer->frames();
      lock.lock();
      if (failed && !error) error = failed;
      written = frames;
      ++done;
      to_caller.notify_all();
    }
    lock.unlock();
    writer.reset();  // closes the file here too: the destructor calls HDF5
  }

  void apply(Item& item) {
    std::visit(
        [&](auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, Frame>)
            writer->append(x.time, x.positions, x.figures, x.muscles);
          else if constexpr (std::is_same_v<T, Attribute>)
            writer->set_attribute(x.name, x.value);
          else
            writer->flush();
        },
        item);
  }

  // Under the lock: a pending error is rethrown (once), a closed queue refuses.
  void check(std::unique_lock<std::mutex>& lock, const std::string& path) {
    if (error) {
      std::exception_ptr e = std::exchange(error, nullptr);
      lock.unlock();
      std::rethrow_exception(e);
    }
    if (closed) throw std::logic_error(path + ": the run file is closed");
  }

  // Queues item once there is room; returns its number.
  std::uint64_t push(Item item, const std::string& path) {
    std::unique_lock lock(mutex);
    check(lock, path);
    to_caller.wait(lock, [&] { return items.size() < capacity; });
    items.push_back(std::move(item));
    to_worker.notify_one();
    return ++queued;
  }

  void wait_for(std::uint64_t number, const std::string& path) {
    std::unique_lock lock(mutex);
    to_caller.wait(lock, [&] { return done >= number; });
    check(lock, path);
  }

  void stop() {
    {
      const std::lock_guard lock(mutex);
      closing = true;
      closed = true;
    }
    to_worker.notify_one();
    if (worker.joinable()) worker.join();
  }
};

RunFileQueue::RunFileQueue(std::unique_ptr<RunFileWriter> writer, std::size_t capacity)
    : s_(std::make_unique<State>()) {
  if (!writer) throw std::invalid_argument("RunFileQueue: no writer");
  if (capacity < 1) throw std::invalid_argument("RunFileQueue: the capacity must be >= 1");
  path_ = writer->path();
  num_nodes_ = writer->num_nodes();
  num_muscles_ = writer->num_muscles();
  s_->written = writer->frames();
  s_->writer = std::move(writer);
  s_->capacity = capacity;
  // Starting the thread orders every HDF5 call made on this thread so far before the worker's.
  // The worker blocks every signal (it inherits the mask it is started with): a SIGINT must
  // land on the caller's threads and interrupt their waits at once, as it does without a queue.
  sigset_t all, previous;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &previous);
  try {
    s_->worker = std::thread([state = s_.get()] { state->run(); });
  } catch (...) {
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    throw;
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

RunFileQueue::~RunFileQueue() {
  s_->stop();
  if (s_->error) {
    try {
      std::rethrow_exception(s_->error);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "run_file: error: %s\n", e.what());
    } catch (...) {
      std::fprintf(stderr, "run_file: error: %s: unknown\n", path_.c_str());
    }
  }
}

void RunFileQueue::append(double time, Eigen::VectorXd positions, SolverFigures figures,
                          MuscleFrame muscles) {
  RunFileWriter::check_frame(path_, num_nodes_, num_muscles_, positions, muscles);
  s_->push(Frame{time, std::move(positions), figures, std::move(muscles)}, path_);
}

void RunFileQueue::set_attribute(std::string name, std::string value) {
  s_->push(Attribute{std::move(name), std::move(value)}, path_);
}

void RunFileQueue::flush() {
  s_->wait_for(s_->push(Flush{}, path_), path_);
}

void RunFileQueue::close() {
  {
    const std::lock_guard lock(s_->mutex);
    if (s_->closed) return;
  }
  s_->stop();
  std::unique_lock lock(s_->mutex);
  if (s_->error) std::rethrow_exception(std::exchange(s_->error, nullptr));
}

int RunFileQueue::frames() const {
  const std::lock_guard lock(s_->mutex);
  return s_->written;
}

}  // namespace tongue::run_file
