// Lock-step survives message loss, end to end: two sequence_player processes drive one sim_server
// (--controllers 2, the two-muscle box) through lossy_relay, which joins the controllers' udpm
// port to the server's and drops a seeded share of the messages each way; the run file equals,
// bit for bit, that of the same controllers on one lossless bus. With two controllers a repeat
// taken twice would make a step with one controller's levels only, so the comparison also holds
// the server to taking each sender's repeat once. The recovery figures (messages dropped, states
// published again, activations sent again, wall time) are printed and recorded as test
// properties. Ports 7900-7902 (quick), 7903-7905 (slow).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/same_run.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SEQUENCE_PLAYER_PATH
#error "SEQUENCE_PLAYER_PATH must name the sequence_player executable"
#endif
#ifndef LOSSY_RELAY_PATH
#error "LOSSY_RELAY_PATH must name the lossy_relay executable"
#endif
#ifndef LOSSY_BUS_SLOW
#error "LOSSY_BUS_SLOW must be 0 (the CI run) or 1 (the long one)"
#endif

namespace tongue::server {
namespace {

namespace fs = std::filesystem;
using testing::bus_url;
using testing::ChildProcess;

// The CI run: 2000 steps (4 s of the box at dt 2 ms) at 5 % loss each way; the long one 20000.
constexpr int kSteps = LOSSY_BUS_SLOW ? 20000 : 2000;
constexpr double kDrop = 0.05;
constexpr int kFirstPort = LOSSY_BUS_SLOW ? 7903 : 7900;
// Longest wait for a whole run [ms]: generous for a loaded machine (on an idle one the lossless
// run of 2000 steps takes about 0.5 s, the lossy one about 17 s, mostly the 50 ms before the
// first repeat of a state).
constexpr int kRunWaitMs = LOSSY_BUS_SLOW ? 1800000 : 240000;
constexpr int kExitWaitMs = 10000;

// Controller 1 ramps flexor up over the run; controller 2 switches extensor between levels, so
// that every step's merged levels differ and a step made with one controller's levels shows.
std::string flexor_schedule() {
  const double end_s = kSteps * 0.002;
  return "entries:\n  - {muscle: flexor, start: 0.0, end: " + std::to_string(end_s) +
         ", level_from: 0.0, level_to: 1.0}\n";
}
std::string extensor_schedule() {
  std::string text = "entries:\n";
  for (int i = 0; i < kSteps / 100; ++i) {
    const double start = i * 0.2, level = 0.1 * (i % 7);
    text += "  - {muscle: extensor, start: " + std::to_string(start) +
            ", end: " + std::to_string(start + 0.1) + ", level: " + std::to_string(level) + "}\n";
  }
  return text;
}

// The first integer after label in text, or -1.
long long figure(const std::string& text, const std::string& label) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("(\\d+) " + label))) return std::stoll(m[1]);
  return -1;
}

class LossyBus : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    write("scene.yaml", testing::kTwoMuscleBoxScene);
    write("flexor.yaml", flexor_schedule());
    write("extensor.yaml", extensor_schedule());
  }

  struct Run {
    double wall_s = 0.0;
    std::string server_err, players_err;
  };

  // One run: the server on server_url, the players on controllers_url (the same URL: no relay),
  // until both players have seen state kSteps; then the server is shut down.
  Run run(const std::string& name, const std::string& server_url,
          const std::string& controllers_url) {
    Run r;
    std::vector<std::unique_ptr<ChildProcess>> players;
    for (const char* muscle : {"flexor", "extensor"})
      players.push_back(std::make_unique<ChildProcess>(
          SEQUENCE_PLAYER_PATH,
          std::vector<std::string>{"--schedule", (dir_ / (std::string(muscle) + ".yaml")).string(),
                                   "--lcm-url", controllers_url, "--max-steps",
                                   std::to_string(kSteps), "--timeout-s", "60"},
          dir_, name + "_" + muscle));
    const auto start = std::chrono::steady_clock::now();
    ChildProcess server(SIM_SERVER_PATH,
                        {(dir_ / "scene.yaml").string(), "--lcm-url", server_url, "--output",
                         (dir_ / (name + ".h5")).string(), "--controllers", "2"},
                        dir_, name + "_server");
    for (auto& p : players) {
      EXPECT_EQ(p->wait_exit(kRunWaitMs), 0) << p->stderr_text() << server.stderr_text();
      r.players_err += p->stderr_text();
    }
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    testing::ServerController(server_url).send_command("shutdown");
    EXPECT_EQ(server.wait_exit(kExitWaitMs), 0) << server.stderr_text();
    r.server_err = server.stderr_text();
    return r;
  }
};

TEST_F(LossyBus, TwoControllersThroughALossyRelayGiveTheLosslessRun) {
  const Run lossless = run("lossless", bus_url(kFirstPort), bus_url(kFirstPort));

  const std::string server_url = bus_url(kFirstPort + 1), controllers_url = bus_url(kFirstPort + 2);
  ChildProcess relay(LOSSY_RELAY_PATH,
                     {"--controllers", controllers_url, "--server", server_url, "--drop",
                      std::to_string(kDrop), "--seed", "2024"},
                     dir_, "relay");
  ASSERT_TRUE(relay.started());
  const auto relay_out = dir_ / "relay_stdout.txt";
  const auto relay_ready = [&relay_out] {
    return testing::read_text(relay_out).find("relaying") != std::string::npos;
  };
  for (int i = 0; i < 1000 && !relay_ready(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(relay_ready());
  const Run lossy = run("lossy", server_url, controllers_url);
  relay.signal(SIGTERM);
  ASSERT_EQ(relay.wait_exit(kExitWaitMs), 0);

  testing::expect_same_results(dir_ / "lossless.h5", dir_ / "lossy.h5", kSteps + 1);

  const std::string counts = testing::read_text(relay_out);
  const long long to_server = figure(counts, "dropped\n"),
                  to_controllers = figure(counts.substr(counts.find("to controllers")), "dropped");
  const testing::RunFile file(dir_ / "lossy.h5");
  const std::string repeated_states = file.string_attribute("/", "repeated_states");
  const std::string repeated_activations = file.string_attribute("/", "repeated_activations");
  // Loss happened, and was recovered by repeats (5 % of about 3 messages a step: about 300).
  EXPECT_GT(to_server, 0) << counts;
  EXPECT_GT(to_controllers, 0) << counts;
  EXPECT_GT(std::stoll(repeated_states), 0);
  EXPECT_NE(lossy.players_err.find("activations sent again"), std::string::npos)
      << lossy.players_err;
  std::printf(
      "loss recovery, %d steps at %g %% loss each way: dropped %lld to the server, %lld to the "
      "controllers; %s states published again, %s repeated activations taken once; wall %.2f s "
      "(lossless %.2f s)\n",
      kSteps, kDrop * 100, to_server, to_controllers, repeated_states.c_str(),
      repeated_activations.c_str(), lossy.wall_s, lossless.wall_s);
  RecordProperty("dropped_to_server", std::to_string(to_server));
  RecordProperty("dropped_to_controllers", std::to_string(to_controllers));
  RecordProperty("repeated_states", repeated_states);
  RecordProperty("wall_s_lossy", std::to_string(lossy.wall_s));
  RecordProperty("wall_s_lossless", std::to_string(lossless.wall_s));
}

}  // namespace
}  // namespace tongue::server
