#pragma once
// A process of a run (lcm-logger, sim_server, a controller, the plots) under the name the summary
// gives it: its command line, the process once started and how it ended.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "child_process.hpp"

namespace tongue::runner {

struct Member {
  Member(std::string n, std::vector<std::string> a) : name(std::move(n)), argv(std::move(a)) {}
  std::string name;
  std::vector<std::string> argv;
  std::unique_ptr<ChildProcess> process;
  std::optional<int> status;  // wait status once ended
  std::string stopped_by;     // the signal the runner sent, if it had to stop it
};

// Starts a member in workdir with its output to <name>.out / <name>.err in folder. Throws
// std::runtime_error when it cannot be started.
void start(Member& m, const std::filesystem::path& workdir, const std::filesystem::path& folder);

// Ends a member still running: waits grace_s, then sends sig and waits again, then SIGKILL.
void stop(Member& m, double grace_s, int sig, const char* sig_name);

// The command line as a shell would take it: arguments with spaces or shell characters quoted.
std::string quote(const std::vector<std::string>& argv);

}  // namespace tongue::runner
