#pragma once
// Helpers for driving the real sim_server executable (and the LCM tools lcm-logger and
// lcm-logplayer) over a real LCM bus (udpm on the loopback) from end-to-end tests and benchmarks:
// the bus URL of a port, a child process guard and the controller's side of the bus (the box
// scenes come with it, from box_scenes.hpp).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "support/box_scenes.hpp"
#include "support/run_command.hpp"

extern char** environ;

namespace tongue::testing {

// The loopback udpm URL of port (ttl 0: never leaves the host); recv_buf_size, when given, asks
// for a larger socket receive buffer (room for bursts of messages).
inline std::string bus_url(int port, std::optional<int> recv_buf_size = std::nullopt) {
  std::string url = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
  if (recv_buf_size) url += "&recv_buf_size=" + std::to_string(*recv_buf_size);
  return url;
}

inline constexpr int kDefaultWaitMs = 5000;  // longest wait for one expected message

// A child process: executable (a path, or a name looked up on the PATH) run with args, its stdout
// and stderr going to <name>_stdout.txt and <name>_stderr.txt in dir. SIGKILLed (and reaped) when
// the guard goes out of scope still running, so that a failing test never leaves one behind.
class ChildProcess {
 public:
  ChildProcess(const std::string& executable, const std::vector<std::string>& args,
               const std::filesystem::path& dir, const std::string& name = "server")
      : err_path_(dir / (name + "_stderr.txt")) {
    const std::string out = (dir / (name + "_stdout.txt")).string();
    const std::string err = err_path_.string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all{executable};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawnp(&pid_, executable.c_str(), &actions, nullptr, argv.data(), environ) != 0)
      pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~ChildProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  // The process id while it runs (not yet reaped), else -1.
  pid_t pid() const { return pid_; }
  void signal(int sig) const {
    if (pid_ > 0) kill(pid_, sig);
  }
  // True while the process has not exited.
  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }
  // The raw wait status (see WIFEXITED, WIFSIGNALED), or nullopt when the process has not ended
  // within timeout_ms (or was never started or already reaped).
  std::optional<int> wait_status(int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (pid_ > 0) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return status;
      }
      if (std::chrono::steady_clock::now() > end) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return std::nullopt;
  }
  // The exit status, or nullopt when it has not exited within timeout_ms (or died of a signal).
  std::optional<int> wait_exit(int timeout_ms) {
    const std::optional<int> status = wait_status(timeout_ms);
    if (status && WIFEXITED(*status)) return WEXITSTATUS(*status);
    return std::nullopt;
  }

  std::string stderr_text() const { return read_text(err_path_); }
  // Whether the process's stderr contains text within timeout_ms (polled).
  bool wait_stderr(const std::string& text, int timeout_ms = kDefaultWaitMs) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (stderr_text().find(text) == std::string::npos) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }

 private:
  pid_t pid_ = -1;
  std::filesystem::path err_path_;
};

// The test's side of the bus: subscribed to the state and model channels of one server (channel
// prefix) on construction, i.e. before the server starts, so that nothing it publishes is missed.
class ServerController {
 public:
  using State = tongue_lcm::lcmt_tongue_state;
  using Model = tongue_lcm::lcmt_tongue_model;
  using Activation = tongue_lcm::lcmt_tongue_activation;

  explicit ServerController(const std::string& url,
                            std::string_view prefix = bus::kDefaultChannelPrefix)
      : lcm_(url), channels_(prefix) {
    lcm_.subscribe(channels_.state, &ServerController::on_state, this);
    lcm_.subscribe(channels_.model, &ServerController::on_model, this);
  }
  bool good() { return lcm_.good(); }
  const bus::Channels& channels() const { return channels_; }

  // The next state (received states before it are dropped) for which accept is true.
  std::optional<State> wait_state(const std::function<bool(const State&)>& accept,
                                  int timeout_ms = kDefaultWaitMs) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (true) {
      while (!states_.empty()) {
        State s = std::move(states_.front());
        states_.pop_front();
        if (accept(s)) return s;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            end - std::chrono::steady_clock::now())
                            .count();
      if (left <= 0) return std::nullopt;
      lcm_.handleTimeout(static_cast<int>(left));
    }
  }
  // The next state of step step (received states before it are dropped).
  std::optional<State> wait_step(std::int64_t step, int timeout_ms = kDefaultWaitMs) {
    return wait_state([step](const State& s) { return s.step == step; }, timeout_ms);
  }
  // The next model not yet returned.
  std::optional<Model> wait_model(int timeout_ms = kDefaultWaitMs) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (models_.empty()) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            end - std::chrono::steady_clock::now())
                            .count();
      if (left <= 0) return std::nullopt;
      lcm_.handleTimeout(static_cast<int>(left));
    }
    Model m = std::move(models_.front());
    models_.pop_front();
    return m;
  }

  static Activation activation(std::int64_t step, const std::vector<std::string>& names,
                               const std::vector<double>& levels) {
    Activation msg;
    msg.utime = 0;
    msg.step = step;
    msg.num_muscles = static_cast<std::int32_t>(names.size());
    msg.names = names;
    msg.levels = levels;
    return msg;
  }
  void send_activation(std::int64_t step, const std::vector<std::string>& names,
                       const std::vector<double>& levels) {
    const Activation msg = activation(step, names, levels);
    lcm_.publish(channels_.activation, &msg);
  }
  // bytes as they are on the activation channel.
  void send_raw(const std::vector<std::uint8_t>& bytes) {
    lcm_.publish(channels_.activation, bytes.data(), static_cast<unsigned>(bytes.size()));
  }
  void send_command(const std::string& command) {
    tongue_lcm::lcmt_tongue_command msg;
    msg.utime = 0;
    msg.command = command;
    lcm_.publish(channels_.command, &msg);
  }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const State* s) {
    states_.push_back(*s);
  }
  void on_model(const lcm::ReceiveBuffer*, const std::string&, const Model* m) {
    models_.push_back(*m);
  }

  lcm::LCM lcm_;
  bus::Channels channels_;
  std::deque<State> states_;
  std::deque<Model> models_;
};

}  // namespace tongue::testing
