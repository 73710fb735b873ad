#pragma once
// A run file written off the caller's thread: a RunFileWriter owned by a worker thread that
// takes frames, attributes and flushes from a bounded queue and applies them in order, so that a
// step pays a copy of its frame instead of the HDF5 writes (extend, compress, write, periodic
// flush). The file is the same, bit for bit, as the one the writer alone would write.
//
// The caller's cost: append copies the frame into a recycled buffer (one the worker has written:
// once as many frames as ever wait at once exist, appends allocate nothing) and queues it in a
// ring of `capacity` slots. It does not wake the worker: the worker wakes on its own every
// kPollInterval, or when capacity / kBatchDivisor frames wait, and then writes everything queued;
// set_attribute, flush, close and a full queue wake it at once. So a frame waits at most about
// kPollInterval before the writer has it.
//
// Back-pressure: when `capacity` items are waiting, append and set_attribute block until there
// is room; nothing is ever dropped. A SIGKILL loses what the writer had not flushed (at most
// about flush_interval) plus what was still queued (at most about kPollInterval of frames).
//
// Errors: a RunFileError (or any exception) the writer throws on the worker is rethrown, the
// same object, to the caller at its next call (append, set_attribute, flush or close), once; the
// call that rethrows it does nothing else. flush and close wait for the worker, so an error of
// anything queued before them surfaces there at the latest.
//
// Threads: HDF5 may be built without thread safety (the default of a build from source; Debian's
// 1.10.8 is built with it, which only serialises every call under one global lock), and its state
// (identifiers, error stacks, the error printing QuietErrors turns off) is then global to the
// process. So from construction to close only the worker calls HDF5 for this file, the caller's
// thread never touches the writer once it is handed over, and no other thread should call HDF5
// (a RunFileReader, another writer) meanwhile.
#include <Eigen/Core>

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include "run_file/run_file_writer.hpp"

namespace tongue::run_file {

class RunFileQueue {
 public:
  static constexpr std::size_t kDefaultCapacity = 256;
  // The worker's sleep between two looks at the queue: short against the writer's flush
  // interval (1 s), long against a step (a few ms), so that it writes frames in batches.
  static constexpr std::chrono::milliseconds kPollInterval{50};
  // capacity / kBatchDivisor frames waiting wake the worker before its poll (fast runs).
  static constexpr std::size_t kBatchDivisor = 4;

  // Takes the writer (created and set up on this thread before the worker starts) and starts
  // the worker. capacity >= 1: items (frames, attributes, flushes) that may wait.
  explicit RunFileQueue(std::unique_ptr<RunFileWriter> writer,
                        std::size_t capacity = kDefaultCapacity);
  // Drains the queue and closes the file (and writes its sidecar) on the worker; never throws.
  // An error nobody was told of is printed on stderr, so that it does not pass unseen.
  ~RunFileQueue();
  RunFileQueue(const RunFileQueue&) = delete;
  RunFileQueue& operator=(const RunFileQueue&) = delete;

  // As RunFileWriter::append, queued (copied). Wrong sizes throw std::invalid_argument here, at
  // once.
  void append(double time, const Eigen::VectorXd& positions, const SolverFigures& figures,
              const MuscleFrame& muscles = {}, const ContactFrame& contact = {});
  // As RunFileWriter::set_attribute, queued: it lands after the frames queued before it.
  void set_attribute(std::string name, std::string value);
  // Flushes the file after everything queued before, and waits until that is done.
  void flush();
  // Drains the queue and closes the file, then rethrows an error not yet reported. Every later
  // call but close throws std::logic_error.
  void close();

  // Frames the writer has written: every one appended once flush or close has returned.
  int frames() const;
  int num_nodes() const { return num_nodes_; }
  int num_muscles() const { return num_muscles_; }
  int num_obstacles() const { return num_obstacles_; }
  const std::string& path() const { return path_; }

 private:
  struct State;
  // Copies of the writer's constants, read before the worker starts: the caller's thread asks
  // the writer nothing afterwards.
  std::string path_;
  int num_nodes_ = 0;
  int num_muscles_ = 0;
  int num_obstacles_ = 0;
  std::unique_ptr<State> s_;
};

}  // namespace tongue::run_file
