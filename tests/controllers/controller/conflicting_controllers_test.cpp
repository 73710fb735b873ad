// Two controllers that name the same muscle, as real processes on a real bus (udpm port 7906):
// sim_server --controllers 2 takes the first message for step 1 and rejects the second
// (overlapping); the rejected controller learns why from the rejection notice and exits 5
// saying so; the other sees the notice about the other sender, and the server, waiting for a
// second message that does not overlap, follows its silence rule (here --on-silence stop: exit 3,
// the run file saying which rejection kept the step from being made).
#include <gtest/gtest.h>

#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "support/run_file.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_SERVER_PATH
#error "SIM_SERVER_PATH must name the sim_server executable"
#endif
#ifndef SEQUENCE_PLAYER_PATH
#error "SEQUENCE_PLAYER_PATH must name the sequence_player executable"
#endif

namespace tongue::controller {
namespace {

using tongue::testing::bus_url;
using tongue::testing::ChildProcess;

constexpr int kExitWaitMs = 60000;  // generous: a loaded machine

class ConflictingControllers : public tongue::testing::TempDirTest {};

TEST_F(ConflictingControllers, TheRejectedOneIsToldAndTheServerStopsAsItsSilenceRuleSays) {
  const std::string url = bus_url(7906);
  write("scene.yaml", tongue::testing::kTwoMuscleBoxScene);
  write("flexor.yaml", "entries:\n  - {muscle: flexor, level: 0.5}\n");
  tongue::testing::ServerController watcher(url);
  ASSERT_TRUE(watcher.good());
  ChildProcess server(
      SIM_SERVER_PATH,
      {(dir_ / "scene.yaml").string(), "--lcm-url", url, "--output", (dir_ / "run.h5").string(),
       "--controllers", "2", "--timeout-ms", "5000", "--on-silence", "stop"},
      dir_, "server");
  // Both players join the running server (through describe), so that their own timeouts do not
  // run while the server starts on a loaded machine.
  ASSERT_TRUE(watcher.wait_step(0, kExitWaitMs)) << server.stderr_text();
  std::vector<std::unique_ptr<ChildProcess>> players;
  for (const char* name : {"one", "two"})
    players.push_back(std::make_unique<ChildProcess>(
        SEQUENCE_PLAYER_PATH,
        std::vector<std::string>{"--schedule", (dir_ / "flexor.yaml").string(), "--lcm-url", url,
                                 "--timeout-s", "4"},
        dir_, name));

  EXPECT_EQ(server.wait_exit(kExitWaitMs), 3) << server.stderr_text();
  std::vector<int> exits;
  for (auto& p : players) exits.push_back(p->wait_exit(kExitWaitMs).value_or(-1));
  // Which one came first is a race: one was rejected (5), the other waited in vain (4).
  ASSERT_TRUE((exits == std::vector<int>{5, 4}) || (exits == std::vector<int>{4, 5}))
      << exits[0] << " " << exits[1] << "\n"
      << players[0]->stderr_text() << players[1]->stderr_text() << server.stderr_text();
  const ChildProcess& rejected = *players[exits[0] == 5 ? 0 : 1];
  const ChildProcess& other = *players[exits[0] == 5 ? 1 : 0];
  EXPECT_NE(
      rejected.stderr_text().find("sequence_player: the server rejected its activation for step 1 "
                                  "(sequence_player:"),
      std::string::npos)
      << rejected.stderr_text();
  EXPECT_NE(rejected.stderr_text().find(
                "overlapping activation: \"flexor\" is already set for step 1 by an earlier "
                "message"),
            std::string::npos)
      << rejected.stderr_text();
  EXPECT_NE(other.stderr_text().find("the server rejected an activation of \"sequence_player:"),
            std::string::npos)
      << other.stderr_text();
  EXPECT_NE(other.stderr_text().find("no state for 4 s after step 0"), std::string::npos)
      << other.stderr_text();

  // The rejected one may have sent its message again (answering a repeated state) before it
  // read its notice: each copy is rejected too.
  const std::regex why(
      "1 of 2 activations for step 1 within 5000 ms \\([0-9]+ rejected, the last: overlapping "
      "activation from \"sequence_player:[0-9]+\"\\)");
  EXPECT_TRUE(std::regex_search(server.stderr_text(), why)) << server.stderr_text();
  const tongue::testing::RunFile run(dir_ / "run.h5");
  const std::string status = run.string_attribute("/", "status");
  EXPECT_EQ(status.rfind("stopped: 1 of 2 activations for step 1", 0), 0u) << status;
  EXPECT_TRUE(std::regex_search(status, why)) << status;
  EXPECT_EQ(run.doubles("/time").size(), 1u);  // no step was made
}

}  // namespace
}  // namespace tongue::controller
