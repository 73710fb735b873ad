#pragma once
// A program the runner started: its own working directory, stdout and stderr to files. The
// destructor kills (SIGKILL) and reaps a child still running, so that no error path of the
// runner leaves a process behind; the normal path stops children with the signal it chooses.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tongue::runner {

class ChildProcess {
 public:
  // Starts argv[0] (a path, or a name looked up on the PATH) in folder, writing stdout and
  // stderr to out and err. Throws std::runtime_error when it cannot be started.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& folder,
               const std::filesystem::path& out, const std::filesystem::path& err);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool running();  // reaps the child when it has ended
  // The wait status once it has ended (see describe_status); nullopt while running.
  std::optional<int> status();
  void signal(int sig) const;
  // Waits up to timeout_s for the end; the status, or nullopt if still running.
  std::optional<int> wait(double timeout_s);

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// "exit status 0", "killed by signal 11 (Segmentation fault)".
std::string describe_status(int wait_status);
// True for a normal exit with status 0.
bool succeeded(int wait_status);

}  // namespace tongue::runner
