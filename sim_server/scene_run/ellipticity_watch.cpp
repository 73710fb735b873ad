#include "scene_run/ellipticity_watch.hpp"

#include <pthread.h>
#include <sched.h>
#include <signal.h>

#include <utility>

namespace tongue::scene_run {

EllipticityWatch::EllipticityWatch(const fem::SolidModel& solid, fem::MeshNumbering numbering)
    : monitor_(solid),
      material_(solid.material()),
      numbering_(std::move(numbering)),
      worker_([this] { run(); }) {}

EllipticityWatch::~EllipticityWatch() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_one();
  worker_.join();
}

std::optional<EllipticityFinding> EllipticityWatch::check(const fem::Vector& u, std::int64_t step,
                                                          double time) {
  std::unique_lock lock(mutex_);
  std::optional<EllipticityFinding> found = wait_and_take(lock);
  // After the run's one finding there is nothing left to look for: the worker is not woken
  // (each wake-up is a system call and a second core's time, which a closed loop's controller
  // can use).
  if (found_loss_) return found;
  u_ = u;  // the same size every step: no reallocation
  step_ = step;
  time_ = time;
  busy_ = true;
  lock.unlock();
  changed_.notify_one();
  return found;
}

std::optional<EllipticityFinding> EllipticityWatch::collect() {
  std::unique_lock lock(mutex_);
  return wait_and_take(lock);
}

void EllipticityWatch::rearm() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !busy_; });
  monitor_.reset();
  found_loss_ = false;
}

std::optional<EllipticityFinding> EllipticityWatch::wait_and_take(
    std::unique_lock<std::mutex>& lock) {
  changed_.wait(lock, [&] { return !busy_; });
  return std::exchange(found_, std::nullopt);
}

void EllipticityWatch::run() {
  // Signals go to the threads that wait for them (the server's loop), as LCM's own thread does.
  sigset_t all;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, nullptr);
  // SCHED_BATCH (sched(7)): the worker's wake-up does not preempt the thread that woke it, which
  // goes on to publish its state; the worker keeps its fair share of the CPU. Any process may
  // ask for it; a refusal only loses that.
  const sched_param batch{};
  pthread_setschedparam(pthread_self(), SCHED_BATCH, &batch);
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return busy_ || stopping_; });
    if (!busy_) return;  // stopping, nothing under way
    lock.unlock();
    std::optional<EllipticityFinding> found;
    if (const auto loss = monitor_.first_loss(u_))
      found = EllipticityFinding{step_, time_, *loss, fem::describe(*loss, material_, numbering_)};
    lock.lock();
    if (found) {
      found_ = std::move(found);
      found_loss_ = true;
    }
    busy_ = false;
    changed_.notify_one();
  }
}

}  // namespace tongue::scene_run
