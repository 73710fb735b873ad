#include "run_file/run_file_queue.hpp"

#include <pthread.h>
#include <sched.h>
#include <signal.h>

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace tongue::run_file {

namespace {

struct Frame {
  double time = 0.0;
  Eigen::VectorXd positions;
  SolverFigures figures;
  MuscleFrame muscles;
  ContactFrame contact;
};
struct Attribute {
  std::string name, value;
};
struct Flush {};
using Item = std::variant<Frame, Attribute, Flush>;

// Copies from into to, reusing to's storage when the sizes match (a recycled frame).
void copy_into(Eigen::VectorXd& to, const Eigen::VectorXd& from) {
  to.resize(from.size());  // no reallocation at the same size
  to = from;
}

}  // namespace

struct RunFileQueue::State {
  std::unique_ptr<RunFileWriter> writer;  // the worker's alone
  std::size_t capacity = 1;
  std::size_t batch = 1;  // frames queued that wake the worker before its poll

  mutable std::mutex mutex;
  std::condition_variable to_worker;  // a batch, an attribute or flush, a full queue, closing
  std::condition_variable to_caller;  // room in the queue, or an item done
  // The queue: a ring of `capacity` slots, so that queuing allocates nothing.
  std::vector<Item> ring;
  std::size_t head = 0, size = 0;
  std::vector<Frame> spare;  // frames written, their buffers kept for the next appends
  bool urgent = false;       // something waits for the worker: wake it now
  std::uint64_t queued = 0;  // items ever queued
  std::uint64_t done = 0;    // items the worker has finished
  int written = 0;           // the writer's frames()
  std::exception_ptr error;  // the first one not yet rethrown
  bool closing = false;
  bool closed = false;  // close has been called
  std::thread worker;

  void run() {
    // SCHED_BATCH (sched(7)): the worker's wake-ups (its poll, a batch) do not preempt the
    // caller's thread; it keeps its fair share of the CPU. A refusal only loses that.
    const sched_param batch_policy{};
    pthread_setschedparam(pthread_self(), SCHED_BATCH, &batch_policy);
    std::unique_lock lock(mutex);
    while (true) {
      // Asleep until a batch is ready, someone waits, or the poll interval has passed: a
      // frame waits at most about kPollInterval, and the caller's append rarely wakes anyone.
      to_worker.wait_for(lock, kPollInterval, [&] { return size >= batch || urgent || closing; });
      urgent = false;
      if (size == 0 && closing) break;  // drained
      while (size > 0) {
        Item item = std::move(ring[head]);
        head = (head + 1) % capacity;
        --size;
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
        if (Frame* f = std::get_if<Frame>(&item)) spare.push_back(std::move(*f));
        if (failed && !error) error = failed;
        written = frames;
        ++done;
        to_caller.notify_all();
      }
    }
    lock.unlock();
    writer.reset();  // closes the file here too: the destructor calls HDF5
  }

  void apply(Item& item) {
    std::visit(
        [&](auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, Frame>)
            writer->append(x.time, x.positions, x.figures, x.muscles, x.contact);
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

  // A frame buffer for the next append: a recycled one when the worker has written one.
  Frame take_spare() {
    const std::lock_guard lock(mutex);
    if (spare.empty()) return Frame{};
    Frame f = std::move(spare.back());
    spare.pop_back();
    return f;
  }

  // Queues item once there is room; returns its number. Wakes the worker only when the item
  // is not a frame, a batch is ready, or the queue is full (the caller then waits for room).
  std::uint64_t push(Item item, const std::string& path) {
    std::unique_lock lock(mutex);
    check(lock, path);
    if (size == capacity) {
      urgent = true;
      to_worker.notify_one();
      to_caller.wait(lock, [&] { return size < capacity; });
    }
    const bool frame = std::holds_alternative<Frame>(item);
    ring[(head + size) % capacity] = std::move(item);
    ++size;
    if (!frame) urgent = true;
    if (urgent || size == batch) to_worker.notify_one();
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
  num_obstacles_ = writer->num_obstacles();
  s_->written = writer->frames();
  s_->writer = std::move(writer);
  s_->capacity = capacity;
  s_->batch = std::max<std::size_t>(1, capacity / kBatchDivisor);
  s_->ring.resize(capacity);
  // Every frame there can be: those queued, the one being written, the one being filled.
  s_->spare.reserve(capacity + 2);
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

void RunFileQueue::append(double time, const Eigen::VectorXd& positions,
                          const SolverFigures& figures, const MuscleFrame& muscles,
                          const ContactFrame& contact) {
  RunFileWriter::check_frame(path_, num_nodes_, num_muscles_, num_obstacles_, positions, muscles,
                             contact);
  Frame f = s_->take_spare();
  f.time = time;
  copy_into(f.positions, positions);
  f.figures = figures;
  copy_into(f.muscles.activations, muscles.activations);
  copy_into(f.muscles.lengths, muscles.lengths);
  copy_into(f.muscles.velocities, muscles.velocities);
  copy_into(f.contact.node_forces, contact.node_forces);
  copy_into(f.contact.obstacle_forces, contact.obstacle_forces);
  f.contact.max_penetration = contact.max_penetration;
  s_->push(std::move(f), path_);
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
