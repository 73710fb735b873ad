// A recorded LCM log reproduces a run: sim_server (lock-step) is driven for 10 steps on one port
// while lcm-logger records the bus; a fresh server on another port then gets only the activation
// channel of that log from lcm-logplayer, and its run file's positions equal the first run's bit
// for bit. The recorded activations are spaced 100 ms apart, so that playback at normal speed
// never sends one before the replaying server has finished the previous step (in lock-step an
// activation for a step ahead of the next one is rejected).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus/channels.hpp"
#include "bus/messages.hpp"
#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

extern char** environ;

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using tongue_lcm::lcmt_tongue_state;

// The scene of sim_server_test.cpp: a 4 x 1 x 1 element block with one muscle, dt 2 ms.
const char* const kScene = R"(
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}
material:
  type: mooney_rivlin5
  density: 1000
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
muscles:
  - {name: flexor, max_force: 0.01, elements: [2, 3], fibres: [{nodes: [2, 3, 4]}]}
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
)";
constexpr int kRecordPort = 7751, kReplayPort = 7752;  // one port per run of this test
constexpr int kSteps = 10;
constexpr int kWaitMs = 5000;

std::string bus_url(int port) {
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

// A child process (found on the PATH), killed with SIGKILL if still running at scope exit.
class Process {
 public:
  Process(std::vector<std::string> argv, const fs::path& out, const fs::path& err) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    if (posix_spawnp(&pid_, args[0], &actions, nullptr, args.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Process() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  bool started() const { return pid_ > 0; }
  void signal(int sig) const {
    if (pid_ > 0) kill(pid_, sig);
  }
  // The exit status; nullopt when not exited within timeout_ms or killed by a signal.
  std::optional<int> wait_exit(int timeout_ms) {
    const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (pid_ > 0) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        if (WIFEXITED(status)) return WEXITSTATUS(status);
        return std::nullopt;
      }
      if (Clock::now() > end) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return std::nullopt;
  }

 private:
  pid_t pid_ = -1;
};

// The test's side of the bus: receives states, sends activations and commands.
class Controller {
 public:
  explicit Controller(const std::string& url) : lcm_(url) {
    lcm_.subscribe(channels_.state, &Controller::on_state, this);
  }
  bool good() { return lcm_.good(); }
  std::optional<lcmt_tongue_state> wait_step(std::int64_t step, int timeout_ms = kWaitMs) {
    const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (true) {
      while (!states_.empty()) {
        lcmt_tongue_state s = std::move(states_.front());
        states_.pop_front();
        if (s.step == step) return s;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
      if (left <= 0) return std::nullopt;
      lcm_.handleTimeout(static_cast<int>(left));
    }
  }
  void send_activation(std::int64_t step, double level) {
    tongue_lcm::lcmt_tongue_activation msg;
    msg.utime = 0;
    msg.step = step;
    msg.num_muscles = 1;
    msg.names = {"flexor"};
    msg.levels = {level};
    lcm_.publish(channels_.activation, &msg);
  }
  void send_command(const std::string& command) {
    tongue_lcm::lcmt_tongue_command msg;
    msg.utime = 0;
    msg.command = command;
    lcm_.publish(channels_.command, &msg);
  }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const lcmt_tongue_state* s) {
    states_.push_back(*s);
  }
  lcm::LCM lcm_;
  bus::Channels channels_;
  std::deque<lcmt_tongue_state> states_;
};

class Replay : public testing::TempDirTest {
 protected:
  std::unique_ptr<Process> start_server(const std::string& url, const std::string& name) {
    return std::make_unique<Process>(
        std::vector<std::string>{SIM_SERVER_PATH, (dir_ / "scene.yaml").string(), "--lcm-url", url,
                                 "--output", (dir_ / (name + ".h5")).string()},
        dir_ / (name + "_stdout.txt"), dir_ / (name + "_stderr.txt"));
  }
  std::string stderr_of(const std::string& name) {
    return testing::read_text(dir_ / (name + "_stderr.txt"));
  }
};

// Activation events on channel in the LCM log at path.
std::vector<tongue_lcm::lcmt_tongue_activation> logged_activations(const fs::path& path,
                                                                   const std::string& channel) {
  std::vector<tongue_lcm::lcmt_tongue_activation> out;
  lcm::LogFile log(path.string(), "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (e->channel != channel) continue;
    tongue_lcm::lcmt_tongue_activation msg;
    if (msg.decode(e->data, 0, static_cast<int>(e->datalen)) >= 0) out.push_back(msg);
  }
  return out;
}

TEST_F(Replay, LoggedActivationsReplayedByLcmLogplayerReproduceThePositions) {
  write("scene.yaml", kScene);
  const fs::path log_path = dir_ / "bus.lcmlog";
  const std::string activation_channel = bus::Channels{}.activation;

  // 1. Record: lcm-logger on the bus, the test driving the server.
  {
    const std::string url = bus_url(kRecordPort);
    Controller controller(url);
    ASSERT_TRUE(controller.good());
    Process logger({"lcm-logger", "--lcm-url=" + url, "--quiet", "--force", log_path.string()},
                   dir_ / "logger_stdout.txt", dir_ / "logger_stderr.txt");
    ASSERT_TRUE(logger.started());
    auto server = start_server(url, "recorded");
    ASSERT_TRUE(server->started());
    ASSERT_TRUE(controller.wait_step(0)) << stderr_of("recorded");
    // The logger is recording once it has written the model and first state (flushed every
    // 100 ms); only then does the first activation go out.
    const auto end = Clock::now() + std::chrono::milliseconds(kWaitMs);
    std::error_code ec;
    while ((!fs::exists(log_path) || fs::file_size(log_path, ec) == 0) && Clock::now() < end)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_GT(fs::file_size(log_path, ec), 0u) << testing::read_text(dir_ / "logger_stderr.txt");
    for (int k = 1; k <= kSteps; ++k) {
      controller.send_activation(k, 0.05 * k + (k % 3) * 0.1);
      ASSERT_TRUE(controller.wait_step(k)) << stderr_of("recorded");
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    controller.send_command("shutdown");
    ASSERT_EQ(server->wait_exit(kWaitMs), 0) << stderr_of("recorded");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the logger's last flush
    logger.signal(SIGINT);
    logger.wait_exit(kWaitMs);
  }
  const auto recorded = logged_activations(log_path, activation_channel);
  ASSERT_EQ(recorded.size(), static_cast<std::size_t>(kSteps));
  for (int k = 1; k <= kSteps; ++k) EXPECT_EQ(recorded[k - 1].step, k);

  // 2. Replay: a fresh server on another port, fed only the activation channel of the log.
  {
    const std::string url = bus_url(kReplayPort);
    Controller controller(url);
    ASSERT_TRUE(controller.good());
    auto server = start_server(url, "replayed");
    ASSERT_TRUE(server->started());
    ASSERT_TRUE(controller.wait_step(0)) << stderr_of("replayed");
    Process player({"lcm-logplayer", "--lcm-url=" + url, "--regexp=^" + activation_channel + "$",
                    log_path.string()},
                   dir_ / "player_stdout.txt", dir_ / "player_stderr.txt");
    ASSERT_TRUE(player.started());
    const auto last = controller.wait_step(kSteps, 15000);
    ASSERT_TRUE(last) << stderr_of("replayed");
    EXPECT_EQ(last->rejected_messages, 0);
    EXPECT_EQ(player.wait_exit(kWaitMs), 0) << testing::read_text(dir_ / "player_stderr.txt");
    controller.send_command("shutdown");
    ASSERT_EQ(server->wait_exit(kWaitMs), 0) << stderr_of("replayed");
  }

  const testing::RunFile first(dir_ / "recorded.h5"), second(dir_ / "replayed.h5");
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(second.ok());
  const std::vector<double> positions = first.doubles("/positions");
  ASSERT_EQ(positions.size(), static_cast<std::size_t>(kSteps + 1) * 20 * 3);
  EXPECT_EQ(second.doubles("/positions"), positions);  // bit for bit
  EXPECT_EQ(second.doubles("/activations"), first.doubles("/activations"));
  EXPECT_EQ(second.doubles("/time"), first.doubles("/time"));
  EXPECT_NE(positions.front(), positions.back());  // the muscle moved something
}

}  // namespace
}  // namespace tongue::server
