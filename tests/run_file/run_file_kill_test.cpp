// kill -9 of a running sim_server (fast mode, free-running): the run file must still open, with
// every frame up to the last flush. RunFileWriter flushes on the first append at least
// flush_interval (1 s) after the previous flush, and RunFileQueue's writer takes queued frames
// at least every 50 ms, so a SIGKILL loses at most the frames of about the last second of wall
// time (plus that poll and one step).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
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

namespace tongue::run_file {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A 80 x 20 x 20 mm block, 8 x 2 x 2 elements (81 nodes), clamped at x = 0, with one muscle.
const char* const kScene = R"(
mesh:
  box: {size: [0.08, 0.02, 0.02], divisions: [8, 2, 2]}
material:
  type: mooney_rivlin5
  density: 1000
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
muscles:
  - {name: flexor, max_force: 0.01, elements: [6, 7], fibres: [{nodes: [6, 7, 8]}]}
damping: {beta: 0.028}
analysis: {type: dynamic, duration: 0.02, dt: 0.002}
)";
constexpr double kDt = 0.002;
constexpr int kExitWaitMs = 5000;  // longest wait for the killed server to be reaped
constexpr int kPort = 7753;        // one port per test (tests/server uses 77xx below 7750)

class StateListener {
 public:
  explicit StateListener(const std::string& url) : lcm_(url) {
    lcm_.subscribe(bus::Channels{}.state, &StateListener::on_state, this);
  }
  bool good() { return lcm_.good(); }
  void handle(int ms) { lcm_.handleTimeout(ms); }
  // (receipt time, step) of every state received.
  std::vector<std::pair<Clock::time_point, std::int64_t>> received;

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&,
                const tongue_lcm::lcmt_tongue_state* s) {
    received.emplace_back(Clock::now(), s->step);
  }
  lcm::LCM lcm_;
};

class RunFileKill : public testing::TempDirTest {};

TEST_F(RunFileKill, SigkillLeavesAReadableFileMissingAtMostAboutOneSecond) {
  const std::string url = testing::bus_url(kPort);
  StateListener listener(url);
  ASSERT_TRUE(listener.good());
  const std::string scene = write("scene.yaml", kScene);
  const fs::path h5 = dir_ / "run.h5";
  testing::ChildProcess server(
      SIM_SERVER_PATH, {scene, "--mode", "fast", "--lcm-url", url, "--output", h5.string()}, dir_);
  ASSERT_TRUE(server.started());

  // Let it run about 2 s from its first state, then kill -9.
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (listener.received.empty() && Clock::now() < deadline) listener.handle(50);
  if (listener.received.empty()) FAIL() << "no state from the server\n" << server.stderr_text();
  const auto kill_at = listener.received.front().first + std::chrono::milliseconds(2000);
  while (Clock::now() < kill_at) listener.handle(10);
  server.signal(SIGKILL);
  const auto killed = Clock::now();
  const std::optional<int> status = server.wait_status(kExitWaitMs);
  ASSERT_TRUE(status);
  ASSERT_TRUE(WIFSIGNALED(*status) && WTERMSIG(*status) == SIGKILL) << server.stderr_text();

  // The last step whose state arrived before (kill - 1 s flush interval - 0.3 s slack): its frame
  // was appended before the last flush.
  std::int64_t last_seen = -1, flushed_for_sure = -1;
  for (const auto& [t, step] : listener.received) {
    last_seen = std::max(last_seen, step);
    if (killed - t > std::chrono::milliseconds(1300))
      flushed_for_sure = std::max(flushed_for_sure, step);
  }
  ASSERT_GT(last_seen, 100) << "the server ran too slowly for this test";

  const testing::RunFile f(h5);
  ASSERT_TRUE(f.ok()) << "the run file does not open after kill -9";
  const std::vector<double> time = f.doubles("/time");
  const auto frames = static_cast<std::int64_t>(time.size());
  EXPECT_GE(frames, flushed_for_sure + 1);
  EXPECT_LE(frames, last_seen + 1);
  for (std::int64_t k = 0; k < frames; ++k) ASSERT_NEAR(time[k], k * kDt, 1e-9) << k;
  const std::vector<double> positions = f.doubles("/positions");
  ASSERT_EQ(positions.size(), static_cast<std::size_t>(frames) * 81 * 3);
  for (double x : positions) ASSERT_TRUE(std::isfinite(x));
  EXPECT_EQ(f.string_attribute("/", "status"), "running");
  // How much was lost, in steps and in wall time before the kill.
  double lost_seconds = 0.0;
  for (const auto& [t, step] : listener.received)
    if (step == frames - 1) lost_seconds = std::chrono::duration<double>(killed - t).count();
  std::cout << "steps seen " << last_seen + 1 << ", frames in file " << frames << ", lost "
            << last_seen + 1 - frames << " steps = " << lost_seconds << " s of wall time\n";
  EXPECT_LT(lost_seconds, 1.3);
}

}  // namespace
}  // namespace tongue::run_file
