// A recorded LCM log reproduces a run: sim_server (lock-step) is driven for 10 steps on one port
// while lcm-logger records the bus; a fresh server on another port then gets only the activation
// channel of that log from lcm-logplayer, and its run file's positions equal the first run's bit
// for bit. The recorded activations are spaced 100 ms apart, so that playback at normal speed
// never sends one before the replaying server has finished the previous step (in lock-step an
// activation for a step ahead of the next one is rejected).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
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
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kRecordPort = 7751, kReplayPort = 7752;  // one port per run of this test
constexpr int kSteps = 10;
constexpr int kWaitMs = 5000;

using testing::bus_url;
using testing::ChildProcess;
using testing::kBoxScene;
using testing::ServerController;

class Replay : public testing::TempDirTest {
 protected:
  std::unique_ptr<ChildProcess> start_server(const std::string& url, const std::string& name) {
    return std::make_unique<ChildProcess>(
        SIM_SERVER_PATH,
        std::vector<std::string>{(dir_ / "scene.yaml").string(), "--lcm-url", url, "--output",
                                 (dir_ / (name + ".h5")).string()},
        dir_, name);
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
  write("scene.yaml", kBoxScene);
  const fs::path log_path = dir_ / "bus.lcmlog";
  const std::string activation_channel = bus::Channels{}.activation;

  // 1. Record: lcm-logger on the bus, the test driving the server.
  {
    const std::string url = bus_url(kRecordPort);
    ServerController controller(url);
    ASSERT_TRUE(controller.good());
    ChildProcess logger("lcm-logger", {"--lcm-url=" + url, "--quiet", "--force", log_path.string()},
                        dir_, "logger");
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
    ASSERT_GT(fs::file_size(log_path, ec), 0u) << logger.stderr_text();
    for (int k = 1; k <= kSteps; ++k) {
      controller.send_activation(k, {"flexor"}, {0.05 * k + (k % 3) * 0.1});
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
    ServerController controller(url);
    ASSERT_TRUE(controller.good());
    auto server = start_server(url, "replayed");
    ASSERT_TRUE(server->started());
    ASSERT_TRUE(controller.wait_step(0)) << stderr_of("replayed");
    ChildProcess player(
        "lcm-logplayer",
        {"--lcm-url=" + url, "--regexp=^" + activation_channel + "$", log_path.string()}, dir_,
        "player");
    ASSERT_TRUE(player.started());
    const auto last = controller.wait_step(kSteps, 15000);
    ASSERT_TRUE(last) << stderr_of("replayed");
    EXPECT_EQ(last->rejected_messages, 0);
    EXPECT_EQ(player.wait_exit(kWaitMs), 0) << player.stderr_text();
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
