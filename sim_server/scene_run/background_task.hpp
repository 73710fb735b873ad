#pragma once
// One job at a time on a thread of its own, for the checks a run makes off the step's critical
// path (EllipticityWatch, ReducedCheckWatch). start() hands a job over and returns at once;
// wait() returns when it has ended. What a job writes is the caller's to read after wait().
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace tongue::scene_run {

class BackgroundTask {
 public:
  BackgroundTask();
  ~BackgroundTask();  // waits for the job under way
  BackgroundTask(const BackgroundTask&) = delete;
  BackgroundTask& operator=(const BackgroundTask&) = delete;

  // Waits for the job under way, then starts `job` on the thread.
  void start(std::function<void()> job);
  // Waits until no job is under way.
  void wait();

 private:
  void run();  // the thread

  std::mutex mutex_;
  std::condition_variable changed_;  // a job handed over or ended, or stopping
  std::function<void()> job_;        // the thread's while busy_
  bool busy_ = false;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace tongue::scene_run
